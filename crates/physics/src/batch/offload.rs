//! The batch engine's frame with its substeps taken elsewhere
//! ([`SubstepOffload`]: the GPU engine, `gpu::GpuEngine`): the batch system
//! keeps the constants, roots and a copy of the state, hands the substeps
//! over, takes back the guard's measure of every strand made there, and
//! judges and recovers the frame's end with its own guard, as
//! [`BatchSystem::step_frame`] does its own. The state itself comes back
//! only where a strand needs it here (a retry, a held batch, a pinned
//! strand); otherwise it stays there ([`BatchSystem::state_is_elsewhere`])
//! until the caller reads it. A frame's start is
//! the last frame's end, so a frame's measure is made once, where the
//! state is; the CPU measures only a start it changed itself (the first
//! frame, a retry, a state set from outside) and a batch it stepped
//! itself (one the guard holds on Exact).

use super::contact::SkinTest;
use super::group::{Advance, FrameCheck, Group, LaneEnds};
use super::guard::{finite_state, measure_lanes};
use super::lanes::{LANES, Lanes};
use super::layout::RootMotion;
use super::system::BatchSystem;
use super::vec::{V3, lane_of, set_lane};
use super::volume::carried;
use crate::frame_balance::{KineticEnergy, StrandMeasure};
use crate::motion::{HeadTrajectory, RigidMotion};

/// Every strand's (q, q̇), strand after strand in index order, one
/// `[f32; 4]` per element (w unused).
pub type FlatState = (Vec<[f32; 4]>, Vec<[f32; 4]>);

/// What advances every strand of a [`BatchSystem`] by one substep in its
/// own memory (the GPU engine, `gpu::GpuEngine`), the state laid out
/// strand after strand in index order, one `[f32; 4]` per element (w
/// unused): see [`BatchSystem::step_frame_offloaded`].
pub trait SubstepOffload {
    /// Takes every strand's state (q, q̇).
    fn upload(&mut self, q: &[[f32; 4]], v: &[[f32; 4]]);
    /// Advances every strand one substep with the head moving as `motion`
    /// over it ([`HeadTrajectory::step_motion_at`]).
    fn substep(&mut self, motion: &RigidMotion);
    /// Keeps every strand's state as the frame's start, in its own memory
    /// (where a failing strand's retry starts from).
    fn keep_start(&mut self);
    /// Every strand's state (q, q̇), or why it could not be read.
    fn download(&mut self) -> Result<FlatState, String>;
    /// Every strand's state as [`Self::keep_start`] kept it, or why it
    /// could not be read.
    fn download_start(&mut self) -> Result<FlatState, String>;
    /// The guard's measure of every strand's current state, in index
    /// order, with the head at `head` (its motion at the frame's end),
    /// Block-diagonal's own kinetic energy summed where `judged_by` asks,
    /// and whether each strand's state is finite; or why it could not be
    /// made.
    fn measure(
        &mut self,
        head: &RigidMotion,
        judged_by: KineticEnergy,
    ) -> Result<Vec<(StrandMeasure, bool)>, String>;
}

impl BatchSystem {
    /// [`Self::step_frame`] with the substeps taken by `offload` in its own
    /// memory (module docs): with `upload`, this system's state goes there
    /// first (it must be current: [`Self::state_is_elsewhere`] false). The
    /// guard's measure of the frame's end is made there and judged here as
    /// [`Self::step_frame`] judges its own; the state itself comes back
    /// only where this frame needs it: a failing strand (its retry starts
    /// from the frame's start, which `offload` kept), a batch the guard
    /// holds on Exact after a retry (it steps its frame here, from the
    /// start, and the device's answer for it is dropped) or a pinned
    /// strand (held at rest here). Otherwise the state stays elsewhere
    /// ([`Self::state_is_elsewhere`]) and this system's copy is the last
    /// one read; the caller reads it back when it needs it
    /// ([`Self::set_state_flat`]). Returns whether this changed a strand,
    /// so that the next frame must upload; an error if the device could
    /// not be read (this system's state is then the last one read, and
    /// its clock has not moved). Without the hair–hair model only (panics
    /// otherwise: the caller steps such a system itself).
    pub fn step_frame_offloaded(
        &mut self,
        head: &dyn HeadTrajectory,
        offload: &mut dyn SubstepOffload,
        upload: bool,
    ) -> Result<bool, String> {
        assert!(
            self.volume.is_none(),
            "the offloaded frame has no hair–hair model"
        );
        let (env, kinds, kinetic) = self.frame_setup();
        let h = env.h_secs;
        let start_secs = self.time_secs;
        if upload {
            assert!(!self.state_elsewhere, "an upload of a state not current");
            let (q, v) = self.state_flat();
            offload.upload(&q, &v);
        }
        let guarded = self.guard.is_some();
        // A start the guard has not measured (a guard just switched on) is
        // measured here, from the state itself.
        if guarded && self.state_elsewhere && self.groups.iter().any(|g| !g.measured) {
            let (q, v) = offload.download()?;
            self.set_state_flat(&q, &v);
        }
        if guarded {
            offload.keep_start();
        }
        for substep in 0..self.settings.substeps {
            offload.substep(&head.step_motion_at(start_secs + substep as f64 * h, h));
        }
        // The start's measure, if this system changed it, and its
        // checkpoint, where its state is the start, while the GPU steps.
        let start_elsewhere = self.state_elsewhere;
        self.start_frame(head, &env, kinetic);
        let end_secs = start_secs + self.settings.substeps as f64 * h;
        let ends = if guarded {
            let measured = offload.measure(&head.motion_at(end_secs), kinetic)?;
            Some(self.lane_ends(&measured))
        } else {
            None
        };
        // A batch the guard holds on Exact after a retry steps Exact here,
        // from the frame's start, as the batch engine's own frame steps it:
        // the device stepped it with the settings' own solver. A pinned
        // strand is held at rest here. Both need the state now.
        let held = self.groups.iter().any(Group::any_held);
        let pinned = self.groups.iter().any(Group::any_pinned);
        let mut read = false;
        if held || pinned {
            self.read_frame(offload, start_elsewhere)?;
            read = true;
        }
        for group in &mut self.groups {
            group.restore_held();
        }
        let substeps = self.settings.substeps;
        let first = match (held, guarded) {
            (true, _) => 0,
            (false, true) => substeps - 1,
            (false, false) => substeps,
        };
        self.time_secs = start_secs + first as f64 * h;
        for substep in first..substeps {
            let motion = head.step_motion_at(self.time_secs, h);
            let contact = SkinTest::of_head(&self.collider, self.settings.contact, &motion, h);
            let end_secs = self.time_secs + h;
            let last = substep + 1 == substeps;
            let end_motion = (last && guarded).then(|| head.motion_at(end_secs));
            let check = self.guard.as_ref().zip(end_motion.as_ref());
            let check = check.map(|(guard, motion)| {
                FrameCheck::new(guard, motion, &self.collider, &self.settings, kinetic)
            });
            // Judged from the device's measures, a batch the device stepped
            // reads none of its state here.
            for (g, group) in self.groups.iter_mut().enumerate() {
                group.step(
                    &motion,
                    &env,
                    kinds,
                    contact,
                    None,
                    check.as_ref(),
                    self.parallel,
                    Advance::Held,
                    ends.as_ref().map(|ends| &ends[g][..]),
                );
            }
            self.time_secs = end_secs;
        }
        // A failing strand is retried here from the frame's start.
        if !read && self.groups.iter().any(Group::any_failed) {
            self.read_frame(offload, start_elsewhere)?;
            read = true;
        }
        if !read {
            self.state_elsewhere = true;
            // Every strand passed the guard's check, finiteness included.
            self.elsewhere_known_finite = guarded;
        }
        self.end_frame(head, start_secs, env, kinds, kinetic);
        Ok(held || pinned || !self.last_events.is_empty())
    }

    /// Reads the frame's end state back from `offload`, and its start into
    /// the checkpoint where this system did not hold it (`start_elsewhere`).
    fn read_frame(
        &mut self,
        offload: &mut dyn SubstepOffload,
        start_elsewhere: bool,
    ) -> Result<(), String> {
        if start_elsewhere {
            let (q, v) = offload.download_start()?;
            self.set_checkpoint_flat(&q, &v);
        }
        let (q, v) = offload.download()?;
        self.set_state_flat(&q, &v);
        Ok(())
    }

    /// Strand-ordered `(measure, finite)` pairs sorted into each group's
    /// batches and lanes (padding lanes `None`).
    fn lane_ends(&self, measured: &[(StrandMeasure, bool)]) -> Vec<Vec<LaneEnds>> {
        let mut ends: Vec<Vec<LaneEnds>> = self
            .groups
            .iter()
            .map(|g| vec![[None; LANES]; g.roots.len().div_ceil(LANES)])
            .collect();
        for (&(g, slot), &end) in self.slots.iter().zip(measured) {
            ends[g][slot / LANES][slot % LANES] = Some(end);
        }
        ends
    }

    /// The guard's measure of every strand's current state, in index
    /// order, with the head at `head`, as a frame's check makes it (the
    /// head's contact over a substep, Block-diagonal's own kinetic energy
    /// where `judged_by` asks), and whether each state is finite: what a
    /// [`SubstepOffload::measure`] returns, made on the CPU (a stand-in
    /// for the device in tests).
    pub fn measure_strands(
        &self,
        head: &RigidMotion,
        judged_by: KineticEnergy,
    ) -> Vec<(StrandMeasure, bool)> {
        let (env, _, _) = self.frame_setup();
        let contact = SkinTest::of_head(&self.collider, self.settings.contact, head, env.h_secs);
        let per_group: Vec<Vec<(StrandMeasure, bool)>> = self
            .groups
            .iter()
            .map(|g| {
                let n = g.n;
                let batches = g.q.chunks(n).zip(g.v.chunks(n)).zip(g.roots.chunks(LANES));
                let batches = batches.zip(&g.models);
                batches
                    .flat_map(|(((q, v), roots), model)| {
                        let motions = carried(head, roots);
                        let root = RootMotion::<Lanes>::gather(&motions);
                        let measured = measure_lanes(
                            &**model,
                            &env,
                            &root,
                            &motions,
                            q,
                            v,
                            contact.as_ref(),
                            None,
                            None,
                            judged_by,
                        );
                        let finite = finite_state(q, v);
                        (0..LANES)
                            .map(|lane| (measured.strand(lane), finite[lane]))
                            .collect::<Vec<_>>()
                    })
                    .collect()
            })
            .collect();
        self.slots
            .iter()
            .map(|&(g, slot)| per_group[g][slot])
            .collect()
    }

    /// Every strand's (q, q̇) in index order, one `[f32; 4]` per element
    /// (w zero): the layout [`SubstepOffload`] takes.
    pub fn state_flat(&self) -> FlatState {
        let (mut q, mut v) = (Vec::new(), Vec::new());
        for &(g, slot) in &self.slots {
            let g = &self.groups[g];
            let (batch, lane) = (slot / LANES, slot % LANES);
            let range = batch * g.n..(batch + 1) * g.n;
            for (out, values) in [(&mut q, &g.q), (&mut v, &g.v)] {
                out.extend(lane_of(&values[range.clone()], lane).map(|[x, y, z]| [x, y, z, 0.0]));
            }
        }
        (q, v)
    }

    /// Sets every strand's (q, q̇) from [`Self::state_flat`]'s layout
    /// (panics if the lengths differ from the element count): the state is
    /// then this system's ([`Self::state_is_elsewhere`] false).
    pub fn set_state_flat(&mut self, q: &[[f32; 4]], v: &[[f32; 4]]) {
        self.write_flat(q, v, |g| (&mut g.q, &mut g.v));
        for g in &mut self.groups {
            g.measured = false;
        }
        self.state_elsewhere = false;
        self.elsewhere_known_finite = false;
    }

    /// Sets the frame's checkpoint, where a retry starts from, from
    /// [`Self::state_flat`]'s layout: the state for the padding lanes (which
    /// copy real strands), then every strand's own.
    fn set_checkpoint_flat(&mut self, q: &[[f32; 4]], v: &[[f32; 4]]) {
        for g in &mut self.groups {
            g.checkpoint.0.clone_from(&g.q);
            g.checkpoint.1.clone_from(&g.v);
        }
        self.write_flat(q, v, |g| (&mut g.checkpoint.0, &mut g.checkpoint.1));
    }

    /// Writes a flat state into each group's lanes that `target` picks.
    fn write_flat(
        &mut self,
        q: &[[f32; 4]],
        v: &[[f32; 4]],
        target: impl Fn(&mut Group) -> (&mut Vec<V3<Lanes>>, &mut Vec<V3<Lanes>>),
    ) {
        let count = self.element_count();
        assert!(
            q.len() == count && v.len() == count,
            "state length must be {count}"
        );
        let mut first = 0;
        for &(g, slot) in &self.slots {
            let g = &mut self.groups[g];
            let (n, batch, lane) = (g.n, slot / LANES, slot % LANES);
            let (q_lanes, v_lanes) = target(g);
            for (dst, src) in [(q_lanes, q), (v_lanes, v)] {
                let values = src[first..first + n].iter().map(|&[x, y, z, _]| [x, y, z]);
                set_lane(&mut dst[batch * n..(batch + 1) * n], lane, values);
            }
            first += n;
        }
    }

    /// Whether the strands' current state is held elsewhere (the GPU
    /// engine's device, [`Self::step_frame_offloaded`]) and this system's
    /// copy is the last one read back: its state readers then answer for
    /// that copy.
    pub fn state_is_elsewhere(&self) -> bool {
        self.state_elsewhere
    }

    /// Takes this system's copy of the state, the last one read back, as
    /// the state (where the state elsewhere is lost: a lost device).
    pub fn keep_last_read_state(&mut self) {
        self.state_elsewhere = false;
        self.elsewhere_known_finite = false;
        for g in &mut self.groups {
            g.measured = false;
        }
    }

    /// With the state elsewhere, whether the guard found every strand's
    /// state finite at the end of the last frame (it judges finiteness
    /// from the measures made where the state is).
    pub fn elsewhere_known_finite(&self) -> bool {
        self.state_elsewhere && self.elsewhere_known_finite
    }
}

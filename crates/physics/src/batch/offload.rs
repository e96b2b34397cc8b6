//! The batch engine's frame with its substeps taken elsewhere
//! ([`SubstepOffload`]: the GPU engine, `gpu::GpuEngine`): the batch system
//! keeps the constants, roots and a copy of the state, hands the substeps
//! over, takes the state back once with the guard's measure of every
//! strand made there, and judges and recovers the frame's end with its own
//! guard, as [`BatchSystem::step_frame`] does its own. A frame's start is
//! the last frame's end, so a frame's measure is made once, where the
//! state is; the CPU measures only a start it changed itself (the first
//! frame, a retry, a state set from outside) and a batch it stepped
//! itself (one the guard holds on Exact).

use super::contact::SkinTest;
use super::group::{Advance, FrameCheck, Group, LaneEnds};
use super::guard::{finite_lanes, measure_lanes};
use super::lanes::{LANES, Lanes};
use super::layout::RootMotion;
use super::system::BatchSystem;
use super::vec::{lane_of, set_lane};
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
    /// Every strand's state (q, q̇), or why it could not be read.
    fn download(&mut self) -> Result<FlatState, String>;
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
    /// memory: with `upload`, this system's state goes there first; the
    /// guard measures the frame's start here, `offload` steps the
    /// substeps, the result comes back and is judged and recovered here
    /// as [`Self::step_frame`] judges and recovers its own (retries on the
    /// CPU; a batch the guard holds on Exact after a retry steps its
    /// frame here, from the start, and the device's answer for it is
    /// dropped). Returns whether this changed a strand after the
    /// download, so that the next frame must upload; an error if the state
    /// could not be read back (this system's state is then the frame's
    /// start, and its clock has not moved). Without the hair–hair model
    /// only (panics otherwise: the caller steps such a system itself).
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
            let (q, v) = self.state_flat();
            offload.upload(&q, &v);
        }
        for substep in 0..self.settings.substeps {
            offload.substep(&head.step_motion_at(start_secs + substep as f64 * h, h));
        }
        // The start's checkpoint (and its measure, if this system changed
        // it) while the GPU steps.
        self.start_frame(head, &env, kinetic);
        let end_secs = start_secs + self.settings.substeps as f64 * h;
        let measured = match &self.guard {
            Some(_) => Some(offload.measure(&head.motion_at(end_secs), kinetic)?),
            None => None,
        };
        let (q, v) = offload.download()?;
        self.set_state_flat(&q, &v);
        let ends = measured.map(|measured| self.lane_ends(&measured));
        // A batch the guard holds on Exact after a retry steps Exact here,
        // from the frame's start, as the batch engine's own frame steps it:
        // the device stepped it with the settings' own solver. The guard
        // judges every batch in the last substep's pass.
        let held = self.groups.iter().any(Group::any_held);
        for group in &mut self.groups {
            group.restore_held();
        }
        let substeps = self.settings.substeps;
        let first = match (held, self.guard.is_some()) {
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
            let end_motion = (last && self.guard.is_some()).then(|| head.motion_at(end_secs));
            let check = self.guard.as_ref().zip(end_motion.as_ref());
            let check = check.map(|(guard, motion)| {
                FrameCheck::new(guard, motion, &self.collider, &self.settings, kinetic)
            });
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
        self.end_frame(head, start_secs, env, kinds, kinetic);
        // A pinned strand is held at rest here each frame: the device must
        // hold it there too.
        let pinned = self.groups.iter().any(Group::any_pinned);
        Ok(held || pinned || !self.last_events.is_empty())
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
                        let (finite_q, finite_v) = (finite_lanes(q), finite_lanes(v));
                        (0..LANES)
                            .map(|lane| (measured.strand(lane), finite_q[lane] && finite_v[lane]))
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
    /// (panics if the lengths differ from the element count).
    pub fn set_state_flat(&mut self, q: &[[f32; 4]], v: &[[f32; 4]]) {
        let count = self.element_count();
        assert!(
            q.len() == count && v.len() == count,
            "state length must be {count}"
        );
        let mut first = 0;
        for &(g, slot) in &self.slots {
            let g = &mut self.groups[g];
            let (n, batch, lane) = (g.n, slot / LANES, slot % LANES);
            g.measured = false;
            for (dst, src) in [(&mut g.q, q), (&mut g.v, v)] {
                let values = src[first..first + n].iter().map(|&[x, y, z, _]| [x, y, z]);
                set_lane(&mut dst[batch * n..(batch + 1) * n], lane, values);
            }
            first += n;
        }
    }
}

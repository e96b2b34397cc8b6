//! [`BatchSystem`]: strands packed into lane batches, stepped frame by
//! frame like a [`crate::HairSystem`].
//!
//! # Packing
//!
//! Strands are grouped by element count N (the quadrature is the system's,
//! the same for all), and within a group packed [`LANES`] to a batch in the
//! order they were added, whatever their other constants: each batch
//! carries its lanes' constants as a [`LaneModel`]. So [`BatchSystem::add_group`]
//! called once per strand (an imported groom, where every strand has its
//! own length and rest shape) fills batches as well as one call with many
//! roots: a strand lands in its group's last batch while it has a free
//! lane, and opens a new batch otherwise. Only a group's last batch can be
//! short; its free lanes (padding) copy its last strand, and are computed
//! and ignored. Batches filled by one call share one [`LaneModel`].
//! Strand indices stay those `add_group` returned: a table maps each to
//! its group and slot (batch · [`LANES`] + lane).

use std::ops::Range;
use std::sync::Arc;

use glam::{DVec3, Vec3};

use super::contact::{NearCells, SkinTest};
use super::forward::{FrameState, advance};
use super::group::{Advance, FrameCheck, Group, StepKinds};
use super::lane_model::LaneModel;
use super::lanes::{LANES, Lanes, Real};
use super::layout::{BatchModel, ElementData, RootMotion, StepEnv};
use super::retry::RetryInputs;
use super::vec::{V3, lane_of, set_lane};
use super::volume::{BatchVolume, GroupView};
use crate::batch::step::exact::Elimination;
use crate::batch::step::{BatchStep, krylov_bytes_per_element};
use crate::collision::{ContactSettings, SignedDistanceField};
use crate::error::ParamError;
use crate::frame_balance::{KineticEnergy, SteppedFrame};
use crate::guard::{Guard, GuardAction, GuardEvent};
use crate::model::StrandModel;
use crate::motion::{HeadTrajectory, RigidMotion, RootPose};
use crate::params::StrandParams;
use crate::settings::{Method, SimSettings};
use crate::volume::InteractionSettings;

/// Bytes of memory the batch path holds, for the throughput study.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MemoryUse {
    /// State, roots and padding, divided by the strand count.
    pub bytes_per_strand: f64,
    /// Step scratch per worker thread (reused every step).
    pub scratch_bytes_per_thread: usize,
}

/// Many strands stepped in f32 lanes; see the [module docs](super).
#[derive(Clone, Debug)]
pub struct BatchSystem {
    pub(super) settings: SimSettings,
    pub(super) groups: Vec<Group>,
    /// Per strand index: its group and slot.
    pub(super) slots: Vec<(usize, usize)>,
    pub(super) time_secs: f64,
    head: RigidMotion,
    pub(super) parallel: bool,
    pub(super) collider: Option<(Arc<SignedDistanceField>, NearCells)>,
    pub(super) guard: Option<Guard>,
    last_resets: Vec<usize>,
    last_pins: Vec<usize>,
    pub(super) last_events: Vec<GuardEvent>,
    reset_count: usize,
    /// Every intervention since the system was built.
    event_count: usize,
    /// The hair–hair model, when on ([`super::volume`]).
    pub(super) volume: Option<BatchVolume>,
    /// The current state is held where the frame was stepped (the GPU
    /// engine's device) and the lanes are the last copy read back
    /// ([`Self::state_is_elsewhere`]).
    pub(super) state_elsewhere: bool,
    /// With the state elsewhere: the last frame's guard found every strand
    /// finite.
    pub(super) elsewhere_known_finite: bool,
}

impl BatchSystem {
    /// An empty system. Fails if a setting is out of range or the method is
    /// not Block-diagonal or Exact.
    pub fn new(settings: SimSettings) -> Result<Self, ParamError> {
        settings.validate()?;
        if !matches!(settings.method, Method::BlockDiagonal | Method::Exact) {
            return Err(ParamError::new(
                "method",
                0.0,
                format!(
                    "the batch path runs `block` and `exact`, not `{}`",
                    settings.method.label()
                ),
            ));
        }
        let interaction = settings.interaction;
        Ok(Self {
            settings,
            groups: Vec::new(),
            slots: Vec::new(),
            time_secs: 0.0,
            head: RigidMotion::default(),
            parallel: true,
            collider: None,
            guard: Some(Guard::default()),
            last_resets: Vec::new(),
            last_pins: Vec::new(),
            last_events: Vec::new(),
            reset_count: 0,
            event_count: 0,
            volume: interaction.enabled.then(|| BatchVolume::new(interaction)),
            state_elsewhere: false,
            elsewhere_known_finite: false,
        })
    }

    /// Adds strands sharing `params`, one per root, at their natural shape
    /// and at rest; returns their indices. They fill the free lanes of the
    /// last batch of strands with as many elements before opening new
    /// batches (module docs, "Packing").
    pub fn add_group(
        &mut self,
        params: &StrandParams,
        roots: &[RootPose],
    ) -> Result<Range<usize>, ParamError> {
        let model = StrandModel::new(params, self.settings.quadrature_points)?;
        Ok(self.add_strands(&BatchModel::new(&model), roots))
    }

    /// [`Self::add_group`] for a model already built (with this system's
    /// quadrature: the f32 constants of a [`StrandModel`] made with
    /// `settings().quadrature_points`).
    pub fn add_strands(&mut self, model: &BatchModel, roots: &[RootPose]) -> Range<usize> {
        let n = model.elements();
        let group = match self.groups.iter().position(|g| g.n == n) {
            Some(g) => g,
            None => {
                self.groups.push(Group::new(n));
                self.groups.len() - 1
            }
        };
        let uniform = Arc::new(LaneModel::splat(model));
        let start = self.slots.len();
        for (i, root) in roots.iter().enumerate() {
            let slot = self.groups[group].push(model, &uniform, *root, start + i);
            self.slots.push((group, slot));
        }
        if let Some(volume) = &mut self.volume {
            volume.state_mut().forget_rest();
        }
        start..self.slots.len()
    }

    /// Lanes holding strands and lanes of padding, over all batches.
    pub fn lanes_used(&self) -> LaneUse {
        let batches: usize = self.groups.iter().map(|g| g.models.len()).sum();
        LaneUse {
            batches,
            strands: self.slots.len(),
            padding: batches * LANES - self.slots.len(),
        }
    }

    /// The settings.
    pub fn settings(&self) -> &SimSettings {
        &self.settings
    }

    /// Turns the hair–hair model on, retunes it, or turns it off; fails if
    /// a setting is out of range. Takes effect at the next frame.
    pub fn set_interaction(&mut self, settings: InteractionSettings) -> Result<(), ParamError> {
        settings.validate()?;
        self.settings.interaction = settings;
        // The guard's reused measures counted the old model's work.
        for group in &mut self.groups {
            group.measured = false;
        }
        match (&mut self.volume, settings.enabled) {
            (Some(volume), true) => volume.state_mut().set_settings(settings),
            (None, true) => self.volume = Some(BatchVolume::new(settings)),
            (_, false) => self.volume = None,
        }
        Ok(())
    }

    /// The hair–hair model's state (grid, rest density, last field), if on.
    pub fn volume(&self) -> Option<&BatchVolume> {
        self.volume.as_ref()
    }

    /// Chooses parallel (rayon over batches) or serial stepping; results
    /// are bit-identical.
    pub fn set_parallel(&mut self, parallel: bool) {
        self.parallel = parallel;
    }

    /// Number of strands.
    pub fn strand_count(&self) -> usize {
        self.slots.len()
    }

    /// Total element count over all strands.
    pub fn element_count(&self) -> usize {
        self.groups.iter().map(|g| g.roots.len() * g.n).sum()
    }

    /// Simulated time in seconds.
    pub fn time_secs(&self) -> f64 {
        self.time_secs
    }

    /// The head's motion at the current time.
    pub fn head(&self) -> &RigidMotion {
        &self.head
    }

    /// Sets the head's collider (head coordinates; it moves with the head),
    /// or removes it with `None`. Contact acts at every quadrature sample,
    /// as in the reference ([`super::contact`]).
    pub fn set_collider(&mut self, collider: Option<Arc<SignedDistanceField>>) {
        self.collider = collider.map(|field| {
            let near = NearCells::new(&field);
            (field, near)
        });
    }

    /// The head's collider, if any.
    pub fn collider(&self) -> Option<&Arc<SignedDistanceField>> {
        self.collider.as_ref().map(|(field, _)| field)
    }

    /// How hair meets the collider.
    pub fn contact_settings(&self) -> ContactSettings {
        self.settings.contact
    }

    /// Sets how hair meets the collider (the settings' `contact`; not
    /// checked here: [`ContactSettings::validate`] says what is in range).
    pub fn set_contact_settings(&mut self, settings: ContactSettings) {
        self.settings.contact = settings;
    }

    /// Sets the guard (`None`: no checks). Default: [`Guard::default`]; a
    /// failing strand is reset at rest ([`super::guard`]).
    pub fn set_guard(&mut self, guard: Option<Guard>) {
        self.guard = guard;
    }

    /// The guard, if on.
    pub fn guard(&self) -> Option<&Guard> {
        self.guard.as_ref()
    }

    /// Indices of the strands the guard reset in the last frame, ascending.
    pub fn last_guard_resets(&self) -> &[usize] {
        &self.last_resets
    }

    /// Indices of the strands the guard pinned in the last frame (see
    /// [`crate::guard::GuardAction::Pinned`]): they kept failing, and are
    /// held at rest in their natural shape from now on.
    pub fn last_guard_pins(&self) -> &[usize] {
        &self.last_pins
    }

    /// The guard's interventions in the last frame, strand by strand: what
    /// failed and by how much ([`crate::guard::GuardCause`]), and whether
    /// the strand was reset or pinned.
    pub fn last_guard_events(&self) -> &[GuardEvent] {
        &self.last_events
    }

    /// How many strand resets and pins the guard made since the system was
    /// built.
    pub fn guard_reset_count(&self) -> usize {
        self.reset_count
    }

    /// How many times the guard stepped in (retries, resets and pins)
    /// since the system was built.
    pub fn guard_event_count(&self) -> usize {
        self.event_count
    }

    /// Advances one frame of `dt_secs` in `substeps` steps, the head moving
    /// along `head`; each substep takes the roots' pose and velocities at
    /// its start and their accelerations averaged over it
    /// ([`HeadTrajectory::step_motion_at`]). With the guard on, strands
    /// that fail its checks are recovered by its policy ([`super::retry`]).
    pub fn step_frame(&mut self, head: &dyn HeadTrajectory) {
        assert!(
            !self.state_elsewhere,
            "a frame on the CPU from a state not current (read it back first)"
        );
        let (env, kinds, kinetic) = self.frame_setup();
        let h = env.h_secs;
        let start_secs = self.time_secs;
        if let Some(volume) = &mut self.volume {
            let views: Vec<GroupView<'_>> = self.groups.iter().map(Group::view).collect();
            volume.prepare(&views, &head.motion_at(start_secs), self.parallel);
        }
        self.start_frame(head, &env, kinetic);
        let volume = self.volume.as_ref();
        for substep in 0..self.settings.substeps {
            let motion = head.step_motion_at(self.time_secs, h);
            let contact = SkinTest::of_head(&self.collider, self.settings.contact, &motion, h);
            let end_secs = self.time_secs + h;
            // The guard judges the frame in its last substep's pass.
            let last = substep + 1 == self.settings.substeps;
            let end_motion = (last && self.guard.is_some()).then(|| head.motion_at(end_secs));
            let check = self.guard.as_ref().zip(end_motion.as_ref());
            let check = check.map(|(guard, motion)| {
                FrameCheck::new(guard, motion, &self.collider, &self.settings, kinetic)
            });
            for (i, group) in self.groups.iter_mut().enumerate() {
                let pulls = volume.map(|v| (v, i));
                let check = check.as_ref();
                group.step(
                    &motion,
                    &env,
                    kinds,
                    contact,
                    pulls,
                    check,
                    self.parallel,
                    Advance::All,
                    None,
                );
            }
            self.time_secs = end_secs;
        }
        self.end_frame(head, start_secs, env, kinds, kinetic);
    }

    /// What every substep of a frame takes: the step's environment, the
    /// kinds of step (own and retry) and the kinetic energy the guard
    /// measures.
    pub(super) fn frame_setup(&self) -> (StepEnv, StepKinds, KineticEnergy) {
        let env = StepEnv {
            h_secs: self.settings.substep_secs(),
            gravity_m_per_s2: self.settings.gravity_m_per_s2.to_array(),
            air_velocity_m_per_s: self.settings.air_velocity_m_per_s.to_array(),
        };
        let kinds = StepKinds {
            own: BatchStep::of(&self.settings),
            retry: BatchStep::retry_of(&self.settings),
        };
        (
            env,
            kinds,
            KineticEnergy::of(self.settings.method, self.settings.scheme),
        )
    }

    /// With the guard on, keeps each group's state as the frame's start
    /// (where a retry starts from) and measures what the last frame's end
    /// did not.
    pub(super) fn start_frame(
        &mut self,
        head: &dyn HeadTrajectory,
        env: &StepEnv,
        kinetic: KineticEnergy,
    ) {
        if self.guard.is_none() {
            return;
        }
        let h = env.h_secs;
        let motion = head.motion_at(self.time_secs);
        let volume = self.volume.as_ref();
        let contact = SkinTest::of_head(&self.collider, self.settings.contact, &motion, h);
        for (i, group) in self.groups.iter_mut().enumerate() {
            // Where the state is elsewhere, so is the frame's start
            // (`step_frame_offloaded` reads it back for a retry).
            if !self.state_elsewhere {
                group.save_checkpoint();
            }
            if !group.measured {
                let pulls = volume.map(|v| (v, i));
                let contact = contact.as_ref();
                group.measure(&motion, env, contact, pulls, kinetic, self.parallel);
            } else if let Some(volume) = volume {
                // The model's pull is new each frame: the reused
                // measure counts its work instead of the old one's.
                volume.exchange_start_work(i, &mut group.measures);
            }
        }
    }

    /// The frame's end: the head's pose, and with the guard on, the
    /// recovery of what its check found ([`super::retry`]) and the record
    /// of it.
    pub(super) fn end_frame(
        &mut self,
        head: &dyn HeadTrajectory,
        start_secs: f64,
        env: StepEnv,
        kinds: StepKinds,
        kinetic: KineticEnergy,
    ) {
        let volume = self.volume.as_ref();
        self.head = head.motion_at(self.time_secs);
        self.last_resets.clear();
        self.last_pins.clear();
        self.last_events.clear();
        if let Some(guard) = &self.guard {
            let frame = SteppedFrame {
                dt_secs: self.settings.dt_secs,
                substeps: self.settings.substeps,
            };
            for (i, group) in self.groups.iter_mut().enumerate() {
                group.retry_failed(&RetryInputs {
                    guard,
                    head,
                    start_secs,
                    frame,
                    env,
                    kinds,
                    measured: kinetic,
                    collider: &self.collider,
                    contact: self.settings.contact,
                    pulls: volume.map(|v| (v, i)),
                });
                group.record_check(start_secs, &mut self.last_events);
            }
            // Groups are by element count, not by index: events in index order.
            self.last_events.sort_by_key(|event| event.strand);
            for event in &self.last_events {
                match event.action {
                    GuardAction::Pinned => self.last_pins.push(event.strand),
                    GuardAction::Reset => self.last_resets.push(event.strand),
                    GuardAction::Retried { .. } => {}
                }
            }
        } else {
            // Stepped unjudged, the state has left the last measures
            // behind (as a reference strand's unguarded step drops its
            // cached measure): a guard switched on again measures afresh.
            for group in &mut self.groups {
                group.measured = false;
            }
        }
        self.reset_count += self.last_resets.len() + self.last_pins.len();
        self.event_count += self.last_events.len();
    }

    /// Strand `index`'s group, batch and lane (panics if out of range).
    fn locate(&self, index: usize) -> (usize, usize, usize) {
        let &(group, slot) = self
            .slots
            .get(index)
            .unwrap_or_else(|| panic!("strand {index} out of range 0..{}", self.slots.len()));
        (group, slot / LANES, slot % LANES)
    }

    fn lane_values(values: &[V3<Lanes>], n: usize, batch: usize, lane: usize) -> Vec<DVec3> {
        lane_of(&values[batch * n..(batch + 1) * n], lane)
            .map(|x| Vec3::from_array(x).as_dvec3())
            .collect()
    }

    /// Strains q of strand `index`, m⁻¹ (panics if out of range).
    pub fn q(&self, index: usize) -> Vec<DVec3> {
        let (g, batch, lane) = self.locate(index);
        let g = &self.groups[g];
        Self::lane_values(&g.q, g.n, batch, lane)
    }

    /// Strain rates q̇ of strand `index`, m⁻¹/s (panics if out of range).
    pub fn v(&self, index: usize) -> Vec<DVec3> {
        let (g, batch, lane) = self.locate(index);
        let g = &self.groups[g];
        Self::lane_values(&g.v, g.n, batch, lane)
    }

    /// Sets strand `index`'s strains and rates (rounded to f32; lengths
    /// must match its element count).
    pub fn set_state(&mut self, index: usize, q: &[DVec3], v: &[DVec3]) {
        let (g, batch, lane) = self.locate(index);
        let g = &mut self.groups[g];
        let n = g.n;
        assert!(q.len() == n && v.len() == n, "state length must be {n}");
        g.measured = false;
        for (dst, src) in [(&mut g.q, q), (&mut g.v, v)] {
            let values = src.iter().map(|s| s.as_vec3().to_array());
            set_lane(&mut dst[batch * n..(batch + 1) * n], lane, values);
        }
    }

    /// Sets the strains strand `index` rests in (rounded to f32; length:
    /// its element count), which the hair–hair model's rest density is
    /// built from ([`crate::Strand::rest_pose`]); the model rebuilds it at
    /// the next frame.
    pub fn set_rest_pose(&mut self, index: usize, q: &[DVec3]) {
        let (g, batch, lane) = self.locate(index);
        let g = &mut self.groups[g];
        let n = g.n;
        assert!(q.len() == n, "rest pose length must be {n}");
        let values = q.iter().map(|k| k.as_vec3().to_array());
        set_lane(&mut g.rest_q[batch * n..(batch + 1) * n], lane, values);
        if let Some(volume) = &mut self.volume {
            volume.state_mut().forget_rest();
        }
    }

    /// The N + 1 element boundary points of strand `index` in world
    /// coordinates, root first (f32 reconstruction of the current state).
    pub fn boundary_points_world(&self, index: usize) -> Vec<Vec3> {
        let (g, batch, lane) = self.locate(index);
        let g = &self.groups[g];
        let n = g.n;
        let motion = self.head.carry(&g.roots[batch * LANES + lane]);
        let origin = motion.position_m.as_vec3();
        let mut s = FrameState::at_root(&RootMotion::<f32>::gather(&[motion]));
        let pick = |x: &V3<Lanes>| V3::new(x.x.lane(lane), x.y.lane(lane), x.z.lane(lane));
        let mut points = vec![origin];
        for (e, length_m) in g.models[batch].lengths_m.iter().enumerate() {
            let i = batch * n + e;
            s = advance(&s, length_m.lane(lane), pick(&g.q[i]), pick(&g.v[i])).0;
            points.push(origin + Vec3::new(s.point_m.x, s.point_m.y, s.point_m.z));
        }
        points
    }

    /// Whether every strain and rate is finite (padding lanes included:
    /// they copy real strands).
    pub fn is_finite(&self) -> bool {
        self.groups.iter().all(|g| {
            g.q.iter().chain(&g.v).all(|x| {
                [x.x, x.y, x.z]
                    .iter()
                    .all(|l| l.to_array().iter().all(|f| f.is_finite()))
            })
        })
    }

    /// Memory held per strand and per worker thread.
    pub fn memory_use(&self) -> MemoryUse {
        let state: usize = self
            .groups
            .iter()
            .map(|g| {
                // Batches filled by one call share their constants.
                let distinct_models = (0..g.models.len())
                    .filter(|&b| b == 0 || !Arc::ptr_eq(&g.models[b], &g.models[b - 1]))
                    .count();
                (g.q.len() + g.v.len()) * std::mem::size_of::<V3<Lanes>>()
                    + g.roots.len() * std::mem::size_of::<RootPose>()
                    + g.strands.len() * std::mem::size_of::<usize>()
                    + g.models.len() * std::mem::size_of::<Arc<LaneModel>>()
                    + distinct_models * g.n * 8 * std::mem::size_of::<Lanes>()
            })
            .sum::<usize>()
            + self.slots.len() * std::mem::size_of::<(usize, usize)>();
        let n_max = self.groups.iter().map(|g| g.n).max().unwrap_or(0);
        MemoryUse {
            bytes_per_strand: state as f64 / self.slots.len().max(1) as f64,
            scratch_bytes_per_thread: n_max
                * (std::mem::size_of::<ElementData<Lanes>>()
                    + std::mem::size_of::<Elimination<Lanes>>()
                    + krylov_bytes_per_element(BatchStep::of(&self.settings))),
        }
    }
}

/// How full the batches are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LaneUse {
    /// Batches of [`LANES`] lanes.
    pub batches: usize,
    /// Lanes that hold a strand.
    pub strands: usize,
    /// Lanes of padding (computed and ignored).
    pub padding: usize,
}

//! Many strands stepped together, in parallel over strands.
//!
//! Strands are independent during a step (contact between strands is not
//! modelled), so the system steps them with rayon; each strand's arithmetic
//! is the same in serial and parallel runs, so both give bit-identical
//! results (a test pins it). One switch, [`HairSystem::set_parallel`],
//! chooses; both share one code path.

use std::ops::Range;
use std::sync::Arc;

use glam::DVec3;
use rayon::prelude::*;

use crate::collision::{ContactInputs, ContactSettings, SignedDistanceField};
use crate::energy::Energies;
use crate::error::ParamError;
use crate::frame_balance::{KineticEnergy, MeasureInputs, SteppedFrame, StrandMeasure};
use crate::guard::{Guard, GuardAction, GuardCause, GuardEvent, GuardState, retry_frame};
use crate::model::StrandModel;
use crate::motion::{HeadTrajectory, RigidMotion, RootPose};
use crate::params::StrandParams;
use crate::settings::{Method, SimSettings};
use crate::step::StageTimes;
use crate::strand::Strand;
use crate::volume::{InteractionSettings, ReferenceVolume};

/// A head of hair: settings, strands and the simulated time.
#[derive(Clone, Debug)]
pub struct HairSystem {
    settings: SimSettings,
    strands: Vec<Strand>,
    time_secs: f64,
    head: RigidMotion,
    parallel: bool,
    last_times: StageTimes,
    guard: Option<Guard>,
    last_events: Vec<GuardEvent>,
    event_count: usize,
    collider: Option<Arc<SignedDistanceField>>,
    volume: Option<ReferenceVolume>,
}

impl HairSystem {
    /// An empty system; fails if a setting is out of range.
    pub fn new(settings: SimSettings) -> Result<Self, ParamError> {
        settings.validate()?;
        Ok(Self {
            strands: Vec::new(),
            time_secs: 0.0,
            head: RigidMotion::default(),
            parallel: true,
            last_times: StageTimes::default(),
            guard: Some(Guard::default()),
            last_events: Vec::new(),
            event_count: 0,
            collider: None,
            volume: settings
                .interaction
                .enabled
                .then(|| ReferenceVolume::new(settings.interaction)),
            settings,
        })
    }

    /// Adds strands sharing `params`, one per root; returns their indices.
    pub fn add_group(
        &mut self,
        params: &StrandParams,
        roots: &[RootPose],
    ) -> Result<Range<usize>, ParamError> {
        let model = Arc::new(StrandModel::new(params, self.settings.quadrature_points)?);
        let start = self.strands.len();
        let method = self.settings.method;
        let scheme = self.settings.scheme;
        self.strands.extend(roots.iter().map(|root| {
            let mut strand = Strand::new(model.clone(), *root, method);
            strand.set_scheme(scheme);
            strand
        }));
        if let Some(volume) = &mut self.volume {
            volume.state_mut().forget_rest();
        }
        Ok(start..self.strands.len())
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
        match (&mut self.volume, settings.enabled) {
            (Some(volume), true) => volume.state_mut().set_settings(settings),
            (None, true) => self.volume = Some(ReferenceVolume::new(settings)),
            (_, false) => {
                self.volume = None;
                self.strands.iter_mut().for_each(Strand::clear_volume_pull);
            }
        }
        Ok(())
    }

    /// The hair–hair model's state (grid, rest density, last field), if on.
    pub fn volume(&self) -> Option<&ReferenceVolume> {
        self.volume.as_ref()
    }

    /// Switches every strand's solver; shapes and velocities are kept.
    pub fn set_method(&mut self, method: Method) {
        self.settings.method = method;
        for s in &mut self.strands {
            s.set_method(method);
            s.set_guard_state(GuardState::default());
        }
    }

    /// Chooses parallel (rayon) or serial stepping; results are identical.
    pub fn set_parallel(&mut self, parallel: bool) {
        self.parallel = parallel;
    }

    /// The strands.
    pub fn strands(&self) -> &[Strand] {
        &self.strands
    }

    /// Mutable access to the strands (state edits, external forces).
    pub fn strands_mut(&mut self) -> &mut [Strand] {
        &mut self.strands
    }

    /// Sets the strains strand `index` rests in ([`Strand::rest_pose`]);
    /// the hair–hair model rebuilds its rest density at the next frame.
    /// Panics if `index` is out of range or `q`'s length is not the
    /// strand's element count.
    pub fn set_rest_pose(&mut self, index: usize, q: &[DVec3]) {
        self.strands[index].set_rest_pose(q);
        if let Some(volume) = &mut self.volume {
            volume.state_mut().forget_rest();
        }
    }

    /// Simulated time in seconds.
    pub fn time_secs(&self) -> f64 {
        self.time_secs
    }

    /// The head's motion at the current time.
    pub fn head(&self) -> &RigidMotion {
        &self.head
    }

    /// Total element count over all strands.
    pub fn element_count(&self) -> usize {
        self.strands.iter().map(|s| s.model().elements()).sum()
    }

    /// Stage times of the last frame, summed over strands and substeps.
    pub fn last_stage_times(&self) -> StageTimes {
        self.last_times
    }

    /// Sets the head's collider (head coordinates; it moves with the head),
    /// or removes it with `None`.
    pub fn set_collider(&mut self, collider: Option<Arc<SignedDistanceField>>) {
        self.collider = collider;
    }

    /// The head's collider, if any.
    pub fn collider(&self) -> Option<&Arc<SignedDistanceField>> {
        self.collider.as_ref()
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

    /// Sets the guard (`None`: no checks, as the stability study runs).
    /// Default: [`Guard::default`].
    pub fn set_guard(&mut self, guard: Option<Guard>) {
        self.guard = guard;
    }

    /// The guard, if on.
    pub fn guard(&self) -> Option<&Guard> {
        self.guard.as_ref()
    }

    /// What the guard did in the last frame, by strand index.
    pub fn last_guard_events(&self) -> &[GuardEvent] {
        &self.last_events
    }

    /// How many times the guard stepped in since the system was built.
    pub fn guard_event_count(&self) -> usize {
        self.event_count
    }

    /// Advances one frame of `dt_secs` in `substeps` steps, the head moving
    /// along `head`. Each substep takes the root's pose and velocities at
    /// its start and its accelerations averaged over it
    /// ([`HeadTrajectory::step_motion_at`]).
    /// With the guard on, a strand that fails its checks is stepped again.
    pub fn step_frame(&mut self, head: &dyn HeadTrajectory) {
        if let Some(volume) = &mut self.volume {
            let motion = head.motion_at(self.time_secs);
            volume.prepare(&mut self.strands, &motion, self.parallel);
        }
        let frame = FrameInputs {
            head,
            start_secs: self.time_secs,
            dt_secs: self.settings.dt_secs,
            substeps: self.settings.substeps,
            gravity: self.settings.gravity_m_per_s2,
            air: self.settings.air_velocity_m_per_s,
            collider: self.collider.as_deref(),
            contact: self.settings.contact,
        };
        let guard = self.guard;
        let step_one = |(index, s): (usize, &mut Strand)| guarded_frame(s, index, &frame, guard);
        let add = |mut a: FrameOutcome, b: FrameOutcome| {
            a.times.accumulate(&b.times);
            a.events.extend(b.events);
            a
        };
        let outcome = if self.parallel {
            self.strands
                .par_iter_mut()
                .enumerate()
                .map(step_one)
                .reduce(FrameOutcome::default, add)
        } else {
            self.strands
                .iter_mut()
                .enumerate()
                .map(step_one)
                .fold(FrameOutcome::default(), add)
        };
        // Advance the clock exactly as the strands sampled it.
        let h = self.settings.substep_secs();
        for _ in 0..self.settings.substeps {
            self.time_secs += h;
        }
        self.head = head.motion_at(self.time_secs);
        self.last_times = outcome.times;
        self.event_count += outcome.events.len();
        self.last_events = outcome.events;
    }

    /// World-space boundary points (N + 1, root first) of strand `index`.
    pub fn boundary_points_world(&self, index: usize) -> Vec<DVec3> {
        let s = &self.strands[index];
        s.boundary_points_world(&self.head.carry(s.root()))
    }

    /// Energies summed over all strands at the current state.
    pub fn energies(&self) -> Energies {
        let mut total = Energies::default();
        for s in &self.strands {
            total.accumulate(
                &s.energies(&self.head.carry(s.root()), self.settings.gravity_m_per_s2),
            );
        }
        total
    }

    /// Whether every strand's state is finite.
    pub fn is_finite(&self) -> bool {
        self.strands.iter().all(Strand::is_finite)
    }
}

/// What every strand's frame shares.
struct FrameInputs<'a> {
    head: &'a dyn HeadTrajectory,
    start_secs: f64,
    dt_secs: f64,
    substeps: u32,
    gravity: DVec3,
    air: DVec3,
    collider: Option<&'a SignedDistanceField>,
    contact: ContactSettings,
}

/// Stage times and guard events of one frame (of one strand, or summed).
#[derive(Default)]
struct FrameOutcome {
    times: StageTimes,
    events: Vec<GuardEvent>,
}

/// Steps strand `s` through one frame in `substeps` steps.
fn plain_frame(s: &mut Strand, frame: &FrameInputs<'_>, substeps: u32) -> StageTimes {
    let h = frame.dt_secs / f64::from(substeps);
    let mut t = frame.start_secs;
    let mut times = StageTimes::default();
    for _ in 0..substeps {
        let motion = frame.head.step_motion_at(t, h);
        let contact = frame.collider.map(|collider| ContactInputs {
            collider,
            head: &motion,
            settings: frame.contact,
            h_secs: h,
        });
        let root = motion.carry(s.root());
        times.accumulate(&s.step_with_contact(&root, frame.gravity, frame.air, h, contact));
        t += h;
    }
    times
}

/// The guard's measure of strand `s` at the end of a frame of `substeps`.
///
/// Both ends of a frame are measured with the contact stiffness of the
/// frame's own step (`frame.substeps`), whatever step a retry takes, so
/// that the contact springs' energy is counted alike at both ends.
fn end_measure(s: &mut Strand, frame: &FrameInputs<'_>) -> StrandMeasure {
    let end_secs = frame.start_secs + frame.dt_secs;
    measure_at(
        s,
        frame,
        end_secs,
        frame.dt_secs / f64::from(frame.substeps),
    )
}

fn measure_at(s: &mut Strand, frame: &FrameInputs<'_>, t_secs: f64, h_secs: f64) -> StrandMeasure {
    let motion = frame.head.motion_at(t_secs);
    let contact = frame.collider.map(|collider| ContactInputs {
        collider,
        head: &motion,
        settings: frame.contact,
        h_secs,
    });
    let root = motion.carry(s.root());
    s.measure(
        &root,
        &MeasureInputs {
            gravity_m_per_s2: frame.gravity,
            air_velocity_m_per_s: frame.air,
            contact,
        },
    )
}

/// [`Guard::check`] of a frame of `s` from `start` to `end`, by the
/// energy the strand's current step conserves
/// ([`crate::frame_balance::KineticEnergy`]).
fn judge(
    guard: &Guard,
    s: &Strand,
    start: &StrandMeasure,
    end: &StrandMeasure,
    frame: SteppedFrame,
) -> Option<GuardCause> {
    let kinetic = KineticEnergy::of(s.method(), s.scheme());
    guard.check(
        s.q(),
        s.v(),
        &start.judged_by(kinetic),
        &end.judged_by(kinetic),
        frame,
    )
}

/// Steps strand `s` (index `index`) through one frame; with a guard, checks
/// the result and recovers as [`crate::guard`] describes.
fn guarded_frame(
    s: &mut Strand,
    index: usize,
    frame: &FrameInputs<'_>,
    guard: Option<Guard>,
) -> FrameOutcome {
    let Some(guard) = guard else {
        return FrameOutcome {
            times: plain_frame(s, frame, frame.substeps),
            events: Vec::new(),
        };
    };
    let mut state = s.guard_state();
    if state.pinned {
        // Held at rest in its rest pose, carried by the head.
        return FrameOutcome::default();
    }
    state.resets.tick();
    if state.hold_frames > 0 {
        state.hold_frames -= 1;
    } else {
        state.substeps = 0;
        if let Some(own_method) = state.own_method.take() {
            s.set_method(own_method);
        }
    }
    let own = frame.substeps.max(state.substeps);
    let start = match s.cached_measure() {
        Some(m) => m,
        None => measure_at(s, frame, frame.start_secs, frame.dt_secs / f64::from(own)),
    };
    s.checkpoint();
    let mut times = plain_frame(s, frame, own);
    let end = end_measure(s, frame);
    let stepped = |substeps| SteppedFrame {
        dt_secs: frame.dt_secs,
        substeps,
    };
    let Some(cause) = judge(&guard, s, &start, &end, stepped(own)) else {
        s.set_cached_measure(Some(end));
        s.set_guard_state(state);
        return FrameOutcome {
            times,
            events: Vec::new(),
        };
    };
    let approximate = !matches!(s.method(), Method::Dense | Method::Exact);
    if approximate {
        state.own_method.get_or_insert(s.method());
        s.set_method(Method::Exact);
    }
    let mut passed_at = None;
    retry_frame(
        &guard,
        own,
        approximate,
        &mut [true],
        |substeps, pending| {
            s.restore_checkpoint(false);
            times.accumulate(&plain_frame(s, frame, substeps));
            let end = end_measure(s, frame);
            if judge(&guard, s, &start, &end, stepped(substeps)).is_none() {
                s.set_cached_measure(Some(end));
                pending[0] = false;
                passed_at = Some(substeps);
            }
        },
    );
    state.hold_frames = guard.hold_frames;
    state.substeps = passed_at.unwrap_or(0);
    let action = match passed_at {
        Some(substeps) => GuardAction::Retried {
            method: s.method(),
            substeps,
        },
        None => {
            let action = state.resets.give_up(&guard);
            state.pinned = action == GuardAction::Pinned;
            if state.pinned {
                s.set_rest_pose_at_rest();
            } else {
                s.restore_checkpoint(true);
            }
            action
        }
    };
    s.set_guard_state(state);
    FrameOutcome {
        times,
        events: vec![GuardEvent {
            strand: index,
            time_secs: frame.start_secs,
            cause,
            action,
        }],
    }
}

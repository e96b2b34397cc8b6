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

use crate::energy::Energies;
use crate::error::ParamError;
use crate::model::StrandModel;
use crate::motion::{HeadTrajectory, RigidMotion, RootPose};
use crate::params::StrandParams;
use crate::settings::{Method, SimSettings};
use crate::step::StageTimes;
use crate::strand::Strand;

/// A head of hair: settings, strands and the simulated time.
#[derive(Clone, Debug)]
pub struct HairSystem {
    settings: SimSettings,
    strands: Vec<Strand>,
    time_secs: f64,
    head: RigidMotion,
    parallel: bool,
    last_times: StageTimes,
}

impl HairSystem {
    /// An empty system; fails if a setting is out of range.
    pub fn new(settings: SimSettings) -> Result<Self, ParamError> {
        settings.validate()?;
        Ok(Self {
            settings,
            strands: Vec::new(),
            time_secs: 0.0,
            head: RigidMotion::default(),
            parallel: true,
            last_times: StageTimes::default(),
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
        self.strands.extend(
            roots
                .iter()
                .map(|root| Strand::new(model.clone(), *root, method)),
        );
        Ok(start..self.strands.len())
    }

    /// The settings.
    pub fn settings(&self) -> &SimSettings {
        &self.settings
    }

    /// Switches every strand's solver; shapes and velocities are kept.
    pub fn set_method(&mut self, method: Method) {
        self.settings.method = method;
        for s in &mut self.strands {
            s.set_method(method);
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

    /// Advances one frame of `dt_secs` in `substeps` steps, the head moving
    /// along `head`. Root motion is sampled at the start of each substep.
    pub fn step_frame(&mut self, head: &dyn HeadTrajectory) {
        let h = self.settings.substep_secs();
        let gravity = self.settings.gravity_m_per_s2;
        let air = self.settings.air_velocity_m_per_s;
        let mut frame_times = StageTimes::default();
        for _ in 0..self.settings.substeps {
            let motion = head.motion_at(self.time_secs);
            let step_one = |s: &mut Strand| s.step(&motion.carry(s.root()), gravity, air, h);
            let add = |mut a: StageTimes, b: StageTimes| {
                a.accumulate(&b);
                a
            };
            let times = if self.parallel {
                self.strands
                    .par_iter_mut()
                    .map(step_one)
                    .reduce(StageTimes::default, add)
            } else {
                self.strands
                    .iter_mut()
                    .map(step_one)
                    .fold(StageTimes::default(), add)
            };
            frame_times.accumulate(&times);
            self.time_secs += h;
        }
        self.head = head.motion_at(self.time_secs);
        self.last_times = frame_times;
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

//! One strand: its model, root, state and step buffers.

use std::sync::Arc;

use glam::DVec3;

use crate::collision::ContactInputs;
use crate::energy::{Energies, energies};
use crate::frame_balance::{MeasureInputs, StrandMeasure};
use crate::guard::GuardState;
use crate::model::StrandModel;
use crate::motion::{RigidMotion, RootPose};
use crate::settings::{Method, StepScheme};
use crate::step::forces::ForceInputs;
use crate::step::generic::measure_strand;
use crate::step::reconstruct::{Kinematics, reconstruct};
use crate::step::solve::Solver;
use crate::step::{StageTimes, StepInputs, StepWorkspace, step_strand};
use crate::volume::VolumePull;
use crate::volume::balance::{PullWork, pull_work};
use crate::volume::pair_points::SampleMotion;

/// A Super-Helix strand clamped to a root on the head.
#[derive(Clone, Debug)]
pub struct Strand {
    model: Arc<StrandModel>,
    root: RootPose,
    q: Vec<DVec3>,
    v: Vec<DVec3>,
    /// The strains the strand rests in ([`Self::rest_pose`]).
    rest_pose: Vec<DVec3>,
    external_n_per_m: Vec<DVec3>,
    volume: VolumeState,
    workspace: StepWorkspace,
    checkpoint_q: Vec<DVec3>,
    checkpoint_v: Vec<DVec3>,
    guard_state: GuardState,
    /// The guard's measure of the current state, while it is valid.
    cached_measure: Option<StrandMeasure>,
}

impl Strand {
    /// A strand at its natural shape, at rest, solved with `method`.
    pub fn new(model: Arc<StrandModel>, root: RootPose, method: Method) -> Self {
        let n = model.elements();
        Self {
            q: model.natural.clone(),
            v: vec![DVec3::ZERO; n],
            rest_pose: model.natural.clone(),
            external_n_per_m: Vec::new(),
            volume: VolumeState::default(),
            workspace: StepWorkspace::new(method),
            checkpoint_q: model.natural.clone(),
            checkpoint_v: vec![DVec3::ZERO; n],
            guard_state: GuardState::default(),
            cached_measure: None,
            model,
            root,
        }
    }

    /// The shared model.
    pub fn model(&self) -> &Arc<StrandModel> {
        &self.model
    }

    /// The root pose on the head.
    pub fn root(&self) -> &RootPose {
        &self.root
    }

    /// Strains q = (τ, κ₁, κ₂) per element, m⁻¹.
    pub fn q(&self) -> &[DVec3] {
        &self.q
    }

    /// Strain rates q̇ per element, m⁻¹/s.
    pub fn v(&self) -> &[DVec3] {
        &self.v
    }

    /// Sets strains and rates (lengths must match the element count).
    pub fn set_state(&mut self, q: &[DVec3], v: &[DVec3]) {
        self.q.copy_from_slice(q);
        self.v.copy_from_slice(v);
        self.cached_measure = None;
    }

    /// The strains the strand rests in, which the hair–hair model's rest
    /// density is built from ([`crate::volume::rest`]): its natural
    /// strains unless told otherwise. A sag-free strand (an imported
    /// groom's, docs/import.md) rests in its groomed shape, which gravity
    /// holds away from its natural one.
    pub fn rest_pose(&self) -> &[DVec3] {
        &self.rest_pose
    }

    /// Sets the strains the strand rests in (length: the element count).
    pub fn set_rest_pose(&mut self, q: &[DVec3]) {
        self.rest_pose.copy_from_slice(q);
    }

    /// The guard's measure of the current state ([`crate::frame_balance`])
    /// for a root moving as `root`: the shared measure at f64
    /// ([`crate::step::generic::measure_strand`]).
    pub fn measure(&self, root: &RigidMotion, inputs: &MeasureInputs) -> StrandMeasure {
        let forces = ForceInputs {
            root,
            gravity_m_per_s2: inputs.gravity_m_per_s2,
            air_velocity_m_per_s: inputs.air_velocity_m_per_s,
            external_n_per_m: &self.external_n_per_m,
            contact: None,
            volume: self.volume.pull(&self.model),
        };
        measure_strand(
            &self.model,
            &self.q,
            &self.v,
            &forces,
            inputs.contact.as_ref(),
        )
    }

    /// The measure the last guarded frame ended with, if the state has not
    /// changed since.
    pub fn cached_measure(&self) -> Option<StrandMeasure> {
        self.cached_measure
    }

    /// Remembers `measure` as the current state's.
    pub fn set_cached_measure(&mut self, measure: Option<StrandMeasure>) {
        self.cached_measure = measure;
    }

    /// Sets the per-sample external force per unit length (N/m; one entry
    /// per quadrature sample, element by element), or clears it with an
    /// empty slice. The guard's measure counts its work; a kept measure of
    /// the state under the old forces is dropped.
    pub fn set_external_forces(&mut self, forces_n_per_m: &[DVec3]) {
        if self.external_n_per_m.as_slice() != forces_n_per_m {
            self.cached_measure = None;
        }
        self.external_n_per_m.clear();
        self.external_n_per_m.extend_from_slice(forces_n_per_m);
    }

    /// Sets the hair–hair model's pull for the coming steps: friction
    /// rate μ (1/s), and per point ([`crate::volume::pair_points`]) the
    /// grid velocity relative to the head's rigid motion there (m/s) and
    /// the pressure
    /// acceleration (m/s²), world axes ([`crate::volume::friction`]).
    pub fn set_volume_pull(
        &mut self,
        friction_per_s: f64,
        relative_target: Vec<DVec3>,
        push: Vec<DVec3>,
    ) {
        // The cached measure counted the old pull's work.
        self.cached_measure = None;
        self.volume = VolumeState {
            on: true,
            friction_per_s,
            relative_target,
            push,
        };
    }

    /// [`Self::set_volume_pull`] that keeps the guard's cached measure:
    /// `samples` are the strand's quadrature samples at its current state,
    /// reconstructed with the head at `head`
    /// ([`crate::volume::reference`]); the old
    /// pull's work there is exchanged for the new one's in the cached
    /// measure ([`crate::volume::balance::PullWork`]) instead of dropping
    /// it.
    pub fn exchange_volume_pull(
        &mut self,
        pull: (f64, Vec<DVec3>, Vec<DVec3>),
        samples: &[SampleMotion],
        head: &RigidMotion,
    ) {
        let cached = self.cached_measure.take();
        let root = head.carry(&self.root);
        let rho_s = self.model.mass_per_length;
        let work = |state: &VolumeState| {
            state
                .pull(&self.model)
                .map_or_else(PullWork::default, |p| pull_work(samples, &root, &p, rho_s))
        };
        let old = work(&self.volume);
        let (friction_per_s, relative_target, push) = pull;
        self.volume = VolumeState {
            on: true,
            friction_per_s,
            relative_target,
            push,
        };
        let new = work(&self.volume);
        self.cached_measure = cached.map(|mut m| {
            PullWork::exchange(&mut m, &old, &new);
            m
        });
    }

    /// Removes the hair–hair model's pull.
    pub fn clear_volume_pull(&mut self) {
        self.cached_measure = None;
        self.volume = VolumeState::default();
    }

    /// The solver method.
    pub fn method(&self) -> Method {
        self.workspace.method
    }

    /// Switches the solver; the state is kept.
    pub fn set_method(&mut self, method: Method) {
        let scheme = self.workspace.scheme;
        self.workspace = StepWorkspace::new(method);
        self.workspace.scheme = scheme;
    }

    /// Steps Block-diagonal with the assembled arrangement's solver (the
    /// subtree blocks of the assembled mass matrix,
    /// [`crate::step::solve::block_diagonal`]), velocity-explicit, instead
    /// of the generic step: the independent check of the generic
    /// Block-diagonal step (`tests/f64_instance.rs`). Undone by
    /// [`Self::set_method`].
    pub fn use_assembled_block_diagonal(&mut self) {
        self.workspace.method = Method::BlockDiagonal;
        self.workspace.solver = Solver::new(Method::BlockDiagonal);
    }

    /// How the strand's steps treat the velocity-dependent forces.
    pub fn scheme(&self) -> StepScheme {
        self.workspace.scheme
    }

    /// Sets how the strand's steps treat the velocity-dependent forces.
    pub fn set_scheme(&mut self, scheme: StepScheme) {
        self.workspace.scheme = scheme;
    }

    /// Step buffers of the last step: the assembled arrangement's
    /// kinematics, mass, forces and solver (Dense, Iterative, the
    /// own-element Block), the generic step's (Exact, Block-diagonal).
    pub fn workspace(&self) -> &StepWorkspace {
        &self.workspace
    }

    /// One step of `h_secs` with the root moving as `root`.
    pub fn step(
        &mut self,
        root: &RigidMotion,
        gravity: DVec3,
        air_velocity: DVec3,
        h_secs: f64,
    ) -> StageTimes {
        self.step_with_contact(root, gravity, air_velocity, h_secs, None)
    }

    /// One step of `h_secs` with the root moving as `root`, pushed out of
    /// the head by `contact` if given.
    pub fn step_with_contact(
        &mut self,
        root: &RigidMotion,
        gravity: DVec3,
        air_velocity: DVec3,
        h_secs: f64,
        contact: Option<ContactInputs<'_>>,
    ) -> StageTimes {
        self.cached_measure = None;
        let inputs = StepInputs {
            h_secs,
            forces: ForceInputs {
                root,
                gravity_m_per_s2: gravity,
                air_velocity_m_per_s: air_velocity,
                external_n_per_m: &self.external_n_per_m,
                contact,
                volume: self.volume.pull(&self.model),
            },
        };
        step_strand(
            &self.model,
            &mut self.q,
            &mut self.v,
            &mut self.workspace,
            &inputs,
        )
    }

    /// The shape and velocities for a root moving as `root`.
    pub fn kinematics(&self, root: &RigidMotion) -> Kinematics {
        let mut kin = Kinematics::default();
        reconstruct(&self.model, &self.q, &self.v, root, &mut kin);
        kin
    }

    /// The N + 1 element boundary points in world coordinates, root first.
    pub fn boundary_points_world(&self, root: &RigidMotion) -> Vec<DVec3> {
        let kin = self.kinematics(root);
        kin.points_m.iter().map(|p| *p + root.position_m).collect()
    }

    /// Energies for a root moving as `root`, under `gravity`.
    pub fn energies(&self, root: &RigidMotion, gravity: DVec3) -> Energies {
        let kin = self.kinematics(root);
        energies(&self.model, &self.q, &kin, root.position_m, gravity)
    }

    /// The strand's standing with the guard.
    pub fn guard_state(&self) -> GuardState {
        self.guard_state
    }

    /// Sets the strand's standing with the guard.
    pub fn set_guard_state(&mut self, state: GuardState) {
        self.guard_state = state;
    }

    /// Remembers the current state (no allocation after the first call).
    pub fn checkpoint(&mut self) {
        self.checkpoint_q.clone_from(&self.q);
        self.checkpoint_v.clone_from(&self.v);
    }

    /// Returns to the state of the last [`Strand::checkpoint`]; with
    /// `at_rest`, with zero strain rates (at rest relative to the root).
    pub fn restore_checkpoint(&mut self, at_rest: bool) {
        self.cached_measure = None;
        self.q.clone_from(&self.checkpoint_q);
        if at_rest {
            self.v.fill(DVec3::ZERO);
        } else {
            self.v.clone_from(&self.checkpoint_v);
        }
    }

    /// Whether every strain and rate is finite.
    pub fn is_finite(&self) -> bool {
        self.q.iter().chain(&self.v).all(|x| x.is_finite())
    }
}

impl Strand {
    /// Puts the strand at rest in its rest pose ([`Self::rest_pose`]: its
    /// natural shape unless told), where the guard pins it.
    pub fn set_rest_pose_at_rest(&mut self) {
        self.q.clone_from(&self.rest_pose);
        self.v.fill(DVec3::ZERO);
        self.cached_measure = None;
    }
}

/// The hair–hair model's pull on one strand, kept between its steps.
#[derive(Clone, Debug, Default)]
struct VolumeState {
    on: bool,
    friction_per_s: f64,
    relative_target: Vec<DVec3>,
    push: Vec<DVec3>,
}

impl VolumeState {
    /// The pull on a strand of `model`, if on.
    fn pull(&self, model: &StrandModel) -> Option<VolumePull<'_>> {
        self.on.then_some(VolumePull {
            friction_per_s: self.friction_per_s,
            relative_target_m_per_s: &self.relative_target,
            push_m_per_s2: &self.push,
            samples_per_element: model.quadrature.len(),
        })
    }
}

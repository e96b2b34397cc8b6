//! The physics engine a run steps: the f64 reference [`HairSystem`] or the
//! f32 [`BatchSystem`], behind one small API: the one simulation core that
//! every face of the app (the headless `helixhair sim`, `helixhair render`,
//! the window's live run and the bench) stands on.
//!
//! # The two engines
//!
//! | | [`EngineKind::Reference`] | [`EngineKind::Batch`] |
//! | --- | --- | --- |
//! | arithmetic | f64, one strand at a time, rayon over strands | f32, [`crate::batch::LANES`] strands per SIMD batch, rayon over batches |
//! | solvers | every [`Method`], per strand | Exact and Block-diagonal, one for all strands |
//! | extras | stability guard with retries, head collider, hair–hair model, stage timings, energies every frame | the same guard policy, retrying a failing strand's whole SIMD batch (`batch/retry.rs`), the same implicit head contact at every quadrature sample, hair–hair model (same grid arithmetic, [`crate::batch::volume`]) |
//! | speed | the baseline | many times the element-steps per second per core, by the CPU's SIMD width (the throughput study, `docs/benchmarks.md`) |
//!
//! The reference is what every solver study and the guard were built on,
//! and stays the default; the batch engine is what makes a full head of
//! thousands of strands interactive. Both start every strand at its rest
//! shape, at rest, and read the same head trajectory, so with Exact they
//! solve the same equations (Exact equals Dense to round-off) and differ
//! only by f32 round-off.
//!
//! # What the uniform API hides
//!
//! - **State** is handed out and taken in f64 ([`Engine::q`],
//!   [`Engine::set_state`]); the batch engine rounds to f32 on the way in.
//!   That is what lets the window carry a strand's shape across an edit
//!   that rebuilds the engine, or switches engines.
//! - **Geometry**: the batch engine keeps each strand's f64
//!   [`StrandModel`] and root next to its lanes, so [`Engine::strand_model`]
//!   and [`Engine::energies`] answer for both (the batch engine's energies
//!   are reconstructed in f64 from its f32 state, on demand: too slow to do
//!   every frame for thousands of strands, cheap once for a report).
//! - **What only one engine has** (the reference's stage timings and guard
//!   events, the batch guard's resets) is reached through
//!   [`Engine::reference`] and [`Engine::batch`], so a caller must say what
//!   it shows for the other.
//!
//! # The head collider
//!
//! [`Engine::set_collider`] is the one place a collider reaches the
//! physics. Both engines collide with it: the reference at every
//! quadrature sample, the batch engine too
//! ([`crate::batch::contact`]), both with the implicit contact (its
//! stiffness and damping in the step matrix; Block-diagonal keeps its
//! diagonal blocks, on both engines).

pub mod gpu_side;
pub mod rest_contact;

pub use gpu_side::GpuSide;
pub use rest_contact::RestContact;

use std::ops::Range;
use std::sync::Arc;

use crate::batch::BatchSystem;
use crate::batch::layout::BatchModel;
use crate::collision::{ContactSettings, SignedDistanceField};
use crate::step::reconstruct::{Kinematics, reconstruct};
use crate::volume::{ModelState, RestDensity, VolumeField};
use crate::{
    Energies, HairSystem, HeadTrajectory, InteractionSettings, Method, ParamError, RigidMotion,
    RootPose, SimSettings, Strand, StrandModel, StrandParams,
};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Which physics engine steps the hair.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EngineKind {
    /// The f64 [`HairSystem`]: every solver, the stability guard, the head
    /// collider, stage timings and energies. The default.
    #[default]
    Reference,
    /// The f32 SIMD [`BatchSystem`] on all cores: Exact or Block-diagonal
    /// only, many times the reference's throughput (`docs/benchmarks.md`).
    Batch,
    /// The batch engine with its substeps taken on the GPU
    /// ([`GpuSide`]): Exact, the head collider and the guard; where the
    /// GPU cannot (no adapter, Block-diagonal, the hair–hair model) the
    /// CPU batch engine steps and [`Engine::gpu_note`] says why.
    Gpu,
}

impl EngineKind {
    /// Every engine, the default first.
    pub const ALL: [EngineKind; 3] = [EngineKind::Reference, EngineKind::Batch, EngineKind::Gpu];

    /// The engines on the CPU, which the benchmarks compare (the GPU
    /// engine's figures are the throughput study's).
    pub const CPU: [EngineKind; 2] = [EngineKind::Reference, EngineKind::Batch];

    /// The solvers the batch engine runs.
    pub const BATCH_METHODS: [Method; 2] = [Method::Exact, Method::BlockDiagonal];

    /// The name `--engine` takes and the JSON report writes: `reference`,
    /// `batch` or `gpu`.
    pub fn label(self) -> &'static str {
        match self {
            Self::Reference => "reference",
            Self::Batch => "batch",
            Self::Gpu => "gpu",
        }
    }

    /// The engine of a [`Self::label`] name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.label() == name)
    }

    /// Whether this engine can run `method`.
    pub fn runs(self, method: Method) -> bool {
        match self {
            Self::Reference => true,
            Self::Batch | Self::Gpu => Self::BATCH_METHODS.contains(&method),
        }
    }
}

/// A hair system on one of the two engines (see the [module docs](self)).
#[derive(Debug)]
pub enum Engine {
    /// The f64 reference.
    Reference(HairSystem),
    /// The f32 batch path, with each strand's f64 model and root.
    Batch {
        /// The lanes.
        system: BatchSystem,
        /// Per strand, in index order: its model (shared within a group)
        /// and its root, for geometry and energies in f64.
        strands: Vec<(Arc<StrandModel>, RootPose)>,
        /// With [`EngineKind::Gpu`], the device that takes the substeps.
        gpu: Option<GpuSide>,
    },
}

/// A clone holds the state as it stands (a GPU engine's read back from
/// its device where it is there); a GPU engine's clone builds its own
/// device on its first frame.
impl Clone for Engine {
    fn clone(&self) -> Self {
        match self {
            Self::Reference(system) => Self::Reference(system.clone()),
            Self::Batch {
                system,
                strands,
                gpu,
            } => Self::Batch {
                system: current(system, gpu).clone(),
                strands: strands.clone(),
                gpu: gpu.clone(),
            },
        }
    }
}

impl Engine {
    /// An empty system on `kind`. Fails if a setting is out of range, or
    /// (field `method`) if the batch engine cannot run the solver.
    pub fn new(kind: EngineKind, settings: SimSettings) -> Result<Self, ParamError> {
        Ok(match kind {
            EngineKind::Reference => Self::Reference(HairSystem::new(settings)?),
            EngineKind::Batch | EngineKind::Gpu => Self::Batch {
                system: BatchSystem::new(settings)?,
                strands: Vec::new(),
                gpu: (kind == EngineKind::Gpu).then(GpuSide::new),
            },
        })
    }

    /// Which engine this is.
    pub fn kind(&self) -> EngineKind {
        match self {
            Self::Reference(_) => EngineKind::Reference,
            Self::Batch { gpu: None, .. } => EngineKind::Batch,
            Self::Batch { gpu: Some(_), .. } => EngineKind::Gpu,
        }
    }

    /// Adds strands sharing `params`, one per root, at rest in their
    /// natural shape; returns their indices.
    pub fn add_group(
        &mut self,
        params: &StrandParams,
        roots: &[RootPose],
    ) -> Result<Range<usize>, ParamError> {
        match self {
            Self::Reference(system) => system.add_group(params, roots),
            Self::Batch {
                system,
                strands,
                gpu,
            } => {
                sync(system, gpu);
                let model = Arc::new(StrandModel::new(
                    params,
                    system.settings().quadrature_points,
                )?);
                let range = system.add_strands(&BatchModel::new(&model), roots);
                strands.extend(roots.iter().map(|r| (model.clone(), *r)));
                if let Some(gpu) = gpu {
                    gpu.invalidate();
                }
                Ok(range)
            }
        }
    }

    /// The reference system, when this is the reference engine.
    pub fn reference(&self) -> Option<&HairSystem> {
        match self {
            Self::Reference(system) => Some(system),
            Self::Batch { .. } => None,
        }
    }

    /// The batch system, when this is the batch engine, with its state
    /// current (on the GPU engine, read back from the device once a frame
    /// where something asks: [`GpuSide::current`]).
    pub fn batch(&self) -> Option<&BatchSystem> {
        match self {
            Self::Reference(_) => None,
            Self::Batch { system, gpu, .. } => Some(current(system, gpu)),
        }
    }

    /// How hair meets the head (either engine steps the same law).
    pub fn contact_settings(&self) -> ContactSettings {
        match self {
            Self::Reference(system) => system.contact_settings(),
            Self::Batch { system, .. } => system.contact_settings(),
        }
    }

    /// Sets how hair meets the head, on either engine.
    pub fn set_contact_settings(&mut self, settings: ContactSettings) {
        match self {
            Self::Reference(system) => system.set_contact_settings(settings),
            Self::Batch { system, gpu, .. } => {
                sync(system, gpu);
                system.set_contact_settings(settings);
                if let Some(gpu) = gpu {
                    gpu.invalidate();
                }
            }
        }
    }

    /// Mutable access to the reference system, when this is the reference
    /// engine.
    pub fn reference_mut(&mut self) -> Option<&mut HairSystem> {
        match self {
            Self::Reference(system) => Some(system),
            Self::Batch { .. } => None,
        }
    }

    /// The settings (the batch engine's solver is one of
    /// [`EngineKind::BATCH_METHODS`]).
    pub fn settings(&self) -> &SimSettings {
        match self {
            Self::Reference(system) => system.settings(),
            Self::Batch { system, .. } => system.settings(),
        }
    }

    /// Makes the strands collide with `collider` (or with nothing).
    ///
    /// The single call site through which a head collider reaches either
    /// engine.
    pub fn set_collider(&mut self, collider: Option<Arc<SignedDistanceField>>) {
        match self {
            Self::Reference(system) => system.set_collider(collider),
            Self::Batch { system, gpu, .. } => {
                sync(system, gpu);
                system.set_collider(collider);
                if let Some(gpu) = gpu {
                    gpu.invalidate();
                }
            }
        }
    }

    /// The head's collider, if any.
    pub fn collider(&self) -> Option<&Arc<SignedDistanceField>> {
        match self {
            Self::Reference(system) => system.collider(),
            Self::Batch { system, .. } => system.collider(),
        }
    }

    /// The head as a support for a strand at rest, with this engine's
    /// contact law ([`RestContact`]): what "set current shape as rest"
    /// solves the rest shape against. `None` without a collider.
    pub fn rest_contact(&self) -> Option<RestContact<'_>> {
        let collider = self.collider()?;
        Some(RestContact::for_engine(
            self.settings(),
            collider,
            *self.head(),
        ))
    }

    /// Sets either engine's stability guard (`None`: no checks; a study
    /// that times the guard's share turns it off).
    pub fn set_guard(&mut self, guard: Option<crate::guard::Guard>) {
        match self {
            Self::Reference(system) => system.set_guard(guard),
            Self::Batch { system, gpu, .. } => {
                sync(system, gpu);
                system.set_guard(guard);
            }
        }
    }

    /// Turns the hair–hair model ([`crate::volume`]) on, retunes it or
    /// turns it off, on either engine.
    pub fn set_interaction(&mut self, settings: InteractionSettings) -> Result<(), ParamError> {
        match self {
            Self::Reference(system) => system.set_interaction(settings),
            Self::Batch { system, gpu, .. } => {
                sync(system, gpu);
                if let Some(gpu) = gpu {
                    gpu.invalidate();
                }
                system.set_interaction(settings)
            }
        }
    }

    /// The hair–hair model's rest density and the field of the last frame,
    /// once a frame has run with the model on.
    pub fn volume_field(&self) -> Option<(&RestDensity, &VolumeField)> {
        let state = self.volume_state()?;
        state.rest().map(|rest| (rest, state.field()))
    }

    /// Wall time of the hair–hair model's pass in the last frame, seconds
    /// (zero when it is off).
    pub fn volume_secs(&self) -> f64 {
        self.volume_state().map_or(0.0, ModelState::last_secs)
    }

    fn volume_state(&self) -> Option<&ModelState> {
        match self {
            Self::Reference(system) => system.volume().map(|v| v.state()),
            Self::Batch { system, .. } => system.volume().map(|v| v.state()),
        }
    }

    /// Advances one frame of `dt_secs` in `substeps` steps, the head moving
    /// along `head`.
    pub fn step_frame(&mut self, head: &dyn HeadTrajectory) {
        match self {
            Self::Reference(system) => system.step_frame(head),
            Self::Batch {
                system,
                strands,
                gpu: Some(gpu),
            } => gpu.step_frame(system, strands, head),
            Self::Batch { system, .. } => system.step_frame(head),
        }
    }

    /// A copy that steps on the CPU: the GPU engine's batch system without
    /// its device (the same f32 arithmetic as [`EngineKind::Batch`]); a
    /// plain clone of the CPU engines. For a pre-roll whose end state a
    /// run starts from (the app's settling on the head), so that the
    /// batch and GPU engines start alike and no device is built for it.
    pub fn cpu_copy(&self) -> Self {
        match self {
            Self::Batch { .. } => match self.clone() {
                Self::Batch {
                    system, strands, ..
                } => Self::Batch {
                    system,
                    strands,
                    gpu: None,
                },
                reference => reference,
            },
            Self::Reference(_) => self.clone(),
        }
    }

    /// The GPU engine's device side, with [`EngineKind::Gpu`].
    pub fn gpu_side(&self) -> Option<&GpuSide> {
        match self {
            Self::Batch { gpu, .. } => gpu.as_ref(),
            Self::Reference(_) => None,
        }
    }

    /// The GPU engine's device side, to give it a device or write its
    /// curves, with [`EngineKind::Gpu`].
    pub fn gpu_side_mut(&mut self) -> Option<&mut GpuSide> {
        match self {
            Self::Batch { gpu, .. } => gpu.as_mut(),
            Self::Reference(_) => None,
        }
    }

    /// With [`EngineKind::Gpu`], what steps the frames, in words: "physics
    /// on the GPU (adapter)", or why the CPU batch engine steps them.
    pub fn gpu_note(&self) -> Option<&str> {
        match self {
            Self::Batch { gpu: Some(gpu), .. } => Some(gpu.note()),
            _ => None,
        }
    }

    /// Number of strands.
    pub fn strand_count(&self) -> usize {
        match self {
            Self::Reference(system) => system.strands().len(),
            Self::Batch { system, .. } => system.strand_count(),
        }
    }

    /// Super-Helix elements over all strands.
    pub fn element_count(&self) -> usize {
        match self {
            Self::Reference(system) => system.element_count(),
            Self::Batch { system, .. } => system.element_count(),
        }
    }

    /// What the stability guard did in the last frame, on either engine
    /// (the same policy: [`crate::guard`]).
    pub fn last_guard_events(&self) -> &[crate::guard::GuardEvent] {
        match self {
            Self::Reference(system) => system.last_guard_events(),
            Self::Batch { system, .. } => system.last_guard_events(),
        }
    }

    /// How many times the guard stepped in since the engine was built.
    pub fn guard_event_count(&self) -> usize {
        match self {
            Self::Reference(system) => system.guard_event_count(),
            Self::Batch { system, .. } => system.guard_event_count(),
        }
    }

    /// Whether every strand's state is finite (on the GPU engine with the
    /// guard on, from its measures where the state is, without a readback).
    pub fn is_finite(&self) -> bool {
        match self {
            Self::Reference(system) => system.is_finite(),
            Self::Batch { system, .. } if system.elsewhere_known_finite() => true,
            Self::Batch { system, gpu, .. } => current(system, gpu).is_finite(),
        }
    }

    /// Simulated time since the engine was built, seconds.
    pub fn time_secs(&self) -> f64 {
        match self {
            Self::Reference(system) => system.time_secs(),
            Self::Batch { system, .. } => system.time_secs(),
        }
    }

    /// The head's motion at the current time.
    pub fn head(&self) -> &RigidMotion {
        match self {
            Self::Reference(system) => system.head(),
            Self::Batch { system, .. } => system.head(),
        }
    }

    /// The N + 1 element boundary points of strand `index`, world
    /// coordinates, root first (the batch engine's in f32, widened).
    /// Panics if `index` is out of range.
    pub fn boundary_points_world(&self, index: usize) -> Vec<DVec3> {
        match self {
            Self::Reference(system) => system.boundary_points_world(index),
            Self::Batch { system, gpu, .. } => current(system, gpu)
                .boundary_points_world(index)
                .into_iter()
                .map(|p| p.as_dvec3())
                .collect(),
        }
    }

    /// Strains q of strand `index`, m⁻¹. Panics if out of range.
    pub fn q(&self, index: usize) -> Vec<DVec3> {
        match self {
            Self::Reference(system) => system.strands()[index].q().to_vec(),
            Self::Batch { system, gpu, .. } => current(system, gpu).q(index),
        }
    }

    /// Strain rates q̇ of strand `index`, m⁻¹/s. Panics if out of range.
    pub fn v(&self, index: usize) -> Vec<DVec3> {
        match self {
            Self::Reference(system) => system.strands()[index].v().to_vec(),
            Self::Batch { system, gpu, .. } => current(system, gpu).v(index),
        }
    }

    /// Sets strand `index`'s strains and rates (lengths must match its
    /// element count; the batch engine rounds them to f32).
    pub fn set_state(&mut self, index: usize, q: &[DVec3], v: &[DVec3]) {
        match self {
            Self::Reference(system) => system.strands_mut()[index].set_state(q, v),
            Self::Batch { system, gpu, .. } => {
                sync(system, gpu);
                system.set_state(index, q, v);
                if let Some(gpu) = gpu {
                    gpu.state_changed();
                }
            }
        }
    }

    /// Sets the strains strand `index` rests in, which the hair–hair
    /// model's rest density is built from ([`crate::Strand::rest_pose`]:
    /// its natural strains unless told; an imported sag-free strand rests
    /// in its groomed shape). Panics if out of range or of the wrong
    /// length.
    pub fn set_rest_pose(&mut self, index: usize, q: &[DVec3]) {
        match self {
            Self::Reference(system) => system.set_rest_pose(index, q),
            Self::Batch { system, gpu, .. } => {
                sync(system, gpu);
                system.set_rest_pose(index, q);
            }
        }
    }

    /// Strand `index`'s model. Panics if out of range.
    pub fn strand_model(&self, index: usize) -> &Arc<StrandModel> {
        match self {
            Self::Reference(system) => system.strands()[index].model(),
            Self::Batch { strands, .. } => &strands[index].0,
        }
    }

    /// Strand `index`'s root, head coordinates. Panics if out of range.
    pub fn root(&self, index: usize) -> &RootPose {
        match self {
            Self::Reference(system) => system.strands()[index].root(),
            Self::Batch { strands, .. } => &strands[index].1,
        }
    }

    /// Frames, points and velocities of strand `index` at the current head
    /// pose, reconstructed in f64 (for the batch engine, from its f32
    /// state).
    pub fn kinematics(&self, index: usize) -> (RigidMotion, Kinematics) {
        let motion = self.head().carry(self.root(index));
        let mut kin = Kinematics::default();
        reconstruct(
            self.strand_model(index),
            &self.q(index),
            &self.v(index),
            &motion,
            &mut kin,
        );
        (motion, kin)
    }

    /// Energies of the current state summed over strands. Every frame's
    /// work on the reference; on the batch engine each strand is rebuilt
    /// in f64 from its f32 state, which costs about a reference frame:
    /// call it for a report, not every displayed frame.
    pub fn energies(&self) -> Energies {
        match self {
            Self::Reference(system) => system.energies(),
            Self::Batch {
                system,
                strands,
                gpu,
            } => {
                let system = current(system, gpu);
                let gravity = system.settings().gravity_m_per_s2;
                let mut total = Energies::default();
                for (i, (model, root)) in strands.iter().enumerate() {
                    let mut strand = Strand::new(model.clone(), *root, Method::Exact);
                    strand.set_state(&system.q(i), &system.v(i));
                    total.accumulate(&strand.energies(&system.head().carry(root), gravity));
                }
                total
            }
        }
    }
}

/// The batch system as its state stands: on the GPU engine with the state
/// on the device, the copy [`GpuSide::current`] reads back.
fn current<'a>(system: &'a BatchSystem, gpu: &'a Option<GpuSide>) -> &'a BatchSystem {
    match gpu {
        Some(gpu) => gpu.current(system),
        None => system,
    }
}

/// Brings a GPU engine's state back into its batch system before anything
/// changes the system ([`GpuSide::sync`]).
fn sync(system: &mut BatchSystem, gpu: &mut Option<GpuSide>) {
    if let Some(gpu) = gpu {
        gpu.sync(system);
    }
}

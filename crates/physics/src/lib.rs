//! Super-Helix hair strands: the model of Bertails et al. 2006, its dense
//! integrator, the block-diagonal integrator of Mitsutake et al. (the seed
//! paper), an exact linear-time solve and an iterative one.
//!
//! A strand is a chain of N helical elements; its generalized coordinates
//! are each element's twist and two curvatures, q_Q = (τ, κ₁, κ₂), so it
//! cannot stretch and its curl is a physical parameter. `docs/physics.md`
//! explains the model, the step and the solvers, and lists the known
//! answers this crate's tests hold the formulas to.
//!
//! # One step
//!
//! [`HairSystem::step_frame`] runs, for every strand (in parallel), the
//! stages of [`step`]: **reconstruct** ([`step::reconstruct`]), **forces**
//! ([`step::forces`]), **mass** ([`step::mass`]), **solve** ([`step::solve`]: Dense,
//! Block-diagonal, Exact or Iterative) and **integrate**. Everything is f64
//! and O(N) per strand except the dense solve.
//!
//! # Many strands
//!
//! [`batch::BatchSystem`] steps Block-diagonal or Exact in f32 with SIMD
//! lanes across strands, in parallel over batches, matching the f64 path
//! within named tolerances (`tests/batch_parity.rs`). With the cargo
//! feature `gpu`, `gpu::GpuEngine` runs the batch engine's Exact and
//! Block-diagonal step as a wgpu compute kernel (`shaders/physics/engine.wgsl`,
//! its CPU twin `gpu::engine_twin`), and `gpu::GpuSystem` the Dense
//! kernel with a workgroup per strand (twins `gpu::twin`,
//! `gpu::dense_twin`); [`batch::step::dense`] is Dense's f32 arithmetic.
//!
//! This crate knows nothing of rendering, windows or file formats; its
//! parameter types derive serde so that callers can embed them in theirs.

#![warn(missing_docs)]

pub mod batch;
pub mod collision;
pub mod energy;
pub mod engine;
pub mod error;
pub mod fit;
pub mod frame_balance;
pub mod geometry;
pub mod gmres;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod guard;
pub mod hair_system;
pub mod model;
pub mod motion;
pub mod natural_shape;
pub mod params;
pub mod settings;
pub mod step;
pub mod strand;
pub mod volume;

pub use energy::Energies;
pub use engine::{Engine, EngineKind};
pub use error::ParamError;
pub use guard::{Guard, GuardAction, GuardCause, GuardEvent, GuardState, ResetMemory};
pub use hair_system::HairSystem;
pub use model::StrandModel;
pub use motion::{Bounce, HeadTrajectory, Oscillation, RigidMotion, RootPose};
pub use natural_shape::NaturalShape;
pub use params::{ElementLayout, StrandParams};
pub use settings::{Method, SimSettings, StepScheme};
pub use step::StageTimes;
pub use strand::Strand;
pub use volume::InteractionSettings;

//! The fast path: many strands stepped in f32, [`LANES`] = 8 at a time in
//! SIMD lanes on every build (one AVX register where the build enables AVX,
//! two SSE registers on baseline x86-64), in parallel over batches.
//!
//! # How it works
//!
//! [`BatchSystem`] holds the same strands as a [`crate::HairSystem`] (same
//! parameters, settings and head motion) but steps them with
//! Block-diagonal or Exact only, in f32, and lays them out for speed:
//!
//! - **Lanes across strands** ([`lanes`]): [`LANES`] = 8 strands of the
//!   same element count form a batch, and every number of the step is a [`Lanes`]
//!   (a `wide::f32x8`), so each arithmetic operation of the step serves the
//!   whole batch as one explicit SIMD instruction: one AVX register where
//!   the build enables AVX (the repository's `.cargo/config.toml` builds for
//!   the native CPU), two SSE registers on baseline x86-64. Nothing depends
//!   on the target for correctness. LLVM's auto-vectoriser is not relied on:
//!   on plain `[f32; 8]` arrays it gave up on the long inlined step
//!   (measured: no faster than 4 lanes).
//! - **Per-lane constants** ([`lane_model`]): each lane carries its own
//!   strand's lengths, stiffness, natural strains, friction, ρS and drag
//!   (a [`LaneModel`]), so strands that share only N and the quadrature
//!   (an imported groom's) fill a batch; strands added one at a time fill
//!   the last batch of their N before a new one opens (the packing of
//!   [`BatchSystem::add_group`]). Lanes stay independent: a strand's
//!   results are bit for bit the same alone or packed with seven others
//!   (`tests/batch_lanes.rs`). The imported Sintel groom (11,241 strands
//!   of 1 to 9 elements) fills 1,410 batches with 39 lanes of padding,
//!   where one strand per batch would pad 78,687 lanes (the groom study,
//!   `helixhair bench --study groom`, times its frame).
//! - **Structure of arrays** ([`layout`]): a batch's state is N strain and
//!   N rate triples of lanes, contiguous; a step allocates nothing.
//! - **Fused stages**: one root-to-tip sweep ([`forward`]: reconstruct,
//!   forces and the element's own mass sums, with time derivatives carried
//!   as angular velocity and acceleration instead of matrix jets,
//!   [`geometry`]; products with a sample's Jacobian taken in the element's
//!   frame), then one tip-to-root sweep that forms each element's
//!   block from suffix sums ([`suffix`]) and solves it
//!   ([`step::block_diagonal`]), or runs the O(N) elimination ([`step::exact`]) and a
//!   third, root-to-tip sweep. Per-element data is written in place: at
//!   8 lanes an element's record is about 1.9 KB, and copying it was 15% of
//!   a step.
//! - **Velocity-implicit Exact** ([`step::implicit`], the default
//!   `StepScheme::VelocityImplicit`, as in the f64 reference): the
//!   derivative G = −∂Q/∂q̇ of the centrifugal, Coriolis and root-rotation
//!   forces joins the step matrix. Sweep 3 gives Δv₀ = P⁻¹ rhs without
//!   integrating; GMRES (at most `corrections` iterations, stopping at a
//!   residual of 1e-5 of |rhs|) then corrects it, lane by lane: every dot
//!   product, Givens rotation and stopping test is a [`Lanes`] value, so
//!   each strand runs its own GMRES inside the batch's SIMD arithmetic.
//!   Each iteration re-solves with the elimination sweep 2 stored
//!   ([`step::exact::solve_again`]: two light sweeps) and forms G z by
//!   polarisation, two kinematic sweeps with rates q̇ ± cz
//!   ([`velocity_terms`]). `StepScheme::VelocityExplicit` (and 0
//!   corrections) runs the explicit step bit for bit as before.
//! - **Velocity-implicit Block-diagonal** ([`step::block_implicit`]):
//!   Block-diagonal with its own Lagrangian's velocity terms
//!   ([`block_terms`], the correction F_true − F_bd from one sweep with the
//!   root held still), its own P = s M_bd + D and G_bd, and the same
//!   GMRES; velocity-explicit, it takes the whole system's terms as
//!   Bertails 2006 did.
//! - **Threads**: rayon over batches; a batch's arithmetic does not depend
//!   on which thread runs it, so serial and parallel runs are bit-identical.
//! - **Collide** ([`contact`], optional): the head's collider
//!   ([`BatchSystem::set_collider`]) pushes on every quadrature sample
//!   with the reference's implicit law: the push joins the sample's force,
//!   and its stiffness and damping enter the step matrix as a point inertia
//!   at the sample (Exact's elimination and Block-diagonal's blocks alike);
//!   the module derives where. Without a collider the sweep has no such
//!   stage at all.
//! - **Hair–hair model** ([`volume`], [`volume::pull`], when
//!   `SimSettings::interaction` is on): once per frame, before the
//!   steps, an f32 sweep per batch gathers every lane's quadrature samples
//!   (position, velocity, mass), the shared f64 code of
//!   [`crate::volume::field`] splats them on the head-fixed grid and reads
//!   back each sample's grid velocity and pressure push, and each batch
//!   gets per sample the known force k = ρS(μu_rel + a) (u_rel relative
//!   to the head). The step takes the friction as it takes air drag: the
//!   force k − μρS (ṙ − c) at each sample (c the root's rigid velocity there)
//!   and hμ in the mass scale, through the step hook
//!   ([`forward::SampleHook::sample_force`]); without the model the
//!   sample loop compiles as before. The guard's measure sums the pull's
//!   force and power with the other external forces ([`measure`]).
//! - **Guard** ([`guard`], on by default): after each frame, each strand is
//!   measured and checked as [`crate::guard`] checks (finite, true speed,
//!   energy against the root's work); one that fails is stepped again from
//!   the frame's start with the reference's policy (`retry.rs`: Exact if it
//!   was Block-diagonal, then twice the substeps, and twice again; the whole
//!   batch re-stepped, the result kept for the failing lanes), and if no
//!   retry holds it is reset to its rest pose (its natural shape unless
//!   told, [`BatchSystem::set_rest_pose`]) at rest; each event is reported
//!   with what failed and by how much ([`BatchSystem::last_guard_events`]),
//!   and a strand that keeps failing is pinned
//!   ([`crate::guard::ResetMemory`]).
//! - **Offload** (`offload.rs`): [`BatchSystem::step_frame_offloaded`]
//!   hands a frame's substeps and the guard's measure to a
//!   [`SubstepOffload`] (the GPU engine), judges the frame from the
//!   measures it hands back with the guard above, and reads the state back
//!   only to recover a strand ([`BatchSystem::state_is_elsewhere`]).
//!
//! The quadrature is the settings' (`SimSettings::quadrature_points`), so a
//! comparison with the f64 reference is like with like. External forces
//! (`Strand::set_external_forces`) are not supported here yet.
//!
//! [`step::dense`] holds an f32 Dense step (the whole 3N×3N step matrix,
//! Cholesky-factored) for one strand or a batch: the arithmetic of the GPU
//! Dense kernel's CPU twin; [`BatchSystem`] itself steps Block-diagonal and
//! Exact (Exact gives Dense's answer in O(N)).
//!
//! Accuracy: f32 against the f64 reference, pinned by
//! `tests/batch_parity.rs` (velocity-explicit) and
//! `tests/batch_stable_step.rs` (velocity-implicit) with named tolerances; contact by
//! `tests/batch_contact.rs` (a drape over a sphere within 1 mm of the f64
//! drape), the guard by `tests/batch_guard.rs` and the hair–hair model by
//! `tests/batch_volume.rs` (its known answers, and agreement with the
//! reference running it).

pub mod block_kinetic;
pub mod block_terms;
pub mod contact;
pub mod forward;
pub mod geometry;
mod group;
pub mod guard;
pub mod lane_model;
pub mod lanes;
pub mod layout;
pub mod measure;
mod offload;
mod retry;
pub mod step;
pub mod suffix;
mod system;
pub mod vec;
pub mod velocity_terms;
pub mod volume;

pub use lane_model::{Constants, LaneModel};
pub use lanes::{LANES, Lanes, Real};
pub use offload::{FlatState, SubstepOffload};
pub use system::{BatchSystem, LaneUse, MemoryUse};

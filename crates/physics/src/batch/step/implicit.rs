//! The velocity-implicit Exact step of a batch: (P + hG) Δv = rhs solved by
//! GMRES, lane by lane, right-preconditioned by the O(N) elimination the
//! step already made (the f64 reference's scheme, [`crate::step`]).
//!
//! # How it works
//!
//! P = s M + D is the matrix [`super::exact`] eliminates; G = −∂Q/∂q̇ holds
//! the derivatives of the centrifugal, Coriolis and root-rotation forces
//! ([`crate::batch::velocity_terms`]). The step:
//!
//! 1. sweeps 1 and 2 of Exact ([`eliminate`]): the elimination of P, kept
//!    per element (W̃, S̃⁻¹), and Σ|rhs|² per lane;
//! 2. sweep 3 ([`back_substitute`]) gives Δv₀ = P⁻¹ rhs, kept, not
//!    integrated;
//! 3. GMRES ([`crate::gmres`], the one both engines run) corrects Δv₀:
//!    each iteration solves z_j = P⁻¹ v_j again with the stored
//!    elimination ([`solve_again`]: the right-hand side folded tip to
//!    root, then back-substituted, two light sweeps; P is not formed
//!    again) and forms G z_j by polarisation, two kinematic sweeps. Every
//!    dot product, rotation and stopping test is per lane: each lane is
//!    its own strand and its own GMRES;
//! 4. Δv = Δv₀ + Σ y_j z_j, and integrate.
//!
//! The vectors live in [`Krylov`], one per worker thread, sized once:
//! stepping allocates nothing. `StepScheme::VelocityExplicit` does not come
//! here at all: [`super::exact::step_exact_with`] keeps its arithmetic bit
//! for bit (the GPU kernels' CPU twins run it).

use super::exact::{Elimination, back_substitute, eliminate, solve_again};
use crate::batch::block_terms::BlockElement;
use crate::batch::forward::SampleHook;
use crate::batch::geometry::Coefficients;
use crate::batch::lane_model::Constants;
use crate::batch::lanes::Real;
use crate::batch::layout::{ElementData, RootMotion, StepEnv};
use crate::batch::suffix::integrate;
use crate::batch::vec::{M3, V3};
use crate::batch::velocity_terms::{OwnProduct, coefficients_of, velocity_product};
use crate::gmres;

/// The velocity-implicit step's buffers for one batch of N elements, reused
/// from step to step: GMRES's vectors, Δv, and the per-element partial sums
/// of the product G z.
#[derive(Clone, Debug)]
pub struct Krylov<T> {
    pub(super) gmres: gmres::Krylov<T>,
    pub(super) delta_v: Vec<V3<T>>,
    pub(super) own: Vec<OwnProduct<T>>,
    /// The helix coefficients of the step's q ([`coefficients_of`]).
    pub(super) coefficients: Vec<Coefficients<T>>,
    /// Block-diagonal's own buffers, sized on its first step
    /// ([`super::block_implicit`]).
    pub(super) block: BlockBuffers<T>,
}

/// What Block-diagonal's velocity-implicit step needs besides GMRES's
/// vectors: its own velocity terms' sweep, their correction at the step's
/// rates and at shifted ones, the inverse of each diagonal block, and
/// each block's share of the head's contact, C_bd ([`super::block_contact`]).
#[derive(Clone, Debug)]
pub struct BlockBuffers<T> {
    pub(super) elements: Vec<BlockElement<T>>,
    pub(super) correction: Vec<V3<T>>,
    pub(super) shifted_rates: Vec<V3<T>>,
    pub(super) plus: Vec<V3<T>>,
    pub(super) minus: Vec<V3<T>>,
    pub(super) inverse: Vec<M3<T>>,
    pub(super) contact_block: Vec<M3<T>>,
}

impl<T: Real> Krylov<T> {
    /// Room for `iterations` (at most 8) GMRES iterations on `n` elements.
    pub fn new(n: usize, iterations: usize) -> Self {
        Self {
            gmres: gmres::Krylov::new(n, iterations),
            delta_v: vec![V3::zero(); n],
            own: vec![OwnProduct::zero(); n],
            coefficients: Vec::new(),
            block: BlockBuffers::default(),
        }
    }

    /// Iterations these buffers hold.
    pub fn iterations(&self) -> usize {
        self.gmres.iterations()
    }
}

/// One velocity-implicit Exact step of every lane's strand, with at most
/// `krylov.iterations()` GMRES iterations (0: the explicit answer, though
/// not bit for bit [`super::exact::step_exact_with`]'s, which integrates
/// inside sweep 3). Moments about each element's own points (`LOCAL`).
/// Returns the iterations the batch ran.
#[expect(
    clippy::too_many_arguments,
    reason = "the step's buffers, as in `step_exact_with`"
)]
#[inline(always)]
pub fn step_exact_implicit<T: Real, H: SampleHook<T>>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    scratch: &mut [ElementData<T>],
    elimination: &mut [Elimination<T>],
    krylov: &mut Krylov<T>,
    hook: &H,
) -> usize {
    // The coefficients depend on q alone: evaluated once, they serve
    // sweep 1 and both sweeps of every product GMRES takes.
    coefficients_of(model, q, &mut krylov.coefficients);
    let known = Some(krylov.coefficients.as_slice());
    let rhs_squared =
        eliminate::<T, true, H>(model, env, root, q, v, scratch, elimination, hook, known);
    let Krylov {
        gmres,
        delta_v,
        own,
        coefficients,
        block: _,
    } = krylov;
    back_substitute::<T, true>(scratch, elimination, |e, dv| delta_v[e] = dv);
    let iterations = gmres::correct(
        gmres.iterations(),
        T::splat_f64(env.h_secs),
        rhs_squared.sqrt(),
        delta_v,
        gmres,
        |b, z| solve_again::<T, true>(scratch, elimination, b, z),
        |x, out| velocity_product(model, root, q, v, scratch, coefficients, x, own, out),
    );
    for ((q, v), dv) in q.iter_mut().zip(v.iter_mut()).zip(delta_v.iter()) {
        integrate(env.h_secs, q, v, *dv);
    }
    iterations
}

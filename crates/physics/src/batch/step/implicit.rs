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
//! 3. GMRES on A P⁻¹ with A = P + hG from Δv₀: the residual is
//!    r₀ = −h G Δv₀; each iteration solves z_j = P⁻¹ v_j again with the
//!    stored elimination ([`solve_again`]: the right-hand side folded tip
//!    to root, then back-substituted, two light sweeps; P is not formed
//!    again), and forms A z_j = v_j + h G z_j (P z_j = v_j exactly), one
//!    polarised product of two kinematic sweeps. Arnoldi, Givens rotations
//!    and the small triangular solve run on [`Real`] values, so every dot
//!    product, rotation and stopping test is per lane: each lane is its
//!    own strand and its own GMRES. A lane stops once its residual is
//!    below [`GMRES_TOLERANCE`] of its |rhs|; its later columns are
//!    made inert (an identity column and a zero right-hand side, so its
//!    later coefficients are zero), and the batch stops when every lane
//!    has, or after `corrections` iterations;
//! 4. Δv = Δv₀ + Σ y_j z_j, and integrate.
//!
//! The Krylov vectors live in [`Krylov`], one per worker thread, sized once:
//! stepping allocates nothing. `StepScheme::VelocityExplicit` does not come
//! here at all: [`super::exact::step_exact_with`] keeps its arithmetic bit
//! for bit (the GPU kernels' CPU twins run it).

use super::exact::{Elimination, back_substitute, eliminate, solve_again};
use crate::batch::forward::EndPointForce;
use crate::batch::geometry::Coefficients;
use crate::batch::lane_model::Constants;
use crate::batch::lanes::Real;
use crate::batch::layout::{ElementData, RootMotion, StepEnv};
use crate::batch::suffix::integrate;
use crate::batch::vec::V3;
use crate::batch::velocity_terms::{OwnProduct, coefficients_of, velocity_product};
use crate::settings::MAX_VELOCITY_CORRECTIONS;
use crate::step::GMRES_TOLERANCE;

/// Most GMRES iterations a step runs.
const MAX_GMRES: usize = MAX_VELOCITY_CORRECTIONS as usize;

/// GMRES's buffers for one batch of N elements, reused from step to step:
/// the Arnoldi basis v₀…v_k, the preconditioned directions z_j = P⁻¹ v_j,
/// Δv, the product G z and its per-element partial sums.
#[derive(Clone, Debug)]
pub struct Krylov<T> {
    basis: Vec<Vec<V3<T>>>,
    directions: Vec<Vec<V3<T>>>,
    delta_v: Vec<V3<T>>,
    product: Vec<V3<T>>,
    own: Vec<OwnProduct<T>>,
    /// The helix coefficients of the step's q ([`coefficients_of`]).
    coefficients: Vec<Coefficients<T>>,
}

impl<T: Real> Krylov<T> {
    /// Room for `iterations` (at most 8) GMRES iterations on `n` elements.
    pub fn new(n: usize, iterations: usize) -> Self {
        let k = iterations.min(MAX_GMRES);
        Self {
            basis: vec![vec![V3::zero(); n]; k + 1],
            directions: vec![vec![V3::zero(); n]; k],
            delta_v: vec![V3::zero(); n],
            product: vec![V3::zero(); n],
            own: vec![OwnProduct::zero(); n],
            coefficients: Vec::new(),
        }
    }

    /// Iterations these buffers hold.
    pub fn iterations(&self) -> usize {
        self.directions.len()
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
pub fn step_exact_implicit<T: Real, H: EndPointForce<T>>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    scratch: &mut [ElementData<T>],
    elimination: &mut [Elimination<T>],
    krylov: &mut Krylov<T>,
    end_force: &mut H,
) -> usize {
    // The coefficients depend on q alone: evaluated once, they serve
    // sweep 1 and both sweeps of every product GMRES takes.
    coefficients_of(model, q, &mut krylov.coefficients);
    let known = Some(krylov.coefficients.as_slice());
    let rhs_squared = eliminate::<T, true, H>(
        model,
        env,
        root,
        q,
        v,
        scratch,
        elimination,
        end_force,
        known,
    );
    let delta_v = &mut krylov.delta_v;
    back_substitute::<T, true>(scratch, elimination, |e, dv| delta_v[e] = dv);
    let iterations = gmres(
        model,
        env,
        root,
        q,
        v,
        scratch,
        elimination,
        rhs_squared.sqrt(),
        krylov,
    );
    for ((q, v), dv) in q.iter_mut().zip(v.iter_mut()).zip(&krylov.delta_v) {
        integrate(env.h_secs, q, v, *dv);
    }
    iterations
}

/// Per lane, Σ a_i · b_i.
#[inline(always)]
fn dot<T: Real>(a: &[V3<T>], b: &[V3<T>]) -> T {
    a.iter()
        .zip(b)
        .fold(T::splat(0.0), |s, (x, y)| s + x.dot(*y))
}

/// Per lane, `if_set` where `mask` is 1 and `otherwise` where it is 0.
#[inline(always)]
fn pick<T: Real>(mask: T, if_set: T, otherwise: T) -> T {
    mask.select_greater(T::splat(0.5), if_set, otherwise)
}

/// GMRES from Δv₀ = `krylov.delta_v`, which it corrects in place; returns
/// the iterations run (the most any lane needed).
#[expect(
    clippy::too_many_arguments,
    reason = "the step's state and buffers, named as the step names them"
)]
#[inline(always)]
fn gmres<T: Real>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    scratch: &[ElementData<T>],
    elimination: &mut [Elimination<T>],
    rhs_norm: T,
    krylov: &mut Krylov<T>,
) -> usize {
    let k_max = krylov.iterations();
    if k_max == 0 {
        return 0;
    }
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    let h = T::splat(env.h_secs);
    let tol = rhs_norm * T::splat(GMRES_TOLERANCE as f32);
    let Krylov {
        basis,
        directions,
        delta_v,
        product,
        own,
        coefficients,
    } = krylov;
    velocity_product(
        model,
        root,
        q,
        v,
        scratch,
        coefficients,
        delta_v,
        own,
        product,
    );
    // r₀ = −h G Δv₀; a lane whose residual is already small (or NaN) is done.
    let beta = h * dot(product, product).sqrt();
    let mut active = beta.select_greater(tol, one, zero);
    if active.all_below(0.5) {
        return 0;
    }
    let scale = pick(active, -h / beta, zero);
    for (b, g) in basis[0].iter_mut().zip(product.iter()) {
        *b = g.scale(scale);
    }
    let mut hessenberg = [[zero; MAX_GMRES]; MAX_GMRES + 1];
    let mut rotations = [(one, zero); MAX_GMRES];
    let mut g = [zero; MAX_GMRES + 1];
    g[0] = pick(active, beta, zero);
    let mut used = 0;
    for j in 0..k_max {
        // z = P⁻¹ v_j; w = A z = v_j + h G z.
        solve_again::<T, true>(scratch, elimination, &basis[j], &mut directions[j]);
        velocity_product(
            model,
            root,
            q,
            v,
            scratch,
            coefficients,
            &directions[j],
            own,
            product,
        );
        let (done, rest) = basis.split_at_mut(j + 1);
        let w = &mut rest[0];
        for ((x, b), gz) in w.iter_mut().zip(&done[j]).zip(product.iter()) {
            *x = *b + gz.scale(h);
        }
        for (i, b) in done.iter().enumerate() {
            let hij = dot(w, b);
            hessenberg[i][j] = hij;
            for (x, y) in w.iter_mut().zip(b) {
                *x = *x - y.scale(hij);
            }
        }
        let w_norm = dot(w, w).sqrt();
        hessenberg[j + 1][j] = w_norm;
        for (i, (c, s)) in rotations.iter().take(j).enumerate() {
            let (a, b) = (hessenberg[i][j], hessenberg[i + 1][j]);
            hessenberg[i][j] = *c * a + *s * b;
            hessenberg[i + 1][j] = *c * b - *s * a;
        }
        let (a, b) = (hessenberg[j][j], hessenberg[j + 1][j]);
        let r = (a * a + b * b).sqrt();
        let nonzero = r.select_greater(zero, one, zero);
        // A lane that stopped earlier gets an inert column: identity, no
        // rotation, zero right-hand side, so its y_j is zero.
        let live = active * nonzero;
        let c = pick(live, a / r, one);
        let s = pick(live, b / r, zero);
        rotations[j] = (c, s);
        for row in hessenberg.iter_mut().take(j) {
            row[j] = pick(active, row[j], zero);
        }
        hessenberg[j][j] = pick(live, r, one);
        hessenberg[j + 1][j] = zero;
        g[j + 1] = pick(active, -s * g[j], zero);
        g[j] = pick(active, c * g[j], zero);
        used = j + 1;
        let residual = g[j + 1].max(-g[j + 1]);
        active = active
            * residual.select_greater(tol, one, zero)
            * w_norm.select_greater(zero, one, zero);
        if active.all_below(0.5) {
            break;
        }
        let inverse = pick(active, one / w_norm, zero);
        for x in w.iter_mut() {
            *x = x.scale(inverse);
        }
    }
    // Back substitution for y, then Δv = Δv₀ + Σ y_j z_j (lanes whose y is
    // not finite keep Δv₀).
    let mut y = [zero; MAX_GMRES];
    let mut finite = one;
    for i in (0..used).rev() {
        let mut sum = g[i];
        for l in i + 1..used {
            sum -= hessenberg[i][l] * y[l];
        }
        y[i] = sum / hessenberg[i][i];
        // y · 0 is 0 for a finite y and NaN otherwise.
        finite = finite * (y[i] * zero).select_below(0.5, one, zero);
    }
    for (y_j, z) in y[..used].iter().zip(directions.iter()) {
        let y_j = pick(finite, *y_j, zero);
        for (dv, zi) in delta_v.iter_mut().zip(z) {
            *dv += zi.scale(y_j);
        }
    }
    used
}

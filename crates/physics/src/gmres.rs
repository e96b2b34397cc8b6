//! The velocity-implicit step's GMRES, written once for both engines: the
//! f64 reference ([`crate::step`], one strand, `T = f64`) and the batch
//! engine ([`crate::batch::step::implicit`], eight strands in SIMD lanes,
//! `T = Lanes`).
//!
//! # What it solves
//!
//! The velocity-implicit step solves (P + hG) Δv = rhs, with P = s M + D
//! (+ contact) the matrix the step's solver eliminates in O(N) and
//! G = −∂Q/∂q̇ the derivative of the centrifugal, Coriolis and
//! root-rotation forces, known only through its products G x
//! ([`crate::step::velocity_terms`], [`crate::batch::velocity_terms`]).
//! [`correct`] starts from Δv₀ = P⁻¹ rhs (the explicit answer the caller
//! already has) and corrects it in place.
//!
//! # How
//!
//! GMRES, right-preconditioned by P: with Δv₀ = P⁻¹ rhs the residual is
//! r₀ = −h G Δv₀. Arnoldi runs on A P⁻¹ with A = P + hG; since P z = v
//! exactly, A z = v + h G z needs one solve with P and one product with G
//! per iteration and no product with P. Givens rotations keep the small
//! least-squares problem triangular, so the residual norm is known at
//! every iteration; the loop stops once it is below [`GMRES_TOLERANCE`]
//! of |rhs|, or after the iterations asked for.
//!
//! Why GMRES and not plain Richardson (Δv ← P⁻¹(rhs − h G Δv)): both cost
//! one product and one solve per iteration, but Richardson diverges where
//! the spectral radius of P⁻¹hG passes 1, which long coiled strands reach
//! (measured: a 0.66 m curl kept gaining energy with 8 Richardson
//! corrections, which Dense's exact solve never did); GMRES minimises the
//! residual over the Krylov space instead.
//!
//! # Lanes
//!
//! Every dot product, rotation and stopping test is a [`Real`] value, so
//! each lane of a batch runs its own GMRES inside the batch's SIMD
//! arithmetic. A lane that has converged (or whose residual is NaN) gets
//! inert columns from then on (an identity column and a zero right-hand
//! side, so its later coefficients are zero); the loop ends when every
//! lane has. A lane whose coefficients are not finite keeps Δv₀. With
//! `T = f64` (one lane) this is textbook GMRES.

use crate::batch::lanes::Real;
use crate::batch::vec::V3;
use crate::settings::MAX_VELOCITY_CORRECTIONS;

/// GMRES stops once its residual is below this fraction of |rhs|.
///
/// Measured on the 0.66 m curl of `tests/stable_step.rs` and the shake of
/// `examples/shake_probe.rs`: at 1e-2 the curl still gained energy on a
/// frame (which the guard caught), at 1e-3 and below never. At 1e-3 the
/// curly example's Exact step drifted 2.9e-5 L from Dense's direct solve
/// over 2 s of shake; at 1e-5 it stays within 1.1e-7 L
/// (`tests/sim_cli.rs`), the f64 reference then being Dense's answer to
/// the precision a test can see. Each tenfold tightening costs about one
/// more iteration (0.7 of an explicit step) where GMRES runs long; on the
/// Sintel groom's frame the two tolerances measured within run-to-run
/// noise (22.3 against 21.0 ms on two threads), since most lanes converge
/// in one or two iterations either way.
pub const GMRES_TOLERANCE: f64 = 1e-5;

/// Most GMRES iterations a step runs: the range of
/// [`crate::StepScheme::VelocityImplicit`]'s `corrections`.
pub const MAX_GMRES: usize = MAX_VELOCITY_CORRECTIONS as usize;

/// GMRES's vectors for N elements, kept from step to step so that stepping
/// allocates nothing: the Arnoldi basis v₀…v_k, the preconditioned
/// directions z_j = P⁻¹ v_j and the product G x.
#[derive(Clone, Debug, Default)]
pub struct Krylov<T> {
    basis: Vec<Vec<V3<T>>>,
    directions: Vec<Vec<V3<T>>>,
    product: Vec<V3<T>>,
}

impl<T: Real> Krylov<T> {
    /// Room for `iterations` (at most [`MAX_GMRES`]) iterations on `n`
    /// elements.
    pub fn new(n: usize, iterations: usize) -> Self {
        let mut krylov = Self {
            basis: Vec::new(),
            directions: Vec::new(),
            product: Vec::new(),
        };
        krylov.reserve(iterations, n);
        krylov
    }

    /// Grows the buffers to `iterations` (at most [`MAX_GMRES`]) iterations
    /// on `n` elements; never shrinks the iteration count.
    pub fn reserve(&mut self, iterations: usize, n: usize) {
        let k = iterations.min(MAX_GMRES);
        for (vectors, count) in [(&mut self.basis, k + 1), (&mut self.directions, k)] {
            if vectors.len() < count {
                vectors.resize(count, Vec::new());
            }
            for x in vectors.iter_mut() {
                x.resize(n, V3::zero());
            }
        }
        self.product.resize(n, V3::zero());
    }

    /// Iterations these buffers hold.
    pub fn iterations(&self) -> usize {
        self.directions.len()
    }
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

/// Corrects `delta_v` (Δv₀ = P⁻¹ rhs on entry) towards the solution of
/// (P + hG) Δv = rhs with at most `iterations` GMRES iterations (module
/// docs); returns the iterations run (the most any lane needed).
///
/// - `h`: the step, seconds; `rhs_norm`: |rhs| per lane.
/// - `solve(v, z)`: z = P⁻¹ v with the caller's elimination.
/// - `product(x, out)`: out = G x.
#[inline(always)]
pub fn correct<T: Real>(
    iterations: usize,
    h: T,
    rhs_norm: T,
    delta_v: &mut [V3<T>],
    krylov: &mut Krylov<T>,
    mut solve: impl FnMut(&[V3<T>], &mut [V3<T>]),
    mut product: impl FnMut(&[V3<T>], &mut [V3<T>]),
) -> usize {
    let k_max = iterations.min(MAX_GMRES);
    if k_max == 0 {
        return 0;
    }
    krylov.reserve(k_max, delta_v.len());
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    let tol = rhs_norm * T::splat_f64(GMRES_TOLERANCE);
    let Krylov {
        basis,
        directions,
        product: g_x,
    } = krylov;
    product(delta_v, g_x);
    // r₀ = −h G Δv₀; a lane whose residual is already small (or NaN) is done.
    let beta = h * dot(g_x, g_x).sqrt();
    let mut active = beta.select_greater(tol, one, zero);
    if active.all_below(0.5) {
        return 0;
    }
    let scale = pick(active, -h / beta, zero);
    for (b, g) in basis[0].iter_mut().zip(g_x.iter()) {
        *b = g.scale(scale);
    }
    let mut hessenberg = [[zero; MAX_GMRES]; MAX_GMRES + 1];
    let mut rotations = [(one, zero); MAX_GMRES];
    let mut g = [zero; MAX_GMRES + 1];
    g[0] = pick(active, beta, zero);
    let mut used = 0;
    for j in 0..k_max {
        // z = P⁻¹ v_j; w = A z = v_j + h G z.
        solve(&basis[j], &mut directions[j]);
        product(&directions[j], g_x);
        let (done, rest) = basis.split_at_mut(j + 1);
        let w = &mut rest[0];
        for ((x, b), gz) in w.iter_mut().zip(&done[j]).zip(g_x.iter()) {
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
        // The earlier rotations on the new column, then a new one.
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

//! Least-squares refinement: Levenberg–Marquardt on the polyline's points.
//!
//! Unknowns: the strains q (3N), a tilt of the root frame (2: rotations
//! about n₁ and n₂; the root point is the polyline's first point), the
//! element length ℓ (all elements equal, so the strand's length is Nℓ), and
//! for every interior polyline point P_i its place on the strand,
//! u_i ∈ [0, N] in elements (arc length s_i = u_i ℓ; the last point is the
//! tip, u_M = N). The residuals are r_i = x(s_i) − (P_i − P₀), so the cost
//! ½Σ|r_i|² is the squared distance of each point to its foot on the
//! strand: the fit does not assume the polyline's points are spaced by arc
//! length (a polyline's chords are shorter than the curve they sample).
//!
//! The Jacobian is analytic ([`super::curve`]):
//!
//! - ∂r_i/∂q_Q = R_e ∂h/∂k for the point's own element e, A_Q − \[x_i\]× B_Q
//!   for every earlier element Q, zero beyond;
//! - ∂r_i/∂(tilt about n_j) = n_j × x_i (the whole strand turns about the
//!   root);
//! - ∂r_i/∂ℓ = (x_i + Σ_Q ∂x_i/∂q_Q q_Q)/ℓ, from the scaling law
//!   x(λℓ, q) = λ x(ℓ, λq) of a chain of helices;
//! - ∂r_i/∂u_i = ℓ n₀(s_i).
//!
//! Each iteration solves (JᵀJ + λ diag JᵀJ) δ = −Jᵀr (Marquardt's scaling
//! makes the mixed units harmless), accepts δ if the cost falls (λ ← λ/3)
//! and otherwise retries with λ ← 4λ. On a curve that a chain of N helices
//! reproduces exactly the residual goes to zero and the iteration converges
//! quadratically, to round-off. Twist is unobservable in a straight element
//! (its column of J vanishes): the damping keeps it at its starting value
//! there.
//!
//! Gauge. Rolling every material frame by the same angle α about its
//! tangent and turning every (κ₁, κ₂) by −α leaves the centreline unchanged,
//! so the root's roll is not fitted: it is fixed afterwards so that n₁ is
//! the caller's reference direction made orthogonal to n₀
//! ([`fix_roll`]).

use glam::{DMat3, DVec3};
use nalgebra::{DMatrix, DVector};

use super::curve::UniformHelixChain;
use crate::geometry::helix::{rotation, skew};

/// Most Levenberg–Marquardt iterations: exact fits converge in 5 to 15;
/// a curve the chain cannot follow stops earlier, on the decrease test.
const MAX_ITERATIONS: usize = 200;
/// Retries with a larger λ before an iteration gives up (λ grows 4¹⁰ ≈ 1e6).
const MAX_RETRIES: usize = 10;
/// Stop when an accepted step lowers the cost by less than this fraction:
/// the deviations then change by under 1e-5 of themselves, far below any
/// tolerance an import uses.
const RELATIVE_DECREASE_STOP: f64 = 1e-10;
/// With a target: an iteration lowering the cost by less than this
/// fraction is slow progress...
const STALL_DECREASE: f64 = 1e-3;
/// ...and a worst deviation this many times the target is far: stop.
const STALL_FAR: f64 = 30.0;
/// Stop when the RMS deviation falls below this fraction of the length:
/// round-off of positions summed along the strand.
const EXACT_RMS_OVER_LENGTH: f64 = 1e-14;
/// Floor of the Marquardt scaling, relative to JᵀJ's largest diagonal
/// entry: keeps unobservable directions (twist of a straight element)
/// damped instead of singular.
const DIAGONAL_FLOOR: f64 = 1e-12;

/// A refined fit: the chain and where each polyline point lies on it.
#[derive(Clone, Debug, PartialEq)]
pub struct Refined {
    /// The fitted strand.
    pub chain: UniformHelixChain,
    /// Arc length (metres) of each polyline point's foot on the strand.
    pub arc_lengths_m: Vec<f64>,
    /// Distance from each polyline point to its foot, metres.
    pub deviations_m: Vec<f64>,
    /// Iterations taken.
    pub iterations: usize,
}

/// Refines `chain` (root at `points_m[0]`) to the polyline, starting the
/// points' places at `arc_lengths_m` (e.g. chord lengths scaled to the
/// chain's length). Stops early once every point is within `good_enough_m`
/// of the strand (0 refines to convergence).
pub fn refine(
    points_m: &[DVec3],
    mut chain: UniformHelixChain,
    arc_lengths_m: &[f64],
    good_enough_m: f64,
) -> Refined {
    let n = chain.elements();
    let m = points_m.len() - 1;
    let targets: Vec<DVec3> = points_m[1..].iter().map(|p| *p - points_m[0]).collect();
    let l0 = chain.element_length_m;
    let mut u: Vec<f64> = arc_lengths_m[1..]
        .iter()
        .map(|s| (s / l0).clamp(0.0, n as f64))
        .collect();
    u[m - 1] = n as f64;
    let mut cost = cost_of(&chain, &u, &targets);
    let mut lambda = 1e-3;
    let mut iterations = 0;
    let exact = 0.5 * m as f64 * (EXACT_RMS_OVER_LENGTH * l0 * n as f64).powi(2);
    while iterations < MAX_ITERATIONS && cost > exact {
        iterations += 1;
        let (jac, res) = jacobian(&chain, &u, &targets);
        let jt = jac.transpose();
        let a = &jt * &jac;
        let g = &jt * &res;
        let floor = DIAGONAL_FLOOR * a.diagonal().max();
        let mut accepted = None;
        for _ in 0..MAX_RETRIES {
            let mut damped = a.clone();
            for i in 0..damped.nrows() {
                damped[(i, i)] += lambda * a[(i, i)].max(floor);
            }
            let Some(delta) = damped.cholesky().map(|c| c.solve(&(-&g))) else {
                lambda *= 4.0;
                continue;
            };
            if let Some((trial, trial_u)) = apply(&chain, &u, &delta) {
                let trial_cost = cost_of(&trial, &trial_u, &targets);
                if trial_cost < cost {
                    accepted = Some((trial, trial_u, trial_cost));
                    break;
                }
            }
            lambda *= 4.0;
        }
        let Some((trial, trial_u, trial_cost)) = accepted else {
            break;
        };
        let decrease = cost - trial_cost;
        chain = trial;
        u = trial_u;
        cost = trial_cost;
        lambda = (lambda / 3.0).max(1e-15);
        if decrease <= RELATIVE_DECREASE_STOP * (cost + decrease) {
            break;
        }
        if good_enough_m > 0.0 {
            // Done once close enough; given up once progress is slow while
            // still far (this N will not meet the tolerance: try the next).
            let worst = worst_deviation(&chain, &u, &targets);
            if worst <= good_enough_m
                || (decrease <= STALL_DECREASE * (cost + decrease)
                    && worst > STALL_FAR * good_enough_m)
            {
                break;
            }
        }
    }
    let sweep = chain.sweep_with(false);
    let l = chain.element_length_m;
    let mut arc = vec![0.0];
    let mut deviations = vec![0.0];
    for (ui, target) in u.iter().zip(&targets) {
        let s = ui * l;
        arc.push(s);
        deviations.push((chain.point_with(&sweep, s, false).position_m - *target).length());
    }
    Refined {
        chain,
        arc_lengths_m: arc,
        deviations_m: deviations,
        iterations,
    }
}

fn worst_deviation(chain: &UniformHelixChain, u: &[f64], targets: &[DVec3]) -> f64 {
    let sweep = chain.sweep_with(false);
    let l = chain.element_length_m;
    u.iter()
        .zip(targets)
        .map(|(ui, t)| (chain.point_with(&sweep, ui * l, false).position_m - *t).length())
        .fold(0.0, f64::max)
}

fn cost_of(chain: &UniformHelixChain, u: &[f64], targets: &[DVec3]) -> f64 {
    let sweep = chain.sweep_with(false);
    let l = chain.element_length_m;
    u.iter()
        .zip(targets)
        .map(|(ui, t)| {
            0.5 * (chain.point_with(&sweep, ui * l, false).position_m - *t).length_squared()
        })
        .sum()
}

/// Columns: q (3N), tilt (2), ℓ (1), u_1..u_{M−1}.
fn jacobian(
    chain: &UniformHelixChain,
    u: &[f64],
    targets: &[DVec3],
) -> (DMatrix<f64>, DVector<f64>) {
    let n = chain.elements();
    let m = targets.len();
    let cols = 3 * n + 3 + (m - 1);
    let mut jac = DMatrix::zeros(3 * m, cols);
    let mut res = DVector::zeros(3 * m);
    let sweep = chain.sweep();
    let l = chain.element_length_m;
    let (n1, n2) = (chain.root_frame.col(1), chain.root_frame.col(2));
    for (i, (ui, target)) in u.iter().zip(targets).enumerate() {
        let p = chain.point(&sweep, ui * l);
        let x = p.position_m;
        let row = 3 * i;
        put_vec(&mut res, row, x - *target);
        let mut j_dot_q = DVec3::ZERO;
        for e in 0..p.element {
            let block = sweep.a[e] - skew(x) * sweep.b[e];
            put_block(&mut jac, row, 3 * e, &block);
            j_dot_q += block * chain.strains_per_m[e];
        }
        put_block(&mut jac, row, 3 * p.element, &p.own_jacobian);
        j_dot_q += p.own_jacobian * chain.strains_per_m[p.element];
        put_col(&mut jac, row, 3 * n, n1.cross(x));
        put_col(&mut jac, row, 3 * n + 1, n2.cross(x));
        put_col(&mut jac, row, 3 * n + 2, (x + j_dot_q) / l);
        if i + 1 < m {
            put_col(&mut jac, row, 3 * n + 3 + i, p.tangent * l);
        }
    }
    (jac, res)
}

/// The chain and places after a step `delta`; `None` if ℓ would not stay
/// positive.
fn apply(
    chain: &UniformHelixChain,
    u: &[f64],
    delta: &DVector<f64>,
) -> Option<(UniformHelixChain, Vec<f64>)> {
    let n = chain.elements();
    let l = chain.element_length_m + delta[3 * n + 2];
    if l.is_nan() || l <= 0.5 * chain.element_length_m || !delta.iter().all(|d| d.is_finite()) {
        return None;
    }
    let strains = (0..n)
        .map(|e| {
            chain.strains_per_m[e] + DVec3::new(delta[3 * e], delta[3 * e + 1], delta[3 * e + 2])
        })
        .collect();
    let tilt = chain.root_frame.col(1) * delta[3 * n] + chain.root_frame.col(2) * delta[3 * n + 1];
    let mut new_u = u.to_vec();
    for i in 0..u.len() - 1 {
        new_u[i] = (u[i] + delta[3 * n + 3 + i]).clamp(0.0, n as f64);
    }
    Some((
        UniformHelixChain {
            root_frame: orthonormalize(rotation(tilt) * chain.root_frame),
            element_length_m: l,
            strains_per_m: strains,
        },
        new_u,
    ))
}

/// Gram–Schmidt on the columns, so round-off never accumulates.
fn orthonormalize(m: DMat3) -> DMat3 {
    let n0 = m.col(0).normalize();
    let n1 = (m.col(1) - m.col(1).dot(n0) * n0).normalize();
    DMat3::from_cols(n0, n1, n0.cross(n1))
}

/// Rolls the chain's material frames about their tangents so that the root
/// frame's n₁ is `reference` made orthogonal to n₀; the centreline does not
/// change (see the module docs).
pub fn fix_roll(chain: &mut UniformHelixChain, reference: DVec3) {
    let n0 = chain.root_frame.col(0);
    let mut want = reference - reference.dot(n0) * n0;
    if want.length_squared() < 1e-12 {
        want = n0.any_orthonormal_vector();
    }
    let want = want.normalize();
    let n1 = chain.root_frame.col(1);
    let alpha = n1.cross(want).dot(n0).atan2(n1.dot(want));
    chain.root_frame = orthonormalize(rotation(n0 * alpha) * chain.root_frame);
    let back = rotation(DVec3::X * -alpha);
    for k in &mut chain.strains_per_m {
        *k = back * *k;
    }
}

fn put_vec(v: &mut DVector<f64>, row: usize, x: DVec3) {
    v[row] = x.x;
    v[row + 1] = x.y;
    v[row + 2] = x.z;
}

fn put_col(m: &mut DMatrix<f64>, row: usize, col: usize, x: DVec3) {
    m[(row, col)] = x.x;
    m[(row + 1, col)] = x.y;
    m[(row + 2, col)] = x.z;
}

fn put_block(m: &mut DMatrix<f64>, row: usize, col: usize, b: &DMat3) {
    for j in 0..3 {
        put_col(m, row, col + j, b.col(j));
    }
}

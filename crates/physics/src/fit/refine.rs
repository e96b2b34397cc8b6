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
//! and otherwise retries with λ ← 4λ. The system is assembled from each
//! point's few non-zero columns and solved with the places eliminated
//! first ([`super::normal`]): a 3N + 3 system instead of 3N + 2 + M. On a
//! curve that a chain of N helices reproduces exactly the residual goes
//! to zero and the iteration converges quadratically, to round-off. Twist is unobservable in a straight element
//! (its column of J vanishes): the damping keeps it at its starting value
//! there.
//!
//! Stopping. A search over N needs each N's verdict, not its optimum:
//! [`EarlyStop`] ends a refinement once every point is within a tenth of
//! the tolerance, once progress is slow far outside it, and once it
//! crawls (three iterations in a row each lowering the cost by under
//! 0.1%) within the tolerance, or outside it while a larger N is left to
//! try. A chain with nearly as many unknowns as the polyline has data
//! (Sintel's 16 points at the cap of 9 elements) crawls for hundreds of
//! iterations at a fraction of a per cent each; only the last N tried
//! keeps crawling outside the tolerance, to the iteration limit.
//!
//! Gauge. Rolling every material frame by the same angle α about its
//! tangent and turning every (κ₁, κ₂) by −α leaves the centreline unchanged,
//! so the root's roll is not fitted: it is fixed afterwards so that n₁ is
//! the caller's reference direction made orthogonal to n₀
//! ([`fix_roll`]).

use glam::{DMat3, DVec3};

use super::curve::UniformHelixChain;
use super::normal::NormalEquations;
use crate::geometry::helix::rotation;

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
/// Near the target, this many slow iterations in a row also stop: the fit
/// is then crawling along directions that barely move the points (a
/// chain with nearly as many unknowns as the polyline has data), where
/// two hundred more iterations gain a few per cent of the deviation.
/// Measured on Sintel with the sag's element counts: without this, two
/// fits in three ran to the iteration limit, most of them already within
/// the tolerance; with it the fit takes a quarter of the time. Three, not
/// one: a single slow step can follow a raised λ; ten cost 40% more time
/// for a p95 fit error 6% lower.
const STALL_ITERATIONS: usize = 3;
/// Stop when the RMS deviation falls below this fraction of the length:
/// round-off of positions summed along the strand.
const EXACT_RMS_OVER_LENGTH: f64 = 1e-14;
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

/// When a refinement may stop before it converges: a search over the
/// element count only needs to know whether each count meets its
/// tolerance.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EarlyStop {
    /// Done once every point is within this distance of the strand,
    /// metres; 0 (the default) refines to convergence and ignores the
    /// rest.
    pub good_enough_m: f64,
    /// The tolerance the caller will test, metres: slow progress with
    /// every point within it stops.
    pub tolerance_m: f64,
    /// Whether the caller has no larger chain to try: then slow progress
    /// outside the tolerance goes on (to the iteration limit), since this
    /// fit is the one kept.
    pub last_try: bool,
}

/// Refines `chain` (root at `points_m[0]`) to the polyline, starting the
/// points' places at `arc_lengths_m` (e.g. chord lengths scaled to the
/// chain's length), stopping early as `stop` allows. With
/// `twist_weight_m` = w > 0 the cost gains ½ Σ_Q (w ℓ τ_Q)²: each
/// radian of an element's twist costs as much as a point w off
/// ([`super::relax_twist`]).
pub fn refine(
    points_m: &[DVec3],
    mut chain: UniformHelixChain,
    arc_lengths_m: &[f64],
    stop: &EarlyStop,
    twist_weight_m: f64,
) -> Refined {
    let good_enough_m = stop.good_enough_m;
    let n = chain.elements();
    let m = points_m.len() - 1;
    let targets: Vec<DVec3> = points_m[1..].iter().map(|p| *p - points_m[0]).collect();
    let l0 = chain.element_length_m;
    let mut u: Vec<f64> = arc_lengths_m[1..]
        .iter()
        .map(|s| (s / l0).clamp(0.0, n as f64))
        .collect();
    u[m - 1] = n as f64;
    let (mut cost, _) = evaluate(&chain, &u, &targets, twist_weight_m);
    let mut lambda = 1e-3;
    let mut iterations = 0;
    let exact = 0.5 * m as f64 * (EXACT_RMS_OVER_LENGTH * l0 * n as f64).powi(2);
    let mut normal = NormalEquations::default();
    let mut delta = Vec::with_capacity(3 * n + 2 + m);
    let mut slow_in_a_row = 0;
    while iterations < MAX_ITERATIONS && cost > exact {
        iterations += 1;
        normal.assemble(&chain, &u, &targets, twist_weight_m);
        let mut accepted = None;
        for _ in 0..MAX_RETRIES {
            if !normal.solve(lambda, &mut delta) {
                lambda *= 4.0;
                continue;
            }
            if let Some((trial, trial_u)) = apply(&chain, &u, &delta) {
                let (trial_cost, trial_worst) =
                    evaluate(&trial, &trial_u, &targets, twist_weight_m);
                if trial_cost < cost {
                    accepted = Some((trial, trial_u, trial_cost, trial_worst));
                    break;
                }
            }
            lambda *= 4.0;
        }
        let Some((trial, trial_u, trial_cost, worst)) = accepted else {
            break;
        };
        let decrease = cost - trial_cost;
        let slow = decrease <= STALL_DECREASE * cost;
        slow_in_a_row = if slow { slow_in_a_row + 1 } else { 0 };
        chain = trial;
        u = trial_u;
        cost = trial_cost;
        lambda = (lambda / 3.0).max(1e-15);
        if decrease <= RELATIVE_DECREASE_STOP * (cost + decrease) {
            break;
        }
        // Done once close enough, or crawling within the tolerance; given
        // up once progress is slow while still far, or crawling outside
        // the tolerance with a larger chain left to try.
        if good_enough_m > 0.0
            && (worst <= good_enough_m
                || (slow && worst > STALL_FAR * good_enough_m)
                || (slow_in_a_row >= STALL_ITERATIONS
                    && (worst <= stop.tolerance_m || !stop.last_try)))
        {
            break;
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

/// The cost ½Σ|r_i|² (+ the twist penalty ½Σ(w ℓ τ_Q)²) and the largest
/// |r_i|, from one sweep.
fn evaluate(
    chain: &UniformHelixChain,
    u: &[f64],
    targets: &[DVec3],
    twist_weight_m: f64,
) -> (f64, f64) {
    let sweep = chain.sweep_with(false);
    let l = chain.element_length_m;
    let twist: f64 = chain
        .strains_per_m
        .iter()
        .map(|q| 0.5 * (twist_weight_m * l * q.x).powi(2))
        .sum();
    u.iter()
        .zip(targets)
        .map(|(ui, t)| (chain.point_with(&sweep, ui * l, false).position_m - *t).length_squared())
        .fold((twist, 0.0), |(cost, worst): (f64, f64), d2| {
            (cost + 0.5 * d2, worst.max(d2.sqrt()))
        })
}

/// The chain and places after a step `delta`; `None` if ℓ would not stay
/// positive.
fn apply(
    chain: &UniformHelixChain,
    u: &[f64],
    delta: &[f64],
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

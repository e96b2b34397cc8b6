//! Failing safe on the fast path: the checks of [`crate::guard`], lane by
//! lane, and a reset.
//!
//! # How it works
//!
//! After each frame, every strand (every lane of every batch) is checked
//! with the same bounds and limits as the f64 [`crate::HairSystem`]
//! ([`Guard`]):
//!
//! - **finite**: every strain and rate is a number. Computed in SIMD as
//!   Σ 0·x over the strand's 6N values, which is 0 in a lane exactly when
//!   all of them are finite (0·∞ and 0·NaN are NaN);
//! - **speed**: the bound Σ_Q ℓ_Q |q̇_Q| (L − s_Q) of
//!   [`crate::guard::speed_bound_m_per_s`] on any point's speed relative to
//!   the root, in f32 lanes. A frame fails above
//!   [`Guard::speed_limit_m_per_s`], or above [`Guard::growth_factor`] times
//!   the bound at the frame's start once past
//!   [`Guard::speed_floor_m_per_s`].
//!
//! **Recovery is a reset**: a failing strand goes back to its natural shape
//! at rest (q = qⁿ, q̇ = 0), and its index is reported
//! ([`super::BatchSystem::last_guard_resets`]). This path does not retry the
//! frame with Exact and more substeps as the f64 guard does: it is the
//! interactive path, where a frame's cost must stay predictable (a retry
//! of a whole batch at 32 substeps would stall the frame it happens in), and
//! lanes share their batch's arithmetic, so one strand cannot be re-stepped
//! on its own without stepping its seven neighbours again. The f64
//! `HairSystem` is the careful path; use it where a recovered trajectory
//! matters more than the frame rate.
//!
//! A strand that passes is not touched, so a healthy run is bit-identical
//! with and without the guard. The checks are O(N) per batch and frame,
//! against the step's O(N × points) per substep.

use super::lanes::{LANES, Lanes, Real};
use super::layout::BatchModel;
use super::vec::V3;
use crate::guard::Guard;

/// Per lane of a batch (`v`: its N rate triples), the speed bound
/// Σ_Q ℓ_Q |q̇_Q| (L − s_Q), m/s.
pub fn speed_bound_m_per_s(model: &BatchModel, v: &[V3<Lanes>]) -> Lanes {
    let mut beyond_m: f32 = model.lengths_m.iter().sum();
    let mut bound = Lanes::splat(0.0);
    for (l, rate) in model.lengths_m.iter().zip(v) {
        bound += rate.dot(*rate).sqrt() * Lanes::splat(l * beyond_m);
        beyond_m -= l;
    }
    bound
}

/// Per lane, whether every value of `values` is finite.
fn finite_lanes(values: &[V3<Lanes>]) -> [bool; LANES] {
    let zero = Lanes::splat(0.0);
    let mut nan_if_not = zero;
    for x in values {
        nan_if_not += x.x * zero + x.y * zero + x.z * zero;
    }
    std::array::from_fn(|i| nan_if_not.lane(i) == 0.0)
}

/// Checks one batch (`q`, `v`: N triples each) that started its frame with
/// speed bounds `start_m_per_s`; resets each failing lane to `model`'s
/// natural shape at rest. Returns the failing lanes.
pub fn check_and_reset(
    guard: &Guard,
    model: &BatchModel,
    q: &mut [V3<Lanes>],
    v: &mut [V3<Lanes>],
    start_m_per_s: Lanes,
) -> [bool; LANES] {
    let finite_q = finite_lanes(q);
    let finite_v = finite_lanes(v);
    let speed = speed_bound_m_per_s(model, v);
    let failed: [bool; LANES] = std::array::from_fn(|i| {
        let speed = f64::from(speed.lane(i));
        let start = f64::from(start_m_per_s.lane(i));
        let grown = guard.growth_factor * start.max(guard.speed_floor_m_per_s);
        // A NaN speed fails the finite test; written so that it fails here too.
        !(finite_q[i] && finite_v[i] && speed <= guard.speed_limit_m_per_s && speed <= grown)
    });
    if failed.contains(&true) {
        for (e, (q, v)) in q.iter_mut().zip(v.iter_mut()).enumerate() {
            let natural = model.natural[e];
            for (i, _) in failed.iter().enumerate().filter(|(_, f)| **f) {
                q.x.set_lane(i, natural[0]);
                q.y.set_lane(i, natural[1]);
                q.z.set_lane(i, natural[2]);
                v.x.set_lane(i, 0.0);
                v.y.set_lane(i, 0.0);
                v.z.set_lane(i, 0.0);
            }
        }
    }
    failed
}

//! The batch path's f32 helix coefficients (`batch::geometry::coefficients`:
//! A = sin x/x, B = (1 − cos x)/x², C = (x − sin x)/x³ with their first two
//! derivatives in y = x²) against the same functions in f64, from their
//! definitions, across the series, the switch to the closed forms and well
//! past it: each within [`F32_COEFFICIENT_TOLERANCE`] of the true value, on
//! the scale the coefficient has there.

use helixhair_physics::batch::geometry::{SERIES_LIMIT_Y, coefficients};
use helixhair_physics::batch::lanes::{LANES, Lanes, Real};

/// Largest error allowed, relative to a coefficient's scale at y
/// ([`scale`]): f32 round-off of sums of about ten terms, with the closed
/// forms' cancellation in the derivatives.
const F32_COEFFICIENT_TOLERANCE: f64 = 2e-6;

/// A, A′, A″, B, B′, B″, C, C′, C″ at y > 0 in f64 from the definitions
/// and the identities A′ = −C − yC′, B′ = (A − 2B)/2y, C′ = (B − 3C)/2y,
/// A″ = −2C′ − yC″, B″ = (A′ − 4B′)/2y, C″ = (B′ − 5C′)/2y. Their
/// cancellation costs f64 about 1e-16/y³, below 1e-10 for the y tested.
fn truth(y: f64) -> [f64; 9] {
    let x = y.sqrt();
    let (sin, cos) = x.sin_cos();
    let a = sin / x;
    let b = (1.0 - cos) / y;
    let c = (x - sin) / (x * y);
    let c1 = (b - 3.0 * c) / (2.0 * y);
    let b1 = (a - 2.0 * b) / (2.0 * y);
    let a1 = -c - y * c1;
    let c2 = (b1 - 5.0 * c1) / (2.0 * y);
    let b2 = (a1 - 4.0 * b1) / (2.0 * y);
    let a2 = -2.0 * c1 - y * c2;
    [a, a1, a2, b, b1, b2, c, c1, c2]
}

/// The coefficients' values at y = 0 (their series' first terms).
const AT_ZERO: [f64; 9] = [
    1.0,
    -1.0 / 6.0,
    2.0 / 120.0,
    1.0 / 2.0,
    -1.0 / 24.0,
    2.0 / 720.0,
    1.0 / 6.0,
    -1.0 / 120.0,
    2.0 / 5040.0,
];

/// A coefficient's scale at y: its own size, or where it passes through
/// zero, its size at y = 0 shrunk as A's swing does (like 1/x): near a
/// zero of sin x the f32 rounding of y alone moves A by about
/// ε·|cos x|/2x, which is no error of the coefficients.
fn scale(i: usize, value: f64, y: f64) -> f64 {
    value.abs().max(AT_ZERO[i].abs() / (1.0 + y).sqrt())
}

/// The worst error over y in `ys`, relative to scale, per coefficient.
fn worst_errors(ys: &[f32]) -> [f64; 9] {
    let mut worst = [0.0f64; 9];
    for chunk in ys.chunks_exact(LANES) {
        let co = coefficients(Lanes::from_fn(|i| chunk[i]), true);
        let got = [co.a, co.b, co.c].concat();
        for (lane, &y) in chunk.iter().enumerate() {
            let want = truth(f64::from(y));
            for i in 0..9 {
                let error = (f64::from(got[i].lane(lane)) - want[i]).abs();
                worst[i] = worst[i].max(error / scale(i, want[i], f64::from(y)));
            }
        }
    }
    worst
}

#[test]
fn f32_coefficients_match_their_definitions_across_series_and_closed_forms() {
    // 0.05 to 100 (x from 0.22 to 10 rad across an element), dense around
    // the switch, in batches of lanes all on one side of it...
    let ys: Vec<f32> = (0..40_000).map(|i| 0.05 + i as f32 * 0.0025).collect();
    let worst = worst_errors(&ys);
    println!("worst errors over scale (A, A', A'', B, .., C''): {worst:?}");
    for (i, w) in worst.iter().enumerate() {
        assert!(*w < F32_COEFFICIENT_TOLERANCE, "coefficient {i}: {w:e}");
    }
    // ...and mixed: each batch with lanes either side of the limit.
    let mixed: Vec<f32> = (0..8_000)
        .map(|i| {
            let y = 0.05 + (i / LANES) as f32 * 0.02;
            if i % 2 == 0 { y } else { y + SERIES_LIMIT_Y }
        })
        .collect();
    let worst = worst_errors(&mixed);
    println!("mixed batches: {worst:?}");
    for (i, w) in worst.iter().enumerate() {
        assert!(*w < F32_COEFFICIENT_TOLERANCE, "coefficient {i}: {w:e}");
    }
}

//! The helix coefficients A, B, C (and B′, C′) as the fit needs them: as
//! few series terms as the argument allows.
//!
//! An element's geometry rests on A = sin x / x, B = (1 − cos x)/x² and
//! C = (x − sin x)/x³ of y = x² = |φ|² ([`crate::geometry::helix`] derives
//! them and explains why they are taken as functions of y). The step
//! evaluates them, with two y-derivatives each, from 20 terms of their
//! Taylor series whatever y is: exact to round-off up to y = 4. A fit
//! evaluates the chain at every polyline point, for every iteration and
//! every trial, and there the series was a fifth of the import's time; but
//! it needs less: the three values for positions and frames, and only B′
//! and C′ for the Jacobian (∂h/∂k), and it spends most of its evaluations
//! at small y (a point near its element's start, an element turning by a
//! fraction of a radian). So [`FitCoefficients::at`] sums only the terms
//! that y needs: the first neglected one is below 2e-17 of every sum,
//! values and derivatives alike ([`terms_for`]), which is as exact as
//! twenty terms in double precision, at a third to a half of the work.
//! Above y = 4 it uses the closed forms, as the step does.

use crate::geometry::helix::{HelixCoefficients, SERIES_LIMIT_Y, series_coefficients};

/// Most series terms (y just below 4).
const MOST_TERMS: usize = 12;

/// Upper ends of the ranges of y and the terms each needs: the smallest
/// count whose first neglected term is below 2e-17 of each of A, B, C, B′,
/// C′ over the whole range (worked out once with exact factorials).
const TERMS_BY_Y: [(f64, usize); 6] = [
    (1.0 / 1024.0, 5),
    (1.0 / 64.0, 6),
    (1.0 / 16.0, 7),
    (0.25, 8),
    (1.0, 10),
    (SERIES_LIMIT_Y, MOST_TERMS),
];

const A_SERIES: [f64; MOST_TERMS] = series_coefficients(1);
const B_SERIES: [f64; MOST_TERMS] = series_coefficients(2);
const C_SERIES: [f64; MOST_TERMS] = series_coefficients(3);

/// How many series terms y < 4 needs.
pub fn terms_for(y: f64) -> usize {
    TERMS_BY_Y
        .iter()
        .find(|(limit, _)| y <= *limit)
        .map_or(MOST_TERMS, |(_, terms)| *terms)
}

/// A, B, C at y = |φ|², with the y-derivatives B′ and C′ of the latter
/// two (the ones the centreline's Jacobian needs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitCoefficients {
    /// sin x / x.
    pub a: f64,
    /// (1 − cos x)/x².
    pub b: f64,
    /// (x − sin x)/x³.
    pub c: f64,
    /// dB/dy.
    pub b1: f64,
    /// dC/dy.
    pub c1: f64,
}

impl FitCoefficients {
    /// The coefficients at y = |φ|² ≥ 0.
    pub fn at(y: f64) -> Self {
        if y < SERIES_LIMIT_Y {
            let k = terms_for(y);
            let mut a = A_SERIES[k - 1];
            let (mut b, mut b1) = (B_SERIES[k - 1], 0.0);
            let (mut c, mut c1) = (C_SERIES[k - 1], 0.0);
            for n in (0..k - 1).rev() {
                a = a * y + A_SERIES[n];
                b1 = b1 * y + b;
                b = b * y + B_SERIES[n];
                c1 = c1 * y + c;
                c = c * y + C_SERIES[n];
            }
            return Self { a, b, c, b1, c1 };
        }
        // Past the series, the step's closed forms (rare in a fit).
        let full = HelixCoefficients::at(y);
        Self {
            a: full.a[0],
            b: full.b[0],
            c: full.c[0],
            b1: full.b[1],
            c1: full.c[1],
        }
    }
}

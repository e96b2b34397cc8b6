//! Closed-form geometry of one Super-Helix element.
//!
//! Inside an element the Darboux vector k = (τ, κ₁, κ₂) is constant in the
//! material frame, so the frame turns about a fixed axis and the centreline
//! is a helix. With φ = σk, x = |φ| and y = x²:
//!
//! - frame:   E(φ) = exp(\[φ\]×) = I + A \[φ\]× + B \[φ\]×²
//! - point:   h(σ, k) = σ J_l(φ) e₀,  J_l(φ) = I + B \[φ\]× + C \[φ\]×²
//!
//! with A = sin x / x, B = (1 − cos x)/x², C = (x − sin x)/x³ and J_l the
//! left Jacobian of SO(3). Writing A, B, C as functions of y (not x) makes
//! them analytic in k, straight elements included: for y < 4 they are
//! evaluated from their Taylor series in y (20 terms: round-off only), above
//! that from sines and cosines. Their first two y-derivatives come from the
//! same series, or from the identities A' = −C − yC', B' = (A − 2B)/2y,
//! C' = (B − 3C)/2y and their derivatives, so Jacobians and jets never
//! divide by zero.

use glam::{DMat3, DVec3};

use crate::geometry::jet::Jet;

/// Below this y = x² the coefficients come from their series.
pub const SERIES_LIMIT_Y: f64 = 4.0;
/// Series terms; the first neglected term is below 4²⁰/42! ≈ 1e-39.
const TERMS: usize = 20;

/// (−1)ⁿ/(2n + offset)! for n = 0..N: the Taylor coefficients in y of A
/// (offset 1), B (2) and C (3), in f64; every evaluation of the helix
/// coefficients (here, the batch step's, the fit's) takes its terms from
/// this.
pub const fn series_coefficients<const N: usize>(offset: u32) -> [f64; N] {
    let mut c = [0.0; N];
    let mut n = 0;
    while n < N {
        let mut factorial = 1.0;
        let mut j = 2;
        while j <= 2 * n as u32 + offset {
            factorial *= j as f64;
            j += 1;
        }
        c[n] = if n % 2 == 0 { 1.0 } else { -1.0 } / factorial;
        n += 1;
    }
    c
}

const A_SERIES: [f64; TERMS] = series_coefficients(1);
const B_SERIES: [f64; TERMS] = series_coefficients(2);
const C_SERIES: [f64; TERMS] = series_coefficients(3);

/// f(y), f'(y), f''(y) of a power series by Horner's rule.
fn horner(c: &[f64; TERMS], y: f64) -> [f64; 3] {
    let (mut p, mut dp, mut half_ddp) = (c[TERMS - 1], 0.0, 0.0);
    for &cn in c[..TERMS - 1].iter().rev() {
        half_ddp = half_ddp * y + dp;
        dp = dp * y + p;
        p = p * y + cn;
    }
    [p, dp, 2.0 * half_ddp]
}

/// A, B, C as functions of y = |φ|², each with its first two y-derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HelixCoefficients {
    /// sin x / x and derivatives.
    pub a: [f64; 3],
    /// (1 − cos x)/x² and derivatives.
    pub b: [f64; 3],
    /// (x − sin x)/x³ and derivatives.
    pub c: [f64; 3],
}

impl HelixCoefficients {
    /// The coefficients at y = |φ|² ≥ 0.
    pub fn at(y: f64) -> Self {
        if y < SERIES_LIMIT_Y {
            return Self {
                a: horner(&A_SERIES, y),
                b: horner(&B_SERIES, y),
                c: horner(&C_SERIES, y),
            };
        }
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
        Self {
            a: [a, a1, a2],
            b: [b, b1, b2],
            c: [c, c1, c2],
        }
    }
}

/// The cross-product matrix \[v\]×, with \[v\]× w = v × w.
pub fn skew(v: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, v.z, -v.y),
        DVec3::new(-v.z, 0.0, v.x),
        DVec3::new(v.y, -v.x, 0.0),
    )
}

/// exp(\[φ\]×): the rotation of the frame across an element, φ = ℓk.
pub fn rotation(phi: DVec3) -> DMat3 {
    let co = HelixCoefficients::at(phi.length_squared());
    let s = skew(phi);
    DMat3::IDENTITY + s * co.a[0] + s * s * co.b[0]
}

/// J_l(φ), the left Jacobian of SO(3): a change δk of an element's strains
/// turns its end frame by the world rotation ℓ R_Q J_l(ℓk) δk.
pub fn left_jacobian(phi: DVec3) -> DMat3 {
    left_jacobian_with(phi, &HelixCoefficients::at(phi.length_squared()))
}

/// [`left_jacobian`] from coefficients already evaluated at y = |φ|².
pub fn left_jacobian_with(phi: DVec3, co: &HelixCoefficients) -> DMat3 {
    let s = skew(phi);
    DMat3::IDENTITY + s * co.b[0] + s * s * co.c[0]
}

/// The centreline of an element at arc length σ, in its start frame, and
/// its Jacobian with respect to the strains: (h(σ, k), ∂h/∂k).
pub fn centreline_and_jacobian(sigma: f64, k: DVec3) -> (DVec3, DMat3) {
    let phi = sigma * k;
    let co = HelixCoefficients::at(phi.length_squared());
    let e0 = DVec3::X;
    let f = e0 + co.b[0] * phi.cross(e0) + co.c[0] * phi.cross(phi.cross(e0));
    (sigma * f, centreline_jacobian_with(sigma, phi, &co))
}

/// ∂h(σ, k)/∂k = σ² ∂f/∂φ at φ = σk, with f(φ) = J_l(φ) e₀:
/// ∂f/∂φ = B(−\[e₀\]×) + C(φe₀ᵀ + (φ·e₀)I − 2e₀φᵀ) + 2B'(φ×e₀)φᵀ + 2C'(φ×(φ×e₀))φᵀ.
pub fn centreline_jacobian_with(sigma: f64, phi: DVec3, co: &HelixCoefficients) -> DMat3 {
    let e0 = DVec3::X;
    let phi_x_e0 = phi.cross(e0);
    let phi_x_phi_x_e0 = phi.cross(phi_x_e0);
    let df = skew(e0) * (-co.b[0])
        + (outer(phi, e0) + DMat3::from_diagonal(DVec3::splat(phi.x)) - outer(e0, phi) * 2.0)
            * co.c[0]
        + outer(phi_x_e0, phi) * (2.0 * co.b[1])
        + outer(phi_x_phi_x_e0, phi) * (2.0 * co.c[1]);
    df * (sigma * sigma)
}

/// The outer product a bᵀ.
pub fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// The geometry of an element at one arc length, from one evaluation of
/// A, B, C (the jets and the Jacobian share it: y = σ²|q|² for both).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointGeometry {
    /// Jet of the centreline h(σ, k) in the element's start frame.
    pub centreline: Jet<DVec3>,
    /// ∂h(σ, k)/∂k at the strains' value, metres².
    pub centreline_jacobian: DMat3,
}

/// [`PointGeometry`] at the element's end, with the frame's turn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EndGeometry {
    /// Centreline and its Jacobian at σ = ℓ.
    pub point: PointGeometry,
    /// Jet of the rotation E(ℓk) across the element.
    pub rotation: Jet<DMat3>,
    /// J_l(ℓk) at the strains' value.
    pub left_jacobian: DMat3,
}

/// The shared part of [`point_geometry`] and [`end_geometry`]: φ = σk as a
/// jet, the coefficients at its value, their jets, and h's jet.
pub(crate) fn geometry_parts(
    sigma: f64,
    k: Jet<DVec3>,
) -> (Jet<DVec3>, HelixCoefficients, [Jet<f64>; 3], PointGeometry) {
    let phi = k.map_linear(|v| v * sigma);
    let y = phi.dot(phi);
    let co = HelixCoefficients::at(y.v);
    let jets = [y.chain(co.a), y.chain(co.b), y.chain(co.c)];
    let e0 = Jet::new(DVec3::X, DVec3::ZERO, DVec3::ZERO);
    let phi_x_e0 = phi.cross(e0);
    let f = e0 + jets[1] * phi_x_e0 + jets[2] * phi.cross(phi_x_e0);
    let point = PointGeometry {
        centreline: f.map_linear(|v| v * sigma),
        centreline_jacobian: centreline_jacobian_with(sigma, phi.v, &co),
    };
    (phi, co, jets, point)
}

/// Jets of the centreline at arc length σ and, at the element's end
/// (σ = `length`), of the centreline and the rotation: what a sweep that
/// needs no Jacobian uses ([`crate::step::reconstruct::free_accelerations`]).
pub fn centreline_jets(sigma: f64, k: Jet<DVec3>, end: bool) -> (Jet<DVec3>, Jet<DMat3>) {
    let phi = k.map_linear(|v| v * sigma);
    let y = phi.dot(phi);
    let co = HelixCoefficients::at(y.v);
    let [a, b, c] = [y.chain(co.a), y.chain(co.b), y.chain(co.c)];
    let e0 = Jet::new(DVec3::X, DVec3::ZERO, DVec3::ZERO);
    let phi_x_e0 = phi.cross(e0);
    let f = e0 + b * phi_x_e0 + c * phi.cross(phi_x_e0);
    let rotation = if end {
        let s = phi.map_linear(skew);
        Jet::constant(DMat3::IDENTITY) + a * s + b * (s * s)
    } else {
        Jet::constant(DMat3::IDENTITY)
    };
    (f.map_linear(|v| v * sigma), rotation)
}

/// Centreline jet and Jacobian at arc length σ, for a strain jet
/// k = (q, q̇, q̈).
pub fn point_geometry(sigma: f64, k: Jet<DVec3>) -> PointGeometry {
    geometry_parts(sigma, k).3
}

/// Centreline, rotation and left Jacobian at the end of an element of
/// length `length`, for a strain jet k = (q, q̇, q̈).
pub fn end_geometry(length: f64, k: Jet<DVec3>) -> EndGeometry {
    end_geometry_and_parts(length, k).0
}

/// [`end_geometry`] with the jet of φ = ℓk and the coefficients it used
/// (what the Jacobians' time derivatives need, [`crate::geometry::helix_rates`]).
pub(crate) fn end_geometry_and_parts(
    length: f64,
    k: Jet<DVec3>,
) -> (EndGeometry, Jet<DVec3>, HelixCoefficients) {
    let (phi, co, [a, b, _], point) = geometry_parts(length, k);
    let s = phi.map_linear(skew);
    let rotation = Jet::constant(DMat3::IDENTITY) + a * s + b * (s * s);
    let end = EndGeometry {
        point,
        rotation,
        left_jacobian: left_jacobian_with(phi.v, &co),
    };
    (end, phi, co)
}

//! Element geometry in f32 for the fast path: the helix coefficients A, B, C
//! and what one element contributes at an arc length σ, with time
//! derivatives written out instead of carried on jets.
//!
//! The f64 reference ([`crate::geometry::helix`], [`crate::step::reconstruct`]) runs the
//! whole sweep on jets, so every frame is a jet of three matrices. Here the
//! frame's time derivatives are carried as its angular velocity ω and
//! acceleration α (world vectors, Ṙ = \[ω\]×R), as in articulated-body
//! dynamics, and only the element-local quantities (φ = σk, the coefficient
//! jets, the local centreline h) are differentiated by hand. With q̈ = 0:
//!
//! - y = φ·φ, ẏ = 2φ·φ̇, ÿ = 2φ̇·φ̇; a coefficient's jet is (f, f′ẏ, f″ẏ² + f′ÿ)
//! - f = e₀ + B g₁ + C g₂ with g₁ = φ×e₀ and g₂ = φ×(φ×e₀) = φₓφ − y e₀; h = σf
//! - across the element: ω′ = ω + R J_l φ̇, α′ = α + ω×(R J_l φ̇) + R (J_l φ̇)˙
//!   with (J_l φ̇)˙ = Ḃ (φ×φ̇) + Ċ φ×(φ×φ̇) + C φ̇×(φ×φ̇)
//!
//! This needs no matrix jets and is about three times cheaper than the
//! reference's arithmetic; the parity tests compare the two.
//!
//! The coefficients come from 11 terms of their series in y below y = 16
//! (x = 4 rad of turn across an element; the first neglected term is
//! 16¹¹/23! ≈ 7e-10; the f64 instance keeps 16, 16¹⁶/33! ≈ 2e-18) and
//! from sines and cosines above; a batch whose lanes
//! are all below 16 skips the closed form. The series reach that far
//! because, in f32, they are the more accurate of the two there: their
//! largest term (0.67 for B at x = 4) against B = 0.10 costs a few ulps,
//! while the closed forms' derivatives cancel, (B − 3C)/2y and so on, and
//! lose up to 1e-5 of C″ near y = 4 (`tests/lane_coefficients.rs`
//! measures both). A limit of 4, as the f64 reference keeps, sent 47% of
//! an imported groom's coefficient evaluations (Sintel, batches with a lane
//! past 4) through both forms, sines, cosines and six divisions included;
//! past 16, 23%.

use super::lanes::Real;
use super::vec::{M3, V3};
use crate::geometry::helix::series_coefficients;

/// Below this y = x² the coefficients come from their series (module docs).
pub const SERIES_LIMIT_Y: f32 = 16.0;
/// Series terms kept at most (the f64 instance's [`Real::SERIES_TERMS`]);
/// f32 keeps 11, enough for its round-off up to [`SERIES_LIMIT_Y`].
const MAX_TERMS: usize = 16;

// The series in f64 ([`series_coefficients`]); each width rounds them
// once ([`Real::splat_f64`]).
const A_SERIES: [f64; MAX_TERMS] = series_coefficients(1);
const B_SERIES: [f64; MAX_TERMS] = series_coefficients(2);
const C_SERIES: [f64; MAX_TERMS] = series_coefficients(3);

/// f(y), f′(y), f″(y) of a power series by Horner's rule, with the
/// first [`Real::SERIES_TERMS`] terms of `c`.
#[inline(always)]
fn horner<T: Real>(c: &[f64; MAX_TERMS], y: T) -> [T; 3] {
    let terms = T::SERIES_TERMS.min(MAX_TERMS);
    let mut p = T::splat_f64(c[terms - 1]);
    let mut dp = T::splat(0.0);
    let mut half_ddp = T::splat(0.0);
    for &cn in c[..terms - 1].iter().rev() {
        half_ddp = half_ddp.mul_add(y, dp);
        dp = dp.mul_add(y, p);
        p = p.mul_add(y, T::splat_f64(cn));
    }
    [p, dp, half_ddp + half_ddp]
}

/// A, B, C at y, each with two y-derivatives.
#[derive(Clone, Copy, Debug)]
pub struct Coefficients<T> {
    /// sin x / x and derivatives.
    pub a: [T; 3],
    /// (1 − cos x)/x² and derivatives.
    pub b: [T; 3],
    /// (x − sin x)/x³ and derivatives.
    pub c: [T; 3],
}

/// The closed forms, used for y ≥ [`SERIES_LIMIT_Y`] (y is clamped there).
#[inline(always)]
fn closed<T: Real>(y: T) -> Coefficients<T> {
    let y = y.max(T::splat(SERIES_LIMIT_Y));
    let x = y.sqrt();
    let (sin, cos) = x.sin_cos();
    let one = T::splat(1.0);
    let two_y = y + y;
    let a = sin / x;
    let b = (one - cos) / y;
    let c = (x - sin) / (x * y);
    let c1 = (b - T::splat(3.0) * c) / two_y;
    let b1 = (a - T::splat(2.0) * b) / two_y;
    let a1 = -c - y * c1;
    let c2 = (b1 - T::splat(5.0) * c1) / two_y;
    let b2 = (a1 - T::splat(4.0) * b1) / two_y;
    let a2 = -T::splat(2.0) * c1 - y * c2;
    Coefficients {
        a: [a, a1, a2],
        b: [b, b1, b2],
        c: [c, c1, c2],
    }
}

/// The coefficients at y = |φ|² ≥ 0, lane by lane. Without `with_a`, A is
/// left zero (points inside an element need only B and C).
#[inline(always)]
pub fn coefficients<T: Real>(y: T, with_a: bool) -> Coefficients<T> {
    let zero = T::splat(0.0);
    let series = Coefficients {
        a: if with_a {
            horner(&A_SERIES, y)
        } else {
            [zero; 3]
        },
        b: horner(&B_SERIES, y),
        c: horner(&C_SERIES, y),
    };
    if y.all_below(SERIES_LIMIT_Y) {
        return series;
    }
    let far = closed(y);
    let pick = |s: [T; 3], f: [T; 3]| {
        [
            y.select_below(SERIES_LIMIT_Y, s[0], f[0]),
            y.select_below(SERIES_LIMIT_Y, s[1], f[1]),
            y.select_below(SERIES_LIMIT_Y, s[2], f[2]),
        ]
    };
    Coefficients {
        a: pick(series.a, far.a),
        b: pick(series.b, far.b),
        c: pick(series.c, far.c),
    }
}

/// An element's centreline at arc length σ, in its start frame.
#[derive(Clone, Copy, Debug)]
pub struct LocalPoint<T> {
    /// h(σ, k), metres.
    pub h: V3<T>,
    /// ḣ with q̈ = 0, m/s.
    pub h_dot: V3<T>,
    /// ḧ with q̈ = 0, m/s².
    pub h_ddot: V3<T>,
    /// ∂h/∂k, metres².
    pub jacobian: M3<T>,
}

/// What the frame does across a whole element (σ = ℓ), besides the point.
#[derive(Clone, Copy, Debug)]
pub struct LocalTurn<T> {
    /// The rotation E = exp(\[φ\]×) across the element.
    pub rotation: M3<T>,
    /// The left Jacobian J_l(φ).
    pub left_jacobian: M3<T>,
    /// J_l φ̇: the end frame's angular velocity relative to the start's.
    pub spin: V3<T>,
    /// (J_l φ̇)˙ with q̈ = 0.
    pub spin_dot: V3<T>,
}

/// The parts of φ's jet that every point of the element shares.
#[derive(Clone, Copy, Debug)]
struct PhiJet<T> {
    phi: V3<T>,
    phi_dot: V3<T>,
    y: T,
    y_dot: T,
    y_ddot: T,
    co: Coefficients<T>,
}

/// y = |σk|² at arc length `sigma` of an element with strains `k`: the
/// argument of the coefficients there.
#[inline(always)]
fn y_at<T: Real>(sigma: T, k: V3<T>) -> T {
    let phi = k.scale(sigma);
    phi.dot(phi)
}

/// The coefficients at arc length `sigma` of an element with strains `k`
/// (with A where `with_a`), exactly as [`local_point`] and [`local_end`]
/// compute them: a step that visits the same points several times at the
/// same q (GMRES, [`crate::batch::step::implicit`]) evaluates them once and passes
/// them to [`local_point_with`] and [`local_end_with`].
#[inline(always)]
pub fn coefficients_at<T: Real>(sigma: T, k: V3<T>, with_a: bool) -> Coefficients<T> {
    coefficients(y_at(sigma, k), with_a)
}

#[inline(always)]
fn phi_jet<T: Real>(sigma: T, k: V3<T>, k_dot: V3<T>, co: Coefficients<T>) -> PhiJet<T> {
    let s = sigma;
    let phi = k.scale(s);
    let phi_dot = k_dot.scale(s);
    let pd = phi.dot(phi_dot);
    let dd = phi_dot.dot(phi_dot);
    PhiJet {
        phi,
        phi_dot,
        // φ·φ, the operations of `y_at`: the bits the coefficients saw.
        y: phi.dot(phi),
        y_dot: pd + pd,
        y_ddot: dd + dd,
        co,
    }
}

/// (f, ḟ, f̈) of a coefficient with derivatives `f` along y's jet.
#[inline(always)]
fn coefficient_jet<T: Real>(f: [T; 3], j: &PhiJet<T>) -> [T; 3] {
    [
        f[0],
        f[1] * j.y_dot,
        (f[2] * j.y_dot).mul_add(j.y_dot, f[1] * j.y_ddot),
    ]
}

#[inline(always)]
fn point_from_jet<T: Real>(sigma: T, j: &PhiJet<T>) -> LocalPoint<T> {
    let zero = T::splat(0.0);
    let one = T::splat(1.0);
    let (phi, pd) = (j.phi, j.phi_dot);
    let [b, bd, bdd] = coefficient_jet(j.co.b, j);
    let [c, cd, cdd] = coefficient_jet(j.co.c, j);
    let g1 = V3::new(zero, phi.z, -phi.y);
    let g1d = V3::new(zero, pd.z, -pd.y);
    let g2 = V3::new(phi.x * phi.x - j.y, phi.x * phi.y, phi.x * phi.z);
    let g2d = phi.scale_add(pd.x, pd.scale_add(phi.x, V3::new(-j.y_dot, zero, zero)));
    let g2dd = pd.scale_add(pd.x + pd.x, V3::new(-j.y_ddot, zero, zero));
    let f = g2.scale_add(c, g1.scale_add(b, V3::new(one, zero, zero)));
    let fd = g2d.scale_add(c, g2.scale_add(cd, g1d.scale_add(b, g1.scale(bd))));
    let fdd = g2dd.scale_add(
        c,
        g2d.scale_add(
            cd + cd,
            g2.scale_add(cdd, g1d.scale_add(bd + bd, g1.scale(bdd))),
        ),
    );
    // ∂f/∂φ, column j: φ_j u + C φₓ e_j + (C φ for j = 0) + (−B [e₀]×)_j,
    // u = 2B′g₁ + 2C′g₂ − 2C e₀.
    let two = T::splat(2.0);
    let u = g2.scale_add(
        two * j.co.c[1],
        g1.scale_add(two * j.co.b[1], V3::new(-(two * c), zero, zero)),
    );
    let cx = c * phi.x;
    let s2 = sigma * sigma;
    let col0 = phi.scale_add(c, u.scale_add(phi.x, V3::new(cx, zero, zero)));
    let col1 = u.scale_add(phi.y, V3::new(zero, cx, -b));
    let col2 = u.scale_add(phi.z, V3::new(zero, b, cx));
    let s = sigma;
    LocalPoint {
        h: f.scale(s),
        h_dot: fd.scale(s),
        h_ddot: fdd.scale(s),
        jacobian: M3::from_cols(col0.scale(s2), col1.scale(s2), col2.scale(s2)),
    }
}

/// The centreline of an element with strains k and rates k̇ at arc length σ
/// (metres, per lane).
#[inline(always)]
pub fn local_point<T: Real>(sigma: T, k: V3<T>, k_dot: V3<T>) -> LocalPoint<T> {
    local_point_with(sigma, k, k_dot, coefficients_at(sigma, k, false))
}

/// [`local_point`] with its coefficients `co` already evaluated
/// ([`coefficients_at`] at the same σ and k): the same bits.
#[inline(always)]
pub fn local_point_with<T: Real>(
    sigma: T,
    k: V3<T>,
    k_dot: V3<T>,
    co: Coefficients<T>,
) -> LocalPoint<T> {
    point_from_jet(sigma, &phi_jet(sigma, k, k_dot, co))
}

/// The element's end point and turn, for an element of length `length_m`
/// (per lane).
#[inline(always)]
pub fn local_end<T: Real>(length_m: T, k: V3<T>, k_dot: V3<T>) -> (LocalPoint<T>, LocalTurn<T>) {
    local_end_with(length_m, k, k_dot, coefficients_at(length_m, k, true))
}

/// [`local_end`] with its coefficients `co` already evaluated
/// ([`coefficients_at`] at σ = ℓ, with A): the same bits.
#[inline(always)]
pub fn local_end_with<T: Real>(
    length_m: T,
    k: V3<T>,
    k_dot: V3<T>,
    co: Coefficients<T>,
) -> (LocalPoint<T>, LocalTurn<T>) {
    let j = phi_jet(length_m, k, k_dot, co);
    let point = point_from_jet(length_m, &j);
    let (phi, pd) = (j.phi, j.phi_dot);
    let one = T::splat(1.0);
    let [b, bd, _] = coefficient_jet(j.co.b, &j);
    let [c, cd, _] = coefficient_jet(j.co.c, &j);
    let a = j.co.a[0];
    let skew = M3::skew(phi);
    let phi_phi = M3::outer(phi, phi);
    // [φ]×² = φφᵀ − y I.
    let rotation =
        (skew.scale(a) + phi_phi.scale(b)).add_diagonal(V3::splat([1.0; 3]).scale(one - b * j.y));
    let left_jacobian =
        (skew.scale(b) + phi_phi.scale(c)).add_diagonal(V3::splat([1.0; 3]).scale(one - c * j.y));
    let m1 = phi.cross(pd);
    let m2 = phi.cross(m1);
    let turn = LocalTurn {
        rotation,
        left_jacobian,
        spin: m2.scale_add(c, m1.scale_add(b, pd)),
        spin_dot: pd.cross(m1).scale_add(c, m2.scale_add(cd, m1.scale(bd))),
    };
    (point, turn)
}

//! Time derivatives of an element's Jacobians, for the velocity terms.
//!
//! The velocity-implicit step needs products G x with G = −∂Q/∂q̇ =
//! 2 ∫ ρS Jᵀ J̇ ds ([`crate::step::velocity_terms`]). J is built from two closed
//! forms per element ([`crate::geometry::helix`]): the centreline's Jacobian
//! ∂h(σ, k)/∂k = σ² ∂f/∂φ (f = J_l(φ) e₀, φ = σk) and the left Jacobian
//! J_l(φ) that turns the end frame. Their time derivatives along the
//! strain rates follow by the product rule from the same coefficients A, B,
//! C of y = |φ|² and their y-derivatives, which [`HelixCoefficients`]
//! already holds to second order: with ẏ = 2 φ·φ̇, Ḃ = B'ẏ, Ċ = C'ẏ,
//! (B')˙ = B''ẏ, (C')˙ = C''ẏ. Nothing is evaluated twice, nothing divides:
//! the reconstruction computes them beside the Jacobians in the same sweep
//! ([`crate::step::reconstruct::reconstruct_with_rates`]).

use glam::{DMat3, DVec3};

use crate::geometry::helix::{HelixCoefficients, outer, skew};

/// d/dt ∂h(σ, k)/∂k (metres² per second and unit strain rate) for φ = σk
/// moving at φ̇ = σk̇: the rate of [`crate::geometry::helix::centreline_jacobian_with`].
///
/// With L(p) = pe₀ᵀ + p_x I − 2e₀pᵀ (linear in p), ∂f/∂φ =
/// −B\[e₀\]× + L(Cφ) + 2B'(φ×e₀)φᵀ + 2C'(φ×(φ×e₀))φᵀ; term by term,
///
/// d/dt ∂f/∂φ = −Ḃ\[e₀\]× + L(Ċφ + Cφ̇) + u φᵀ + u' φ̇ᵀ,
///
/// u = 2(B'(φ×e₀))˙ + 2(C'(φ×(φ×e₀)))˙, u' = 2B'(φ×e₀) + 2C'(φ×(φ×e₀)):
/// two outer products, grouped by their right-hand vector.
pub fn centreline_jacobian_rate(
    sigma: f64,
    phi: DVec3,
    phi_rate: DVec3,
    co: &HelixCoefficients,
) -> DMat3 {
    let e0 = DVec3::X;
    let y_rate = 2.0 * phi.dot(phi_rate);
    let phi_x_e0 = phi.cross(e0);
    let phi_x_phi_x_e0 = phi.cross(phi_x_e0);
    let rate_x_e0 = phi_rate.cross(e0);
    let d_phi_x_phi_x_e0 = phi_rate.cross(phi_x_e0) + phi.cross(rate_x_e0);
    let p = phi * (co.c[1] * y_rate) + phi_rate * co.c[0];
    let linear = outer(p, e0) + DMat3::from_diagonal(DVec3::splat(p.x)) - outer(e0, p) * 2.0;
    let u = (phi_x_e0 * (co.b[2] * y_rate)
        + rate_x_e0 * co.b[1]
        + phi_x_phi_x_e0 * (co.c[2] * y_rate)
        + d_phi_x_phi_x_e0 * co.c[1])
        * 2.0;
    let u_rate = (phi_x_e0 * co.b[1] + phi_x_phi_x_e0 * co.c[1]) * 2.0;
    let df = skew(e0) * (-co.b[1] * y_rate) + linear + outer(u, phi) + outer(u_rate, phi_rate);
    df * (sigma * sigma)
}

/// d/dt J_l(φ) for φ moving at φ̇: the rate of
/// [`crate::geometry::helix::left_jacobian_with`], J_l = I + B\[φ\]× + C\[φ\]×².
pub fn left_jacobian_rate(phi: DVec3, phi_rate: DVec3, co: &HelixCoefficients) -> DMat3 {
    let y_rate = 2.0 * phi.dot(phi_rate);
    let s = skew(phi);
    let s_rate = skew(phi_rate);
    s * (co.b[1] * y_rate)
        + s_rate * co.b[0]
        + (s * s) * (co.c[1] * y_rate)
        + (s_rate * s + s * s_rate) * co.c[0]
}

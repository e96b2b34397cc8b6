//! The pressure term: hair denser than its rest density is pushed out.
//!
//! # Equation of state, not a pressure solve
//!
//! The peers split two ways. McAdams et al. (2009) solve for a pressure
//! on the grid (a Poisson problem per step), and Unreal's Niagara groom
//! solver carries a pressure grid; Blender's hair volume instead pulls
//! toward a "density target" with a "density strength" (its manual's
//! names), an equation of state: pressure is a function of the local
//! density, and its gradient is an explicit force. We take the equation of
//! state. It costs one pass over
//! the nodes and one over the samples, needs no solver, and is exactly
//! zero where no node is over its threshold, which is what the rest pose
//! needs ([`super::rest`]); its price is a stability bound, √P h < Δx,
//! that the default keeps with room (see
//! [`super::settings::InteractionSettings::pressure_m2_per_s2`]).
//!
//! # The form
//!
//! Each node's excess is e_n = max(ρ_n − ρ*_n, 0) / ρ̄ (a fraction of the
//! typical rest density), and a sample at x feels the acceleration
//! a = −P ∇ẽ(x), ẽ(x) = Σ w_n(x) e_n the trilinear interpolation of the
//! excess. Hair flows down the excess's gradient, out of the over-full
//! cells; where every node around a sample is at or below its threshold,
//! a is exactly zero.

use glam::DVec3;

use super::grid::Stencil;

/// Excess fraction e_n per node, written to `out` (as long as `density`),
/// from node densities (kg/m³), thresholds ρ*_n (kg/m³) and the typical
/// rest density ρ̄.
pub fn excess(density: &[f64], threshold: &[f64], typical_kg_per_m3: f64, out: &mut [f64]) {
    for ((e, rho), limit) in out.iter_mut().zip(density).zip(threshold) {
        *e = (rho - limit).max(0.0) / typical_kg_per_m3;
    }
}

/// The pressure's acceleration a = −P ∇ẽ at the point of `stencil`,
/// m/s², with P in m²/s² and the node excesses `excess`.
pub fn push_m_per_s2(stencil: &Stencil, excess: &[f64], pressure_m2_per_s2: f64) -> DVec3 {
    let mut gradient = DVec3::ZERO;
    for (node, g) in stencil.nodes.iter().zip(stencil.gradients) {
        let e = excess[*node];
        if e > 0.0 {
            gradient += e * g;
        }
    }
    -pressure_m2_per_s2 * gradient
}

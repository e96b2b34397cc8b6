//! Splat: strand samples spread their mass and momentum onto the grid's
//! nodes with the trilinear weights, giving the hair's density and its
//! mean velocity around each node.
//!
//! A sample stands for the hair of its quadrature weight: mass
//! m = ρS · w (kg). Node n gathers m_n = Σ w_n(x_i) m_i and
//! p_n = Σ w_n(x_i) m_i v_i, so ρ_n = m_n / Δx³ is the hair's density there
//! (kg of hair per m³ of space) and u_n = p_n / m_n its mass-weighted mean
//! velocity. Positions are in head coordinates (the grid's), velocities in
//! world coordinates: a mean of velocities does not care where the origin
//! is.

use glam::DVec3;

use super::grid::Grid;

/// One strand sample as the model sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplePoint {
    /// Position in head coordinates, metres.
    pub position_m: DVec3,
    /// Velocity in world coordinates, m/s.
    pub velocity_m_per_s: DVec3,
    /// Mass the sample stands for, kg (ρS times its quadrature weight).
    pub mass_kg: f64,
}

/// Mass and momentum on every node of a grid.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeSums {
    /// Σ w m per node, kg.
    pub mass_kg: Vec<f64>,
    /// Σ w m v per node, kg·m/s.
    pub momentum: Vec<DVec3>,
}

impl NodeSums {
    /// Density at node `n`, kg/m³.
    pub fn density_kg_per_m3(&self, grid: &Grid, n: usize) -> f64 {
        self.mass_kg[n] / grid.cell_volume_m3()
    }

    /// Mean velocity at node `n` (zero at an empty node), m/s.
    pub fn velocity_m_per_s(&self, n: usize) -> DVec3 {
        let m = self.mass_kg[n];
        if m > 0.0 {
            self.momentum[n] / m
        } else {
            DVec3::ZERO
        }
    }
}

/// Spreads `points` onto `grid`, reusing `sums`' buffers. Points outside
/// the grid are left out.
pub fn splat<'a>(
    grid: &Grid,
    points: impl IntoIterator<Item = &'a SamplePoint>,
    sums: &mut NodeSums,
) {
    let n = grid.node_count();
    sums.mass_kg.clear();
    sums.mass_kg.resize(n, 0.0);
    sums.momentum.clear();
    sums.momentum.resize(n, DVec3::ZERO);
    for p in points {
        let Some(stencil) = grid.stencil(p.position_m) else {
            continue;
        };
        for (node, w) in stencil.nodes.iter().zip(stencil.weights) {
            let m = w * p.mass_kg;
            sums.mass_kg[*node] += m;
            sums.momentum[*node] += m * p.velocity_m_per_s;
        }
    }
}

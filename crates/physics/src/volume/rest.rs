//! Rest density: how dense the hair is, node by node, in the groom's rest
//! pose, and the threshold above which the pressure term pushes.
//!
//! The threshold of node n is ρ*_n = max(ρ_rest,n, ρ̄) (1 + [`REST_SLACK`]),
//! where ρ_rest,n is the density the rest pose splats there and ρ̄ the
//! density the average sample of the rest pose sits in (mass-weighted:
//! Σ m_n ρ_n / Σ m_n). So
//!
//! - in the rest pose no node is above its threshold, and the pressure is
//!   exactly zero everywhere: the model cannot fight the rest shape;
//! - hair may gather anywhere up to the density hair typically has at rest
//!   (ρ̄), e.g. where it falls into space that was empty at rest, and near
//!   the roots, where the rest pose is denser than ρ̄, up to the rest
//!   pose's own density;
//! - beyond that it is pushed out, which is what keeps a head of hair from
//!   collapsing into a thin shell as its strands sag onto each other.
//!
//! A per-node threshold, not one density for the whole head, is what the
//! first point needs: a groom is far denser at the scalp than at the tips.

use super::grid::Grid;
use super::splat::{NodeSums, SamplePoint, splat_pieces};

/// Relative slack on the threshold, so that the round-off of carrying the
/// rest pose into head coordinates again cannot make a pressure at rest.
pub const REST_SLACK: f64 = 1e-6;

/// The grid and the per-node density thresholds of the rest pose.
#[derive(Clone, Debug, PartialEq)]
pub struct RestDensity {
    /// The grid, fitted to the rest pose.
    pub grid: Grid,
    /// ρ*_n per node, kg/m³.
    pub threshold_kg_per_m3: Vec<f64>,
    /// ρ̄: the density the average rest sample sits in, kg/m³.
    pub typical_kg_per_m3: f64,
}

impl RestDensity {
    /// The rest density of `points` (the rest pose, head coordinates, at
    /// rest) on a grid of cells of `cell_m` fitted to them with
    /// `margin_m` on each side; `None` without points or mass.
    pub fn new(points: &[SamplePoint], cell_m: f64, margin_m: f64) -> Option<RestDensity> {
        let grid = Grid::fitted(points.iter().map(|p| p.position_m), cell_m, margin_m)?;
        let mut sums = NodeSums::default();
        // The frames' splat, so that the rest pose sums exactly alike.
        let (mut pieces, mut cells) = (Vec::new(), Vec::new());
        splat_pieces(&grid, &[points], &mut sums, &mut pieces, &mut cells, false);
        let density: Vec<f64> = (0..grid.node_count())
            .map(|n| sums.density_kg_per_m3(&grid, n))
            .collect();
        let total: f64 = (0..sums.len()).map(|n| sums.mass_kg(n)).sum();
        if total <= 0.0 || !total.is_finite() {
            return None;
        }
        let typical = density
            .iter()
            .enumerate()
            .map(|(n, rho)| sums.mass_kg(n) * rho)
            .sum::<f64>()
            / total;
        let threshold = density
            .iter()
            .map(|rho| rho.max(typical) * (1.0 + REST_SLACK))
            .collect();
        Some(RestDensity {
            grid,
            threshold_kg_per_m3: threshold,
            typical_kg_per_m3: typical,
        })
    }
}

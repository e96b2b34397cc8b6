//! The splat ([`super::splat`]) of points held four to a group, lane by
//! lane, as the batch engine gathers them (`crate::batch::volume`): each
//! point's arithmetic is the scalar splat's, bit for bit, and the points
//! add to the nodes in the same order (a group's lanes in turn, the
//! groups in order), so the sums are those of the scalar splat of the
//! same points in that order.
//!
//! What lanes buy: the cell search ([`super::cell::Locator::locate_lanes`]) and the
//! eight corner weights times the mass run for four points at once, in
//! f64x4 with the points in lanes, where the scalar splat runs them one
//! point at a time with the axes in lanes (or none); and the gather writes
//! its lanes as they are, without spreading them point by point. Only the
//! eight scattered adds per point stay one point at a time: two points of
//! one group often share nodes, and their order fixes every bit.

use glam::DVec3;
use wide::f64x4;

use super::cell::{CellLanes, OUTSIDE};
use super::grid::Grid;
use super::splat::{NodeSums, SamplePoint, in_pieces, slices_in};

/// Four sample points ([`SamplePoint`]), lane by lane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointLanes {
    /// Positions in head coordinates, metres: x, y and z, lane by lane.
    pub position_m: [f64x4; 3],
    /// Velocities in world coordinates, m/s: x, y and z, lane by lane.
    pub velocity_m_per_s: [f64x4; 3],
    /// Masses the points stand for, kg (zero for a batch's padding).
    pub mass_kg: f64x4,
}

impl PointLanes {
    /// Lane `k`'s point.
    pub fn lane(&self, k: usize) -> SamplePoint {
        let [x, y, z] = self.position_m.map(|a| a.as_array()[k]);
        let [u, v, w] = self.velocity_m_per_s.map(|a| a.as_array()[k]);
        SamplePoint {
            position_m: DVec3::new(x, y, z),
            velocity_m_per_s: DVec3::new(u, v, w),
            mass_kg: self.mass_kg.as_array()[k],
        }
    }

    /// Lane `k`'s velocity, m/s.
    #[inline(always)]
    pub fn velocity(&self, k: usize) -> DVec3 {
        let [u, v, w] = self.velocity_m_per_s.map(|a| a.as_array()[k]);
        DVec3::new(u, v, w)
    }
}

/// Adds the four points of `p`, in lane order, to the eight nodes around
/// each, in `cell` (theirs, [`super::cell::Locator::locate_lanes`]). Per point this is
/// [`super::splat`]'s `add_point`: the weights w_c = (x_i y_j) z_k, the
/// mass m w_c, and node += (m w_c)·[1, v].
#[inline(always)]
fn add_lanes(offsets: &[usize; 8], p: &PointLanes, cell: &CellLanes, nodes: &mut [f64x4]) {
    let one = f64x4::splat(1.0);
    let [x, y, z] = cell.frac.map(|f| [one - f, f]);
    // Corner c's weight times the mass, lane by lane, in the order of
    // `Locator::offsets`.
    let mass: [[f64; 4]; 8] =
        std::array::from_fn(|c| (x[c & 1] * y[(c >> 1) & 1] * z[c >> 2] * p.mass_kg).to_array());
    let masses = p.mass_kg.as_array();
    for k in 0..4 {
        let first = cell.first[k];
        if first == OUTSIDE || masses[k] == 0.0 {
            continue;
        }
        let v = p.velocity(k);
        let per_mass = f64x4::new([1.0, v.x, v.y, v.z]);
        // One bounds check for the cell's nodes, not one per node.
        let first = first as usize;
        let around = &mut nodes[first..=first + offsets[7]];
        for (offset, m) in offsets.iter().zip(&mass) {
            around[*offset] += f64x4::splat(m[k]) * per_mass;
        }
    }
}

/// Groups whose cells are found before any of them is added: the cell
/// search is a long chain of dependent instructions (a division, a floor,
/// the index), and with the cells of a block found first the adds' node
/// addresses are loads, so the processor can run ahead across points.
const BLOCK: usize = 32;

/// Spreads the points of `parts` (groups of four, the parts one after
/// the other, cut between groups) onto `grid`, as [`super::splat::splat_pieces`]
/// does: in [`super::splat::SPLAT_PIECES`] fixed pieces, in parallel when
/// `parallel`, with the same numbers either way; zero-mass lanes and
/// points outside the grid add nothing. Every group's cells, the parts one
/// after the other, are written to `cells` (resized).
pub fn splat_lane_pieces(
    grid: &Grid,
    parts: &[&[PointLanes]],
    sums: &mut NodeSums,
    pieces: &mut Vec<NodeSums>,
    cells: &mut Vec<CellLanes>,
    parallel: bool,
) {
    let total: usize = parts.iter().map(|p| p.len()).sum();
    cells.resize(total, CellLanes::default());
    let locator = grid.locator();
    let one = |range: std::ops::Range<usize>, nodes: &mut [f64x4], cells: &mut [CellLanes]| {
        let mut at = 0;
        for part in slices_in(parts, range) {
            for block in part.chunks(BLOCK) {
                let cells = &mut cells[at..at + block.len()];
                at += block.len();
                for (p, cell) in block.iter().zip(cells.iter_mut()) {
                    *cell = locator.locate_lanes(&p.position_m);
                }
                for (p, cell) in block.iter().zip(cells.iter()) {
                    add_lanes(&locator.offsets, p, cell, nodes);
                }
            }
        }
    };
    in_pieces(grid, (sums, pieces), cells, parallel, one);
}

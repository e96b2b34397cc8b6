//! Splat: the model's points spread their mass and momentum onto the
//! grid's nodes with the trilinear weights, giving the hair's density and
//! its mean velocity around each node.
//!
//! A point stands for the hair of its pair of quadrature nodes
//! ([`super::pair_points`]): mass m = ρS ℓ (w_a + w_b) (kg). Node n
//! gathers m_n = Σ w_n(x_i) m_i and p_n = Σ w_n(x_i) m_i v_i, so ρ_n = m_n / Δx³ is the hair's density there
//! (kg of hair per m³ of space) and u_n = p_n / m_n its mass-weighted mean
//! velocity. Positions are in head coordinates (the grid's), velocities in
//! world coordinates: a mean of velocities does not care where the origin
//! is.
//!
//! # Layout
//!
//! A node's mass and momentum sit together in one f64x4, [m, p_x, p_y,
//! p_z]: a sample adds m_i w_n [1, v_x, v_y, v_z] to each of its eight
//! nodes with one four-lane multiply and add, and the two nodes of a cell
//! edge along x share a cache line. The lanes' arithmetic is the scalar
//! one (m·1 is m), so the sums are those of three momenta and a mass
//! added one by one, bit for bit.

use glam::DVec3;
use rayon::prelude::*;
use wide::f64x4;

use super::cell::{Cell, Locator};
use super::grid::Grid;

/// One point of the model: a pair of quadrature nodes' centre of mass
/// ([`super::pair_points`]), or any point with a mass and a velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplePoint {
    /// Position in head coordinates, metres.
    pub position_m: DVec3,
    /// Velocity in world coordinates, m/s.
    pub velocity_m_per_s: DVec3,
    /// Mass the point stands for, kg (ρS ℓ times its nodes' quadrature
    /// weights).
    pub mass_kg: f64,
}

/// Mass and momentum on every node of a grid.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeSums {
    /// Per node [Σ w m (kg), Σ w m v (kg·m/s, three lanes)].
    nodes: Vec<f64x4>,
}

impl NodeSums {
    /// Σ w m at node `n`, kg.
    pub fn mass_kg(&self, n: usize) -> f64 {
        self.nodes[n].as_array()[0]
    }

    /// Σ w m v at node `n`, kg·m/s.
    pub fn momentum(&self, n: usize) -> DVec3 {
        let [_, x, y, z] = *self.nodes[n].as_array();
        DVec3::new(x, y, z)
    }

    /// Number of nodes summed (zero before the first splat).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether no node has been summed yet.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Density at node `n`, kg/m³.
    pub fn density_kg_per_m3(&self, grid: &Grid, n: usize) -> f64 {
        self.mass_kg(n) / grid.cell_volume_m3()
    }

    /// Mean velocity at node `n` (zero at an empty node), m/s.
    pub fn velocity_m_per_s(&self, n: usize) -> DVec3 {
        let m = self.mass_kg(n);
        if m > 0.0 {
            self.momentum(n) / m
        } else {
            DVec3::ZERO
        }
    }
}

/// Adds point `p`, in `cell` ([`Locator::locate`]), to the eight nodes
/// around it.
#[inline(always)]
fn add_point(locator: &Locator, p: &SamplePoint, cell: Option<Cell>, nodes: &mut [f64x4]) {
    if p.mass_kg == 0.0 {
        return;
    }
    let Some(cell) = cell else {
        return;
    };
    let v = p.velocity_m_per_s;
    let per_mass = f64x4::new([1.0, v.x, v.y, v.z]);
    // One bounds check for the cell's nodes, not one per node.
    let offsets = &locator.offsets;
    let first = cell.first as usize;
    let around = &mut nodes[first..=first + offsets[7]];
    for (offset, w) in offsets.iter().zip(cell.weights()) {
        let m = w * p.mass_kg;
        around[*offset] += f64x4::splat(m) * per_mass;
    }
}

/// Pieces [`splat_pieces`] cuts the points into, whatever the thread
/// count: each piece splats into sums of its own, and the pieces are
/// added node by node in order, so a parallel splat gives the serial
/// one's numbers bit for bit. Four keeps two to eight cores busy at four
/// copies of the node sums (a 2 cm grid around a head: about 1 MB each).
pub const SPLAT_PIECES: usize = 4;

/// Nodes one task adds up when the pieces are summed (and one task of
/// the node pass, [`super::field`]).
pub(super) const NODES_PER_TASK: usize = 4096;

/// Spreads the points of `parts` (in order, cut anywhere) onto `grid` in
/// [`SPLAT_PIECES`] pieces, each into its buffer of `pieces` (reused),
/// in parallel when `parallel`; the pieces' sums are added into `sums`.
/// Points outside the grid are left out, and so are points of zero mass
/// (a batch's padding): they would add only zeros. Every point's cell
/// (`None` outside), the parts one after the other, is written to `cells`
/// (resized), for the read-back to reuse.
pub fn splat_pieces(
    grid: &Grid,
    parts: &[&[SamplePoint]],
    sums: &mut NodeSums,
    pieces: &mut Vec<NodeSums>,
    cells: &mut Vec<Option<Cell>>,
    parallel: bool,
) {
    let total: usize = parts.iter().map(|p| p.len()).sum();
    cells.resize(total, None);
    let locator = grid.locator();
    let one = |range: std::ops::Range<usize>, nodes: &mut [f64x4], cells: &mut [Option<Cell>]| {
        let points = slices_in(parts, range).flatten();
        for (p, cell) in points.zip(cells.iter_mut()) {
            *cell = locator.locate(p.position_m);
            add_point(&locator, p, *cell, nodes);
        }
    };
    in_pieces(grid, (sums, pieces), cells, parallel, one);
}

/// Cuts `items` (points, or groups of points, in order) into
/// [`SPLAT_PIECES`] pieces, has `one(range, nodes, items of the range)`
/// splat each piece into its zeroed buffer of `pieces`, in parallel when
/// `parallel`, and adds the pieces node by node, in order, into `sums`:
/// the one piece-and-sum scheme of every splat.
pub(super) fn in_pieces<T: Send>(
    grid: &Grid,
    (sums, pieces): (&mut NodeSums, &mut Vec<NodeSums>),
    items: &mut [T],
    parallel: bool,
    one: impl Fn(std::ops::Range<usize>, &mut [f64x4], &mut [T]) + Sync,
) {
    let total = items.len();
    let bounds: Vec<usize> = (0..=SPLAT_PIECES)
        .map(|k| k * total / SPLAT_PIECES)
        .collect();
    pieces.resize_with(SPLAT_PIECES, NodeSums::default);
    let mut item_pieces = Vec::with_capacity(SPLAT_PIECES);
    let mut rest = items;
    for k in 0..SPLAT_PIECES {
        let (piece, after) = rest.split_at_mut(bounds[k + 1] - bounds[k]);
        item_pieces.push(piece);
        rest = after;
    }
    let one = |(k, (piece, items)): (usize, (&mut NodeSums, &mut &mut [T]))| {
        piece.nodes.clear();
        piece.nodes.resize(grid.node_count(), f64x4::ZERO);
        one(bounds[k]..bounds[k + 1], &mut piece.nodes, items);
    };
    if parallel {
        let pieces = pieces.par_iter_mut().zip(item_pieces.par_iter_mut());
        pieces.enumerate().for_each(one);
    } else {
        let pieces = pieces.iter_mut().zip(item_pieces.iter_mut());
        pieces.enumerate().for_each(one);
    }
    sums.nodes.resize(grid.node_count(), f64x4::ZERO);
    let pieces = &*pieces;
    let add = |(task, sum): (usize, &mut [f64x4])| {
        let start = task * NODES_PER_TASK;
        for (i, s) in sum.iter_mut().enumerate() {
            let node = start + i;
            *s = pieces
                .iter()
                .map(|piece| piece.nodes[node])
                .fold(f64x4::ZERO, |a, b| a + b);
        }
    };
    for_each_node_block(&mut sums.nodes, parallel, add);
}

/// Runs `f` on each block of [`NODES_PER_TASK`] nodes of `nodes` with the
/// block's number, in parallel when `parallel`: every node's numbers its
/// own, so the same bits either way.
pub(super) fn for_each_node_block<T: Send>(
    nodes: &mut [T],
    parallel: bool,
    f: impl Fn((usize, &mut [T])) + Sync + Send,
) {
    if parallel {
        let chunks = nodes.par_chunks_mut(NODES_PER_TASK);
        chunks.enumerate().for_each(f);
    } else {
        let chunks = nodes.chunks_mut(NODES_PER_TASK);
        chunks.enumerate().for_each(f);
    }
}

/// The slices of `parts` whose items' indices in the whole (parts one
/// after the other) lie in `range`.
pub(super) fn slices_in<'a, T>(
    parts: &'a [&'a [T]],
    range: std::ops::Range<usize>,
) -> impl Iterator<Item = &'a [T]> {
    let mut start = 0;
    parts.iter().map(move |part| {
        let (from, to) = (start, start + part.len());
        start = to;
        let lo = range.start.clamp(from, to) - from;
        let hi = range.end.clamp(from, to) - from;
        &part[lo..hi]
    })
}

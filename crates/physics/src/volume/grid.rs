//! The grid the hair volume lives on: a box of cubic cells fitted to the
//! head and its hair at rest, fixed in head coordinates, and the trilinear
//! stencil that ties a point to the eight nodes around it.
//!
//! Fixed in head coordinates, the grid moves with the head, so a node
//! stands for the same place on the head at every frame and the rest
//! density of that place ([`super::rest`]) can be compared with today's.
//! Nodes sit on the cell corners; a point inside the box spreads onto the
//! eight corners of its cell with the trilinear weights
//! w = Π (1 − |x − x_n| / Δx), which sum to one, and reads them back with
//! the same weights (PIC: the grid's velocity is read back as it is, no
//! FLIP increment; a FLIP blend would need the grid velocity of the
//! previous frame and adds noise the friction would have to damp).
//! A point outside the box takes no part in the model.

use glam::DVec3;

use super::cell::{Cell, Locator};

/// Most nodes a grid may have: 2²¹ (about 130³), 2.1 M f64 masses and
/// momenta, 67 MB. A cell so small that the box would need more is
/// coarsened to fit.
pub const MAX_NODES: usize = 1 << 21;

/// A box of cubic cells, in head coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Corner of node (0, 0, 0), metres.
    pub origin_m: DVec3,
    /// Edge of a cell, metres.
    pub cell_m: f64,
    /// Nodes along x, y and z (at least 2 each).
    pub dims: [usize; 3],
}

/// The eight nodes around a point, their weights and the weights'
/// gradients (1/m).
#[derive(Clone, Copy, Debug)]
pub struct Stencil {
    /// Node indices.
    pub nodes: [usize; 8],
    /// Trilinear weights; they sum to one.
    pub weights: [f64; 8],
    /// ∇w of each weight at the point, 1/m; they sum to zero.
    pub gradients: [DVec3; 8],
}

impl Grid {
    /// The grid of cells of `cell_m` that holds every point of `points`
    /// with `margin_m` to spare on each side; `None` without points.
    pub fn fitted(
        points: impl IntoIterator<Item = DVec3>,
        cell_m: f64,
        margin_m: f64,
    ) -> Option<Grid> {
        let (lo, hi) = points
            .into_iter()
            .fold(None, |acc: Option<(DVec3, DVec3)>, p| {
                Some(acc.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
            })?;
        let (lo, hi) = (lo - DVec3::splat(margin_m), hi + DVec3::splat(margin_m));
        let extent = hi - lo;
        let mut cell = cell_m;
        let count = |cell: f64| {
            extent
                .to_array()
                .map(|e| (e / cell).ceil().max(1.0) as usize + 1)
        };
        while count(cell).iter().product::<usize>() > MAX_NODES {
            cell *= 1.25;
        }
        Some(Grid {
            origin_m: lo,
            cell_m: cell,
            dims: count(cell),
        })
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.dims.iter().product()
    }

    /// The grid made ready for finding cells ([`Locator`]).
    pub fn locator(&self) -> Locator {
        Locator::new(self)
    }

    /// Index of node (i, j, k).
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        (k * self.dims[1] + j) * self.dims[0] + i
    }

    /// Position of node (i, j, k), head coordinates, metres.
    pub fn node_position(&self, i: usize, j: usize, k: usize) -> DVec3 {
        self.origin_m + DVec3::new(i as f64, j as f64, k as f64) * self.cell_m
    }

    /// Volume of one cell, m³ (also the volume a node stands for).
    pub fn cell_volume_m3(&self) -> f64 {
        self.cell_m.powi(3)
    }

    /// The stencil of point `p` (head coordinates), or `None` outside the box.
    #[inline]
    pub fn stencil(&self, p: DVec3) -> Option<Stencil> {
        let locator = self.locator();
        Some(locator.stencil(&locator.locate(p)?))
    }

    /// The cell holding `p` (head coordinates), or `None` outside the box
    /// ([`Locator::locate`]).
    #[inline]
    pub fn locate(&self, p: DVec3) -> Option<Cell> {
        self.locator().locate(p)
    }
}

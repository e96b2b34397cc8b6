//! Finding the cell of the grid ([`super::grid`]) that holds a point, and
//! the point's trilinear weights in it: what every sample's splat and its
//! read-back start with. The splat finds each sample's cell once per
//! frame and the read-back reuses it ([`super::field::VolumeField::cells`]).
//!
//! A point x (head coordinates) sits at x' = (x − origin) / Δx in cell
//! units; its cell along an axis is ⌊x'⌋ (the last cell for a point on the
//! box's far face) and its place in the cell f = x' − ⌊x'⌋. The corner
//! nodes' weights are products of the 1-D weights 1 − f (lower node) and
//! f (upper node), which sum to one.
//!
//! [`Locator`] keeps what a search needs ready (each axis's last cell and
//! far face, the node strides as f64, the corner offsets): the cell's
//! first node is found in f64, where the node indices are exact integers
//! (a grid has at most 2²¹ nodes), and turned into an index once, exactly
//! (x + 2⁵² has x in its low bits), instead of a conversion per axis (an
//! f64 to usize conversion is about ten instructions on x86-64 without
//! AVX-512) and the index arithmetic after.

use glam::DVec3;
use wide::f64x4;

use super::grid::{Grid, Stencil};

/// The cell of the grid holding a point ([`Locator::locate`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// Index of the cell's lowest corner node (u32, so that a kept cell
    /// and its `Option` take 32 bytes: a grid has at most 2²¹ nodes).
    pub first: u32,
    /// The point's position in the cell, 0..=1 per axis.
    pub frac: [f64; 3],
}

impl Cell {
    /// Per axis, the 1-D weights of the lower and the upper node,
    /// [1 − f, f].
    #[inline(always)]
    pub fn one_d(&self) -> [[f64; 2]; 3] {
        self.frac.map(|f| [1.0 - f, f])
    }

    /// The trilinear weights w = wx wy wz of the eight corners, in the
    /// order of [`Locator::offsets`]; they sum to one.
    #[inline(always)]
    pub fn weights(&self) -> [f64; 8] {
        let [x, y, z] = self.one_d();
        std::array::from_fn(|c| x[c & 1] * y[(c >> 1) & 1] * z[c >> 2])
    }
}

/// The cells of four points, lane by lane ([`Locator::locate_lanes`]):
/// what the batch engine's splat keeps for its read-back, 28 bytes a
/// point instead of an `Option<Cell>`'s 40.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CellLanes {
    /// Each point's cell's first node, [`OUTSIDE`] for a point outside the
    /// box.
    pub first: [u32; 4],
    /// Each point's position in its cell, per axis (x, y, z), lane by lane.
    pub frac: [f64x4; 3],
}

/// [`CellLanes::first`] of a point outside the box (a grid has at most
/// 2²¹ nodes, so no cell starts there).
pub const OUTSIDE: u32 = u32::MAX;

impl CellLanes {
    /// Lane `k`'s cell, as [`Locator::locate`] finds it; `None` outside.
    #[inline(always)]
    pub fn lane(&self, k: usize) -> Option<Cell> {
        let first = self.first[k];
        (first != OUTSIDE).then(|| Cell {
            first,
            frac: self.frac.map(|f| f.as_array()[k]),
        })
    }
}

/// A grid made ready for finding cells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Locator {
    /// The grid's origin (x, y, z, 0), metres.
    origin_m: f64x4,
    cell_m: f64,
    /// Per axis, the last cell's index (and 0).
    last_cell: f64x4,
    /// Per axis, the far face in cell units, the last cell's index + 1
    /// (and 0).
    far_face: f64x4,
    /// Nodes along x, and in an xy layer.
    strides: [f64; 2],
    /// Offsets of a cell's eight corner nodes from its first
    /// ([`Cell::first`]); corner c has bit a of c set when it is the upper
    /// node along axis a. The last is the largest.
    pub offsets: [usize; 8],
}

impl Locator {
    /// The locator of `grid`.
    pub fn new(grid: &Grid) -> Self {
        let [nx, ny, _] = grid.dims;
        let step = [1, nx, nx * ny];
        Self {
            origin_m: f64x4::new(grid.origin_m.extend(0.0).to_array()),
            cell_m: grid.cell_m,
            last_cell: f64x4::new(lanes(|a| (grid.dims[a] - 2) as f64)),
            far_face: f64x4::new(lanes(|a| (grid.dims[a] - 2) as f64 + 1.0)),
            strides: [nx as f64, (nx * ny) as f64],
            offsets: std::array::from_fn(|c| (0..3).map(|a| ((c >> a) & 1) * step[a]).sum()),
        }
    }

    /// The cell holding `p` (head coordinates): its first corner node and
    /// `p`'s position in it; `None` outside the box. The three axes go in
    /// the lanes of one f64x4 (the fourth holds 0, inside), each lane's
    /// arithmetic the scalar one: x' = (x − origin) / Δx, inside when
    /// 0 ≤ x' ≤ far face, cell min(last cell, ⌊x'⌋), f = x' − cell.
    #[inline(always)]
    pub fn locate(&self, p: DVec3) -> Option<Cell> {
        let local = (f64x4::new([p.x, p.y, p.z, 0.0]) - self.origin_m) / f64x4::splat(self.cell_m);
        let inside = local.simd_ge(f64x4::ZERO) & local.simd_le(self.far_face);
        if inside.to_bitmask() != 0b1111 {
            return None;
        }
        // (No NaN is left: a NaN is never inside.)
        let base = self.last_cell.fast_min(local.floor());
        let [fx, fy, fz, _] = (local - base).to_array();
        let [bx, by, bz, _] = base.to_array();
        let [sy, sz] = self.strides;
        Some(Cell {
            first: exact_index(bx + by * sy + bz * sz),
            frac: [fx, fy, fz],
        })
    }

    /// The cells of four points at `position_m` (head coordinates, axis by
    /// axis, lane by lane): each lane's arithmetic that of
    /// [`Self::locate`], the axes now in separate registers and the points
    /// in lanes, so each lane finds exactly what `locate` finds.
    #[inline(always)]
    pub fn locate_lanes(&self, position_m: &[f64x4; 3]) -> CellLanes {
        let origin = self.origin_m.as_array();
        let (last, far) = (self.last_cell.as_array(), self.far_face.as_array());
        let cell = f64x4::splat(self.cell_m);
        let local: [f64x4; 3] =
            std::array::from_fn(|a| (position_m[a] - f64x4::splat(origin[a])) / cell);
        let inside = (0..3).fold(f64x4::splat(f64::from_bits(u64::MAX)), |all, a| {
            all & local[a].simd_ge(f64x4::ZERO) & local[a].simd_le(f64x4::splat(far[a]))
        });
        let base: [f64x4; 3] =
            std::array::from_fn(|a| f64x4::splat(last[a]).fast_min(local[a].floor()));
        let [sy, sz] = self.strides;
        let index = base[0] + base[1] * f64x4::splat(sy) + base[2] * f64x4::splat(sz);
        let (index, inside) = (index.to_array(), inside.to_bitmask());
        CellLanes {
            first: std::array::from_fn(|k| {
                if inside & (1 << k) != 0 {
                    exact_index(index[k])
                } else {
                    OUTSIDE
                }
            }),
            frac: std::array::from_fn(|a| local[a] - base[a]),
        }
    }

    /// The stencil of a point in `cell`: its nodes, weights and the
    /// weights' gradients.
    #[inline]
    pub fn stencil(&self, cell: &Cell) -> Stencil {
        let inv = 1.0 / self.cell_m;
        // Per axis the 1-D weight of the lower and upper node, and its
        // derivative (1/m).
        let [x, y, z] = cell.one_d();
        let d = [-inv, inv];
        Stencil {
            nodes: self.offsets.map(|o| cell.first as usize + o),
            weights: cell.weights(),
            gradients: std::array::from_fn(|c| {
                let (i, j, k) = (c & 1, (c >> 1) & 1, c >> 2);
                DVec3::new(d[i] * y[j] * z[k], x[i] * d[j] * z[k], x[i] * y[j] * d[k])
            }),
        }
    }
}

/// Four lanes: `f(axis)` for the three axes, then 0.
fn lanes(f: impl Fn(usize) -> f64) -> [f64; 4] {
    [f(0), f(1), f(2), 0.0]
}

/// 2⁵²: from 2⁵² to 2⁵³ the f64s are the integers, with the integer part
/// in the low 52 bits of the mantissa.
const TWO_POW_52: f64 = 4_503_599_627_370_496.0;

/// `x` as an index, for an `x` that is an integer from 0 to 2³² − 1
/// (exactly): x + 2⁵² is exact, and its mantissa's low bits are x. Two
/// instructions where `as u32` takes about six.
#[inline(always)]
fn exact_index(x: f64) -> u32 {
    (x + TWO_POW_52).to_bits() as u32
}

//! Which points can feel the head's collider at all: a screen run before
//! each lookup of the signed distance field, on the step's contact
//! ([`crate::batch::contact`]) and the guard's measure of it ([`crate::batch::guard`]).
//!
//! A lookup is eight grid values, a gradient and a force, per point; most
//! points of a head of hair are nowhere near the scalp. [`NearCells`] keeps
//! one bit per grid cell, set where some point of the cell can be within
//! the contact skin, and [`SkinTest`] takes a point into the grid and
//! reads its bit. The test is exact: a point it rejects has a force of
//! exactly zero, so results do not depend on it (module docs of
//! [`crate::batch::contact`], "Cost").

use glam::{DMat3, DVec3};

use std::sync::Arc;

use crate::collision::{ContactInputs, ContactSettings, SignedDistanceField};
use crate::motion::RigidMotion;

/// The eight corners of a grid cell, as offsets.
const CELL_CORNERS: [(usize, usize, usize); 8] = [
    (0, 0, 0),
    (1, 0, 0),
    (0, 1, 0),
    (1, 1, 0),
    (0, 0, 1),
    (1, 0, 1),
    (0, 1, 1),
    (1, 1, 1),
];

/// Slack of the cell test, metres: far above the rounding of a trilinear
/// lookup (1e-18 m on centimetre distances), far below anything physical.
const CORNER_MARGIN_M: f64 = 1e-12;

/// Which cells of a field's grid can hold a point within the contact skin:
/// one bit per cell, set where the lowest of its eight corner values is
/// within the skin (the lookup interpolates between them, so a point of a
/// cell with every corner beyond the skin feels no force). A skipped point
/// costs one bit instead of eight grid values and the gradient: most
/// points of a head of hair are nowhere near the scalp. 2 bits per cell
/// (the set and the set grown by a cell): 512 KiB for the largest field
/// ([`MAX_CELLS`](crate::collision::sdf::MAX_CELLS)).
#[derive(Clone, Debug, PartialEq)]
pub struct NearCells {
    /// Cell i's bit at index i < `count`; then, at `count` + i, the same
    /// set grown by one cell along every axis (set where cell i or one of
    /// its 26 neighbours is near). The exact test reads the first half; the
    /// f32 lane screen ([`super::lane_screen`]) reads a point's own cell
    /// where it is well inside it, and the grown set where it is within
    /// rounding of a face, so that rounding can never move it out of a
    /// near cell's reach.
    bits: Vec<u64>,
    cells: [usize; 3],
    count: usize,
}

impl NearCells {
    /// The cells of `field` that may be within `skin_m` of its surface.
    pub fn new(field: &SignedDistanceField, skin_m: f64) -> Self {
        let cells = field.dims.map(|d| d.saturating_sub(1));
        let count = cells[0] * cells[1] * cells[2];
        let mut bits = vec![0u64; (2 * count).div_ceil(64)];
        for z in 0..cells[2] {
            for y in 0..cells[1] {
                for x in 0..cells[0] {
                    let corners = CELL_CORNERS.map(|(dx, dy, dz)| field.at(x + dx, y + dy, z + dz));
                    let lowest = corners.iter().copied().fold(f64::INFINITY, f64::min);
                    // An interpolated value can round below its lowest
                    // corner by an ulp or so: the margin keeps the test on
                    // the safe side. A NaN corner counts as near (the
                    // lookup would give a NaN force, not none).
                    if corners.iter().any(|c| c.is_nan()) || lowest <= skin_m + CORNER_MARGIN_M {
                        let i = x + cells[0] * (y + cells[1] * z);
                        bits[i / 64] |= 1 << (i % 64);
                    }
                }
            }
        }
        grow_by_one_cell(&mut bits, cells, count);
        Self { bits, cells, count }
    }

    /// Cells in the grid.
    pub fn cell_count(&self) -> usize {
        self.count
    }

    /// Cells along x, y and z.
    pub fn cells(&self) -> [usize; 3] {
        self.cells
    }

    /// Whether cell (x, y, z) may be within the skin.
    #[inline(always)]
    pub fn contains(&self, x: usize, y: usize, z: usize) -> bool {
        let i = x + self.cells[0] * (y + self.cells[1] * z);
        i < self.count && bit(&self.bits, i)
    }

    /// For `index` = x + cells_x (y + cells_y z) below [`Self::cell_count`],
    /// whether that cell may be within the skin; for `count` + that index,
    /// whether it or one of its neighbours may be.
    #[inline(always)]
    pub fn screen_contains(&self, index: usize) -> bool {
        bit(&self.bits, index)
    }
}

/// Bit `i` of `bits` (false past the end).
#[inline(always)]
fn bit(bits: &[u64], i: usize) -> bool {
    bits.get(i / 64)
        .is_some_and(|word| word & (1 << (i % 64)) != 0)
}

/// Sets, in the second half of `bits` (from index `count`), the first
/// half's cells (one per cell of a `cells` grid, x fastest) with every set
/// cell's 26 neighbours.
fn grow_by_one_cell(bits: &mut [u64], cells: [usize; 3], count: usize) {
    let index = |x: usize, y: usize, z: usize| x + cells[0] * (y + cells[1] * z);
    let around = |c: usize, n: usize| c.saturating_sub(1)..(c + 2).min(n);
    for z in 0..cells[2] {
        for y in 0..cells[1] {
            for x in 0..cells[0] {
                if !bit(bits, index(x, y, z)) {
                    continue;
                }
                for nz in around(z, cells[2]) {
                    for ny in around(y, cells[1]) {
                        for nx in around(x, cells[0]) {
                            let i = count + index(nx, ny, nz);
                            bits[i / 64] |= 1 << (i % 64);
                        }
                    }
                }
            }
        }
    }
}

/// The head's collider for one step, with its [`NearCells`]: whether a
/// point can feel it.
#[derive(Clone, Copy, Debug)]
pub struct SkinTest<'a> {
    /// The contact inputs the lookups use.
    pub inputs: ContactInputs<'a>,
    /// The cells that may be within the skin.
    pub near: &'a NearCells,
    /// The head's frame transposed: world offsets to head coordinates.
    body_from_world: DMat3,
}

impl<'a> SkinTest<'a> {
    /// The test for `inputs`; `near` must be [`NearCells::new`] of the
    /// inputs' collider and skin.
    pub fn new(inputs: ContactInputs<'a>, near: &'a NearCells) -> Self {
        Self {
            inputs,
            near,
            body_from_world: inputs.head.world_from_body.transpose(),
        }
    }

    /// The test for the head moving as `motion`, with the step length
    /// `h_secs` the contact's stiffness is set for; `None` without a
    /// `collider` (with its near cells).
    pub fn of_head(
        collider: &'a Option<(Arc<SignedDistanceField>, NearCells)>,
        settings: ContactSettings,
        motion: &'a RigidMotion,
        h_secs: f64,
    ) -> Option<Self> {
        collider.as_ref().map(|(collider, near)| {
            let inputs = ContactInputs {
                collider,
                head: motion,
                settings,
                h_secs,
            };
            Self::new(inputs, near)
        })
    }

    /// Whether the point at `point_m` (world) can feel the collider: false
    /// only where [`ContactInputs::force`] is exactly zero, because the
    /// point is outside the field's grid or in a cell that is not
    /// [`NearCells`]. The position is computed with the same operations as
    /// in the full lookup, so the cell is the one the lookup would use.
    #[inline(always)]
    pub fn may_touch(&self, point_m: DVec3) -> bool {
        let field = self.inputs.collider;
        let local = self.body_from_world * (point_m - self.inputs.head.position_m);
        let g = (local - field.origin_m) / field.cell_m;
        let max = |d: usize| d.saturating_sub(1) as f64;
        if g.min_element() < 0.0
            || g.x > max(field.dims[0])
            || g.y > max(field.dims[1])
            || g.z > max(field.dims[2])
        {
            return false;
        }
        let cell = |a: usize| (g[a] as usize).min(field.dims[a].saturating_sub(2));
        self.near.contains(cell(0), cell(1), cell(2))
    }

    /// Whether a point at `point_m` (world) moving at `velocity_m_per_s`
    /// can feel the collider during the step: [`Self::may_touch`] where it
    /// is, and with `implicit` (the Exact steps' implicit contact,
    /// [`ContactInputs::implicit_force`], which also acts on a point that
    /// will enter the skin during the step) where it is headed.
    #[inline(always)]
    pub fn may_feel(&self, point_m: DVec3, velocity_m_per_s: DVec3, implicit: bool) -> bool {
        if self.may_touch(point_m) {
            return true;
        }
        let h = self.inputs.h_secs;
        implicit
            && self.may_touch(point_m + h * (velocity_m_per_s - self.surface_velocity(point_m)))
    }

    /// The velocity of the head's surface at world point `point_m`, m/s.
    fn surface_velocity(&self, point_m: DVec3) -> DVec3 {
        let head = self.inputs.head;
        head.velocity_m_per_s
            + head
                .angular_velocity_rad_per_s
                .cross(point_m - head.position_m)
    }
}

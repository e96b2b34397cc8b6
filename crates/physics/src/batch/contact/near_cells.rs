//! Which points can feel the head's collider at all: a screen run before
//! each lookup of the signed distance field, on the step's contact
//! ([`crate::batch::contact`]) and the guard's measure of it ([`crate::batch::guard`]).
//!
//! A lookup is eight grid values, a gradient and a force, per point; most
//! points of a head of hair are nowhere near the scalp. [`NearCells`] keeps
//! per grid cell the lowest distance any point of it can have from the
//! surface, and [`SkinTest`] takes a point into the grid and compares its
//! cell's value with the skin plus how far the point moves towards the
//! surface in a step. The test is exact: a point it rejects has a force of
//! exactly zero, so results do not depend on it (module docs of
//! [`crate::batch::contact`], "Cost").

use std::cmp::Ordering;

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

/// Relative slack on the exact test's reach h |v − v_surface|: the field's
/// normal is unit to round-off (1e-15), so h |v_rel · n| ≤ reach.
const REACH_SLACK: f64 = 1e-9;

/// How far from the head's surface each cell of a field's grid lies: per
/// cell, the lowest of its eight corner values (the lookup interpolates
/// between them, so no point of the cell is nearer than that). Whether a
/// point can feel the contact law then costs one value instead of eight
/// grid values and the gradient: most points of a head of hair are
/// nowhere near the scalp. Two f32 per cell (the cell's own and the lowest
/// over it and its 26 neighbours): 16 MiB for the largest field
/// ([`MAX_CELLS`](crate::collision::sdf::MAX_CELLS)), as much as the
/// field's own values.
#[derive(Clone, Debug, PartialEq)]
pub struct NearCells {
    /// Cell i's lowest corner value at index i < `count`, metres, rounded
    /// down to f32 (−∞ where a corner is NaN: the lookup would give a NaN
    /// force, not none); then, at `count` + i, the lowest over cell i and
    /// its 26 neighbours. The exact test reads the first half; the f32 lane
    /// screen ([`super::lane_screen`]) reads a point's own cell where it is
    /// well inside it, and the grown half where it is within rounding of a
    /// face, so that rounding can never move it out of a near cell's reach.
    lowest_m: Vec<f32>,
    cells: [usize; 3],
    count: usize,
}

impl NearCells {
    /// The cells of `field` and how near each is to its surface.
    pub fn new(field: &SignedDistanceField) -> Self {
        let cells = field.dims.map(|d| d.saturating_sub(1));
        let count = cells[0] * cells[1] * cells[2];
        let mut lowest_m = vec![f32::INFINITY; 2 * count];
        for z in 0..cells[2] {
            for y in 0..cells[1] {
                for x in 0..cells[0] {
                    let corners = CELL_CORNERS.map(|(dx, dy, dz)| field.at(x + dx, y + dy, z + dz));
                    let lowest = if corners.iter().any(|c| c.is_nan()) {
                        f64::NEG_INFINITY
                    } else {
                        corners.iter().copied().fold(f64::INFINITY, f64::min)
                    };
                    lowest_m[x + cells[0] * (y + cells[1] * z)] = round_down(lowest);
                }
            }
        }
        lowest_over_neighbours(&mut lowest_m, cells, count);
        Self {
            lowest_m,
            cells,
            count,
        }
    }

    /// Cells in the grid.
    pub fn cell_count(&self) -> usize {
        self.count
    }

    /// Cells along x, y and z.
    pub fn cells(&self) -> [usize; 3] {
        self.cells
    }

    /// For `index` = x + cells_x (y + cells_y z) below [`Self::cell_count`],
    /// no point of that cell is nearer the surface than this, metres; for
    /// `count` + that index, no point of it or its neighbours. Rounded
    /// down to f32; +∞ past the end.
    #[inline(always)]
    pub fn lowest_m(&self, index: usize) -> f32 {
        self.lowest_m.get(index).copied().unwrap_or(f32::INFINITY)
    }
}

/// The largest f32 at or below `x`.
fn round_down(x: f64) -> f32 {
    let rounded = x as f32;
    if f64::from(rounded) > x {
        rounded.next_down()
    } else {
        rounded
    }
}

/// Sets, in the second half of `lowest_m` (from index `count`), each cell's
/// lowest over the first half's values of it and its 26 neighbours (one per
/// cell of a `cells` grid, x fastest).
fn lowest_over_neighbours(lowest_m: &mut [f32], cells: [usize; 3], count: usize) {
    let index = |x: usize, y: usize, z: usize| x + cells[0] * (y + cells[1] * z);
    let around = |c: usize, n: usize| c.saturating_sub(1)..(c + 2).min(n);
    for z in 0..cells[2] {
        for y in 0..cells[1] {
            for x in 0..cells[0] {
                let own = lowest_m[index(x, y, z)];
                for nz in around(z, cells[2]) {
                    for ny in around(y, cells[1]) {
                        for nx in around(x, cells[0]) {
                            let grown = &mut lowest_m[count + index(nx, ny, nz)];
                            *grown = grown.min(own);
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
    /// inputs' collider.
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

    /// Whether a point at `point_m` (world) moving at `velocity_m_per_s`
    /// can feel the contact law during the step: false only where
    /// [`ContactInputs::force`] (without `implicit`) or
    /// [`ContactInputs::implicit_force`] (with it) gives no force. The
    /// explicit law acts where d < skin; the implicit one where
    /// d + h min(v_rel · n, 0) < skin, and h |v_rel · n| is at most the
    /// reach h |v − v_surface|. d is at least the lowest corner value of
    /// the point's cell, so a point is rejected only where that lowest
    /// value, less the reach, is beyond the skin, or outside the field's
    /// grid (no lookup there). The position is computed with the same
    /// operations as in the lookup, so the cell is the one it would use.
    #[inline(always)]
    pub fn may_feel(&self, point_m: DVec3, velocity_m_per_s: DVec3, implicit: bool) -> bool {
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
        let cells = self.near.cells();
        let lowest = f64::from(
            self.near
                .lowest_m(cell(0) + cells[0] * (cell(1) + cells[1] * cell(2))),
        );
        let reach = if implicit {
            let relative = velocity_m_per_s - self.surface_velocity(point_m);
            self.inputs.h_secs * relative.length() * (1.0 + REACH_SLACK)
        } else {
            0.0
        };
        // A NaN anywhere compares as nothing and keeps the point (its force
        // is NaN).
        (lowest - reach).partial_cmp(&(self.inputs.settings.skin_m + CORNER_MARGIN_M))
            != Some(Ordering::Greater)
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

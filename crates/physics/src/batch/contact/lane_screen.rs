//! The contact screen for a whole batch at once: which lanes' points can
//! feel the head's collider, in f32 lanes, before any lane's exact test.
//!
//! # Why
//!
//! [`SkinTest::may_feel`] is exact and scalar: per lane it widens the
//! point to f64, takes it into head coordinates, divides by the cell and
//! reads the cell's lowest distance, which it compares with the skin plus
//! the point's reach over the step. On an
//! imported groom it ran at every element end point of every lane (where
//! contact acted then), in the step and in the guard's measure, and fewer
//! than 3% of those points passed it (Sintel on a still head: 58,365 of
//! 2,000,000); the screening alone was about a seventh of a frame's CPU
//! time. Contact now acts at every quadrature sample, so the screen runs
//! there.
//!
//! # How it works
//!
//! Per batch and step, each lane's root is taken into grid coordinates
//! once, in f64 ([`LaneScreen::new`]). A point relative to its root is then
//! mapped by the head's rotation scaled to cells, in lanes: eight points
//! for nine multiply-adds; the cell, whether the point is near a cell face,
//! the value's place in [`NearCells`] and the point's reach over the step
//! h |v − v_surface| are found in lanes too, and only the cell's lowest
//! distance is read lane by lane ([`NearCells::lowest_m`]). A lane whose
//! cell, less the reach, is beyond the skin is skipped; the others go on
//! to the exact test, so results are bit for bit those of the exact test
//! alone.
//!
//! **Why this never skips a point the exact test keeps.** While every term
//! summed into a grid coordinate is below `LARGEST_CELLS` (2¹² cells),
//! the f32 coordinate is within 10⁻² cells of the f64 one (a few ulps of
//! 2¹², plus the rotation rounded to f32). So:
//!
//! - a coordinate more than `FACE_MARGIN` (1/32 cell) from every face of
//!   a cell of the grid has the exact test's cell, and reads that cell's
//!   own value;
//! - a coordinate nearer a face, or in the one-cell band just outside the
//!   grid, may belong to the next cell: it reads the lowest value over its
//!   cell and the 26 around it, at most the exact test's;
//! - a coordinate below −1 or at or above cells + 1 is outside [0, cells]
//!   exactly, where the exact test rejects too;
//! - a lane with a larger term, or a non-finite one, is left to the exact
//!   test;
//! - the f32 reach is at least the exact test's f64 one: the speed is
//!   raised by `REACH_SLACK` of the sum of every term's magnitude (far
//!   above the f32 rounding of the head's surface velocity and the
//!   difference) and a floor, the skin by `SKIN_MARGIN_M`.

use std::cmp::Ordering;

use glam::{DMat3, DVec3};

use super::near_cells::{NearCells, SkinTest};
use crate::batch::lanes::{LANES, Real};
use crate::batch::vec::V3;

/// One batch's screen for one step (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct LaneScreen {
    /// Each lane's root point in grid coordinates (cells from the grid's
    /// first point, head axes): x of every lane, then y, then z, so that a
    /// coordinate's lanes load as one vector.
    root_cells: [[f32; LANES]; 3],
    /// Each lane's root point minus the head's position, world, metres
    /// (laid out as `root_cells`).
    root_from_head_m: [[f32; LANES]; 3],
    /// Rows of the head's body-from-world rotation over the cell size:
    /// world metres to grid cells.
    cells_from_world: [[f32; 3]; 3],
    /// The head's velocity, m/s, and angular velocity, rad/s, world.
    head_velocity_m_per_s: [f32; 3],
    head_angular_velocity_rad_per_s: [f32; 3],
    /// Step length, seconds (the implicit contact's look-ahead).
    h_secs: f32,
    /// The contact skin, metres, rounded up to f32, with
    /// [`SKIN_MARGIN_M`]: a lane is kept unless its cell is farther than
    /// this plus its reach.
    skin_limit_m: f32,
}

impl LaneScreen {
    /// The screen of `test` for a batch whose lane i is rooted at
    /// `root_positions_m[i]` (world, metres).
    pub fn new(test: &SkinTest<'_>, root_positions_m: &[DVec3; LANES]) -> Self {
        let field = test.inputs.collider;
        let head = test.inputs.head;
        let body_from_world: DMat3 = head.world_from_body.transpose();
        let to_cells = |root: DVec3| {
            let local = body_from_world * (root - head.position_m);
            ((local - field.origin_m) / field.cell_m)
                .as_vec3()
                .to_array()
        };
        let rows = body_from_world.transpose();
        let row = |v: DVec3| (v / field.cell_m).as_vec3().to_array();
        Self {
            root_cells: by_axis(root_positions_m.map(to_cells)),
            root_from_head_m: by_axis(
                root_positions_m.map(|r| (r - head.position_m).as_vec3().to_array()),
            ),
            cells_from_world: [row(rows.x_axis), row(rows.y_axis), row(rows.z_axis)],
            head_velocity_m_per_s: head.velocity_m_per_s.as_vec3().to_array(),
            head_angular_velocity_rad_per_s: head.angular_velocity_rad_per_s.as_vec3().to_array(),
            h_secs: test.inputs.h_secs as f32,
            skin_limit_m: test.inputs.settings.skin_m as f32 + SKIN_MARGIN_M,
        }
    }

    /// Per lane (bit i for lane i), whether the point `point_m` (relative
    /// to the lane's root, world axes) moving at `velocity_m_per_s` may
    /// feel the collider: a superset of [`SkinTest::may_feel`] with the
    /// same `implicit`, so a clear bit means no force at all.
    #[inline(always)]
    pub fn may_feel<T: Real>(
        &self,
        near: &NearCells,
        point_m: V3<T>,
        velocity_m_per_s: V3<T>,
        implicit: bool,
    ) -> u32 {
        let root: V3<T> = lanes3(&self.root_cells);
        let offset = self.in_cells(point_m);
        let size = largest_abs(root).max(largest_abs(offset));
        let index = screen_index(near, root + offset, size);
        let reach = if implicit {
            self.reach(point_m, velocity_m_per_s)
        } else {
            T::splat(0.0)
        };
        let mut mask = 0;
        for lane in 0..T::WIDTH {
            let i = index.lane(lane);
            let may = if i.is_nan() {
                true
            } else if i < 0.0 {
                false
            } else {
                let (lowest, reach) = (near.lowest_m(i as usize), reach.lane(lane));
                // The f32 difference rounds by at most an ulp of its terms.
                let rounding = (lowest.abs() + reach) * REACH_SLACK;
                // A NaN compares as nothing: the lane is kept.
                (lowest - reach).partial_cmp(&(self.skin_limit_m + rounding))
                    != Some(Ordering::Greater)
            };
            mask |= u32::from(may) << lane;
        }
        mask
    }

    /// Per lane, at least the exact test's reach h |v − v_surface(p)| for a
    /// point `point_m` (relative to its root) moving at `velocity_m_per_s`:
    /// the f32 speed raised by [`REACH_SLACK`] of every term summed into it
    /// and [`SPEED_FLOOR_M_PER_S`].
    #[inline(always)]
    fn reach<T: Real>(&self, point_m: V3<T>, velocity_m_per_s: V3<T>) -> T {
        let from_head = lanes3::<T>(&self.root_from_head_m) + point_m;
        let head_velocity = V3::splat(self.head_velocity_m_per_s);
        let w = V3::splat(self.head_angular_velocity_rad_per_s);
        let relative = velocity_m_per_s - (head_velocity + w.cross(from_head));
        let terms =
            sum_abs(velocity_m_per_s) + sum_abs(head_velocity) + sum_abs(w) * sum_abs(from_head);
        let speed = relative.dot(relative).sqrt();
        let slack = T::splat(REACH_SLACK);
        T::splat(self.h_secs) * (speed + slack * (speed + terms) + T::splat(SPEED_FLOOR_M_PER_S))
    }

    /// A world offset `d` (metres) in grid cells, head axes.
    #[inline(always)]
    fn in_cells<T: Real>(&self, d: V3<T>) -> V3<T> {
        let row = |r: [f32; 3]| d.dot(V3::splat(r));
        let [x, y, z] = self.cells_from_world;
        V3::new(row(x), row(y), row(z))
    }
}

/// Largest grid coordinate, in cells, that the screen's f32 arithmetic
/// handles itself: at 2¹² its rounding stays below [`FACE_MARGIN`] / 3.
/// A lane with a larger term (a root or a step far from the head) is passed
/// on to the exact test.
const LARGEST_CELLS: f32 = 4096.0;

/// How close to a cell face, in cells, a screened coordinate reads the
/// grown set instead of its own cell's value: more than three times the
/// screen's rounding (module docs).
const FACE_MARGIN: f32 = 1.0 / 32.0;

/// Relative slack of the screen's f32 reach and difference: some hundred
/// f32 ulps (2⁻²³ each), far above their rounding (module docs).
const REACH_SLACK: f32 = 1e-5;

/// Speed, m/s, added to every reach: covers the rounding of a speed near
/// zero, where relative slack is none.
const SPEED_FLOOR_M_PER_S: f32 = 1e-6;

/// Metres added to the skin: above the skin's own rounding to f32 (2 nm at
/// the largest skin, 2 cm) and the exact test's margin (1e-12 m).
const SKIN_MARGIN_M: f32 = 1e-6;

/// Per lane, the index into [`NearCells::lowest_m`] that grid point `grid`
/// (cells) reads (see the module docs for why its value is never above
/// the exact test's): the point's own cell, or the grown half where it is
/// within rounding of a face; −1 where it is outside the grid, NaN where
/// the screen leaves the lane to the exact test. `size` is the largest
/// magnitude of the terms summed into `grid`, which marks those lanes.
/// Everything is found in lanes; only the value is read lane by lane.
#[inline(always)]
fn screen_index<T: Real>(near: &NearCells, grid: V3<T>, size: T) -> T {
    let cells = near.cells();
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    // NaN in every lane with a non-finite coordinate (∞ · 0 is NaN), and in
    // every lane whose terms are too large to screen.
    let unscreened = grid.x * zero
        + grid.y * zero
        + grid.z * zero
        + size.select_greater(T::splat(LARGEST_CELLS), T::splat(f32::NAN), zero);
    let (mut outside, mut at_face) = (zero, zero);
    let mut axis_cell = |g: T, count: usize| {
        let floor = g.floor();
        let last = T::splat(count.saturating_sub(1) as f32);
        // Outside [−1, cells + 1): outside [0, cells] exactly, rejected there.
        outside += floor.select_below(-1.0, one, zero)
            + floor.select_greater(T::splat(count as f32), one, zero);
        // Off the grid's cells or within the margin of a face: the grown set.
        let fraction = g - floor;
        at_face += fraction.select_below(FACE_MARGIN, one, zero)
            + fraction.select_greater(T::splat(1.0 - FACE_MARGIN), one, zero)
            + floor.select_below(0.0, one, zero)
            + floor.select_greater(last, one, zero);
        let clamped = floor.max(zero);
        clamped.select_greater(last, last, clamped)
    };
    let x = axis_cell(grid.x, cells[0]);
    let y = axis_cell(grid.y, cells[1]);
    let z = axis_cell(grid.z, cells[2]);
    let row = T::splat(cells[0] as f32);
    let plane = T::splat((cells[0] * cells[1]) as f32);
    // Exact in f32: a field has at most 2²¹ cells (MAX_CELLS), and the
    // grown half of the values doubles that.
    let own = x + row * y + plane * z;
    let index = own + at_face.select_greater(zero, T::splat(near.cell_count() as f32), zero);
    outside.select_greater(T::splat(0.5), T::splat(-1.0), index) + unscreened
}

/// Per-lane triples regrouped by axis: x of every lane, then y, then z.
fn by_axis(per_lane: [[f32; 3]; LANES]) -> [[f32; LANES]; 3] {
    std::array::from_fn(|axis| std::array::from_fn(|lane| per_lane[lane][axis]))
}

/// Per lane, the largest |component| of `v`.
#[inline(always)]
fn largest_abs<T: Real>(v: V3<T>) -> T {
    let abs = |a: T| a.max(-a);
    abs(v.x).max(abs(v.y)).max(abs(v.z))
}

/// A triple of per-lane arrays (x, y, z) as one vector of lanes.
#[inline(always)]
fn lanes3<T: Real>(a: &[[f32; LANES]; 3]) -> V3<T> {
    V3::new(
        T::from_fn(|i| a[0][i]),
        T::from_fn(|i| a[1][i]),
        T::from_fn(|i| a[2][i]),
    )
}

/// Per lane, |x| + |y| + |z| of `v` (at least its length).
#[inline(always)]
fn sum_abs<T: Real>(v: V3<T>) -> T {
    let abs = |a: T| a.max(-a);
    abs(v.x) + abs(v.y) + abs(v.z)
}

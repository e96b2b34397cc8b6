//! The contact screen for a whole batch at once: which lanes' points can
//! feel the head's collider, in f32 lanes, before any lane's exact test.
//!
//! # Why
//!
//! [`SkinTest::may_feel`] is exact and scalar: per lane it widens the
//! point to f64, takes it into head coordinates, divides by the cell and
//! reads one bit, twice with the implicit contact's predicted point. On an
//! imported groom it ran at every element end point of every lane, in the
//! step and in the guard's measure, and fewer than 3% of those points
//! passed it (Sintel on a still head: 58,365 of 2,000,000); the screening
//! alone was about a seventh of a frame's CPU time.
//!
//! # How it works
//!
//! Per batch and step, each lane's root is taken into grid coordinates
//! once, in f64 ([`LaneScreen::new`]). A point relative to its root is then
//! mapped by the head's rotation scaled to cells, in lanes: eight points
//! for nine multiply-adds. Each lane's cell is read from
//! [`NearCells::grown_contains_index`], the near set grown by one cell, and a lane
//! whose cell there is clear is skipped; the others go on to the exact
//! test, so results are bit for bit those of the exact test alone.
//!
//! **Why this never skips a point the exact test keeps.** The f32 grid
//! coordinate differs from the f64 one by a few ulps of the larger of the
//! root's and the point's coordinates, far below a cell for any point
//! within 10⁵ cells of the grid, and a point farther out than that is
//! outside the grid either way. Floors of two numbers less than a cell
//! apart differ by at most one, and clamping to the grid keeps that, so the
//! exact test's cell is the screened cell or one of its 26 neighbours, all
//! covered by the grown set. A coordinate outside [−1, cells + 1) is
//! outside [0, cells] exactly, where the exact test rejects too. A
//! non-finite coordinate is passed on to the exact test.

use glam::{DMat3, DVec3};

use super::lanes::{LANES, Real};
use super::near_cells::{NearCells, SkinTest};
use super::vec::V3;

/// One batch's screen for one step (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct LaneScreen {
    /// Each lane's root point in grid coordinates (cells from the grid's
    /// first point, head axes).
    root_cells: [[f32; 3]; LANES],
    /// Each lane's root point minus the head's position, world, metres.
    root_from_head_m: [[f32; 3]; LANES],
    /// Rows of the head's body-from-world rotation over the cell size:
    /// world metres to grid cells.
    cells_from_world: [[f32; 3]; 3],
    /// The head's velocity, m/s, and angular velocity, rad/s, world.
    head_velocity_m_per_s: [f32; 3],
    head_angular_velocity_rad_per_s: [f32; 3],
    /// Step length, seconds (the implicit contact's look-ahead).
    h_secs: f32,
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
            root_cells: root_positions_m.map(to_cells),
            root_from_head_m: root_positions_m.map(|r| (r - head.position_m).as_vec3().to_array()),
            cells_from_world: [row(rows.x_axis), row(rows.y_axis), row(rows.z_axis)],
            head_velocity_m_per_s: head.velocity_m_per_s.as_vec3().to_array(),
            head_angular_velocity_rad_per_s: head.angular_velocity_rad_per_s.as_vec3().to_array(),
            h_secs: test.inputs.h_secs as f32,
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
        let lanes3 = |a: &[[f32; 3]; LANES]| {
            V3::new(
                T::from_fn(|i| a[i][0]),
                T::from_fn(|i| a[i][1]),
                T::from_fn(|i| a[i][2]),
            )
        };
        let grid = lanes3(&self.root_cells) + self.in_cells(point_m);
        let mut mask = near_mask(near, grid);
        if implicit {
            // Where the exact test's predicted point goes: p + h (v − v_surface(p)).
            let from_head = lanes3(&self.root_from_head_m) + point_m;
            let w = V3::splat(self.head_angular_velocity_rad_per_s);
            let surface = V3::splat(self.head_velocity_m_per_s) + w.cross(from_head);
            let moved = (velocity_m_per_s - surface).scale(T::splat(self.h_secs));
            mask |= near_mask(near, grid + self.in_cells(moved));
        }
        mask
    }

    /// A world offset `d` (metres) in grid cells, head axes.
    #[inline(always)]
    fn in_cells<T: Real>(&self, d: V3<T>) -> V3<T> {
        let row = |r: [f32; 3]| d.dot(V3::splat(r));
        let [x, y, z] = self.cells_from_world;
        V3::new(row(x), row(y), row(z))
    }
}

/// Per lane, whether grid point `grid` (cells) lies in a cell of `near`'s
/// grown set (see the module docs for why that covers the exact test).
/// The cell and its place in the grid are found in lanes; only the bit is
/// read lane by lane.
#[inline(always)]
fn near_mask<T: Real>(near: &NearCells, grid: V3<T>) -> u32 {
    let cells = near.cells();
    let (zero, one) = (T::splat(0.0), T::splat(1.0));
    // NaN in every lane with a non-finite coordinate (∞ · 0 is NaN).
    let finite_or_nan = grid.x * zero + grid.y * zero + grid.z * zero;
    let mut outside = zero;
    let mut axis_cell = |g: T, count: usize| {
        let floor = g.floor();
        let last = T::splat(count.saturating_sub(1) as f32);
        // Outside [−1, cells]: outside [0, cells] exactly, rejected there.
        outside += floor.select_below(-1.0, one, zero)
            + floor.select_greater(T::splat(count as f32), one, zero);
        let clamped = floor.max(zero);
        clamped.select_greater(last, last, clamped)
    };
    let x = axis_cell(grid.x, cells[0]);
    let y = axis_cell(grid.y, cells[1]);
    let z = axis_cell(grid.z, cells[2]);
    let row = T::splat(cells[0] as f32);
    let plane = T::splat((cells[0] * cells[1]) as f32);
    // Exact in f32: a field has at most 2²⁴ cells (MAX_CELLS).
    let index = x + row * y + plane * z;
    let index = outside.select_greater(T::splat(0.5), T::splat(-1.0), index) + finite_or_nan;
    let mut mask = 0;
    for lane in 0..T::WIDTH {
        let i = index.lane(lane);
        let may = if i.is_nan() {
            true
        } else {
            i >= 0.0 && near.grown_contains_index(i as usize)
        };
        mask |= u32::from(may) << lane;
    }
    mask
}

//! A signed distance field on a regular grid, sampled trilinearly.

use glam::DVec3;

use super::error::CollisionError;
use super::sdf_build;

/// Most grid points a field may have: 128³, 16 MiB of f64.
pub const MAX_CELLS: usize = 128 * 128 * 128;
/// Grid cells of margin around the mesh's bounding box: room for the
/// contact skin and for samples approaching from outside.
pub const MARGIN_CELLS: usize = 3;

/// Distance to a surface, negative inside (where its winding number is
/// above 1/2: the surface need not be closed), on a grid in the
/// surface's own (head) coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct SignedDistanceField {
    /// Position of grid point (0, 0, 0), metres.
    pub origin_m: DVec3,
    /// Grid spacing, metres.
    pub cell_m: f64,
    /// Grid points along x, y, z.
    pub dims: [usize; 3],
    /// Signed distance at each grid point, metres, x fastest.
    pub distance_m: Vec<f64>,
}

impl SignedDistanceField {
    /// Samples the signed distance to the triangle mesh (`positions_m`,
    /// `triangles`) on a grid of spacing `cell_m`. Exact within a band of a
    /// few cells around the surface; beyond it the distance is clamped to
    /// the band (contact only needs the near field). The sign is the
    /// mesh's winding number's ([`crate::collision::winding`]): the mesh may
    /// be open, with holes, or carry flipped or doubled triangles.
    pub fn from_triangles(
        positions_m: &[DVec3],
        triangles: &[[u32; 3]],
        cell_m: f64,
    ) -> Result<Self, CollisionError> {
        sdf_build::build(positions_m, triangles, cell_m)
    }

    /// The signed distance (metres) and its gradient (unit length where
    /// defined) at `p_m`, head coordinates; `None` outside the grid, where
    /// nothing is near the surface.
    pub fn sample(&self, p_m: DVec3) -> Option<(f64, DVec3)> {
        let g = (p_m - self.origin_m) / self.cell_m;
        let max = |d: usize| (d - 1) as f64;
        if g.min_element() < 0.0
            || g.x > max(self.dims[0])
            || g.y > max(self.dims[1])
            || g.z > max(self.dims[2])
        {
            return None;
        }
        let i = [
            (g.x as usize).min(self.dims[0] - 2),
            (g.y as usize).min(self.dims[1] - 2),
            (g.z as usize).min(self.dims[2] - 2),
        ];
        let t = g - DVec3::new(i[0] as f64, i[1] as f64, i[2] as f64);
        // The cell's eight corners: grid point (x, y, z) is entry
        // x + nx (y + ny z), so corner (dx, dy, dz) is the cell's first
        // plus dx + nx dy + nx ny dz, all within one slice read once (plain
        // indexing: nested array maps here were a twentieth of a groom's
        // frame, their closures not inlined).
        let (row, plane) = (self.dims[0], self.dims[0] * self.dims[1]);
        let first = i[0] + row * (i[1] + self.dims[1] * i[2]);
        let cell = &self.distance_m[first..=first + 1 + row + plane];
        let c = |dx: usize, dy: usize, dz: usize| cell[dx + row * dy + plane * dz];
        // Trilinear value and its exact gradient.
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let (c00, c10) = (
            lerp(c(0, 0, 0), c(1, 0, 0), t.x),
            lerp(c(0, 1, 0), c(1, 1, 0), t.x),
        );
        let (c01, c11) = (
            lerp(c(0, 0, 1), c(1, 0, 1), t.x),
            lerp(c(0, 1, 1), c(1, 1, 1), t.x),
        );
        let (c0, c1) = (lerp(c00, c10, t.y), lerp(c01, c11, t.y));
        let value = lerp(c0, c1, t.z);
        let dx = |y: usize, z: usize| c(1, y, z) - c(0, y, z);
        let gx = lerp(
            lerp(dx(0, 0), dx(1, 0), t.y),
            lerp(dx(0, 1), dx(1, 1), t.y),
            t.z,
        );
        let dy = |x: usize, z: usize| c(x, 1, z) - c(x, 0, z);
        let gy = lerp(
            lerp(dy(0, 0), dy(1, 0), t.x),
            lerp(dy(0, 1), dy(1, 1), t.x),
            t.z,
        );
        let gz = c1 - c0;
        let gradient = DVec3::new(gx, gy, gz) / self.cell_m;
        Some((value, gradient.normalize_or_zero()))
    }

    /// The stored distance at grid point (x, y, z).
    pub fn at(&self, x: usize, y: usize, z: usize) -> f64 {
        self.distance_m[x + self.dims[0] * (y + self.dims[1] * z)]
    }
}

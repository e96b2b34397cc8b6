//! Building a signed distance field: exact distances in a narrow band
//! around the triangles, signs from the winding number.
//!
//! 1. Every grid point within [`BAND_CELLS`] of a triangle's bounding box
//!    gets the exact distance to the nearest such triangle (closest point
//!    on a triangle, Ericson's region test). Points outside every such box
//!    get the band width: contact needs only the near field.
//! 2. Every point is inside where the mesh's generalized winding number
//!    there is above 1/2 ([`WindingNumber`]), and its distance is then
//!    negated.
//!
//! Why the winding number: the sign used to come from the nearest
//! triangle's normal in the band and a flood fill of the outside beyond
//! it. An artist's bust is open (cut below the chest, holes for the eyes
//! and mouth), and the flood ran in through the cut: the whole inside read
//! as outside, and hair that sank deeper than the band was never pushed
//! back. The winding number needs no closed surface and no consistent
//! nearest normal.
//!
//! The winding number is the dear part (a tree walk with a solid angle per
//! near triangle), so it is not evaluated at every point. Away from the
//! triangles it is harmonic, smooth, and its side of 1/2 changes only
//! near an opening of the mesh: the grid is cut into blocks of
//! [`SIGN_BLOCK_CELLS`] cells a side, and a block that no triangle's
//! bounding box overlaps and whose eight corners lie on the same side takes
//! their sign; the other blocks (those the surface passes through, and
//! blocks across an opening) are
//! evaluated point by point. The result is the point-by-point sign except
//! within a block of the film spanning an opening, where the winding
//! number passes 1/2 in open space and inside and outside are a matter of
//! definition (`tests/collision.rs` checks an open sphere point by point:
//! 11 of 123,596 points differ, all on the hole's disk).
//!
//! O(T · band³) for the distances and O(grid · log T) for the signs, over
//! grid slices in parallel.

use glam::DVec3;
use rayon::prelude::*;

use super::error::CollisionError;
use super::sdf::{MARGIN_CELLS, MAX_CELLS, SignedDistanceField};
use super::winding::WindingNumber;

/// Half-width of the exact band, in cells.
pub const BAND_CELLS: usize = 3;

/// Cells per side of the blocks whose sign may come from their corners
/// (module docs). 4: a block is 125 points for 8 corner evaluations, shared
/// with the neighbours, and the shell of blocks the surface passes through
/// stays a block or two thick. `helixhair export` of the curly example
/// (the default head's field and little else), three runs of each build
/// alternated: 1.31–1.70 s with every point evaluated, 0.70–0.80 s with
/// blocks and [`WindingNumber`]'s one `atan2` per point.
pub const SIGN_BLOCK_CELLS: usize = 4;

pub(super) fn build(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    cell_m: f64,
) -> Result<SignedDistanceField, CollisionError> {
    if triangles.is_empty() {
        return Err(CollisionError::Empty);
    }
    if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
        return Err(CollisionError::NotFinite { vertex });
    }
    for (triangle, t) in triangles.iter().enumerate() {
        if let Some(&vertex) = t.iter().find(|&&v| v as usize >= positions.len()) {
            return Err(CollisionError::IndexOutOfRange {
                triangle,
                vertex,
                vertices: positions.len(),
            });
        }
    }
    let (lo, hi) = triangles.iter().flatten().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &v| (lo.min(positions[v as usize]), hi.max(positions[v as usize])),
    );
    let margin = (MARGIN_CELLS + BAND_CELLS) as f64 * cell_m;
    let extent = (hi - lo + 2.0 * margin) / cell_m;
    let cells = (extent.x + 2.0) * (extent.y + 2.0) * (extent.z + 2.0);
    if cell_m.is_nan() || cell_m <= 0.0 || !cells.is_finite() || cells > MAX_CELLS as f64 {
        return Err(CollisionError::BadGrid {
            cell_m,
            cells,
            max: MAX_CELLS,
        });
    }
    let dims = [
        extent.x.ceil() as usize + 1,
        extent.y.ceil() as usize + 1,
        extent.z.ceil() as usize + 1,
    ];
    let origin = lo - DVec3::splat(margin);
    let band = BAND_CELLS as f64 * cell_m;
    let index = |x: usize, y: usize, z: usize| x + dims[0] * (y + dims[1] * z);
    let mut distance = vec![f64::INFINITY; dims[0] * dims[1] * dims[2]];
    for t in triangles {
        let [a, b, c] = t.map(|v| positions[v as usize]);
        let cell_of = |p: DVec3, round_up: bool| {
            let g = (p - origin) / cell_m;
            let g = if round_up { g.ceil() } else { g.floor() };
            [g.x, g.y, g.z].map(|v| v.max(0.0) as usize)
        };
        let lo_c = cell_of(a.min(b).min(c) - DVec3::splat(band), false);
        let hi_c = cell_of(a.max(b).max(c) + DVec3::splat(band), true);
        for z in lo_c[2]..=hi_c[2].min(dims[2] - 1) {
            for y in lo_c[1]..=hi_c[1].min(dims[1] - 1) {
                for x in lo_c[0]..=hi_c[0].min(dims[0] - 1) {
                    let p = origin + DVec3::new(x as f64, y as f64, z as f64) * cell_m;
                    let q = closest_point_on_triangle(p, a, b, c);
                    let d = p.distance(q);
                    let slot = &mut distance[index(x, y, z)];
                    *slot = slot.min(d);
                }
            }
        }
    }
    let winding = WindingNumber::new(positions, triangles);
    let point =
        |x: usize, y: usize, z: usize| origin + DVec3::new(x as f64, y as f64, z as f64) * cell_m;
    // Each triangle's bounding box, in cells from the origin.
    let boxes: Vec<[DVec3; 2]> = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| (positions[v as usize] - origin) / cell_m);
            [a.min(b).min(c), a.max(b).max(c)]
        })
        .collect();
    let blocks = BlockSigns::new(dims, &boxes, |[x, y, z]| winding.inside(point(x, y, z)));
    distance
        .par_chunks_mut(dims[0] * dims[1])
        .enumerate()
        .for_each(|(z, slice)| {
            for (i, d) in slice.iter_mut().enumerate() {
                let (x, y) = (i % dims[0], i / dims[0]);
                let inside = blocks
                    .sign([x, y, z])
                    .unwrap_or_else(|| winding.inside(point(x, y, z)));
                // Beyond the band's boxes, the band's width; within them
                // the exact distance, even past the band (a plateau at
                // the band's width next to exact values would leave cells
                // with no gradient where hair moves).
                let magnitude = if d.is_finite() { *d } else { band };
                *d = if inside { -magnitude } else { magnitude };
            }
        });
    Ok(SignedDistanceField {
        origin_m: origin,
        cell_m,
        dims,
        distance_m: distance,
    })
}

/// The sign of each block of [`SIGN_BLOCK_CELLS`] cells that can take it
/// from its corners (module docs).
struct BlockSigns {
    /// Blocks per axis.
    counts: [usize; 3],
    /// Per block: `Some(inside)` when the whole block has one sign.
    uniform: Vec<Option<bool>>,
}

impl BlockSigns {
    /// Evaluates `inside` at every block corner, and marks the blocks that
    /// any of the triangles' bounding boxes `boxes` (in cells) overlaps:
    /// inside those the winding number may jump.
    fn new(
        dims: [usize; 3],
        boxes: &[[DVec3; 2]],
        inside: impl Fn([usize; 3]) -> bool + Sync,
    ) -> Self {
        let b = SIGN_BLOCK_CELLS;
        // Corner coordinates per axis: 0, b, 2b, …, and the last point.
        let corners = dims.map(|n| {
            let mut c: Vec<usize> = (0..n).step_by(b).collect();
            if c.last() != Some(&(n - 1)) {
                c.push(n - 1);
            }
            c
        });
        let counts = corners.each_ref().map(|c| c.len() - 1);
        let corner_count = corners[0].len() * corners[1].len();
        let corner_inside: Vec<bool> = (0..corner_count * corners[2].len())
            .into_par_iter()
            .map(|i| {
                let (xy, k) = (i % corner_count, i / corner_count);
                let (ci, cj) = (xy % corners[0].len(), xy / corners[0].len());
                inside([corners[0][ci], corners[1][cj], corners[2][k]])
            })
            .collect();
        let corner = |i: usize, j: usize, k: usize| {
            corner_inside[i + corners[0].len() * (j + corners[1].len() * k)]
        };
        let mut crossed = vec![false; counts[0] * counts[1] * counts[2]];
        for [lo, hi] in boxes {
            // The blocks the box overlaps, one more below (a box on a block
            // boundary touches both blocks).
            let range = |axis: usize| {
                let last = counts[axis] - 1;
                let first = ((lo[axis] / b as f64).floor() - 1.0).max(0.0) as usize;
                first.min(last)..=((hi[axis] / b as f64).floor().max(0.0) as usize).min(last)
            };
            for k in range(2) {
                for j in range(1) {
                    for i in range(0) {
                        crossed[i + counts[0] * (j + counts[1] * k)] = true;
                    }
                }
            }
        }
        let uniform = (0..counts[0] * counts[1] * counts[2])
            .into_par_iter()
            .map(|block| {
                let (i, j, k) = (
                    block % counts[0],
                    (block / counts[0]) % counts[1],
                    block / (counts[0] * counts[1]),
                );
                let sign = corner(i, j, k);
                let corners_agree =
                    (0..8).all(|c| corner(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)) == sign);
                (corners_agree && !crossed[block]).then_some(sign)
            })
            .collect();
        BlockSigns { counts, uniform }
    }

    /// The sign of grid point `p` when its block has one.
    fn sign(&self, p: [usize; 3]) -> Option<bool> {
        let [i, j, k] = [0, 1, 2].map(|a| (p[a] / SIGN_BLOCK_CELLS).min(self.counts[a] - 1));
        self.uniform[i + self.counts[0] * (j + self.counts[1] * k)]
    }
}

/// The point of triangle (a, b, c) closest to `p` (Ericson, Real-Time
/// Collision Detection, 5.1.5).
pub fn closest_point_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

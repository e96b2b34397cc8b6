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
//! O(T · band³) for the distances and O(grid · log T) for the signs, over
//! grid slices in parallel: Sintel's 5,952-triangle bust on a 4 mm grid
//! builds in about a second on two cores.

use glam::DVec3;
use rayon::prelude::*;

use super::error::CollisionError;
use super::sdf::{MARGIN_CELLS, MAX_CELLS, SignedDistanceField};
use super::winding::WindingNumber;

/// Half-width of the exact band, in cells.
pub const BAND_CELLS: usize = 3;

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
    distance
        .par_chunks_mut(dims[0] * dims[1])
        .enumerate()
        .for_each(|(z, slice)| {
            for (i, d) in slice.iter_mut().enumerate() {
                let (x, y) = (i % dims[0], i / dims[0]);
                let p = origin + DVec3::new(x as f64, y as f64, z as f64) * cell_m;
                // Beyond the band's boxes, the band's width; within them
                // the exact distance, even past the band (a plateau at
                // the band's width next to exact values would leave cells
                // with no gradient where hair moves).
                let magnitude = if d.is_finite() { *d } else { band };
                *d = if winding.inside(p) {
                    -magnitude
                } else {
                    magnitude
                };
            }
        });
    Ok(SignedDistanceField {
        origin_m: origin,
        cell_m,
        dims,
        distance_m: distance,
    })
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

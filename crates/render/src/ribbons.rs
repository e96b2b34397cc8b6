//! Strands to ribbon vertices: every point twice (one per side of the
//! ribbon), two triangles per segment.
//!
//! The vertex shader (`ribbon_vertex` in `shaders/common.wgsl`) moves each
//! side across the strand's projected tangent, so a ribbon always faces the
//! camera (or the light, in the shadow passes) and never needs rebuilding
//! when the view turns. Here each point gets what the shader needs: the
//! tangent (central differences), how far along the strand it lies (by arc
//! length, for the taper and the shading along the strand), and a random
//! number per strand (for highlight jitter).

use glam::Vec3;

use crate::gpu::gpu_data::StrandVertex;
use crate::scene::HairStrands;

/// A number in [0, 1) that looks random, from a strand index.
pub fn strand_random(index: u32) -> f32 {
    let mut x = index.wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B;
    x ^= x >> 16;
    x = x.wrapping_mul(0x7FEB_352D);
    x ^= x >> 15;
    (x >> 8) as f32 / (1u32 << 24) as f32
}

/// Unit tangents of a polyline by central differences (one-sided at the
/// ends); repeated points borrow their neighbour's tangent.
fn tangents(points: &[Vec3]) -> Vec<Vec3> {
    let n = points.len();
    let mut out: Vec<Vec3> = (0..n)
        .map(|i| {
            let ahead = points[(i + 1).min(n - 1)];
            let behind = points[i.saturating_sub(1)];
            (ahead - behind).normalize_or_zero()
        })
        .collect();
    for i in 1..n {
        if out[i] == Vec3::ZERO {
            out[i] = out[i - 1];
        }
    }
    out
}

/// Fraction of arc length from the root at each point.
fn arc_fractions(points: &[Vec3]) -> Vec<f32> {
    let mut s = Vec::with_capacity(points.len());
    let mut total = 0.0;
    s.push(0.0);
    for w in points.windows(2) {
        total += (w[1] - w[0]).length();
        s.push(total);
    }
    s.iter()
        .map(|x| if total > 0.0 { x / total } else { 0.0 })
        .collect()
}

/// The ribbon vertices and triangle indices of `hair`. Strands with fewer
/// than two points draw nothing.
pub fn ribbon_mesh(hair: &HairStrands) -> (Vec<StrandVertex>, Vec<u32>) {
    let strands = &hair.strands;
    let mut vertices = Vec::with_capacity(2 * strands.points.len());
    let mut indices = Vec::with_capacity(6 * strands.points.len());
    for (i, points) in strands.iter().enumerate() {
        if points.len() < 2 {
            continue;
        }
        let colour = strand_colour(&hair.colours, i);
        let seed = strand_random(i as u32);
        let first = vertices.len() as u32;
        for ((p, t), along) in points
            .iter()
            .zip(tangents(points))
            .zip(arc_fractions(points))
        {
            for side in [-1.0, 1.0] {
                vertices.push(StrandVertex {
                    position_m: p.to_array(),
                    tangent: t.to_array(),
                    colour: colour.to_array(),
                    params: [along, side, seed],
                });
            }
        }
        ribbon_indices(first, points.len() as u32, &mut indices);
    }
    (vertices, indices)
}

/// Strand `index`'s colour in `colours`, dark grey where it has none.
pub fn strand_colour(colours: &[Vec3], index: usize) -> Vec3 {
    colours.get(index).copied().unwrap_or(Vec3::splat(0.2))
}

/// Appends the two triangles of each segment of a ribbon of `points`
/// points (two vertices each, sides alternating) whose first vertex is
/// `first_vertex`: nothing for fewer than two points.
pub fn ribbon_indices(first_vertex: u32, points: u32, indices: &mut Vec<u32>) {
    for k in 0..points.saturating_sub(1) {
        let a = first_vertex + 2 * k;
        indices.extend([a, a + 1, a + 2, a + 1, a + 3, a + 2]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strand_buffers::StrandBuffers;

    #[test]
    fn each_point_gives_two_sides_and_each_segment_two_triangles() {
        let mut strands = StrandBuffers::default();
        strands.push_strand([Vec3::ZERO, Vec3::X, Vec3::new(3.0, 0.0, 0.0)]);
        strands.push_strand([Vec3::Y]);
        strands.push_strand([Vec3::ZERO, Vec3::NEG_Y]);
        let hair = HairStrands {
            strands,
            colours: vec![Vec3::ONE; 3],
            root_width_m: 1e-4,
            tip_width_m: 5e-5,
        };
        let (vertices, indices) = ribbon_mesh(&hair);
        assert_eq!(vertices.len(), 2 * (3 + 2));
        assert_eq!(indices.len(), 6 * (2 + 1));
        let along: Vec<f32> = vertices[..6]
            .iter()
            .step_by(2)
            .map(|v| v.params[0])
            .collect();
        assert_eq!(along, [0.0, 1.0 / 3.0, 1.0]);
        assert_eq!(vertices[0].tangent, [1.0, 0.0, 0.0]);
        assert_eq!(vertices[6].tangent, [0.0, -1.0, 0.0]);
        assert!(indices.iter().all(|&i| (i as usize) < vertices.len()));
    }

    #[test]
    fn strand_randoms_are_spread_over_the_unit_interval() {
        let xs: Vec<f32> = (0..1000).map(strand_random).collect();
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
        let mean = xs.iter().sum::<f32>() / 1000.0;
        assert!((mean - 0.5).abs() < 0.05, "{mean}");
    }
}

//! Where imported strands grow: roots attached to the head, and guides
//! spread over the scalp.
//!
//! **Attachment.** Each root is attached to the head triangle nearest to
//! it, at the barycentric coordinates of the closest point there (a brute
//! search over the triangles: O(roots × triangles), about a second for the
//! Sintel groom on its bust, done once at import). The head moves rigidly
//! and roots are stored in head coordinates, so head motion carries them;
//! the barycentric record is what a deforming head would need. The surface
//! normal there (interpolated from the mesh's vertex normals) sets the root
//! frame's reference: n₁ is the inward normal made orthogonal to the
//! strand's first tangent, as for roots grown on the scalp
//! ([`crate::head::groom`]), so κ₁ bends a strand towards the head.
//!
//! **Guides.** `--guides K` simulates K strands and draws the rest
//! following them. The K are chosen by farthest-point sampling of the
//! roots: start from the first strand, then repeatedly take the root
//! farthest from every guide chosen so far. That spreads guides evenly
//! over the scalp whatever the groom's density (a dense fringe gets no
//! more guides than its area deserves), in O(K × strands).

use glam::DVec3;
use helixhair_physics::collision::closest_point_on_triangle;
use helixhair_render::HeadMesh;

/// A root's place on the head.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attachment {
    /// Index of the nearest triangle.
    pub triangle: u32,
    /// Barycentric coordinates of the closest point on it.
    pub barycentric: DVec3,
    /// Outward unit normal there.
    pub normal: DVec3,
    /// Distance from the root to the surface, metres.
    pub distance_m: f64,
}

/// The nearest triangle of `head` to `root`; `None` for a mesh without
/// triangles.
pub fn attach(head: &HeadMesh, root: DVec3) -> Option<Attachment> {
    let mesh = &head.mesh;
    let mut best: Option<(f64, usize, DVec3)> = None;
    for t in 0..mesh.triangle_count() {
        let [a, b, c] = mesh.triangle(t).map(|p| p.as_dvec3());
        let p = closest_point_on_triangle(root, a, b, c);
        let d = (p - root).length_squared();
        if best.is_none_or(|(bd, _, _)| d < bd) {
            best = Some((d, t, p));
        }
    }
    let (d2, t, p) = best?;
    let [a, b, c] = mesh.triangle(t).map(|p| p.as_dvec3());
    let bary = barycentric(p, a, b, c);
    let corners = &mesh.indices[3 * t..3 * t + 3];
    let from_vertices = if mesh.normals.len() == mesh.positions.len() {
        corners
            .iter()
            .zip(bary.to_array())
            .map(|(&i, w)| mesh.normals[i as usize].as_dvec3() * w)
            .sum::<DVec3>()
    } else {
        DVec3::ZERO
    };
    let normal = from_vertices
        .try_normalize()
        .or_else(|| (b - a).cross(c - a).try_normalize())
        .unwrap_or(DVec3::Y);
    Some(Attachment {
        triangle: t as u32,
        barycentric: bary,
        normal,
        distance_m: d2.sqrt(),
    })
}

/// Barycentric coordinates of `p` (on the triangle's plane) in (a, b, c).
fn barycentric(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let (d00, d01, d11) = (v0.dot(v0), v0.dot(v1), v1.dot(v1));
    let (d20, d21) = (v2.dot(v0), v2.dot(v1));
    let denom = d00 * d11 - d01 * d01;
    if denom.abs() < f64::MIN_POSITIVE {
        return DVec3::new(1.0, 0.0, 0.0);
    }
    let v = (d11 * d20 - d01 * d21) / denom;
    let w = (d00 * d21 - d01 * d20) / denom;
    DVec3::new(1.0 - v - w, v, w)
}

/// Indices of `k` roots spread by farthest-point sampling (all of them,
/// in order, when `k` ≥ their number), sorted.
pub fn farthest_point_guides(roots: &[DVec3], k: usize) -> Vec<usize> {
    if k >= roots.len() {
        return (0..roots.len()).collect();
    }
    let mut chosen = Vec::with_capacity(k);
    let mut nearest = vec![f64::INFINITY; roots.len()];
    let mut next = 0;
    while chosen.len() < k {
        chosen.push(next);
        let from = roots[next];
        let mut far = (0.0, next);
        for (i, (r, d)) in roots.iter().zip(&mut nearest).enumerate() {
            *d = d.min((*r - from).length_squared());
            if *d > far.0 {
                far = (*d, i);
            }
        }
        next = far.1;
    }
    chosen.sort_unstable();
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn farthest_point_sampling_takes_the_corners_of_a_line_first() {
        let roots: Vec<DVec3> = (0..11).map(|i| DVec3::X * i as f64).collect();
        assert_eq!(farthest_point_guides(&roots, 2), vec![0, 10]);
        assert_eq!(farthest_point_guides(&roots, 3), vec![0, 5, 10]);
        assert_eq!(farthest_point_guides(&roots, 20).len(), 11);
    }

    #[test]
    fn barycentric_coordinates_rebuild_the_point() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let p = DVec3::new(0.2, 0.3, 0.0);
        let w = barycentric(p, a, b, c);
        assert!((a * w.x + b * w.y + c * w.z - p).length() < 1e-15);
    }
}

//! Triangle meshes as the renderer draws them, and the head: a mesh with
//! its scalp marked.
//!
//! A mesh is three flat arrays (positions, normals, indices), the layout a
//! GPU upload and an OBJ file both use. The head marks its scalp per
//! triangle, because roots are sampled over triangles and an OBJ group
//! (`g scalp`) is a set of faces.

use glam::Vec3;

/// An indexed triangle mesh, metres, world coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, metres.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position.
    pub normals: Vec<Vec3>,
    /// Three indices per triangle, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
}

impl Mesh {
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The corner positions of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        let i = &self.indices[3 * t..3 * t + 3];
        [0, 1, 2].map(|k| self.positions[i[k] as usize])
    }

    /// The corner normals of triangle `t`.
    pub fn triangle_normals(&self, t: usize) -> [Vec3; 3] {
        let i = &self.indices[3 * t..3 * t + 3];
        [0, 1, 2].map(|k| self.normals[i[k] as usize])
    }

    /// Area of triangle `t`, square metres.
    pub fn triangle_area_m2(&self, t: usize) -> f32 {
        let [a, b, c] = self.triangle(t);
        0.5 * (b - a).cross(c - a).length()
    }

    /// Replaces the normals by area-weighted averages of the face normals
    /// around each vertex (smooth shading).
    pub fn compute_normals(&mut self) {
        let mut normals = vec![Vec3::ZERO; self.positions.len()];
        for t in 0..self.triangle_count() {
            let [a, b, c] = self.triangle(t);
            // The cross product's length is twice the area: area weighting.
            let n = (b - a).cross(c - a);
            for k in 0..3 {
                normals[self.indices[3 * t + k] as usize] += n;
            }
        }
        self.normals = normals
            .into_iter()
            .map(|n| n.try_normalize().unwrap_or(Vec3::Y))
            .collect();
    }

    /// Smallest and largest corner of the axis-aligned bounding box.
    pub fn bounds_m(&self) -> (Vec3, Vec3) {
        self.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        )
    }
}

/// A head: its mesh and which triangles are scalp (where hair grows).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HeadMesh {
    /// The whole head, scalp included.
    pub mesh: Mesh,
    /// Indices of the scalp triangles in `mesh`, ascending.
    pub scalp_triangles: Vec<u32>,
}

impl HeadMesh {
    /// Per-vertex scalp weight: the fraction of a vertex's triangles that
    /// are scalp (1 inside the scalp, 0 away from it, in between along its
    /// edge). The head shader tints the scalp with it so thin hair reads
    /// fuller, and the fractions soften the edge of the tint.
    ///
    /// A head that is scalp all over is a mesh loaded without a `scalp`
    /// group (an imported groom's bust, [`crate::obj::load_mesh_obj`]): it
    /// has no scalp to show, and is drawn in skin, not brown.
    pub fn scalp_vertex_weights(&self) -> Vec<f32> {
        let n = self.mesh.positions.len();
        if self.scalp_triangles.len() >= self.mesh.triangle_count() {
            return vec![0.0; n];
        }
        let (mut scalp, mut all) = (vec![0.0f32; n], vec![0.0f32; n]);
        for &i in &self.mesh.indices {
            all[i as usize] += 1.0;
        }
        for &t in &self.scalp_triangles {
            for k in 0..3 {
                scalp[self.mesh.indices[3 * t as usize + k] as usize] += 1.0;
            }
        }
        scalp
            .iter()
            .zip(&all)
            .map(|(s, a)| if *a > 0.0 { s / a } else { 0.0 })
            .collect()
    }

    /// The head moved rigidly: turned by `rotation`, then moved to
    /// `position_m` (world from head coordinates), normals turned with it.
    pub fn posed(&self, rotation: glam::Mat3, position_m: Vec3) -> HeadMesh {
        let mut out = self.clone();
        for p in &mut out.mesh.positions {
            *p = rotation * *p + position_m;
        }
        for n in &mut out.mesh.normals {
            *n = rotation * *n;
        }
        out
    }

    /// Total scalp area, square metres.
    pub fn scalp_area_m2(&self) -> f32 {
        self.scalp_triangles
            .iter()
            .map(|&t| self.mesh.triangle_area_m2(t as usize))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> Mesh {
        let mut mesh = Mesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, -1.0), Vec3::NEG_Z],
            normals: Vec::new(),
            indices: vec![0, 1, 2, 0, 2, 3],
        };
        mesh.compute_normals();
        mesh
    }

    #[test]
    fn normals_of_a_flat_quad_point_up() {
        let mesh = quad();
        for n in &mesh.normals {
            assert!((*n - Vec3::Y).length() < 1e-6, "{n}");
        }
        assert_eq!(mesh.bounds_m(), (Vec3::NEG_Z, Vec3::X));
    }

    #[test]
    fn scalp_weights_are_the_share_of_scalp_triangles() {
        let head = HeadMesh {
            mesh: quad(),
            scalp_triangles: vec![1],
        };
        assert_eq!(head.scalp_vertex_weights(), [0.5, 0.0, 0.5, 1.0]);
        assert!((head.scalp_area_m2() - 0.5).abs() < 1e-6);
    }

    #[test]
    fn a_head_that_is_scalp_all_over_is_drawn_in_skin() {
        // Issue 32, item 6: an imported bust (no scalp group, so every face
        // counts as scalp for collision) was drawn in the scalp's brown.
        let head = HeadMesh {
            mesh: quad(),
            scalp_triangles: vec![0, 1],
        };
        assert_eq!(head.scalp_vertex_weights(), [0.0; 4]);
    }
}

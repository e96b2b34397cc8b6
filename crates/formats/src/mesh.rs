//! A triangle mesh given as plain buffers, for writing a head beside the
//! hair (USD `Mesh` prim).

use glam::Vec3;

/// A triangle mesh: vertices in metres (Y up) and triangles as indices.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// The vertex positions in metres.
    pub vertices_m: Vec<Vec3>,
    /// Three vertex indices per triangle, counter-clockwise seen from
    /// outside.
    pub triangles: Vec<[u32; 3]>,
}

//! A triangle mesh given as plain buffers, for writing a head beside the
//! hair (USD `Mesh` prim).

use glam::{DMat3, DVec3, Vec3};

/// A triangle mesh: vertices in metres (Y up) and triangles as indices.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// The vertex positions in metres.
    pub vertices_m: Vec<Vec3>,
    /// Three vertex indices per triangle, counter-clockwise seen from
    /// outside.
    pub triangles: Vec<[u32; 3]>,
}

/// Where a mesh is at one time: a rigid motion taking the mesh's own
/// coordinates to the world's, `world = rotation · own + translation_m`
/// (a moving head; written as USD `xformOp:transform` time samples).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshPose {
    /// The time code (a frame number in USD's convention), as the
    /// animation's frames use.
    pub time_code: f64,
    /// The rotation, world from mesh.
    pub rotation: DMat3,
    /// The mesh origin in the world, metres.
    pub translation_m: DVec3,
}

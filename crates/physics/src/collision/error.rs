//! Why a collider could not be built.

use thiserror::Error;

/// A mesh or grid setting the signed distance field cannot be built from.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum CollisionError {
    /// No triangles.
    #[error("the collision mesh has no triangles")]
    Empty,
    /// A triangle names a vertex that does not exist.
    #[error("triangle {triangle} uses vertex {vertex}, but the mesh has {vertices} vertices")]
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
        /// The bad vertex index.
        vertex: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// A vertex position is NaN or infinite.
    #[error("vertex {vertex} of the collision mesh is not finite")]
    NotFinite {
        /// Vertex index.
        vertex: usize,
    },
    /// The grid cell size is not a positive length, or the grid would be
    /// too large.
    #[error(
        "grid cell {cell_m} m gives {cells} cells (allowed: a positive size, at most {max} cells)"
    )]
    BadGrid {
        /// The cell size asked for, metres.
        cell_m: f64,
        /// Cells it would take.
        cells: f64,
        /// The most allowed.
        max: usize,
    },
}

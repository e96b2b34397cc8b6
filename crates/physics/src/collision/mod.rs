//! Hair against the head: a signed distance field and a contact force.
//!
//! The head is given as triangles (positions in head coordinates; this
//! crate knows no mesh file format). [`SignedDistanceField::from_triangles`]
//! samples the distance to the surface on a regular grid, negative inside,
//! once; inside is where the mesh's winding number is above 1/2
//! ([`winding`]), so a bust cut open below the chest, with holes for the
//! eyes, still has one; a query is then a trilinear lookup, O(1), so contact costs the same
//! for a 500-triangle head as for a 50,000-triangle one.
//!
//! Contact is a penalty force per unit length at every quadrature sample,
//! in the step's "forces" stage ([`contact`]): a sample closer to the
//! surface than a skin of [`ContactSettings::skin_m`] is pushed out along
//! the field's gradient, with a spring-damper whose stiffness is tied to
//! the step (k = α ρS / h²). Both CPU engines take the spring and damper
//! into the step matrix, as they take the strand's own stiffness, so the
//! push stays stable at any α and at whatever step the app runs; the GPU
//! kernels still apply it as an explicit force, at α below the explicit
//! limit ([`contact`] has both forms). The collider moves
//! rigidly with the head: samples are taken into head coordinates, and the
//! damping acts on the velocity relative to the moving surface. The force
//! is capped ([`ContactSettings::max_acceleration_m_per_s2`]), so a head
//! that jumps into the hair pushes it away instead of flinging it.

pub mod contact;
pub mod error;
pub mod sdf;
mod sdf_build;
pub mod winding;

pub use contact::{ContactInputs, ContactSettings};
pub use error::CollisionError;
pub use sdf::SignedDistanceField;
pub use sdf_build::{SIGN_BLOCK_CELLS, closest_point_on_triangle};
pub use winding::WindingNumber;

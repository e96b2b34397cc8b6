//! Where a strand grows from: a [`Root`] in a style, in head coordinates.
//!
//! Kept apart from [`crate::style`] so that every section of a style that
//! lists roots (a group's `roots`, an imported groom's strands) can use it
//! without depending on the whole style (`crate::style` re-exports it).

use glam::DVec3;
use helixhair_physics::RootPose;
use serde::{Deserialize, Serialize};

/// The reference direction of a root when the file gives none: +z, the
/// direction the face looks in head coordinates.
pub const DEFAULT_REFERENCE: DVec3 = DVec3::Z;

/// Where a strand grows from, in head coordinates (metres, y up, z towards
/// the face; the head sits at the origin).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Root {
    /// Root point in metres.
    pub position_m: DVec3,
    /// Growth direction at the root: the strand's first tangent. Any
    /// non-zero length; it is normalised.
    pub direction: DVec3,
    /// Sets the strand's material frame: its first material axis n₁ is the
    /// part of `reference` orthogonal to `direction` (any orthogonal axis
    /// when they are parallel). The natural curvature κ₁ bends the strand
    /// about n₁, so this turns the plane in which a curl starts. Default
    /// [`DEFAULT_REFERENCE`].
    #[serde(
        default = "default_reference",
        skip_serializing_if = "is_default_reference"
    )]
    pub reference: DVec3,
}

fn default_reference() -> DVec3 {
    DEFAULT_REFERENCE
}

fn is_default_reference(reference: &DVec3) -> bool {
    *reference == DEFAULT_REFERENCE
}

impl Root {
    /// A root with the default reference direction.
    pub fn new(position_m: DVec3, direction: DVec3) -> Self {
        Self {
            position_m,
            direction,
            reference: DEFAULT_REFERENCE,
        }
    }

    /// The physics root frame; the direction must be non-zero (as
    /// [`Style::validate`](crate::style::Style::validate) checks).
    pub fn pose(&self) -> RootPose {
        RootPose::from_direction(self.position_m, self.direction, self.reference)
    }
}

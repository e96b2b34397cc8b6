//! The head collider the app hands to the physics.
//!
//! The physics crate owns collision: a signed distance field built from
//! triangles in head coordinates, moving rigidly with the head trajectory,
//! and a penalty contact in the step's force stage
//! (`helixhair_physics::collision`). The field is built from the head mesh
//! as `helixhair render` builds it ([`head_collider`]: the mesh parts that
//! carry the scalp), once, and shared by the window's runs (main and
//! compare) through an `Arc`.

use std::sync::Arc;

use helixhair_physics::collision::SignedDistanceField;
use helixhair_physics::engine::Engine;
use helixhair_render::HeadMesh;

use crate::head::groom::head_collider;

/// A collider built from the head mesh, shared by every run.
#[derive(Clone, Debug)]
pub struct HeadCollider {
    field: Arc<SignedDistanceField>,
}

impl HeadCollider {
    /// Builds the collider of `head` (head coordinates, metres).
    pub fn from_head(head: &HeadMesh) -> Result<Self, String> {
        head_collider(head)
            .map(|field| Self {
                field: Arc::new(field),
            })
            .map_err(|e| format!("head collision is off: {e}"))
    }

    /// The distance field.
    pub fn field(&self) -> &SignedDistanceField {
        &self.field
    }

    /// Makes `engine` collide its strands with this collider (through
    /// [`Engine::set_collider`]; both engines push with the same implicit
    /// contact at every quadrature sample).
    pub fn attach(&self, engine: &mut Engine) {
        engine.set_collider(Some(self.field.clone()));
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use helixhair_render::head_generate::default_head;

    use super::*;

    #[test]
    fn the_default_heads_field_is_negative_inside_and_positive_outside() {
        let collider = HeadCollider::from_head(&default_head()).unwrap();
        let field = collider.field();
        // The skull's centre is inside; the crown is 10 cm above it.
        let (inside, _) = field.sample(DVec3::ZERO).unwrap();
        assert!(inside < -0.01, "{inside}");
        let (above, gradient) = field.sample(DVec3::new(0.0, 0.105, 0.0)).unwrap();
        assert!(above > 0.0 && above < 0.01, "{above}");
        assert!(gradient.y > 0.9, "{gradient}");
    }

    /// Only the skull collided: the default neck was a separate tube, left
    /// out of the field, and hair fell through neck and shoulders. The
    /// head is now one closed surface, and both are inside the field.
    #[test]
    fn the_neck_and_shoulders_collide_too() {
        let collider = HeadCollider::from_head(&default_head()).unwrap();
        let field = collider.field();
        for (inside, what) in [
            (DVec3::new(0.0, -0.16, -0.005), "neck"),
            (DVec3::new(0.11, -0.245, -0.005), "shoulder"),
        ] {
            let (d, _) = field.sample(inside).expect("in the grid");
            assert!(d < -0.005, "{what} at {inside}: {d} m");
        }
        // Beside the neck is outside.
        let (d, gradient) = field
            .sample(DVec3::new(0.06, -0.16, -0.005))
            .expect("in the grid");
        assert!(d > 0.005 && d < 0.03, "{d} m");
        assert!(gradient.x > 0.8, "{gradient}");
    }
}

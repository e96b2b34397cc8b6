//! The light's point of view for the deep opacity map.
//!
//! # How the deep opacity map works (Yuksel and Keyser 2008)
//!
//! 1. **depth**: the hair is drawn from the light into a depth texture,
//!    which then holds, per texel, the depth of the first hair the light
//!    meets.
//! 2. **opacity**: the hair is drawn again, additively, into an RGBA
//!    texture whose four channels are layers starting at that first depth
//!    and ending 1, 2, 4 and 8 layer thicknesses behind it. Each fragment
//!    adds its opacity to every layer that ends behind it, so channel k
//!    holds all the hair between the first strand and the end of layer k.
//! 3. **lookup**: a shaded point finds its depth behind the first hair and
//!    interpolates the layers there; light reaching it is exp(−opacity).
//!
//! Because the layers follow the hair's own first surface instead of fixed
//! depths, four layers are enough for a whole head of hair. The light is
//! directional, so its view is orthographic and depths are linear: one ndc
//! depth unit is [`LightView::depth_range_m`] metres.

use glam::camera::rh::{proj::directx, view};
use glam::{Mat4, Vec3};

/// An orthographic view from a directional light that sees a whole box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightView {
    /// The light's clip coordinates from world coordinates.
    pub clip_from_world: Mat4,
    /// Metres of depth per unit of ndc depth.
    pub depth_range_m: f32,
    /// Width (and height) of the square the light sees, metres.
    pub extent_m: f32,
}

impl LightView {
    /// Fits a view looking along `-towards_light` around the box `lo..hi`.
    pub fn fit(towards_light: Vec3, lo: Vec3, hi: Vec3) -> Self {
        let centre = 0.5 * (lo + hi);
        let radius_m = (0.5 * (hi - lo).length()).max(1e-3);
        let direction = towards_light.normalize_or(Vec3::Y);
        let up = if direction.y.abs() > 0.95 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        let eye = centre + direction * 2.0 * radius_m;
        let view_from_world = view::look_at_mat4(eye, centre, up);
        let (near, far) = (radius_m, 3.0 * radius_m);
        let clip_from_view =
            directx::orthographic(-radius_m, radius_m, -radius_m, radius_m, near, far);
        Self {
            clip_from_world: clip_from_view * view_from_world,
            depth_range_m: far - near,
            extent_m: 2.0 * radius_m,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_fits_and_depth_grows_away_from_the_light() {
        let (lo, hi) = (Vec3::splat(-0.2), Vec3::splat(0.2));
        let light = LightView::fit(Vec3::new(1.0, 1.0, 0.0), lo, hi);
        let ndc = |p: Vec3| light.clip_from_world.project_point3(p);
        for corner in [
            lo,
            hi,
            Vec3::new(-0.2, 0.2, 0.2),
            Vec3::new(0.2, -0.2, -0.2),
        ] {
            let c = ndc(corner);
            assert!(c.abs().max_element() <= 1.0 + 1e-5, "{corner} -> {c}");
            assert!(c.z >= 0.0, "{c}");
        }
        let near = ndc(Vec3::new(0.1, 0.1, 0.0)).z;
        let far = ndc(Vec3::new(-0.1, -0.1, 0.0)).z;
        let metres = (far - near) * light.depth_range_m;
        assert!(
            (metres - 0.2f32.sqrt() * 0.2f32.sqrt() * 2f32.sqrt()).abs() < 1e-4,
            "{metres}"
        );
    }
}

//! The orbit camera: a point it looks at, and where on a sphere around that
//! point the eye sits.
//!
//! Artists orbit a head: yaw turns around the vertical axis, pitch raises
//! the eye, distance zooms. Keeping those three numbers (instead of a view
//! matrix) makes every input gesture a change of one of them, and the view
//! can never roll. The window's input handling lives in the app; the math
//! lives here so headless renders and the window agree.
//!
//! Conventions: y up, yaw 0 puts the eye on +z (in front of the face, which
//! looks along +z), positive yaw turns the eye towards +x, positive pitch
//! raises it. Projections map depth to [0, 1] with y up, as wgpu wants.

use glam::camera::rh::{proj::directx, view};
use glam::{Mat4, Vec3};

/// Nearest pitch to the poles, radians: at ±90° the up vector and the view
/// direction would be parallel.
pub const MAX_PITCH_RAD: f32 = 1.55;

/// An orbit camera around `target_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitCamera {
    /// The point looked at, metres, world coordinates.
    pub target_m: Vec3,
    /// Turn around the vertical axis, radians; 0 looks at the face.
    pub yaw_rad: f32,
    /// Elevation of the eye, radians, within ±[`MAX_PITCH_RAD`].
    pub pitch_rad: f32,
    /// Distance from the eye to the target, metres.
    pub distance_m: f32,
    /// Vertical field of view, radians.
    pub fov_y_rad: f32,
}

impl Default for OrbitCamera {
    /// A three-quarter portrait of a head at the origin: 35° to the side,
    /// slightly above, 0.8 m away with a 30° lens, which frames a head with
    /// shoulder-length hair.
    fn default() -> Self {
        Self {
            target_m: Vec3::new(0.0, -0.05, 0.0),
            yaw_rad: 35f32.to_radians(),
            pitch_rad: 12f32.to_radians(),
            distance_m: 0.8,
            fov_y_rad: 30f32.to_radians(),
        }
    }
}

impl OrbitCamera {
    /// Where the eye is, metres, world coordinates.
    pub fn eye_m(&self) -> Vec3 {
        let pitch = self.pitch_rad.clamp(-MAX_PITCH_RAD, MAX_PITCH_RAD);
        let (sy, cy) = self.yaw_rad.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        self.target_m + self.distance_m * Vec3::new(cp * sy, sp, cp * cy)
    }

    /// View matrix: camera coordinates from world coordinates.
    pub fn view_from_world(&self) -> Mat4 {
        view::look_at_mat4(self.eye_m(), self.target_m, Vec3::Y)
    }

    /// Projection for an image `aspect` = width / height wide: clip
    /// coordinates from camera coordinates. Near and far planes scale with
    /// the distance so depth precision follows the zoom.
    pub fn clip_from_view(&self, aspect: f32) -> Mat4 {
        let near = self.distance_m * 0.05;
        let far = self.distance_m * 4.0;
        directx::perspective(self.fov_y_rad, aspect, near, far)
    }

    /// Clip coordinates from world coordinates.
    pub fn clip_from_world(&self, aspect: f32) -> Mat4 {
        self.clip_from_view(aspect) * self.view_from_world()
    }

    /// Turns the eye around the target by `d_yaw_rad` and `d_pitch_rad`
    /// (pitch is clamped short of the poles).
    pub fn orbit(&mut self, d_yaw_rad: f32, d_pitch_rad: f32) {
        self.yaw_rad += d_yaw_rad;
        self.pitch_rad = (self.pitch_rad + d_pitch_rad).clamp(-MAX_PITCH_RAD, MAX_PITCH_RAD);
    }

    /// Moves the eye towards the target by `factor` (< 1 zooms in), keeping
    /// the distance positive.
    pub fn zoom(&mut self, factor: f32) {
        self.distance_m = (self.distance_m * factor).max(1e-3);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yaw_zero_looks_at_the_face_from_plus_z() {
        let camera = OrbitCamera {
            target_m: Vec3::ZERO,
            yaw_rad: 0.0,
            pitch_rad: 0.0,
            distance_m: 2.0,
            fov_y_rad: 1.0,
        };
        assert!((camera.eye_m() - Vec3::new(0.0, 0.0, 2.0)).length() < 1e-6);
        // The target lands in the middle of the image, at a depth in (0, 1).
        let clip = camera.clip_from_world(1.5) * camera.target_m.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        assert!(ndc.x.abs() < 1e-6 && ndc.y.abs() < 1e-6, "{ndc}");
        assert!(ndc.z > 0.0 && ndc.z < 1.0, "{ndc}");
        // A point above the target is above the middle (y up).
        let up = camera.clip_from_world(1.5) * Vec3::new(0.0, 0.1, 0.0).extend(1.0);
        assert!(up.y / up.w > 0.0);
    }

    #[test]
    fn orbit_keeps_the_distance_and_clamps_the_pitch() {
        let mut camera = OrbitCamera::default();
        camera.orbit(0.7, 10.0);
        assert_eq!(camera.pitch_rad, MAX_PITCH_RAD);
        let d = (camera.eye_m() - camera.target_m).length();
        assert!((d - camera.distance_m).abs() < 1e-5);
        camera.zoom(0.5);
        assert!((camera.distance_m - 0.4).abs() < 1e-6);
    }
}

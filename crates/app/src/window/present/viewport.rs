//! The 3D view: what the renderer is asked to draw, and how the mouse and
//! keys move the camera and the head.
//!
//! Input, as in most 3D tools:
//!
//! | gesture | effect |
//! | --- | --- |
//! | left drag | orbit the camera around its target |
//! | right or middle drag, or Shift + left drag | pan |
//! | wheel, trackpad scroll or pinch | zoom |
//! | F | frame the head |
//! | Alt + left drag | turn and tilt the head (the hair follows) |
//! | Alt + right drag | move the head |
//!
//! Drawing: the simulation gives guide strands; the picture shows many
//! more drawn strands that follow them ([`crate::window::live::drawn`], the same strands
//! `helixhair render` draws), carried with the head, so a few dozen
//! simulated guides read as a full head of hair.

use glam::{DVec3, Vec3};
use helixhair_render::OrbitCamera;

use crate::window::live::head_motion::ManualPose;

/// Strands drawn by default (at most; a style may ask for fewer).
pub const DEFAULT_RENDER_STRANDS: usize = 1000;

/// Orbit speed, radians per point dragged.
const ORBIT_RAD_PER_PT: f32 = 0.008;

/// Head turn speed under Alt-drag, radians per point.
const HEAD_TURN_RAD_PER_PT: f64 = 0.006;

/// A camera that frames the head and its hair from a three-quarter view,
/// the head turning about `pivot_m` (the origin for the default head;
/// [`crate::head::of_style`]).
pub fn framed_camera(pivot_m: DVec3) -> OrbitCamera {
    let mut camera = OrbitCamera::default();
    camera.target_m += pivot_m.as_vec3();
    camera
}

/// Pans `camera` by a drag of (`dx`, `dy`) points in a view `height_pt`
/// points tall: the target moves so the scene follows the pointer.
pub fn pan(camera: &mut OrbitCamera, dx: f32, dy: f32, height_pt: f32) {
    let view = camera.view_from_world();
    let right = Vec3::new(view.x_axis.x, view.y_axis.x, view.z_axis.x);
    let up = Vec3::new(view.x_axis.y, view.y_axis.y, view.z_axis.y);
    let metres_per_pt =
        2.0 * camera.distance_m * (0.5 * camera.fov_y_rad).tan() / height_pt.max(1.0);
    camera.target_m += (-dx * right + dy * up) * metres_per_pt;
}

/// Orbits `camera` by a drag of (`dx`, `dy`) points.
pub fn orbit(camera: &mut OrbitCamera, dx: f32, dy: f32) {
    camera.orbit(-dx * ORBIT_RAD_PER_PT, dy * ORBIT_RAD_PER_PT);
}

/// Turns the user's head pose by an Alt-drag of (`dx`, `dy`) points.
pub fn turn_head(pose: &mut ManualPose, dx: f32, dy: f32) {
    pose.turn_rad = (pose.turn_rad + f64::from(dx) * HEAD_TURN_RAD_PER_PT).clamp(-1.4, 1.4);
    pose.tilt_rad = (pose.tilt_rad + f64::from(dy) * HEAD_TURN_RAD_PER_PT).clamp(-0.7, 0.7);
}

/// Moves the user's head pose by an Alt-right-drag, in the camera's plane.
pub fn move_head(pose: &mut ManualPose, camera: &OrbitCamera, dx: f32, dy: f32, height_pt: f32) {
    let mut probe = *camera;
    pan(&mut probe, -dx, -dy, height_pt);
    let delta = (probe.target_m - camera.target_m).as_dvec3();
    pose.offset_m = (pose.offset_m + delta).clamp(DVec3::splat(-0.3), DVec3::splat(0.3));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panning_follows_the_pointer_at_the_target_depth() {
        let mut camera = OrbitCamera {
            yaw_rad: 0.0,
            pitch_rad: 0.0,
            target_m: Vec3::ZERO,
            ..OrbitCamera::default()
        };
        // Looking along −z: dragging right by a full view height moves the
        // target left by the view's height at the target's depth.
        let height_m = 2.0 * camera.distance_m * (0.5 * camera.fov_y_rad).tan();
        pan(&mut camera, 500.0, 0.0, 500.0);
        assert!((camera.target_m - Vec3::new(-height_m, 0.0, 0.0)).length() < 1e-5);
    }
}

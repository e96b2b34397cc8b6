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
//! more render strands interpolated from them ([`interpolate_strands`]),
//! rooted on the scalp and carried with the head, so a few dozen simulated
//! guides read as a full head of hair.

use glam::{DMat3, DVec3, Vec3};
use helixhair_render::interpolate::{Interpolation, InterpolationSpec, interpolate_strands};
use helixhair_render::scalp_sampling::poisson_disk_on_scalp;
use helixhair_render::{HairStrands, HeadMesh, OrbitCamera, StrandBuffers};

use super::head_motion::ManualPose;

/// Render strands drawn by default.
pub const DEFAULT_RENDER_STRANDS: usize = 1000;

/// Points per render strand.
const RENDER_POINTS: usize = 24;

/// Orbit speed, radians per point dragged.
const ORBIT_RAD_PER_PT: f32 = 0.008;

/// Head turn speed under Alt-drag, radians per point.
const HEAD_TURN_RAD_PER_PT: f64 = 0.006;

/// A camera that frames the head and its hair from a three-quarter view.
pub fn framed_camera() -> OrbitCamera {
    OrbitCamera::default()
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

/// What the view draws besides the simulation: the render strands' roots
/// and colours, made once.
#[derive(Clone, Debug)]
pub struct HairLook {
    roots_head_m: Vec<Vec3>,
    colours: Vec<Vec3>,
}

impl HairLook {
    /// `count` render strands on `head`'s scalp, dark brown with a little
    /// variation from strand to strand.
    pub fn new(head: &HeadMesh, count: usize) -> Self {
        let roots_head_m: Vec<Vec3> = poisson_disk_on_scalp(head, count, 11)
            .into_iter()
            .map(|s| s.position_m)
            .collect();
        let colours = (0..roots_head_m.len())
            .map(|i| {
                let t = ((i as f32 * 0.618_034).fract() - 0.5) * 0.25;
                Vec3::new(0.13, 0.07, 0.035) * (1.0 + t)
            })
            .collect();
        Self {
            roots_head_m,
            colours,
        }
    }

    /// Render strands following `guides` on a head at `pose` (rotation,
    /// position): the first `max_strands` of them (the interactive preview
    /// draws fewer; the roots come in dart-throwing order, so any first
    /// part of them is spread over the whole scalp).
    pub fn strands(
        &self,
        guides: &StrandBuffers,
        pose: (DMat3, DVec3),
        max_strands: usize,
    ) -> HairStrands {
        let rotation = pose.0.as_mat3();
        let position = pose.1.as_vec3();
        let roots: Vec<Vec3> = self
            .roots_head_m
            .iter()
            .take(max_strands)
            .map(|&r| rotation * r + position)
            .collect();
        let spec = InterpolationSpec {
            method: Interpolation::Nearest,
            points_per_strand: RENDER_POINTS,
            length_variation: 0.15,
            seed: 3,
        };
        HairStrands {
            strands: interpolate_strands(guides, &roots, &spec),
            colours: self.colours[..roots.len()].to_vec(),
            root_width_m: 4e-4,
            tip_width_m: 1e-4,
        }
    }
}

/// `head` moved rigidly to `pose` (rotation, position).
pub fn posed_head(head: &HeadMesh, pose: (DMat3, DVec3)) -> HeadMesh {
    let rotation = pose.0.as_mat3();
    let position = pose.1.as_vec3();
    let mut out = head.clone();
    for p in &mut out.mesh.positions {
        *p = rotation * *p + position;
    }
    for n in &mut out.mesh.normals {
        *n = rotation * *n;
    }
    out
}

#[cfg(test)]
mod tests {
    use helixhair_render::head_generate::default_head;

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

    #[test]
    fn render_roots_ride_with_the_head() {
        let head = default_head();
        let look = HairLook::new(&head, 50);
        let mut guides = StrandBuffers::default();
        guides.push_strand([Vec3::new(0.0, 0.1, 0.0), Vec3::new(0.0, 0.0, -0.1)]);
        let still = look.strands(&guides, (DMat3::IDENTITY, DVec3::ZERO), usize::MAX);
        let moved = look.strands(
            &guides,
            (DMat3::IDENTITY, DVec3::new(0.0, 0.0, 0.5)),
            usize::MAX,
        );
        assert_eq!(still.strands.strand_count(), 50);
        let (a, b) = (still.strands.strand(7)[0], moved.strands.strand(7)[0]);
        assert!((b - a - Vec3::new(0.0, 0.0, 0.5)).length() < 1e-5);
    }
}

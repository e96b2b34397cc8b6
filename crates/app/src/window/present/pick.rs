//! What lies under the pointer in the 3D view: the ray through a pixel,
//! where it meets the head or the hair, and how large a brush of a given
//! radius looks there. The brush tools centre their sphere on that point,
//! so the brush follows the surface under the cursor.
//!
//! The ray is the camera's: the pointer's position in the view unprojected
//! through the inverse of the camera's clip-from-world matrix at the near
//! and far planes. The head is met by an exact ray–triangle test over the
//! posed mesh (Möller–Trumbore); the hair, which has no surface, is met at
//! the nearest point along the ray that lies within a pick distance of a
//! hair point.

use glam::{DVec3, Vec2, Vec4};
use helixhair_render::{Mesh, OrbitCamera};

/// A ray from `origin_m` along unit `direction`, world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where it starts (on the near plane), metres.
    pub origin_m: DVec3,
    /// Its unit direction.
    pub direction: DVec3,
}

impl Ray {
    /// The point `t_m` metres along the ray.
    pub fn at(&self, t_m: f64) -> DVec3 {
        self.origin_m + t_m * self.direction
    }
}

/// The ray through `pointer_pt` (points from the view's top left) of a
/// view `size_pt` points large, seen by `camera`.
pub fn pointer_ray(camera: &OrbitCamera, size_pt: Vec2, pointer_pt: Vec2) -> Ray {
    let aspect = size_pt.x / size_pt.y.max(1.0);
    let world_from_clip = camera.clip_from_world(aspect).inverse();
    let ndc = Vec2::new(
        2.0 * pointer_pt.x / size_pt.x.max(1.0) - 1.0,
        1.0 - 2.0 * pointer_pt.y / size_pt.y.max(1.0),
    );
    let unproject = |depth: f32| {
        let p = world_from_clip * Vec4::new(ndc.x, ndc.y, depth, 1.0);
        (p.truncate() / p.w).as_dvec3()
    };
    let (near, far) = (unproject(0.0), unproject(1.0));
    Ray {
        origin_m: near,
        direction: (far - near).normalize(),
    }
}

/// Distance along `ray` to the nearest triangle of `mesh`, if it meets one.
pub fn ray_mesh(ray: &Ray, mesh: &Mesh) -> Option<f64> {
    mesh.indices
        .chunks_exact(3)
        .filter_map(|t| {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions[i as usize].as_dvec3());
            ray_triangle(ray, a, b, c)
        })
        .min_by(f64::total_cmp)
}

/// Möller–Trumbore: distance along `ray` to triangle `a b c`, either side.
fn ray_triangle(ray: &Ray, a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = ray.direction.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-14 {
        return None;
    }
    let s = ray.origin_m - a;
    let u = s.dot(p) / det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = ray.direction.dot(q) / det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) / det;
    (t > 0.0).then_some(t)
}

/// Distance along `ray` to the nearest hair point within `pick_m` of it.
pub fn ray_hair(ray: &Ray, strands: &[Vec<DVec3>], pick_m: f64) -> Option<f64> {
    strands
        .iter()
        .flatten()
        .filter_map(|&p| {
            let t = (p - ray.origin_m).dot(ray.direction);
            (t > 0.0 && ray.at(t).distance(p) <= pick_m).then_some(t)
        })
        .min_by(f64::total_cmp)
}

/// Where `ray` meets the plane through `point_m` facing the camera along
/// `normal`; `None` when parallel or behind.
pub fn ray_plane(ray: &Ray, point_m: DVec3, normal: DVec3) -> Option<DVec3> {
    let denom = ray.direction.dot(normal);
    if denom.abs() < 1e-12 {
        return None;
    }
    let t = (point_m - ray.origin_m).dot(normal) / denom;
    (t > 0.0).then(|| ray.at(t))
}

/// How many points a length of `radius_m` at `point_m` spans in a view
/// `height_pt` points tall.
pub fn radius_pt(camera: &OrbitCamera, point_m: DVec3, radius_m: f64, height_pt: f32) -> f32 {
    let depth_m = (point_m - camera.eye_m().as_dvec3()).length().max(1e-6);
    let view_height_m = 2.0 * depth_m * f64::from(0.5 * camera.fov_y_rad).tan();
    (radius_m / view_height_m * f64::from(height_pt)) as f32
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn facing_camera() -> OrbitCamera {
        OrbitCamera {
            target_m: Vec3::ZERO,
            yaw_rad: 0.0,
            pitch_rad: 0.0,
            distance_m: 1.0,
            fov_y_rad: 30f32.to_radians(),
        }
    }

    #[test]
    fn the_centre_pixel_looks_at_the_target_and_a_corner_along_the_frustum() {
        let camera = facing_camera();
        let size = Vec2::new(800.0, 600.0);
        let ray = pointer_ray(&camera, size, size / 2.0);
        // Eye at +z looking along −z.
        assert!((ray.direction - DVec3::NEG_Z).length() < 1e-6);
        assert!(ray.origin_m.x.abs() < 1e-6 && ray.origin_m.y.abs() < 1e-6);
        // The top edge's middle: half the vertical field of view up.
        let top = pointer_ray(&camera, size, Vec2::new(400.0, 0.0));
        let angle = top.direction.angle_between(DVec3::NEG_Z);
        assert!((angle - 15f64.to_radians()).abs() < 1e-5, "{angle}");
        assert!(top.direction.y > 0.0);
    }

    #[test]
    fn a_ray_meets_the_nearest_triangle_and_the_nearest_hair_point() {
        let ray = Ray {
            origin_m: DVec3::new(0.0, 0.0, 1.0),
            direction: DVec3::NEG_Z,
        };
        // Two squares across the ray at z = 0.2 and z = −0.3.
        let mut mesh = Mesh {
            positions: Vec::new(),
            normals: Vec::new(),
            indices: Vec::new(),
        };
        for z in [-0.3f32, 0.2] {
            let base = mesh.positions.len() as u32;
            for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions.push(Vec3::new(x, y, z));
                mesh.normals.push(Vec3::Z);
            }
            mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
        }
        let t = ray_mesh(&ray, &mesh).unwrap();
        assert!((t - 0.8).abs() < 1e-6, "{t}");
        let strands = vec![
            vec![DVec3::new(0.004, 0.0, 0.5), DVec3::new(0.0, 0.0, 0.1)],
            vec![DVec3::new(0.05, 0.0, 0.9)],
        ];
        let t = ray_hair(&ray, &strands, 0.005).unwrap();
        assert!((t - 0.5).abs() < 1e-12, "{t}");
        let p = ray_plane(&ray, DVec3::new(3.0, 2.0, -0.1), DVec3::Z).unwrap();
        assert!((p - DVec3::new(0.0, 0.0, -0.1)).length() < 1e-12);
    }

    #[test]
    fn a_brush_radius_spans_its_share_of_the_view_height() {
        let camera = facing_camera();
        // At the target (1 m away) the view is 2 tan 15° m tall.
        let tall_m = 2.0 * 15f64.to_radians().tan();
        let px = radius_pt(&camera, DVec3::ZERO, 0.1, 600.0);
        assert!((f64::from(px) - 0.1 / tall_m * 600.0).abs() < 1e-3, "{px}");
    }
}

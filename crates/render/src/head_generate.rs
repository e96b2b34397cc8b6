//! The project's default head, built procedurally: a stylised bust that
//! needs no downloaded asset and no licence.
//!
//! # How it is built
//!
//! A latitude–longitude sphere is bent into a head: each direction d from
//! the head's centre is scaled by per-axis radii that change over the
//! sphere (a longer back of the skull, a narrowing jaw, a chin lower than
//! the crown), then pushed out or in along d by a few smooth bumps (nose,
//! brow, cheeks, ears) and dents (eye sockets). A tapered cylinder below is
//! the neck. Every shape term is a smooth function of d, so normals come
//! out smooth from [`Mesh::compute_normals`].
//!
//! The scalp is every head triangle whose three corners lie above the
//! hairline, a curve over the sphere that sits at the forehead in front,
//! above the ears at the sides and at the nape behind (see [`on_scalp`]).
//!
//! Coordinates: metres, y up, the face looking along +z, the centre of the
//! cranium at the origin (about ear height), as the styles assume.
//! `cargo run -p helixhair-render --example make_head` writes this mesh to
//! `assets/head.obj` with the scalp as OBJ group `scalp`.

use std::f32::consts::{PI, TAU};

use glam::Vec3;

use crate::mesh::HeadMesh;

/// Rings of the head sphere from crown to chin.
pub const HEAD_RINGS: usize = 48;
/// Vertices around each ring.
pub const HEAD_SEGMENTS: usize = 64;
/// Rings of the neck cylinder.
const NECK_RINGS: usize = 6;

/// A smooth bump of `height_m` centred on direction `centre`, falling off
/// with angular `width_rad`.
fn bump(d: Vec3, centre: Vec3, width_rad: f32, height_m: f32) -> f32 {
    let angle = d.dot(centre.normalize()).clamp(-1.0, 1.0).acos();
    height_m * (-(angle / width_rad).powi(2)).exp()
}

/// The head surface point in direction `d` (a unit vector from the
/// cranium's centre).
pub fn head_point_m(d: Vec3) -> Vec3 {
    let below = (-d.y).max(0.0);
    // Half-widths, metres: the jaw narrows the lower half.
    let radius_x = 0.074 * (1.0 - 0.30 * below.powi(2));
    let radius_y = if d.y > 0.0 { 0.100 } else { 0.120 };
    let radius_z = if d.z > 0.0 {
        0.090 * (1.0 - 0.30 * below.powi(2))
    } else {
        0.100 * (1.0 - 0.50 * below.powi(2))
    };
    let mirrored = Vec3::new(d.x.abs(), d.y, d.z);
    let relief = bump(d, Vec3::new(0.0, -0.04, 1.0), 0.10, 0.007) // nose bridge
        + bump(d, Vec3::new(0.0, -0.20, 1.0), 0.12, 0.020) // nose tip
        + bump(d, Vec3::new(0.0, -0.42, 1.0), 0.20, 0.008) // lips
        + bump(d, Vec3::new(0.0, -0.78, 0.62), 0.16, 0.010) // chin
        + bump(d, Vec3::new(0.0, 0.16, 1.0), 0.35, 0.004) // brow
        + bump(mirrored, Vec3::new(0.55, -0.25, 0.8), 0.25, 0.005) // cheeks
        + bump(mirrored, Vec3::new(1.0, -0.02, -0.08), 0.14, 0.012) // ears
        - bump(mirrored, Vec3::new(0.36, 0.03, 0.93), 0.16, 0.005); // eye sockets
    // The jaw and chin sit forward of the skull's centre, the nape too.
    let forward_m = 0.045 * below.powf(1.5);
    Vec3::new(d.x * radius_x, d.y * radius_y, d.z * radius_z + forward_m) + relief * d
}

/// Whether `p` lies inside the head (nearer the centre than the surface in
/// its direction).
fn inside_head(p: Vec3) -> bool {
    let r = p.length();
    r == 0.0 || r < head_point_m(p / r).length()
}

/// Height of the head's underside above the point (`x_m`, `z_m`) of the
/// horizontal plane, found by bisection between the centre's height
/// (inside) and a point below the chin (outside).
fn underside_y_m(x_m: f32, z_m: f32) -> f32 {
    let (mut inside, mut outside) = (0.0f32, -0.2f32);
    for _ in 0..30 {
        let mid = 0.5 * (inside + outside);
        if inside_head(Vec3::new(x_m, mid, z_m)) {
            inside = mid;
        } else {
            outside = mid;
        }
    }
    outside
}

/// Whether the head surface in direction `d` grows hair: above a hairline
/// at the forehead in front, above the ears at the sides and down to the
/// nape at the back.
pub fn on_scalp(d: Vec3) -> bool {
    let hairline = if d.z > 0.0 {
        0.12 + 0.33 * d.z
    } else {
        0.12 + 0.62 * d.z
    };
    d.y > hairline
}

/// Unit direction of ring `ring` (0 = crown, [`HEAD_RINGS`] = chin),
/// segment `segment` (0 = face, turning towards +x).
fn sphere_direction(ring: usize, segment: usize) -> Vec3 {
    let theta = PI * ring as f32 / HEAD_RINGS as f32;
    let phi = TAU * segment as f32 / HEAD_SEGMENTS as f32;
    Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        theta.sin() * phi.cos(),
    )
}

/// Adds triangle `corners` (counter-clockwise from outside), marking it
/// scalp when `scalp` says so.
fn push_triangle(head: &mut HeadMesh, corners: [u32; 3], scalp: bool) {
    if scalp {
        head.scalp_triangles.push(head.mesh.triangle_count() as u32);
    }
    head.mesh.indices.extend(corners);
}

/// Builds the default head (about 6,900 triangles, two fifths of them
/// scalp).
///
/// Vertices: the crown pole, rings 1 to [`HEAD_RINGS`] − 1 of
/// [`HEAD_SEGMENTS`] vertices each, the chin pole, then the neck's rings.
/// Rings wrap around without a seam, so normals are smooth everywhere.
pub fn default_head() -> HeadMesh {
    let segments = HEAD_SEGMENTS as u32;
    let mut head = HeadMesh::default();
    let mut directions = vec![Vec3::Y];
    for ring in 1..HEAD_RINGS {
        directions.extend((0..HEAD_SEGMENTS).map(|s| sphere_direction(ring, s)));
    }
    directions.push(Vec3::NEG_Y);
    head.mesh.positions = directions.iter().map(|&d| head_point_m(d)).collect();
    let chin = directions.len() as u32 - 1;
    // Vertex of ring `r` (1..HEAD_RINGS), segment `s` (wrapping); the poles
    // stand in for rings 0 and HEAD_RINGS.
    let vertex = |r: u32, s: u32| match r {
        0 => 0,
        r if r == HEAD_RINGS as u32 => chin,
        r => 1 + (r - 1) * segments + s % segments,
    };
    let scalp = |corners: [u32; 3]| corners.iter().all(|&i| on_scalp(directions[i as usize]));
    for r in 0..HEAD_RINGS as u32 {
        for s in 0..segments {
            let (a, b) = (vertex(r, s), vertex(r + 1, s));
            let (a1, b1) = (vertex(r, s + 1), vertex(r + 1, s + 1));
            if r > 0 {
                push_triangle(&mut head, [a, b, a1], scalp([a, b, a1]));
            }
            if r + 1 < HEAD_RINGS as u32 {
                push_triangle(&mut head, [a1, b, b1], scalp([a1, b, b1]));
            }
        }
    }
    // The neck: a tube hanging from the underside of the head, flaring at
    // the bottom into the start of the shoulders (wide in x, shallow in
    // z). Its top ring lies on the head's surface, so no part of the neck
    // is inside the skull: the head stays a closed solid of its own, as a
    // collider needs.
    let neck_first = head.mesh.positions.len() as u32;
    for ring in 0..=NECK_RINGS {
        let t = ring as f32 / NECK_RINGS as f32;
        let y_m = -0.05 - 0.19 * t;
        let flare = t.powi(4);
        let (radius_x_m, radius_z_m) = (0.052 + 0.10 * flare, 0.047 + 0.025 * flare);
        for segment in 0..HEAD_SEGMENTS {
            let (sin, cos) = (TAU * segment as f32 / HEAD_SEGMENTS as f32).sin_cos();
            let (x_m, z_m) = (radius_x_m * sin, -0.005 + radius_z_m * cos);
            let y_m = if ring == 0 {
                underside_y_m(x_m, z_m)
            } else {
                y_m
            };
            head.mesh.positions.push(Vec3::new(x_m, y_m, z_m));
        }
    }
    let neck = |r: u32, s: u32| neck_first + r * segments + s % segments;
    for r in 0..NECK_RINGS as u32 {
        for s in 0..segments {
            let (a, b, a1, b1) = (
                neck(r, s),
                neck(r + 1, s),
                neck(r, s + 1),
                neck(r + 1, s + 1),
            );
            push_triangle(&mut head, [a, b, a1], false);
            push_triangle(&mut head, [a1, b, b1], false);
        }
    }
    // A cap closes the neck's bottom, so the neck, too, bounds a solid.
    for (ring, outward_y) in [(NECK_RINGS as u32, -1.0f32)] {
        let centre = head.mesh.positions.len() as u32;
        let ring_centre = (0..segments)
            .map(|s| head.mesh.positions[neck(ring, s) as usize])
            .sum::<Vec3>()
            / segments as f32;
        head.mesh.positions.push(ring_centre);
        for s in 0..segments {
            let (a, b) = (neck(ring, s), neck(ring, s + 1));
            // Counter-clockwise seen from outside: up for the top cap,
            // down for the bottom one.
            let corners = if outward_y > 0.0 {
                [centre, a, b]
            } else {
                [centre, b, a]
            };
            push_triangle(&mut head, corners, false);
        }
    }
    head.mesh.compute_normals();
    head
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Vertices of the head sphere (poles and rings), before the neck's.
    const HEAD_VERTICES: usize = 2 + (HEAD_RINGS - 1) * HEAD_SEGMENTS;

    #[test]
    fn the_scalp_is_the_top_and_back_of_the_head() {
        let head = default_head();
        let scalp = head.scalp_triangles.len();
        let total = head.mesh.triangle_count();
        assert!(scalp > total / 6 && scalp < total / 2, "{scalp} of {total}");
        // Scalp area of a real adult head is about 0.06 m²; a stylised one
        // should be the same order.
        let area = head.scalp_area_m2();
        assert!((0.02..0.09).contains(&area), "{area} m²");
        for &t in &head.scalp_triangles {
            let centre = head.mesh.triangle(t as usize).iter().sum::<Vec3>() / 3.0;
            assert!(centre.y > 0.0 || centre.z < 0.0, "{centre}");
        }
    }

    #[test]
    fn normals_point_outwards_and_the_face_looks_along_plus_z() {
        let head = default_head();
        for (p, n) in head.mesh.positions[..HEAD_VERTICES]
            .iter()
            .zip(&head.mesh.normals)
        {
            // Outward except in the deep folds (ears, nose sides).
            assert!(n.dot(*p) > -0.5 * p.length(), "{p} {n}");
        }
        let (lo, hi) = head.mesh.bounds_m();
        assert!(hi.z > 0.1 && lo.z > -0.11, "nose in front: {lo} {hi}");
        assert!((hi.y - 0.1).abs() < 0.01, "crown at 10 cm: {hi}");
    }
}

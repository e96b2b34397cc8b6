//! The project's default head, built procedurally: a stylised bust that
//! needs no downloaded asset and no licence.
//!
//! # How it is built
//!
//! A latitude–longitude sphere is bent into a head: each direction d from
//! the head's centre is scaled by per-axis radii that change over the
//! sphere (a longer back of the skull, a narrowing jaw, a chin lower than
//! the crown), then pushed out or in along d by a few smooth bumps (nose,
//! brow, cheeks, ears) and dents (eye sockets). Every shape term is a
//! smooth function of d, so normals come out smooth from
//! [`Mesh::compute_normals`](crate::mesh::Mesh::compute_normals).
//!
//! The sphere's rings are not parallels: the first [`SCALP_RINGS`] run
//! from the crown down to the hairline, a curve that sits at the forehead
//! in front, above the ears at the sides and at the nape behind
//! ([`on_scalp`]), the last of them exactly on it, so the scalp (the
//! triangles above it) has a smooth edge. The next rings cover the face
//! down to a join curve under the jaw and at the base of the skull, and
//! from there the same rings bend into the neck and flare into shoulders,
//! closed by a pole at the bottom: head, neck and shoulders are one closed
//! surface, with no crack at the jaw and no rim where a separate neck tube
//! would end, and all of it collides.
//!
//! Coordinates: metres, y up, the face looking along +z, the centre of the
//! cranium at the origin (about ear height), as the styles assume.
//! `cargo run -p helixhair-render --example make_head` writes this mesh to
//! `assets/head.obj` with the scalp as OBJ group `scalp`.

use std::f32::consts::{PI, TAU};

use glam::Vec3;

use crate::mesh::HeadMesh;

/// Rings of the scalp, from the crown to the hairline.
pub const SCALP_RINGS: usize = 24;
/// Rings of the face, ears and nape, from the hairline to where the neck
/// joins.
pub const FACE_RINGS: usize = 22;
/// Vertices around each ring.
pub const HEAD_SEGMENTS: usize = 64;
/// Rings that bend the join curve into the neck's top.
const JOIN_RINGS: usize = 5;
/// The neck and shoulders below the join, top to bottom: height, half
/// width (x) and half depth (z) of each ring, metres; an ellipse around
/// (0, y, [`NECK_CENTRE_Z_M`]). The last rings round the bust's bottom off
/// towards its pole, so it ends without a rim.
const NECK_PROFILE: [(f32, f32, f32); 10] = [
    (-0.125, 0.046, 0.046),
    (-0.150, 0.046, 0.046),
    (-0.175, 0.048, 0.047),
    (-0.195, 0.055, 0.050),
    (-0.210, 0.070, 0.055),
    (-0.222, 0.095, 0.062),
    (-0.232, 0.125, 0.068),
    (-0.242, 0.148, 0.072),
    (-0.256, 0.148, 0.070),
    (-0.266, 0.110, 0.052),
];
/// Height of the bust's bottom pole, metres.
const BOTTOM_Y_M: f32 = -0.272;
/// Depth of the neck's axis, metres (a little behind the cranium's centre).
const NECK_CENTRE_Z_M: f32 = -0.005;

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

/// Whether the head surface in direction `d` grows hair: above a hairline
/// at the forehead in front, above the ears at the sides and down to the
/// nape at the back.
pub fn on_scalp(d: Vec3) -> bool {
    // Height 0.12 + 0.33 z in front and 0.12 + 0.62 z behind (lower at the
    // nape), joined smoothly above the ears: |z| is rounded off within
    // 0.15 of z = 0, so the hairline has no corner there; it arches over
    // each ear (azimuth about 95°), as real hairlines do, instead of
    // running across the ear's bump.
    let rounded_abs_z = (d.z * d.z + 0.15f32.powi(2)).sqrt() - 0.15;
    let around = glam::Vec2::new(d.x.abs(), d.z).normalize_or_zero();
    let from_ear_rad = around
        .dot(glam::Vec2::new(0.997, -0.08))
        .clamp(-1.0, 1.0)
        .acos();
    let over_ear = 0.14 * (-(from_ear_rad / 0.4).powi(2)).exp();
    let hairline = 0.12 + 0.475 * d.z - 0.145 * rounded_abs_z + over_ear;
    d.y > hairline
}

/// Unit direction at polar angle `theta` from the crown and azimuth `phi`
/// (0 = face, turning towards +x).
fn direction(theta: f32, phi: f32) -> Vec3 {
    Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        theta.sin() * phi.cos(),
    )
}

/// Polar angle of the hairline at azimuth `phi`: where [`on_scalp`]'s
/// boundary crosses that meridian (bisection; the scalp is the cap above).
pub fn hairline_theta(phi: f32) -> f32 {
    let (mut above, mut below) = (0.0f32, PI);
    for _ in 0..40 {
        let mid = 0.5 * (above + below);
        if on_scalp(direction(mid, phi)) {
            above = mid;
        } else {
            below = mid;
        }
    }
    0.5 * (above + below)
}

/// Polar angle where the neck joins the head at azimuth `phi`: under the
/// jaw in front (150°), at the base of the skull behind (128°).
fn join_theta(phi: f32) -> f32 {
    (139.0 + 11.0 * phi.cos()).to_radians()
}

/// Adds triangle `corners` (counter-clockwise from outside), marking it
/// scalp when `scalp` says so.
fn push_triangle(head: &mut HeadMesh, corners: [u32; 3], scalp: bool) {
    if scalp {
        head.scalp_triangles.push(head.mesh.triangle_count() as u32);
    }
    head.mesh.indices.extend(corners);
}

/// The rings of the bust, crown to bottom, [`HEAD_SEGMENTS`] points each.
fn rings() -> Vec<Vec<Vec3>> {
    let phis: Vec<f32> = (0..HEAD_SEGMENTS)
        .map(|s| TAU * s as f32 / HEAD_SEGMENTS as f32)
        .collect();
    let mut rings = Vec::new();
    // The scalp: rings spaced evenly in angle from the crown down to the
    // hairline, the last one on it, so the scalp's edge is a smooth curve
    // instead of the stair steps of a grid cut along its cells.
    for r in 1..=SCALP_RINGS {
        let t = r as f32 / SCALP_RINGS as f32;
        rings.push(
            phis.iter()
                .map(|&phi| head_point_m(direction(t * hairline_theta(phi), phi)))
                .collect(),
        );
    }
    // The face, ears and nape, down to the join with the neck.
    for r in 1..=FACE_RINGS {
        let t = r as f32 / FACE_RINGS as f32;
        rings.push(
            phis.iter()
                .map(|&phi| {
                    let top = hairline_theta(phi);
                    head_point_m(direction(top + t * (join_theta(phi) - top), phi))
                })
                .collect(),
        );
    }
    // The join: a cubic (Hermite) from the head's surface, leaving it
    // along its meridian, to the neck's top ring, arriving straight down,
    // so head and neck are one smooth surface with no crack or rim.
    let neck_ring = |(y_m, half_x_m, half_z_m): (f32, f32, f32)| -> Vec<Vec3> {
        phis.iter()
            .map(|&phi| {
                Vec3::new(
                    half_x_m * phi.sin(),
                    y_m,
                    NECK_CENTRE_Z_M + half_z_m * phi.cos(),
                )
            })
            .collect()
    };
    let neck_top = neck_ring(NECK_PROFILE[0]);
    let join: Vec<(Vec3, Vec3)> = phis
        .iter()
        .map(|&phi| {
            let theta = join_theta(phi);
            let p = head_point_m(direction(theta, phi));
            let ahead = head_point_m(direction(theta + 1e-3, phi));
            (p, (ahead - p).normalize_or_zero())
        })
        .collect();
    for k in 1..JOIN_RINGS {
        let t = k as f32 / JOIN_RINGS as f32;
        let (h00, h10) = (
            2.0 * t.powi(3) - 3.0 * t * t + 1.0,
            t.powi(3) - 2.0 * t * t + t,
        );
        let (h01, h11) = (-2.0 * t.powi(3) + 3.0 * t * t, t.powi(3) - t * t);
        rings.push(
            join.iter()
                .zip(&neck_top)
                .map(|(&(p, along), &n)| {
                    let span_m = p.distance(n);
                    h00 * p + h10 * span_m * along + h01 * n + h11 * span_m * Vec3::NEG_Y
                })
                .collect(),
        );
    }
    rings.extend(NECK_PROFILE.iter().map(|&ring| neck_ring(ring)));
    rings
}

/// Builds the default head with its neck and shoulders: one closed,
/// smooth surface (7,680 triangles; the scalp is the cap of
/// [`SCALP_RINGS`] rings whose edge is the hairline).
///
/// Vertices: the crown pole, the rings of [`HEAD_SEGMENTS`] vertices each
/// (scalp, face, join, neck and shoulders), then the bottom pole. Rings
/// wrap around without a seam, so normals are smooth everywhere, and every
/// edge is shared by exactly two triangles: the surface is watertight, as
/// the collider's inside test needs.
pub fn default_head() -> HeadMesh {
    let segments = HEAD_SEGMENTS as u32;
    let rings = rings();
    let mut head = HeadMesh::default();
    head.mesh.positions.push(head_point_m(Vec3::Y));
    for ring in &rings {
        head.mesh.positions.extend(ring);
    }
    let bottom = head.mesh.positions.len() as u32;
    head.mesh
        .positions
        .push(Vec3::new(0.0, BOTTOM_Y_M, NECK_CENTRE_Z_M));
    let last = rings.len() as u32 + 1;
    // Vertex of ring `r` (1..last), segment `s` (wrapping); the poles
    // stand in for rings 0 and `last`.
    let vertex = |r: u32, s: u32| match r {
        0 => 0,
        r if r == last => bottom,
        r => 1 + (r - 1) * segments + s % segments,
    };
    for r in 0..last {
        let scalp = r < SCALP_RINGS as u32;
        for s in 0..segments {
            let (a, b) = (vertex(r, s), vertex(r + 1, s));
            let (a1, b1) = (vertex(r, s + 1), vertex(r + 1, s + 1));
            if r > 0 {
                push_triangle(&mut head, [a, b, a1], scalp);
            }
            if r + 1 < last {
                push_triangle(&mut head, [a1, b, b1], scalp);
            }
        }
    }
    head.mesh.compute_normals();
    head
}

#[cfg(test)]
#[path = "head_generate_tests.rs"]
mod tests;

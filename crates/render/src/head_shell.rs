//! Keeping drawn strands out of the head: a radial shell around it.
//!
//! Strands drawn between simulated guides (or guides simulated without a
//! collider) can cut into the head and would be drawn inside it. Before drawing,
//! every strand point inside the head is pushed out to its surface (plus a
//! small gap), so hair lies on the head instead of vanishing into it. This
//! changes only the picture, never the simulation.
//!
//! # How it works
//!
//! Seen from a centre inside the head, a head is (nearly) star-shaped: each
//! direction meets its surface once. The shell stores, on a
//! latitude–longitude grid of directions, the largest distance of the mesh
//! from the centre (triangles are sampled densely enough to touch every
//! cell they cross; empty cells take their neighbours' value). A point is
//! inside when it is nearer the centre than the shell in its direction.
//! Look-ups are O(1), so hundreds of thousands of points cost milliseconds.

use std::f32::consts::{PI, TAU};

use glam::Vec3;

use crate::mesh::Mesh;

/// Latitude cells.
const ROWS: usize = 90;
/// Longitude cells.
const COLUMNS: usize = 180;

/// The head's outer radius per direction from a centre inside it.
#[derive(Clone, Debug, PartialEq)]
pub struct HeadShell {
    centre_m: Vec3,
    radius_m: Vec<f32>,
}

/// atan(x) for |x| ≤ 1: an odd minimax polynomial, within about 1e-5 rad.
/// The shell's angles use it, not the platform's `atan2` and `acos`, so
/// that a GPU pass (`shaders/ribbons.wgsl`, the same operations) finds
/// the same place on the shell to f32 round-off: llvmpipe's own `acos`
/// and `atan2` differ from the CPU's by enough to move drawn hair by
/// 20 µm where the shell is steep.
fn atan_unit(x: f32) -> f32 {
    let x2 = x * x;
    let p = -0.011_721_2_f32;
    let p = p * x2 + 0.052_653_32;
    let p = p * x2 - 0.116_432_87;
    let p = p * x2 + 0.193_543_46;
    let p = p * x2 - 0.332_623_47;
    let p = p * x2 + 0.999_977_26;
    p * x
}

/// atan2(y, x) in (−π, π] from [`atan_unit`].
fn atan2_poly(y: f32, x: f32) -> f32 {
    let (ay, ax) = (y.abs(), x.abs());
    let (small, large) = if ay > ax { (ax, ay) } else { (ay, ax) };
    if large == 0.0 {
        return 0.0;
    }
    let mut r = atan_unit(small / large);
    if ay > ax {
        r = 0.5 * PI - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    if y < 0.0 { -r } else { r }
}

/// A unit direction's polar angle from +y (0 to π) and longitude from +z
/// towards +x (0 to 2π), the shell's two coordinates.
fn angles(d: Vec3) -> (f32, f32) {
    let theta = atan2_poly((d.x * d.x + d.z * d.z).sqrt(), d.y);
    let mut phi = atan2_poly(d.x, d.z);
    if phi < 0.0 {
        phi += TAU;
    }
    (theta, phi)
}

fn cell_of(direction: Vec3) -> (usize, usize) {
    let (theta, phi) = angles(direction);
    let row = ((theta / PI) * ROWS as f32) as usize;
    let column = ((phi / TAU) * COLUMNS as f32) as usize;
    (row.min(ROWS - 1), column % COLUMNS)
}

impl HeadShell {
    /// Latitude cells of [`Self::radii_m`].
    pub const ROWS: usize = ROWS;
    /// Longitude cells of [`Self::radii_m`].
    pub const COLUMNS: usize = COLUMNS;

    /// The shell of `mesh` around the centre of its vertices' bounding box
    /// (inside any head-like mesh).
    pub fn new(mesh: &Mesh) -> Self {
        let (lo, hi) = mesh.bounds_m();
        let centre_m = if lo.is_finite() && hi.is_finite() {
            0.5 * (lo + hi)
        } else {
            Vec3::ZERO
        };
        let mut radius_m = vec![0.0f32; ROWS * COLUMNS];
        let cell_m = (hi - lo).max_element().max(1e-6) * PI / ROWS as f32 / 4.0;
        for t in 0..mesh.triangle_count() {
            let [a, b, c] = mesh.triangle(t);
            let longest = (b - a).length().max((c - b).length()).max((a - c).length());
            let steps = ((longest / cell_m).ceil() as usize).clamp(1, 64);
            for i in 0..=steps {
                for j in 0..=steps - i {
                    let (u, v) = (i as f32 / steps as f32, j as f32 / steps as f32);
                    let d = a + u * (b - a) + v * (c - a) - centre_m;
                    let r = d.length();
                    if r > 0.0 {
                        let (row, column) = cell_of(d / r);
                        let cell = &mut radius_m[row * COLUMNS + column];
                        *cell = cell.max(r);
                    }
                }
            }
        }
        fill_empty_cells(&mut radius_m);
        Self { centre_m, radius_m }
    }

    /// The centre the shell is measured from.
    pub fn centre_m(&self) -> Vec3 {
        self.centre_m
    }

    /// The shell's distance from the centre per cell, metres, row after
    /// row ([`Self::ROWS`] × [`Self::COLUMNS`]; row 0 around +y, column 0
    /// towards +z, longitude turning towards +x): what a GPU pass looks up.
    pub fn radii_m(&self) -> &[f32] {
        &self.radius_m
    }

    /// Keeps a strand (root first) out of the head, root to tip: each point
    /// keeps its step from the previous one, and is pushed out to the shell
    /// plus `gap_m` when that step would enter the head. A strand that the
    /// physics let fall through the skull thus slides over the scalp the
    /// way it was heading, instead of being projected onto whatever surface
    /// is nearest.
    pub fn drape(&self, points: &mut [Vec3], gap_m: f32) {
        let Some(&root) = points.first() else {
            return;
        };
        let (mut before, mut placed) = (root, root);
        for p in &mut points[1..] {
            let step = *p - before;
            before = *p;
            placed = self.push_out(placed + step, gap_m);
            *p = placed;
        }
    }

    /// The shell's distance from the centre in `direction` (unit),
    /// interpolated bilinearly between the four nearest cell centres (in
    /// latitude and longitude, longitude wrapping around): continuous, so
    /// that a direction's round-off moves the answer by round-off and not
    /// by a cell's step (a GPU's `acos` and `atan2` are not the CPU's).
    pub fn radius_m(&self, direction: Vec3) -> f32 {
        let (theta, phi) = angles(direction);
        let u = (theta / PI * ROWS as f32 - 0.5).clamp(0.0, (ROWS - 1) as f32);
        let v = phi / TAU * COLUMNS as f32 - 0.5;
        let (row, fu) = (u.floor(), u - u.floor());
        let (column, fv) = (v.floor(), v - v.floor());
        let row0 = row as usize;
        let row1 = (row0 + 1).min(ROWS - 1);
        let column0 = (column as i32).rem_euclid(COLUMNS as i32) as usize;
        let column1 = (column0 + 1) % COLUMNS;
        let at = |r: usize, c: usize| self.radius_m[r * COLUMNS + c];
        let top = at(row0, column0) + fv * (at(row0, column1) - at(row0, column0));
        let bottom = at(row1, column0) + fv * (at(row1, column1) - at(row1, column0));
        top + fu * (bottom - top)
    }

    /// `p` moved out to the shell plus `gap_m` along its direction from the
    /// centre, if it is inside; else `p`.
    pub fn push_out(&self, p: Vec3, gap_m: f32) -> Vec3 {
        let d = p - self.centre_m;
        let r = d.length();
        if r <= 0.0 {
            return p;
        }
        let surface = self.radius_m(d / r) + gap_m;
        if r < surface {
            self.centre_m + d * (surface / r)
        } else {
            p
        }
    }
}

/// Gives every empty cell the largest value of its filled neighbours,
/// repeatedly, until none is empty (or nothing is filled at all).
fn fill_empty_cells(radius_m: &mut [f32]) {
    while radius_m.contains(&0.0) && radius_m.iter().any(|&r| r > 0.0) {
        let before = radius_m.to_vec();
        for row in 0..ROWS {
            for column in 0..COLUMNS {
                if before[row * COLUMNS + column] > 0.0 {
                    continue;
                }
                let mut best = 0.0f32;
                for (dr, dc) in [(-1i32, 0i32), (1, 0), (0, -1), (0, 1)] {
                    let r = row as i32 + dr;
                    if (0..ROWS as i32).contains(&r) {
                        let c = (column as i32 + dc).rem_euclid(COLUMNS as i32) as usize;
                        best = best.max(before[r as usize * COLUMNS + c]);
                    }
                }
                radius_m[row * COLUMNS + column] = best;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::head_generate::{default_head, head_point_m};

    /// [`atan_unit`]'s polynomial's error (its coefficients' minimax bound
    /// is 1e-5 rad; f32 evaluation adds round-off).
    const ATAN_TOL_RAD: f32 = 1.5e-5;

    #[test]
    fn the_shells_angles_are_the_platforms_within_their_stated_error() {
        let mut worst = 0.0f32;
        for i in 0..2000 {
            let a = i as f32 * 0.618_034 * TAU;
            let b = (i as f32 / 1999.0) * PI;
            let d = Vec3::new(b.sin() * a.sin(), b.cos(), b.sin() * a.cos());
            let (theta, phi) = angles(d);
            let phi_std = d.x.atan2(d.z).rem_euclid(TAU);
            let theta_std = d.y.clamp(-1.0, 1.0).acos();
            let dphi = (phi - phi_std).abs();
            worst = worst
                .max((theta - theta_std).abs())
                .max(dphi.min(TAU - dphi));
        }
        assert!(worst < ATAN_TOL_RAD, "{worst}");
    }

    #[test]
    fn points_inside_the_default_head_are_pushed_to_its_surface() {
        let head = default_head();
        let shell = HeadShell::new(&head.mesh);
        for d in [
            Vec3::Y,
            Vec3::new(0.3, 0.5, -0.8).normalize(),
            Vec3::new(-1.0, 0.2, 0.1).normalize(),
        ] {
            let surface = head_point_m(d);
            let inside = shell.centre_m() + 0.5 * (surface - shell.centre_m());
            let pushed = shell.push_out(inside, 0.001);
            let dist_pushed = (pushed - shell.centre_m()).length();
            let dist_surface = (surface - shell.centre_m()).length();
            assert!(
                (dist_pushed - dist_surface).abs() < 0.006,
                "{d}: {dist_pushed} vs {dist_surface}"
            );
            let outside = surface * 1.3;
            assert_eq!(shell.push_out(outside, 0.001), outside);
        }
    }
}

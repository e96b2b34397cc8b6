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

fn cell_of(direction: Vec3) -> (usize, usize) {
    let theta = direction.y.clamp(-1.0, 1.0).acos();
    let phi = direction.x.atan2(direction.z).rem_euclid(TAU);
    let row = ((theta / PI) * ROWS as f32) as usize;
    let column = ((phi / TAU) * COLUMNS as f32) as usize;
    (row.min(ROWS - 1), column % COLUMNS)
}

impl HeadShell {
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

    /// The shell's distance from the centre in `direction` (unit).
    pub fn radius_m(&self, direction: Vec3) -> f32 {
        let (row, column) = cell_of(direction);
        self.radius_m[row * COLUMNS + column]
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

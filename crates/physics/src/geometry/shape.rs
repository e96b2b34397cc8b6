//! A strand's shape alone: element frames and end points from the strains,
//! without the velocities, accelerations, quadrature samples and
//! Jacobians that a step needs ([`crate::step::reconstruct`]).
//!
//! Drawing and exporting ask for the shape of thousands of strands a frame;
//! the full reconstruction costs several times more for values they never
//! read. This is the same sweep root to tip on plain values: R_{Q+1} =
//! R_Q exp([ℓ_Q k_Q]×) and p_{Q+1} = p_Q + R_Q h(ℓ_Q, k_Q)
//! ([`crate::geometry::helix`]), so a point at arc length σ inside element Q is
//! p_Q + R_Q h(σ, k_Q).

use glam::{DMat3, DVec3};

use crate::geometry::helix::{centreline_and_jacobian, rotation};
use crate::model::StrandModel;
use crate::motion::RigidMotion;

/// Frames R_Q at element starts plus the tip frame (N + 1), and element
/// boundary points relative to the root point (N + 1), for strains `q` and
/// a root at `root` (its rotation; its position is not added): the
/// `frames` and `points_m` that [`crate::step::reconstruct::reconstruct`] gives.
pub fn frames_and_points(
    model: &StrandModel,
    q: &[DVec3],
    root: &RigidMotion,
) -> (Vec<DMat3>, Vec<DVec3>) {
    let n = model.elements().min(q.len());
    let mut frames = Vec::with_capacity(n + 1);
    let mut points = Vec::with_capacity(n + 1);
    let (mut frame, mut point) = (root.world_from_body, DVec3::ZERO);
    frames.push(frame);
    points.push(point);
    for (&length_m, &k) in model.lengths_m.iter().zip(q).take(n) {
        point += frame * centreline_and_jacobian(length_m, k).0;
        frame *= rotation(length_m * k);
        frames.push(frame);
        points.push(point);
    }
    (frames, points)
}

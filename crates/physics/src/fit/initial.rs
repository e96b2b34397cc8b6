//! The fit's starting point: strains read off the polyline's own turning.
//!
//! Walking along a curve, the material frame turns at the Darboux vector's
//! rate. The polyline gives that turning directly: at each vertex the
//! tangent is the bisector of the two segments meeting there (at the ends,
//! the mirror image of the neighbour's tangent in the end segment, which is
//! exact for a circular arc, whose chord bisects its end tangents). Cut the
//! strand into N equal elements and read the tangent T_Q at each element
//! boundary; element Q must turn T_Q into T_{Q+1}. The smallest rotation
//! that does so, angle θ about T_Q × T_{Q+1}, spread over the element's
//! length ℓ, is a world Darboux vector ω = θ ê/ℓ; in the element's material
//! frame the strains are k_Q = R_Qᵀ ω, and the next frame is the current
//! one turned by ℓω. This is the discrete parallel transport (Bishop)
//! frame: it has no twist, so a helix comes out as arcs whose curvature
//! turns element to element. That is close enough for the least-squares
//! refinement ([`super::refine`]) to find the twist.

use glam::{DMat3, DVec3};

use super::curve::UniformHelixChain;
use crate::geometry::helix::rotation;
use crate::motion::RootPose;

/// Chord lengths along a polyline: s_0 = 0, s_i = Σ_{j<i} |P_{j+1} − P_j|.
pub fn chord_arc_lengths(points_m: &[DVec3]) -> Vec<f64> {
    let mut s = Vec::with_capacity(points_m.len());
    let mut total = 0.0;
    s.push(0.0);
    for w in points_m.windows(2) {
        total += (w[1] - w[0]).length();
        s.push(total);
    }
    s
}

/// Unit tangents at the polyline's vertices (bisectors inside, mirrored
/// neighbours at the ends). Needs at least two distinct points.
pub fn vertex_tangents(points_m: &[DVec3]) -> Vec<DVec3> {
    let chords: Vec<DVec3> = points_m
        .windows(2)
        .map(|w| (w[1] - w[0]).normalize_or_zero())
        .collect();
    let m = chords.len();
    if m == 1 {
        return vec![chords[0]; 2];
    }
    let mut t = Vec::with_capacity(m + 1);
    t.push(DVec3::ZERO);
    for i in 1..m {
        t.push((chords[i - 1] + chords[i]).normalize_or(chords[i]));
    }
    t.push(DVec3::ZERO);
    let mirror = |chord: DVec3, neighbour: DVec3| 2.0 * chord.dot(neighbour) * chord - neighbour;
    t[0] = mirror(chords[0], t[1]).normalize_or(chords[0]);
    t[m] = mirror(chords[m - 1], t[m - 1]).normalize_or(chords[m - 1]);
    t
}

/// The tangent at chord arc length `s`, interpolated between vertices.
fn tangent_at(arc: &[f64], tangents: &[DVec3], s: f64) -> DVec3 {
    let i = arc.partition_point(|&a| a <= s).clamp(1, arc.len() - 1) - 1;
    let span = arc[i + 1] - arc[i];
    let t = if span > 0.0 {
        ((s - arc[i]) / span).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (tangents[i] * (1.0 - t) + tangents[i + 1] * t).normalize_or(tangents[i])
}

/// A chain of `elements` equal elements following the polyline's turning,
/// its root frame's n₁ taken from `reference` (see [`RootPose::from_direction`]).
pub fn initial_chain(points_m: &[DVec3], elements: usize, reference: DVec3) -> UniformHelixChain {
    let arc = chord_arc_lengths(points_m);
    let tangents = vertex_tangents(points_m);
    let length = *arc.last().unwrap_or(&0.0);
    let l = length / elements as f64;
    let boundary: Vec<DVec3> = (0..=elements)
        .map(|q| tangent_at(&arc, &tangents, q as f64 * l))
        .collect();
    let root = RootPose::from_direction(DVec3::ZERO, boundary[0], reference).head_from_root;
    let mut frame: DMat3 = root;
    let mut strains = Vec::with_capacity(elements);
    for q in 0..elements {
        let from = frame.col(0);
        let to = boundary[q + 1];
        let axis = from.cross(to);
        let angle = axis.length().atan2(from.dot(to));
        let omega = axis.normalize_or_zero() * (angle / l);
        strains.push(frame.transpose() * omega);
        frame = rotation(omega * l) * frame;
    }
    UniformHelixChain {
        root_frame: root,
        element_length_m: l,
        strains_per_m: strains,
    }
}

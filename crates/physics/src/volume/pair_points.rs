//! The model's points: one per pair of an element's quadrature nodes,
//! the pair's centre of mass, moving with its mean velocity and carrying
//! its mass.
//!
//! # What a point stands for
//!
//! Element e of a strand (length ℓ, mass per length ρS) is sampled by the
//! step at its quadrature nodes s_j with weights w_j (Σ w_j = 1). The
//! model takes the nodes two by two in order ((0, 1), (2, 3), …; the last
//! alone when their count is odd) and makes each pair one point: mass
//! ρS ℓ (w_a + w_b), position x̄ = (w_a x_a + w_b x_b) / (w_a + w_b) and
//! velocity v̄ likewise. The grid receives exactly the hair's mass and
//! momentum (what splatting every node with its own mass ρS w_j ℓ
//! deposits in total), only spread from half as many places. The field
//! is read back at the same points, and both nodes of a pair feel their
//! point's reading (grid velocity and push), each with the drag on its
//! own velocity.
//!
//! # Why pairs: what each choice measured
//!
//! - Every node (the model before): gather, splat and read-back are per
//!   point, and they were 36–38% of a frame on the full head, over the
//!   30% target.
//! - One point per element: a quarter of the points at the default four
//!   nodes, but the density field grows lumpy where an element is about
//!   as long as a cell (1–2 cm against 2 cm): on the small test head
//!   shaken with the pressure at the top of its range (10 m²/s², one
//!   substep) the largest excess density in the second frame was 0.48 of
//!   the typical rest density against 0.19 with every node, and the
//!   push's overshoot put real energy into two strands (the guard flagged
//!   and re-stepped them; `tests/volume_guard.rs` fails).
//! - Pairs: half the points, and no guard event anywhere in that test's
//!   range. docs/volume.md, "Cost", has the measured share of a frame.
//!
//! The peers splat one point per strand vertex; for a groom of 16 points
//! per strand and 15 elements that is one point per element, half the
//! density of points used here.
//!
//! # The arithmetic
//!
//! Both engines compute a point in f64, in node order: with the pair's
//! weights w_a + w_b and shares w_a / (w_a + w_b), w_b / (w_a + w_b)
//! found once per element shape ([`pair_weights`]), the mean
//! x̄ = share_a x_a + share_b x_b on positions relative to the strand's
//! root point (world axes), then carry the mean
//! into head coordinates as `body_from_world * (root + x̄ − head)`, with
//! mass (ρS ℓ) (w_a + w_b); the batch engine widens its f32 lanes first
//! and does the same operations lane by lane (`crate::batch::volume`).
//! Velocities stay in world axes: a mean of velocities does not care
//! where the origin is.

use glam::DVec3;

use super::splat::SamplePoint;
use crate::motion::RigidMotion;

/// Quadrature nodes one point stands for (the last point of an element
/// with an odd node count stands for one).
pub const NODES_PER_POINT: usize = 2;

/// Points per element for `nodes` quadrature nodes per element.
pub fn points_per_element(nodes: usize) -> usize {
    nodes.div_ceil(NODES_PER_POINT)
}

/// The index, among a strand's points, of the point that stands for node
/// `j` of element `e`, with `nodes` quadrature nodes per element.
#[inline(always)]
pub fn point_of(e: usize, j: usize, nodes: usize) -> usize {
    e * points_per_element(nodes) + j / NODES_PER_POINT
}

/// One point's share of its element: the weight of its nodes, and each
/// node's part of that weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairWeights {
    /// w_a + w_b (w_a alone for a lone node): the point's fraction of the
    /// element's mass.
    pub sum: f64,
    /// w_a / (w_a + w_b) and w_b / (w_a + w_b) (1 and 0 for a lone node):
    /// the mean is share_a x_a + share_b x_b, with no division per point.
    pub share: [f64; NODES_PER_POINT],
}

/// The pairs' weights of an element whose quadrature weights are
/// `weights`, pair by pair.
pub fn pair_weights(weights: &[f64]) -> Vec<PairWeights> {
    weights
        .chunks(NODES_PER_POINT)
        .map(|pair| {
            let sum: f64 = pair.iter().sum();
            PairWeights {
                sum,
                share: std::array::from_fn(|k| pair.get(k).map_or(0.0, |w| w / sum)),
            }
        })
        .collect()
}

/// Where a strand's points go: its root point and the head, and its mass
/// per length.
#[derive(Clone, Copy, Debug)]
pub struct Placement<'a> {
    /// The strand's root point, world, metres.
    pub root_m: DVec3,
    /// The head the samples were reconstructed with.
    pub head: &'a RigidMotion,
    /// ρS, kg/m.
    pub mass_per_length: f64,
}

/// The points of a strand whose quadrature samples are `samples` (element
/// by element, `weights.len()` per element, positions relative to the
/// root point), its elements `lengths_m` long, placed as `at`: one per
/// pair of nodes, in head coordinates, written to `out`.
pub fn pair_points(
    samples: &[SampleMotion],
    weights: &[f64],
    lengths_m: &[f64],
    at: &Placement<'_>,
    out: &mut Vec<SamplePoint>,
) {
    let body_from_world = at.head.world_from_body.transpose();
    let pairs = pair_weights(weights);
    out.clear();
    let elements = samples.chunks_exact(weights.len().max(1)).zip(lengths_m);
    for (nodes, length_m) in elements {
        let points = nodes.chunks(NODES_PER_POINT).zip(&pairs);
        out.extend(points.map(|(nodes, pair)| {
            let (position, velocity) = pair_mean(nodes, &pair.share);
            SamplePoint {
                position_m: body_from_world * (at.root_m + position - at.head.position_m),
                velocity_m_per_s: velocity,
                mass_kg: at.mass_per_length * length_m * pair.sum,
            }
        }));
    }
}

/// The mean position and velocity of one pair of `nodes` (or one node)
/// with their `share`s of the pair's weight, in node order.
fn pair_mean(nodes: &[SampleMotion], share: &[f64; NODES_PER_POINT]) -> (DVec3, DVec3) {
    let mut terms = nodes
        .iter()
        .zip(share)
        .map(|(s, w)| (*w * s.position_m, *w * s.velocity_m_per_s));
    let first = terms.next().unwrap_or((DVec3::ZERO, DVec3::ZERO));
    terms.fold(first, |(x, v), (dx, dv)| (x + dx, v + dv))
}

/// One quadrature sample's place and motion, what the pull's work needs:
/// the reference's gather keeps them from the reconstruction it makes
/// anyway ([`super::reference`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SampleMotion {
    /// Position relative to the strand's root point, world axes, metres.
    pub position_m: DVec3,
    /// Velocity, world, m/s.
    pub velocity_m_per_s: DVec3,
    /// Quadrature weight times element length, metres.
    pub weight_m: f64,
}

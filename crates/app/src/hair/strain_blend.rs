//! Drawn strands rebuilt in the strands' own parameter space: each drawn
//! strand blends its guides' current strains (τ, κ₁, κ₂ per element) and
//! grows from its own root frame with the physics' reconstruction.
//!
//! # Why not blend positions
//!
//! Averaging the points of two curly guides whose curls are out of phase
//! cancels the curls: two helices half a turn apart average to a nearly
//! straight line, and a field of such averages reads as a zigzag hairnet
//! instead of ringlets. Production groomers avoid it the same way: XGen and
//! Yeti clump drawn strands around a guide and apply curl per strand;
//! Unreal's groom and Ornatrix carry each drawn strand's own rest shape by
//! the guides' deformation, never averaging two shapes point by point. For
//! Super-Helices the strains *are* the shape's own coordinates: a helix of
//! radius r and pitch c is the same (τ, κ₁, κ₂) whatever its phase, so a
//! blend of strains keeps radius, pitch and handedness, and the drawn
//! strand's own root frame (on its part of the scalp, combed like its
//! guides) sets its phase.
//!
//! # How it works
//!
//! A [`DrawnStrand`] holds, per element e, a `base` strain and a short
//! list of sources (guide g, element j of g, weight w), with element j
//! the one at the same fraction of the strand's length. Each frame its
//! strains are k_e = base_e + Σ w q_g\[j\]; for a procedural group the base
//! is zero (a blend of the guides' strains), for an imported strand it is
//! its own imported strains minus the same blend of its guides' imported
//! strains (the strand is its own rest shape, bent as its guides bend).
//! [`strand_curve`] then sweeps the frames root to tip (the sweep of
//! [`helixhair_physics::geometry::shape::frames_and_points`]) and samples each
//! element along its helix.

use glam::{DMat3, DVec3, Vec3};
use helixhair_physics::RootPose;
use helixhair_physics::geometry::helix::{left_jacobian, rotation};
use helixhair_physics::motion::RigidMotion;

/// Largest angle the tangent turns between two drawn points, radians: a
/// curl is drawn round (a ringlet turn of 2π gets at least 14 points).
pub const MAX_TURN_RAD: f64 = 0.45;

/// Most points drawn per element.
pub const MAX_POINTS_PER_ELEMENT: usize = 16;

/// Where one element of a drawn strand takes its strain from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StrainSource {
    /// Guide strand (index in the simulation).
    pub guide: usize,
    /// Element of that guide.
    pub element: usize,
    /// Weight; an element's weights sum to 1.
    pub weight: f64,
}

/// One drawn strand: its root frame (head coordinates), its elements'
/// lengths, and where each element's strain comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnStrand {
    /// Root point and frame, head coordinates.
    pub root: RootPose,
    /// Element lengths, metres.
    pub lengths_m: Vec<f64>,
    /// Strain added to the blend, per element, m⁻¹ (zero for procedural
    /// strands).
    pub base: Vec<DVec3>,
    /// The blend's sources, per element.
    pub sources: Vec<Vec<StrainSource>>,
    /// The guide it gathers onto towards its tip, and how far (0 to 1):
    /// the `render` section's `clump`.
    pub clump: Option<(usize, f64)>,
    /// Guides (simulation index, weight) whose blended shape the strand's
    /// tip follows, for groups that do not clump (see
    /// [`helixhair_render::strand_shape::follow_guides`]); empty: none.
    pub follow: Vec<(usize, f64)>,
}

/// The element of a strand with `lengths_m` at `fraction` of its length.
pub fn element_at(lengths_m: &[f64], fraction: f64) -> usize {
    let total: f64 = lengths_m.iter().sum();
    let target = fraction.clamp(0.0, 1.0) * total;
    let mut start = 0.0;
    for (j, &l) in lengths_m.iter().enumerate() {
        if target < start + l {
            return j;
        }
        start += l;
    }
    lengths_m.len().saturating_sub(1)
}

/// The sources of a strand with `lengths_m` blending `guides` (each its
/// index, weight and element lengths): element e takes each guide's
/// element at the same fraction of length (measured at e's middle).
pub fn blend_sources(lengths_m: &[f64], guides: &[(usize, f64, &[f64])]) -> Vec<Vec<StrainSource>> {
    let total: f64 = lengths_m.iter().sum::<f64>().max(f64::MIN_POSITIVE);
    let mut start = 0.0;
    lengths_m
        .iter()
        .map(|&l| {
            let middle = (start + 0.5 * l) / total;
            start += l;
            guides
                .iter()
                .map(|&(guide, weight, guide_lengths)| StrainSource {
                    guide,
                    element: element_at(guide_lengths, middle),
                    weight,
                })
                .collect()
        })
        .collect()
}

impl DrawnStrand {
    /// The guide this strand is drawn as, unchanged, if it is one: each
    /// element takes that guide's same element whole, with nothing added,
    /// no clumping and no following (an imported guide drawn as
    /// simulated). Such a strand's curve is its guide's, which the GPU
    /// engine can write on the device (`physics::gpu::curves`).
    pub fn own_guide(&self) -> Option<usize> {
        let guide = self.sources.first()?.first()?.guide;
        let whole = self.sources.iter().enumerate().all(|(e, sources)| {
            matches!(sources.as_slice(), [s] if s.guide == guide && s.element == e && s.weight == 1.0)
        });
        let unchanged = self.base.iter().all(|b| *b == DVec3::ZERO);
        (whole && unchanged && self.clump.is_none() && self.follow.is_empty()).then_some(guide)
    }

    /// Its strains now, from every guide's strains `q` (indexed by guide).
    pub fn strains(&self, q: &[Vec<DVec3>]) -> Vec<DVec3> {
        self.sources
            .iter()
            .zip(&self.base)
            .map(|(sources, &base)| {
                base + sources
                    .iter()
                    .map(|s| {
                        let guide = &q[s.guide];
                        s.weight * guide.get(s.element).copied().unwrap_or(DVec3::ZERO)
                    })
                    .sum::<DVec3>()
            })
            .collect()
    }
}

/// The centreline of a strand with element lengths `lengths_m` and strains
/// `q`, grown from `root` (its point and frame; head coordinates), each
/// element sampled so the tangent turns at most [`MAX_TURN_RAD`] between
/// points. Root first; the last point is the tip.
pub fn strand_curve(root: &RootPose, lengths_m: &[f64], q: &[DVec3]) -> Vec<DVec3> {
    let motion = RigidMotion::at_rest(root.position_m, root.head_from_root);
    helix_polyline(&motion, lengths_m, q)
}

/// The centreline of a strand whose root moves as `motion` (its
/// `position_m` and `world_from_body`), sampled as [`strand_curve`].
pub fn helix_polyline(motion: &RigidMotion, lengths_m: &[f64], q: &[DVec3]) -> Vec<DVec3> {
    let n = lengths_m.len().min(q.len());
    let lengths_m = &lengths_m[..n];
    let (frames, points) = sweep(lengths_m, &q[..n], motion.world_from_body);
    let mut out = Vec::with_capacity(4 * n + 1);
    for (e, (&length_m, &k)) in lengths_m.iter().zip(q).enumerate() {
        let turns = (length_m * k.length() / MAX_TURN_RAD).ceil() as usize;
        let samples = turns.clamp(1, MAX_POINTS_PER_ELEMENT);
        // Each of the element's equal pieces is the same piece of helix,
        // turned by the frames before it: one step and one rotation serve
        // them all.
        let piece_m = length_m / samples as f64;
        let (step, turn) = (centreline(piece_m, k), rotation(piece_m * k));
        let (mut frame, mut point) = (frames[e], motion.position_m + points[e]);
        for _ in 0..samples {
            out.push(point);
            point += frame * step;
            frame *= turn;
        }
    }
    out.push(motion.position_m + points[n]);
    out
}

/// Frames at element starts and boundary points relative to the root,
/// the sweep of [`frames_and_points`] (R_{Q+1} = R_Q exp([ℓ_Q k_Q]×),
/// p_{Q+1} = p_Q + R_Q h(ℓ_Q, k_Q)) on plain element lengths, for drawn
/// strands that have no strand model of their own.
fn sweep(lengths_m: &[f64], q: &[DVec3], root: DMat3) -> (Vec<DMat3>, Vec<DVec3>) {
    let mut frames = Vec::with_capacity(q.len() + 1);
    let mut points = Vec::with_capacity(q.len() + 1);
    let (mut frame, mut point) = (root, DVec3::ZERO);
    frames.push(frame);
    points.push(point);
    for (&length_m, &k) in lengths_m.iter().zip(q) {
        point += frame * centreline(length_m, k);
        frame *= rotation(length_m * k);
        frames.push(frame);
        points.push(point);
    }
    (frames, points)
}

/// The centreline h(σ, k) = σ J_l(σk) e₀ of an element in its start frame
/// (the point of [`helixhair_physics::geometry::helix::centreline_and_jacobian`]
/// without its Jacobian, which drawing never reads).
fn centreline(sigma: f64, k: DVec3) -> DVec3 {
    sigma * (left_jacobian(sigma * k) * DVec3::X)
}

/// A curve in `f32`, as drawing takes it.
pub fn to_f32(curve: &[DVec3]) -> impl Iterator<Item = Vec3> + '_ {
    curve.iter().map(|p| p.as_vec3())
}

#[cfg(test)]
mod tests {
    use glam::DMat3;
    use helixhair_render::StrandBuffers;
    use helixhair_render::interpolate::{Interpolation, InterpolationSpec, interpolate_strands};

    use super::*;

    /// Ringlet strains: twist τ and curvature κ₁, m⁻¹. The centreline's
    /// curvature is κ and its torsion τ: a helix of radius κ/(κ² + τ²) =
    /// 12 mm and pitch 2π τ/(κ² + τ²) = 3 cm, as curly.ron's.
    const TAU: f64 = 28.63;
    const KAPPA: f64 = 71.94;

    /// 1 mm elements: the polyline through their ends is the helix to
    /// (κ ℓ)²/24 ≈ 1e-4 relative curvature.
    fn lengths() -> Vec<f64> {
        vec![0.001; 250]
    }

    /// A root growing down −y, its frame turned by `phase_rad` about the
    /// growth direction (which turns the curl's phase).
    fn root(x_m: f64, phase_rad: f64) -> RootPose {
        let spin = DMat3::from_axis_angle(DVec3::NEG_Y, phase_rad);
        RootPose::from_direction(DVec3::new(x_m, 0.0, 0.0), DVec3::NEG_Y, spin * DVec3::Z)
    }

    /// Median curvature (circumradius of consecutive points) and the sign
    /// of the torsion (handedness) of a polyline.
    fn curvature_and_handedness(points: &[DVec3]) -> (f64, f64) {
        let mut kappas: Vec<f64> = points
            .windows(3)
            .map(|w| {
                let (a, b, c) = (w[1] - w[0], w[2] - w[1], w[2] - w[0]);
                2.0 * a.cross(b).length() / (a.length() * b.length() * c.length())
            })
            .collect();
        kappas.sort_by(f64::total_cmp);
        let torsion: f64 = points
            .windows(4)
            .map(|w| (w[1] - w[0]).cross(w[2] - w[1]).dot(w[3] - w[2]))
            .sum();
        (kappas[kappas.len() / 2], torsion.signum())
    }

    /// Curly guides out of phase drew a zigzag: averaging their points
    /// cancels the curls. A strand that blends their strains and grows
    /// from its own root keeps their radius, pitch and handedness.
    #[test]
    fn a_strand_between_two_curls_out_of_phase_keeps_their_curl() {
        let q = vec![DVec3::new(TAU, KAPPA, 0.0); 250];
        let helix_curvature = KAPPA;
        let (a, b) = (root(0.0, 0.0), root(0.02, std::f64::consts::PI));
        let guide_a = strand_curve(&a, &lengths(), &q);
        let guide_b = strand_curve(&b, &lengths(), &q);
        for guide in [&guide_a, &guide_b] {
            let (kappa, hand) = curvature_and_handedness(guide);
            assert!((kappa / helix_curvature - 1.0).abs() < 1e-3, "{kappa}");
            assert_eq!(hand, 1.0);
        }
        let guide_lengths = lengths();
        let drawn = DrawnStrand {
            root: root(0.01, 1.0),
            lengths_m: lengths(),
            base: vec![DVec3::ZERO; 250],
            sources: blend_sources(
                &lengths(),
                &[(0, 0.5, &guide_lengths), (1, 0.5, &guide_lengths)],
            ),
            clump: None,
            follow: Vec::new(),
        };
        let strains = drawn.strains(&[q.clone(), q.clone()]);
        let curve = strand_curve(&drawn.root, &drawn.lengths_m, &strains);
        let (kappa, hand) = curvature_and_handedness(&curve);
        assert!(
            (kappa / helix_curvature - 1.0).abs() < 1e-3,
            "drawn curvature {kappa} m⁻¹, guides {helix_curvature} m⁻¹"
        );
        assert_eq!(hand, 1.0, "handedness");
        // Its curl radius and pitch: a turn of the helix (arc 2π/√(κ²+τ²))
        // advances one pitch along the axis and returns to radius r.
        let turn = (2.0 * std::f64::consts::PI / KAPPA.hypot(TAU) / 0.001).round() as usize;
        let pitch = curve[turn].distance(curve[0]);
        let want = 2.0 * std::f64::consts::PI * TAU / (KAPPA * KAPPA + TAU * TAU);
        assert!(
            (pitch / want - 1.0).abs() < 0.02,
            "pitch {pitch} m, want {want} m"
        );

        // The old way, the guides' points averaged at the same root, is
        // not a curl of the same radius (here: nearly straight).
        let mut guides = StrandBuffers::default();
        guides.push_strand(to_f32(&guide_a));
        guides.push_strand(to_f32(&guide_b));
        let spec = InterpolationSpec {
            method: Interpolation::Blend3,
            points_per_strand: 251,
            length_variation: 0.0,
            seed: 1,
        };
        let averaged = interpolate_strands(&guides, &[Vec3::new(0.01, 0.0, 0.0)], &spec);
        let averaged: Vec<DVec3> = averaged.strand(0).iter().map(|p| p.as_dvec3()).collect();
        let (kappa, _) = curvature_and_handedness(&averaged);
        assert!(kappa < 0.7 * helix_curvature, "averaged curvature {kappa}");
    }
}

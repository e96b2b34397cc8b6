//! Drawn strands shaped by their guides after they are swept: clumped onto
//! a guide towards the tip, curls clumped with a phase and radius of their
//! own, and straight hair following its guides' blended shape. Plain `f32`
//! geometry on polylines (root first), the CPU reference of the device's
//! `stage_guide_shapes` and `stage_shape` (`shaders/strand_shape.wgsl`,
//! [`crate::gpu::device_shape`]), which run the same loops in the same
//! order.
//!
//! # Clumping
//!
//! [`clump_onto`] moves the point at arc length s the fraction
//! `amount` · s/L of the way to the guide's point at the same arc length:
//! strands leave the scalp where they grow and meet their guide near the
//! tip, as XGen's and Yeti's clump modifiers do.
//!
//! # Curls that do not all curl in step
//!
//! A clump's drawn strands grow from nearby roots whose frames barely
//! differ, so they curl in phase, and gathering their points onto the
//! guide's curve pulls them into that one helix: seen together they read
//! as a regular net. XGen and Yeti clump first and curl after; the same
//! here ([`clump_curl_onto`]): a strand is split into its centreline (the
//! moving average over one turn of the curl, [`centreline`]) and its curl
//! (what is left); the centreline is gathered onto the guide's centreline
//! as the points were, and the curl is put back around it, turned about
//! the centreline by the strand's own phase and scaled by its own radius
//! factor. Turning the curl about its axis shifts its phase and leaves the
//! strand's course alone.
//!
//! # Following
//!
//! Straight and wavy strands take their shape from gravity and the head:
//! a strand rebuilt from its guides' strains alone, from a root whose
//! frame differs from theirs, can carry their bend over the skull away
//! from the head. [`follow_guides`] pulls it onto its guides' blended
//! shape from its own root ([`blended_shape`]), fully at the tip and not
//! at all at the root.

use std::f32::consts::TAU;

use glam::Vec3;

use crate::interpolate::resampled_shape;

/// Points of a guide's resampled shape that following strands blend.
pub const FOLLOW_POINTS: usize = 32;

/// Most guides one strand follows (a three-guide blend, with room).
pub const MAX_FOLLOW: usize = 4;

/// The arc length of one turn of a curl whose strains have mean magnitude
/// `mean_strain_per_m` (m⁻¹; |k|² = curvature² + torsion², so a helix
/// turns once every 2π/|k|); `None` for straight hair (below 1 m⁻¹).
pub fn curl_period_m(mean_strain_per_m: f32) -> Option<f32> {
    (mean_strain_per_m > 1.0).then(|| TAU / mean_strain_per_m)
}

/// What a guide gives the strands shaped by it: its curve, the period of
/// its curl, its curve's centreline over that period (empty for straight
/// hair) and its shape resampled at [`FOLLOW_POINTS`] as offsets from its
/// root ([`stage_guide_shapes`]).
#[derive(Clone, Debug, PartialEq)]
pub struct GuideShape {
    /// The guide's curve, root first.
    pub curve: Vec<Vec3>,
    /// One turn of its curl, arc length, metres (`None`: straight).
    pub period_m: Option<f32>,
    /// Its centreline ([`centreline`]), empty where straight.
    pub axis: Vec<Vec3>,
    /// [`resampled_shape`] at [`FOLLOW_POINTS`].
    pub shape: Vec<Vec3>,
}

/// The shape of a guide with `curve` whose strains have mean magnitude
/// `mean_strain_per_m` (m⁻¹): the CPU twin of `stage_guide_shapes`.
pub fn stage_guide_shapes(curve: Vec<Vec3>, mean_strain_per_m: f32) -> GuideShape {
    let period_m = curl_period_m(mean_strain_per_m);
    let axis = period_m.map_or_else(Vec::new, |p| centreline(&curve, p));
    let shape = resampled_shape(&curve, FOLLOW_POINTS);
    GuideShape {
        curve,
        period_m,
        axis,
        shape,
    }
}

/// A strand's clump: the guide it gathers onto, how far (0 to 1) and, for
/// curls, its own phase (radians) and radius factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clump {
    /// The guide (an index into the guides the caller hands in).
    pub guide: usize,
    /// How far it gathers at the tip, 0 to 1.
    pub amount: f32,
    /// Its curl's phase about the clump's centreline, radians.
    pub phase_rad: f32,
    /// Its curl's radius against the guide's.
    pub curl_scale: f32,
}

/// How one drawn strand is shaped: clumped, then following.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Shaping {
    /// Its clump, if any.
    pub clump: Option<Clump>,
    /// Guides (index, weight) whose blended shape its tip follows; empty:
    /// none. At most [`MAX_FOLLOW`].
    pub follow: Vec<(usize, f32)>,
}

impl Shaping {
    /// Whether it leaves the strand as it is.
    pub fn is_none(&self) -> bool {
        self.clump.is_none() && self.follow.is_empty()
    }
}

/// Shapes `strand` (root first) as `shaping` says, from `guides` (the
/// indices `shaping` names): the CPU twin of `stage_shape`.
pub fn stage_shape(strand: &mut [Vec3], shaping: &Shaping, guides: &[GuideShape]) {
    if let Some(clump) = shaping.clump {
        let guide = &guides[clump.guide];
        match guide.period_m {
            Some(period_m) => clump_curl_onto_axis(
                strand,
                &guide.axis,
                clump.amount,
                period_m,
                (clump.phase_rad, clump.curl_scale),
            ),
            None => clump_onto(strand, &guide.curve, clump.amount),
        }
    }
    if !shaping.follow.is_empty() && !strand.is_empty() {
        let follow: Vec<(&[Vec3], f32)> = shaping
            .follow
            .iter()
            .map(|&(g, w)| (guides[g].shape.as_slice(), w))
            .collect();
        let blended = blended_shape(&follow, strand[0]);
        follow_guides(strand, &blended);
    }
}

/// Gathers `strand` (root first) onto `guide` (root first, same
/// coordinates) towards its tip: the point at arc length s (along the
/// strand as it was) moves the fraction `amount` · s/L of the way to the
/// guide's point at the same arc length (its tip beyond its length).
pub fn clump_onto(strand: &mut [Vec3], guide: &[Vec3], amount: f32) {
    let total_m = arc_length_m(strand);
    if total_m <= 0.0 || guide.len() < 2 {
        return;
    }
    let mut walk = ArcWalk::default();
    let (mut s_m, mut before) = (0.0f32, strand[0]);
    for p in strand.iter_mut() {
        s_m += p.distance(before);
        before = *p;
        let target = walk.point_at(guide, s_m);
        *p = p.lerp(target, amount * s_m / total_m);
    }
}

/// A walk along a polyline by increasing arc length: the segment reached
/// and the arc length at its start.
#[derive(Clone, Copy, Debug, Default)]
struct ArcWalk {
    segment: usize,
    segment_start_m: f32,
}

impl ArcWalk {
    /// The point of `path` (at least two points) at arc length `s_m`, no
    /// less than the last asked: clamped to the last segment's end.
    fn point_at(&mut self, path: &[Vec3], s_m: f32) -> Vec3 {
        while self.segment + 2 < path.len()
            && self.segment_start_m + path[self.segment].distance(path[self.segment + 1]) < s_m
        {
            self.segment_start_m += path[self.segment].distance(path[self.segment + 1]);
            self.segment += 1;
        }
        let (a, b) = (path[self.segment], path[self.segment + 1]);
        let span_m = a.distance(b).max(f32::MIN_POSITIVE);
        a.lerp(b, ((s_m - self.segment_start_m) / span_m).clamp(0.0, 1.0))
    }
}

/// The polyline's length, metres, summed root to tip.
fn arc_length_m(points: &[Vec3]) -> f32 {
    let mut total_m = 0.0f32;
    for w in points.windows(2) {
        total_m += w[0].distance(w[1]);
    }
    total_m
}

/// The centreline of `points` (a polyline, root first): each point
/// replaced by the mean of the points within half of `period_m` of arc
/// length on either side (fewer near the ends). A sliding window: both
/// ends only move towards the tip, carrying their arc lengths and the
/// window's sum.
pub fn centreline(points: &[Vec3], period_m: f32) -> Vec<Vec3> {
    let n = points.len();
    let half = 0.5 * period_m;
    let (mut lo, mut hi) = (0usize, 0usize);
    // Arc lengths at point i, at lo and at hi + 1.
    let (mut s_i, mut s_lo, mut s_next) = (0.0f32, 0.0f32, 0.0f32);
    if n > 1 {
        s_next = points[0].distance(points[1]);
    }
    let mut sum = points.first().copied().unwrap_or(Vec3::ZERO);
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        if i > 0 {
            s_i += points[i].distance(points[i - 1]);
        }
        while s_lo < s_i - half {
            sum -= points[lo];
            s_lo += points[lo].distance(points[lo + 1]);
            lo += 1;
        }
        while hi + 1 < n && s_next <= s_i + half {
            hi += 1;
            sum += points[hi];
            if hi + 1 < n {
                s_next += points[hi].distance(points[hi + 1]);
            }
        }
        out.push(sum / (hi + 1 - lo) as f32);
    }
    out
}

/// `v` turned by `angle_rad` about the unit `axis` (Rodrigues); as it is
/// where `axis` is zero.
pub fn turn_about(axis: Vec3, angle_rad: f32, v: Vec3) -> Vec3 {
    if axis == Vec3::ZERO {
        return v;
    }
    let (sin, cos) = angle_rad.sin_cos();
    v * cos + axis.cross(v) * sin + axis * (axis.dot(v) * (1.0 - cos))
}

/// Gathers `strand`'s centreline onto `guide`'s towards the tip by `amount`
/// (as [`clump_onto`] does points), keeping the strand's own curl around
/// it, turned about the centreline by `phase_rad` and scaled by
/// `curl_scale` (both ramped in over the first turn, so the root stays
/// where it grows). `period_m`: one turn of the curl, arc length.
pub fn clump_curl_onto(
    strand: &mut [Vec3],
    guide: &[Vec3],
    amount: f32,
    period_m: f32,
    variation: (f32, f32),
) {
    let guide_axis = centreline(guide, period_m);
    clump_curl_onto_axis(strand, &guide_axis, amount, period_m, variation);
}

/// [`clump_curl_onto`] with the guide's centreline already made.
pub fn clump_curl_onto_axis(
    strand: &mut [Vec3],
    guide_axis: &[Vec3],
    amount: f32,
    period_m: f32,
    (phase_rad, curl_scale): (f32, f32),
) {
    let n = strand.len();
    if n < 3 || guide_axis.len() < 2 {
        return;
    }
    let axis = centreline(strand, period_m);
    let axis_total_m = arc_length_m(&axis);
    let mut walk = ArcWalk::default();
    let (mut s_m, mut before) = (0.0f32, strand[0]);
    let (mut s_axis_m, mut axis_before) = (0.0f32, axis[0]);
    for (i, p) in strand.iter_mut().enumerate() {
        s_m += p.distance(before);
        before = *p;
        // The centreline's point gathered onto the guide's.
        s_axis_m += axis[i].distance(axis_before);
        axis_before = axis[i];
        let target = if axis_total_m > 0.0 {
            let on_guide = walk.point_at(guide_axis, s_axis_m);
            axis[i].lerp(on_guide, amount * s_axis_m / axis_total_m)
        } else {
            axis[i]
        };
        let ramp = (s_m / period_m).min(1.0);
        let along = (axis[(i + 1).min(n - 1)] - axis[i.saturating_sub(1)]).normalize_or_zero();
        let scale = 1.0 + (curl_scale - 1.0) * ramp;
        // At the root the centreline stays (amount · 0) and the curl is
        // whole and unturned: the root point does not move.
        *p = target + scale * turn_about(along, ramp * phase_rad, *p - axis[i]);
    }
}

/// The guides' shapes (each [`FOLLOW_POINTS`] offsets from its own root)
/// blended with their weights, moved to start at `root`.
pub fn blended_shape(follow: &[(&[Vec3], f32)], root: Vec3) -> Vec<Vec3> {
    let mut blended = vec![root; FOLLOW_POINTS];
    for &(shape, weight) in follow {
        for (b, s) in blended.iter_mut().zip(shape) {
            *b += weight * *s;
        }
    }
    blended
}

/// Pulls a drawn strand (root first) onto `blended`, its guides' blended
/// shape from its own root, fully at the tip and not at all at the root
/// ([`clump_onto`] with amount 1).
pub fn follow_guides(strand: &mut [Vec3], blended: &[Vec3]) {
    clump_onto(strand, blended, 1.0);
}

#[cfg(test)]
#[path = "strand_shape_tests.rs"]
mod tests;

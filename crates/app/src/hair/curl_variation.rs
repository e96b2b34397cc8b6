//! Curled drawn strands that do not all curl in step: each strand of a
//! clump keeps its own curl, with its own phase and a little more or less
//! radius, around the ringlet's axis.
//!
//! A clump's drawn strands grow from nearby roots whose frames barely
//! differ, so rebuilt from the same guides' strains they curl in phase; and
//! gathering their points onto the guide's own curve ([`clump_onto`])
//! pulls them into that one helix. Seen together they read as a regular
//! net (issue 32, item 10). XGen and Yeti clump first and curl after; the
//! same here ([`clump_curl_onto`]): a strand is split into its centreline
//! (the moving average over one turn of the curl, [`centreline`]) and its
//! curl (what is left); the centreline is gathered onto the guide's
//! centreline as the points were, and the curl is put back around it,
//! turned about the centreline by the strand's own phase and scaled by its
//! own radius factor ([`curl_variation`]: random per strand, the same every
//! frame). Turning the curl about its axis shifts its phase and leaves the
//! strand's course alone; turning the root frame instead would swing the
//! whole helix about the root's tangent, and strands would fly apart.

use std::f64::consts::TAU;

use glam::{DVec3, Quat, Vec3};
use helixhair_render::rng::SplitMix64;

/// How much a drawn strand's curl radius may differ from its guide's, as a
/// fraction: ±20%, as Yeti's default curl radius noise.
pub const CURL_RADIUS_VARIATION: f32 = 0.2;

/// How far a drawn strand's curl phase may differ from its clump's,
/// radians: ±0.6 (about a tenth of a turn each way). Strands of a ringlet
/// curl nearly together (that is what makes it a ringlet); a phase drawn
/// from the whole circle turned the fringe into frizz.
pub const CURL_PHASE_VARIATION_RAD: f32 = 0.6;

/// Seed of the per-strand variation (mixed with the strand's index).
const VARIATION_SEED: u64 = 0xC04C_5EED;

/// Drawn strand `index`'s curl phase (radians, within
/// ±[`CURL_PHASE_VARIATION_RAD`]) and radius factor
/// (1 ± [`CURL_RADIUS_VARIATION`]); the same for the same index every
/// frame.
pub fn curl_variation(index: usize) -> (f32, f32) {
    let mut rng = SplitMix64::new(VARIATION_SEED ^ (index as u64).wrapping_mul(0x9E37_79B9));
    let phase = CURL_PHASE_VARIATION_RAD * (2.0 * rng.next_f32() - 1.0);
    let scale = 1.0 + CURL_RADIUS_VARIATION * (2.0 * rng.next_f32() - 1.0);
    (phase, scale)
}

/// Gathers `strand` (root first) onto `guide` (root first, same
/// coordinates) towards its tip: the point at arc length s moves the
/// fraction `amount` · s/L of the way to the guide's point at the same arc
/// length, so strands leave the scalp where they grow and meet their
/// guide's curl near the tip, in phase.
pub fn clump_onto(strand: &mut [Vec3], guide: &[Vec3], amount: f32) {
    let total_m: f32 = strand.windows(2).map(|w| w[0].distance(w[1])).sum();
    if total_m <= 0.0 || guide.len() < 2 {
        return;
    }
    let (mut s_m, mut before) = (0.0f32, strand[0]);
    let (mut segment, mut segment_start_m) = (0usize, 0.0f32);
    for p in strand.iter_mut() {
        s_m += p.distance(before);
        before = *p;
        // The guide's point at arc length s (its tip beyond its length).
        while segment + 2 < guide.len()
            && segment_start_m + guide[segment].distance(guide[segment + 1]) < s_m
        {
            segment_start_m += guide[segment].distance(guide[segment + 1]);
            segment += 1;
        }
        let span_m = guide[segment]
            .distance(guide[segment + 1])
            .max(f32::MIN_POSITIVE);
        let t = ((s_m - segment_start_m) / span_m).clamp(0.0, 1.0);
        let target = guide[segment].lerp(guide[segment + 1], t);
        *p = p.lerp(target, amount * s_m / total_m);
    }
}

/// The arc length of one turn of a curl with strains `q` (per element,
/// m⁻¹): 2π / |q| for a helix (|q|² = curvature² + torsion²), from the
/// mean over the elements; `None` for straight hair.
pub fn curl_period_m(q: &[DVec3]) -> Option<f32> {
    let mean = q.iter().map(|k| k.length()).sum::<f64>() / q.len().max(1) as f64;
    (mean > 1.0).then(|| (TAU / mean) as f32)
}

/// The centreline of `points` (a polyline, root first): each point
/// replaced by the mean of the points within half of `period_m` of arc
/// length on either side (fewer near the ends).
pub fn centreline(points: &[Vec3], period_m: f32) -> Vec<Vec3> {
    let mut s = Vec::with_capacity(points.len());
    let mut total = 0.0f32;
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            total += p.distance(points[i - 1]);
        }
        s.push(total);
    }
    let mut prefix = Vec::with_capacity(points.len() + 1);
    prefix.push(Vec3::ZERO);
    for p in points {
        prefix.push(*prefix.last().unwrap_or(&Vec3::ZERO) + *p);
    }
    let half = 0.5 * period_m;
    let (mut lo, mut hi) = (0usize, 0usize);
    s.iter()
        .map(|&si| {
            while s[lo] < si - half {
                lo += 1;
            }
            while hi + 1 < s.len() && s[hi + 1] <= si + half {
                hi += 1;
            }
            (prefix[hi + 1] - prefix[lo]) / (hi + 1 - lo) as f32
        })
        .collect()
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
    (phase_rad, curl_scale): (f32, f32),
) {
    let n = strand.len();
    if n < 3 || guide.len() < 2 {
        return;
    }
    let axis = centreline(strand, period_m);
    let mut target = axis.clone();
    clump_onto(&mut target, &centreline(guide, period_m), amount);
    let mut s = 0.0f32;
    let mut before = strand[0];
    for (i, p) in strand.iter_mut().enumerate() {
        s += p.distance(before);
        before = *p;
        let ramp = (s / period_m).min(1.0);
        let along = (axis[(i + 1).min(n - 1)] - axis[i.saturating_sub(1)]).normalize_or_zero();
        let turn = Quat::from_axis_angle(along, ramp * phase_rad);
        let scale = 1.0 + (curl_scale - 1.0) * ramp;
        // At the root the centreline stays (amount · 0) and the curl is
        // whole and unturned: the root point does not move.
        *p = target[i] + scale * (turn * (*p - axis[i]));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A helix about the vertical line through `centre`, radius `r`,
    /// falling `pitch` per turn, starting at `phase`, `n` points over
    /// `turns` turns.
    fn helix(centre: Vec3, r: f32, pitch: f32, phase: f32, turns: f32, n: usize) -> Vec<Vec3> {
        (0..n)
            .map(|k| {
                let t = turns * std::f32::consts::TAU * k as f32 / (n - 1) as f32;
                centre
                    + Vec3::new(
                        r * (t + phase).cos(),
                        -pitch * t / std::f32::consts::TAU,
                        r * (t + phase).sin(),
                    )
            })
            .collect()
    }

    #[test]
    fn the_centreline_of_a_helix_is_its_axis_away_from_the_ends() {
        let r = 0.01;
        let points = helix(Vec3::ZERO, r, 0.03, 0.0, 6.0, 601);
        // One turn's arc: √((2πr)² + pitch²).
        let period = ((std::f32::consts::TAU * r).powi(2) + 0.03f32.powi(2)).sqrt();
        let axis = centreline(&points, period);
        for p in &axis[120..480] {
            assert!(Vec3::new(p.x, 0.0, p.z).length() < 0.1 * r, "{p}");
        }
    }

    #[test]
    fn a_clumped_curl_keeps_its_own_phase_and_radius_around_the_guides_axis() {
        // Known answer: a guide helix about x = 0 and a strand helix of the
        // same radius about x = 0.02, half a turn out of phase. Clumped
        // fully, the strand's axis goes onto the guide's at the tip, while
        // the strand stays a curl of its own radius and phase (gathering
        // its points, as `clump_onto` does, would lay it on the guide).
        let r = 0.008;
        let pitch = 0.03;
        let period = ((std::f32::consts::TAU * r).powi(2) + pitch * pitch).sqrt();
        let guide = helix(Vec3::ZERO, r, pitch, 0.0, 6.0, 601);
        let mut strand = helix(Vec3::X * 0.02, r, pitch, std::f32::consts::PI, 6.0, 601);
        let root = strand[0];
        clump_curl_onto(&mut strand, &guide, 1.0, period, (0.0, 1.0));
        assert!((strand[0] - root).length() < 1e-6, "the root moved");
        // Near the tip (away from the end's averaging), one turn back: the
        // axis has moved (arc length s of L) s/L of the way from x = 0.02
        // to the guide's at x = 0.
        for k in 480..520 {
            let p = strand[k];
            let g = guide[k];
            let axis_x = 0.02 * (1.0 - k as f32 / 600.0);
            let about_axis = Vec3::new(p.x - axis_x, 0.0, p.z).length();
            assert!(
                (about_axis - r).abs() < 0.25 * r,
                "point {k}: radius {about_axis}"
            );
            // Half a turn out of phase: opposite sides of the axis.
            assert!(p.distance(g) > 1.5 * r, "point {k} lies on the guide");
        }
    }

    #[test]
    fn a_turned_curl_is_the_same_helix_in_another_phase() {
        // Known answer: a strand that is its guide, clumped with a phase of
        // π, stays a helix of the same radius about the same axis, on the
        // opposite side of it from the guide one turn along.
        let r = 0.008;
        let pitch = 0.03;
        let period = ((std::f32::consts::TAU * r).powi(2) + pitch * pitch).sqrt();
        let guide = helix(Vec3::ZERO, r, pitch, 0.0, 6.0, 601);
        let mut strand = guide.clone();
        clump_curl_onto(
            &mut strand,
            &guide,
            0.7,
            period,
            (std::f32::consts::PI, 1.0),
        );
        for k in 150..450 {
            let (p, g) = (strand[k], guide[k]);
            let about_axis = Vec3::new(p.x, 0.0, p.z).length();
            assert!(
                (about_axis - r).abs() < 0.1 * r,
                "point {k}: radius {about_axis}"
            );
            assert!(p.distance(g) > 1.8 * r, "point {k} did not turn");
        }
        // Phases and radii vary from strand to strand, the same each frame.
        let all: Vec<(f32, f32)> = (0..50).map(curl_variation).collect();
        assert_eq!(all, (0..50).map(curl_variation).collect::<Vec<_>>());
        let spread = all.iter().map(|v| v.0).fold(f32::MIN, f32::max)
            - all.iter().map(|v| v.0).fold(f32::MAX, f32::min);
        // Spread over the allowed range (±0.6 rad), within it.
        assert!(
            spread > CURL_PHASE_VARIATION_RAD,
            "phases span {spread} rad"
        );
        assert!(all.iter().all(|v| v.0.abs() <= CURL_PHASE_VARIATION_RAD));
        assert!(
            all.iter()
                .all(|v| (v.1 - 1.0).abs() <= CURL_RADIUS_VARIATION)
        );
    }
}

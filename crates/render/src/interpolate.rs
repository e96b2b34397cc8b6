//! Render strands from guide strands: the physics simulates a few guides,
//! the picture shows many more strands that follow them.
//!
//! # How it works
//!
//! Each guide is resampled at the same number of points, evenly by arc
//! length, and stored as offsets from its own root: its *shape*. A render
//! strand at root r takes the guides whose roots are nearest to r and is
//! r + Σ wᵢ shapeᵢ(s), so it keeps the guides' curl instead of being pulled
//! towards a line between them:
//!
//! - [`Interpolation::Nearest`]: the nearest guide's shape only (w = 1).
//!   Curls stay crisp and strands clump around their guide, as curly and
//!   coily hair does.
//! - [`Interpolation::Blend3`]: the three nearest guides, weighted by
//!   inverse squared distance (a guide at the root itself gets all the
//!   weight). Smooth transitions between guides, as straight and wavy hair
//!   wants; curls of guides out of phase partly cancel.
//!
//! Each render strand also gets its own length, shortened by up to
//! `length_variation`, so tips thin out as real hair's do.

use glam::Vec3;

use crate::rng::SplitMix64;
use crate::strand_buffers::StrandBuffers;

/// How a render strand takes its shape from the guides near it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// The nearest guide's shape.
    Nearest,
    /// The three nearest guides' shapes, weighted by inverse squared
    /// distance.
    Blend3,
}

/// What render strands to make.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InterpolationSpec {
    /// The method.
    pub method: Interpolation,
    /// Points of every render strand (at least 2).
    pub points_per_strand: usize,
    /// Largest fraction by which a strand is shorter than its guides
    /// (0 = all full length).
    pub length_variation: f32,
    /// Seed of the per-strand lengths.
    pub seed: u64,
}

/// A polyline resampled at `n` points evenly spaced by arc length, as
/// offsets from its first point.
pub fn resampled_shape(points: &[Vec3], n: usize) -> Vec<Vec3> {
    let Some(&root) = points.first() else {
        return vec![Vec3::ZERO; n];
    };
    let mut arc = vec![0.0f32];
    for w in points.windows(2) {
        arc.push(arc[arc.len() - 1] + (w[1] - w[0]).length());
    }
    let total = arc[arc.len() - 1];
    let mut segment = 0;
    (0..n)
        .map(|k| {
            let s = total * k as f32 / (n - 1).max(1) as f32;
            while segment + 2 < arc.len() && arc[segment + 1] < s {
                segment += 1;
            }
            if points.len() == 1 {
                return Vec3::ZERO;
            }
            let span = (arc[segment + 1] - arc[segment]).max(f32::MIN_POSITIVE);
            let t = ((s - arc[segment]) / span).clamp(0.0, 1.0);
            points[segment].lerp(points[segment + 1], t) - root
        })
        .collect()
}

/// The guides nearest to `root` with their weights (summing to 1): one
/// for [`Interpolation::Nearest`], three weighted by inverse squared
/// distance for [`Interpolation::Blend3`] (all to a guide at `root`).
pub fn guide_weights(guide_roots: &[Vec3], root: Vec3, method: Interpolation) -> Vec<(usize, f32)> {
    let mut nearest: Vec<(usize, f32)> = guide_roots
        .iter()
        .map(|g| g.distance_squared(root))
        .enumerate()
        .collect();
    let keep = match method {
        Interpolation::Nearest => 1,
        Interpolation::Blend3 => 3,
    };
    let keep = keep.min(nearest.len());
    if keep < nearest.len() {
        nearest.select_nth_unstable_by(keep - 1, |a, b| a.1.total_cmp(&b.1));
    }
    nearest.truncate(keep);
    if let Some(&(i, _)) = nearest.iter().find(|(_, d2)| *d2 < 1e-14) {
        return vec![(i, 1.0)];
    }
    let total: f32 = nearest.iter().map(|(_, d2)| 1.0 / d2).sum();
    nearest
        .iter()
        .map(|&(i, d2)| (i, 1.0 / d2 / total))
        .collect()
}

/// One render strand per root of `render_roots`, shaped after `guides`
/// (whose first points are their roots). No guides, no strands.
pub fn interpolate_strands(
    guides: &StrandBuffers,
    render_roots: &[Vec3],
    spec: &InterpolationSpec,
) -> StrandBuffers {
    let mut out = StrandBuffers::default();
    let n = spec.points_per_strand.max(2);
    let guide_roots: Vec<Vec3> = guides.iter().filter_map(|g| g.first().copied()).collect();
    if guide_roots.len() != guides.strand_count() || guide_roots.is_empty() {
        return out;
    }
    let shapes: Vec<Vec<Vec3>> = guides.iter().map(|g| resampled_shape(g, n)).collect();
    let mut rng = SplitMix64::new(spec.seed);
    let variation = spec.length_variation.clamp(0.0, 0.9);
    for &root in render_roots {
        let weights = guide_weights(&guide_roots, root, spec.method);
        let length = 1.0 - variation * rng.next_f32();
        out.push_strand((0..n).map(|k| {
            // Where this point falls on the guides, as a fractional index.
            let x = length * k as f32;
            let i = (x as usize).min(n - 2);
            let t = x - i as f32;
            root + weights
                .iter()
                .map(|&(g, w)| w * shapes[g][i].lerp(shapes[g][i + 1], t))
                .sum::<Vec3>()
        }));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn helix(root: Vec3, phase: f32) -> Vec<Vec3> {
        (0..200)
            .map(|k| {
                let a = k as f32 * 0.1 + phase;
                root + Vec3::new(
                    0.01 * a.cos() - 0.01 * phase.cos(),
                    -0.002 * k as f32,
                    0.01 * a.sin() - 0.01 * phase.sin(),
                )
            })
            .collect()
    }

    fn spec(method: Interpolation) -> InterpolationSpec {
        InterpolationSpec {
            method,
            points_per_strand: 200,
            length_variation: 0.0,
            seed: 1,
        }
    }

    #[test]
    fn resampling_keeps_the_ends_and_spaces_points_evenly() {
        let line = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 3.0, 0.0)];
        let shape = resampled_shape(&line, 5);
        assert_eq!(shape[0], Vec3::ZERO);
        assert!((shape[4] - Vec3::new(1.0, 3.0, 0.0)).length() < 1e-6);
        assert!((shape[1] - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-6);
    }

    #[test]
    fn nearest_copies_the_guide_shape_so_the_curl_is_kept() {
        let mut guides = StrandBuffers::default();
        guides.push_strand(helix(Vec3::ZERO, 0.0));
        guides.push_strand(helix(Vec3::X, 3.0));
        let root = Vec3::new(0.1, 0.0, 0.0);
        let out = interpolate_strands(&guides, &[root], &spec(Interpolation::Nearest));
        for (a, b) in out.strand(0).iter().zip(guides.strand(0)) {
            assert!((*a - root - *b).length() < 1e-4, "{a} {b}");
        }
    }

    #[test]
    fn blend_weights_guides_by_distance_and_keeps_a_shared_curl() {
        let mut guides = StrandBuffers::default();
        for x in [0.0, 0.02, 0.04] {
            guides.push_strand(helix(Vec3::new(x, 0.0, 0.0), 0.0));
        }
        let out = interpolate_strands(
            &guides,
            &[Vec3::new(0.01, 0.0, 0.005)],
            &spec(Interpolation::Blend3),
        );
        // Guides in phase: the blend is the same helix.
        let strand = out.strand(0);
        let radius =
            (strand[30] - strand[0] - (guides.strand(0)[30] - guides.strand(0)[0])).length();
        assert!(radius < 1e-4, "{radius}");
        let weights = guide_weights(
            &[Vec3::ZERO, Vec3::X],
            Vec3::new(0.25, 0.0, 0.0),
            Interpolation::Blend3,
        );
        let w0 = weights.iter().find(|(i, _)| *i == 0).map(|w| w.1);
        assert!((w0.unwrap_or(0.0) - 0.9).abs() < 1e-5, "{weights:?}");
    }

    #[test]
    fn length_variation_shortens_strands_within_bounds() {
        let mut guides = StrandBuffers::default();
        guides.push_strand((0..11).map(|k| Vec3::new(0.0, -0.01 * k as f32, 0.0)));
        let roots = vec![Vec3::ZERO; 50];
        let spec = InterpolationSpec {
            length_variation: 0.2,
            ..spec(Interpolation::Nearest)
        };
        let out = interpolate_strands(&guides, &roots, &spec);
        for strand in out.iter() {
            let tip = -strand[strand.len() - 1].y;
            assert!((0.08 - 1e-5..=0.1 + 1e-5).contains(&tip), "{tip}");
        }
    }
}

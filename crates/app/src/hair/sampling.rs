//! Simulated strands as a fixed number of points evenly spaced along their
//! helices, for export.
//!
//! The physics' state is one strain vector per element; the strand between
//! element ends is a piece of helix with a closed-form centreline,
//! p_Q + R_Q h(σ, q_Q) ([`helixhair_physics::geometry::helix::centreline_and_jacobian`]).
//! A file format wants polylines with a chosen point count (TressFX: the
//! same power of two on every strand), so here point k of n sits at arc
//! length s_k = L k / (n − 1) from the root, evaluated on the element that
//! holds it: the points lie exactly on the simulated curve, not on a
//! polyline through the element ends (which, for a curl of a few elements
//! per turn, would cut the turns short).
//!
//! Super-Helices do not stretch, so arc length along the centreline is the
//! strand's rest arc length: the points are evenly spaced along the hair
//! whatever its shape, and the root and tip are the physics' own end
//! points.

use glam::{DVec3, Vec3};
use helixhair_physics::engine::Engine;
use helixhair_physics::geometry::helix::centreline_and_jacobian;
use helixhair_physics::geometry::shape::frames_and_points;

/// Fewest points a sampled strand has (a root and a tip).
pub const MIN_POINTS_PER_STRAND: usize = 2;

/// The points of strand `index` of `engine` at `count` arc lengths evenly
/// spaced from root to tip (at least [`MIN_POINTS_PER_STRAND`]), metres,
/// world coordinates, reconstructed in f64 on either engine.
/// Panics if `index` is out of range.
pub fn sample_strand_f64(engine: &Engine, index: usize, count: usize) -> Vec<DVec3> {
    let count = count.max(MIN_POINTS_PER_STRAND);
    let model = engine.strand_model(index);
    let motion = engine.head().carry(engine.root(index));
    let q_all = engine.q(index);
    // The shape alone: several times cheaper than Engine::kinematics.
    let (frames, ends) = frames_and_points(model, &q_all, &motion);
    let lengths_m = &model.lengths_m;
    let total_m: f64 = lengths_m.iter().sum();
    let last = q_all.len().saturating_sub(1);
    let mut points = Vec::with_capacity(count);
    // Walk the elements once: the arc lengths increase with k.
    let (mut element, mut element_start_m) = (0, 0.0);
    for k in 0..count {
        if k + 1 == count {
            // The tip is the physics' own end point.
            points.push(motion.position_m + ends[q_all.len()]);
            break;
        }
        let s_m = total_m * k as f64 / (count - 1) as f64;
        while element < last && s_m >= element_start_m + lengths_m[element] {
            element_start_m += lengths_m[element];
            element += 1;
        }
        let sigma_m = (s_m - element_start_m).clamp(0.0, lengths_m[element]);
        let start = motion.position_m + ends[element];
        let along = centreline_and_jacobian(sigma_m, q_all[element]).0;
        points.push(start + frames[element] * along);
    }
    points
}

/// [`sample_strand_f64`] in `f32`, as every hair file stores points.
pub fn sample_strand(engine: &Engine, index: usize, count: usize) -> Vec<Vec3> {
    sample_strand_f64(engine, index, count)
        .into_iter()
        .map(DVec3::as_vec3)
        .collect()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::sim::build::SimOverrides;
    use crate::sim::headless::HeadlessSim;
    use crate::style::Style;

    fn sim(ron: &str) -> HeadlessSim {
        let style = Style::from_ron(ron, Path::new("test.ron")).unwrap_or_else(|e| panic!("{e}"));
        HeadlessSim::new(&style, SimOverrides::default()).expect("builds")
    }

    /// A straight strand without gravity stays on its growth line: sample
    /// k is k L / (n − 1) from the root along the root's direction.
    #[test]
    fn a_straight_strand_is_sampled_evenly_along_its_line() {
        let sim = sim(r#"(version: 1, name: "s",
            sim: (gravity_m_per_s2: (0.0, 0.0, 0.0)),
            groups: [(name: "g",
                params: (length_m: 0.3, elements: 7, natural_shape: Straight),
                roots: [(position_m: (0.01, 0.1, 0.0), direction: (0.0, 0.6, 0.8))])])"#);
        let points = sample_strand_f64(sim.engine(), 0, 11);
        assert_eq!(points.len(), 11);
        let root = DVec3::new(0.01, 0.1, 0.0);
        let direction = DVec3::new(0.0, 0.6, 0.8);
        for (k, p) in points.iter().enumerate() {
            let want = root + direction * (0.3 * k as f64 / 10.0);
            assert!(p.distance(want) < 1e-12, "point {k}: {p} not {want}");
        }
    }

    /// On a curl, samples at every element end (n − 1 a multiple of the
    /// element count) are the physics' own boundary points, and the
    /// polyline through many samples is as long as the strand (it cannot
    /// stretch; chords are at most as long as their arcs).
    #[test]
    fn samples_on_a_curl_hit_the_element_ends_and_keep_the_length() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/styles/curly.ron");
        let style = Style::load(Path::new(path)).expect("loads");
        let mut sim = HeadlessSim::new(&style, SimOverrides::default()).expect("builds");
        sim.run(5).expect("finite");
        let engine = sim.engine();
        let elements = engine.strand_model(0).elements();
        let length_m: f64 = engine.strand_model(0).lengths_m.iter().sum();
        let boundaries = engine.boundary_points_world(0);
        let per = 4;
        let points = sample_strand_f64(engine, 0, elements * per + 1);
        for (j, b) in boundaries.iter().enumerate() {
            let d = points[j * per].distance(*b);
            assert!(d < 1e-9, "boundary {j} is {d} m from its sample");
        }
        let fine = sample_strand_f64(engine, 0, 2001);
        let polyline_m: f64 = fine.windows(2).map(|w| w[0].distance(w[1])).sum();
        assert!(
            polyline_m <= length_m * (1.0 + 1e-12),
            "{polyline_m} > {length_m}"
        );
        assert!(
            polyline_m > length_m * (1.0 - 1e-4),
            "{polyline_m} ≪ {length_m}"
        );
        // Two points make root and tip.
        let ends = sample_strand(engine, 0, 2);
        assert_eq!(ends[0], boundaries[0].as_vec3());
        assert_eq!(ends[1], boundaries[elements].as_vec3());
    }
}

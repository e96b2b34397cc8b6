//! Simulated strands as smooth polylines for drawing.
//!
//! The physics reports one point per element boundary, but each element is
//! a piece of helix: a curly strand of 15 elements makes several turns, and
//! its boundary points alone would draw a zigzag. Here every element is
//! sampled along its own closed-form centreline, p_Q + R_Q h(σ, q_Q)
//! ([`helixhair_physics::geometry::helix`]), finely enough that consecutive points
//! turn by at most [`MAX_TURN_RAD`].

use glam::{DVec3, Vec3};
use helixhair_physics::engine::Engine;
use helixhair_render::StrandBuffers;

use crate::hair::strain_blend::helix_polyline;
pub use crate::hair::strain_blend::{MAX_POINTS_PER_ELEMENT, MAX_TURN_RAD};

/// The centreline of strand `index`, root first, metres, world
/// coordinates (reconstructed in f64 on either engine).
pub fn guide_curve(engine: &Engine, index: usize) -> Vec<DVec3> {
    let motion = engine.head().carry(engine.root(index));
    let lengths_m = &engine.strand_model(index).lengths_m;
    helix_polyline(&motion, lengths_m, &engine.q(index))
}

/// The centrelines of every strand of `engine`, in `f32` for drawing.
pub fn guide_curves(engine: &Engine) -> StrandBuffers {
    let mut buffers = StrandBuffers::default();
    for i in 0..engine.strand_count() {
        buffers.push_strand(
            guide_curve(engine, i)
                .into_iter()
                .map(|p: DVec3| p.as_vec3()),
        );
    }
    buffers
}

/// Converts a point to `f32`.
pub fn to_f32(p: DVec3) -> Vec3 {
    p.as_vec3()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::sim::build::SimOverrides;
    use crate::sim::headless::HeadlessSim;
    use crate::style::Style;

    #[test]
    fn curves_pass_through_the_element_boundaries_and_sample_curls_finely() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/styles/curly.ron");
        let style = Style::load(Path::new(path)).expect("loads");
        let mut sim = HeadlessSim::new(&style, SimOverrides::default()).expect("builds");
        sim.run(3).expect("finite");
        let system = sim.engine();
        let curve = guide_curve(system, 0);
        let boundaries = system.boundary_points_world(0);
        assert!(curve.len() > 2 * boundaries.len(), "{} points", curve.len());
        // Consecutive chords turn by about the curvature times the spacing:
        // at most MAX_TURN_RAD, with 20% for chords across element joins.
        let turns = curve
            .windows(3)
            .map(|w| (w[1] - w[0]).angle_between(w[2] - w[1]));
        let max_turn = turns.fold(0.0, f64::max);
        assert!(max_turn < 1.2 * MAX_TURN_RAD, "turn {max_turn} rad");
        for b in &boundaries {
            let nearest = curve
                .iter()
                .map(|p| p.distance(*b))
                .fold(f64::MAX, f64::min);
            assert!(nearest < 1e-9, "boundary {b} is {nearest} m from the curve");
        }
        assert_eq!(curve.first(), boundaries.first());
        assert_eq!(guide_curves(system).strand_count(), system.strand_count());
    }
}

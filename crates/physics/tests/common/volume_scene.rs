//! The small head of the hair–hair model's tests (`tests/volume.rs` on the
//! reference, `tests/batch_volume.rs` on the batch engine): one scene, so
//! the two engines' known answers and their agreement are about the same
//! hair.

use glam::DVec3;
use helixhair_physics::{NaturalShape, RootPose, StrandParams};

use super::shake_scene::ShakeThenStill;

/// Roots on the upper half of a 10 cm head, curly strands of 20 cm:
/// `rings` rings of `count_per_ring` roots.
pub fn small_head(count_per_ring: usize, rings: usize) -> (StrandParams, Vec<RootPose>) {
    let params = StrandParams {
        length_m: 0.2,
        elements: 8,
        natural_shape: NaturalShape::Helix {
            radius_m: 0.012,
            step_m: 0.03,
        },
        ..StrandParams::default()
    };
    let mut roots = Vec::new();
    for ring in 0..rings {
        let polar = 0.3 + 1.0 * ring as f64 / rings as f64;
        for k in 0..count_per_ring {
            let azimuth = std::f64::consts::TAU * k as f64 / count_per_ring as f64;
            let n = DVec3::new(
                polar.sin() * azimuth.cos(),
                polar.cos(),
                polar.sin() * azimuth.sin(),
            );
            roots.push(RootPose::from_direction(0.1 * n, n, DVec3::Y));
        }
    }
    (params, roots)
}

/// Steps `system` through `head` (a shake, then 3 s still) with `step`,
/// and returns its kinetic energy (`kinetic_j`) at the end of the shake,
/// after each still second, and at the end.
pub fn kinetic_after_shake<S>(
    system: &mut S,
    head: &ShakeThenStill,
    step: fn(&mut S, &ShakeThenStill),
    kinetic_j: fn(&S) -> f64,
) -> Vec<f64> {
    let frames_shake = (head.shake_secs * 60.0).ceil() as usize;
    let mut seconds = Vec::new();
    for frame in 0..frames_shake + 180 {
        step(system, head);
        if frame >= frames_shake && (frame - frames_shake).is_multiple_of(60) {
            seconds.push(kinetic_j(system));
        }
    }
    seconds.push(kinetic_j(system));
    seconds
}

/// The calm-down's known answer: with the model the kinetic energy after
/// the shake (`with`, from [`kinetic_after_shake`]) falls every second and
/// ends below the run without it (`without`).
pub fn assert_calms_down(with: &[f64], without: &[f64]) {
    for w in with.windows(2) {
        assert!(w[1] < w[0], "kinetic energy rose after the shake: {with:?}");
    }
    assert!(
        with.last() < without.last(),
        "with {with:?}, without {without:?}"
    );
}

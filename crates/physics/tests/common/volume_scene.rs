//! The small head of the hair–hair model's tests (`tests/volume.rs` on the
//! reference, `tests/batch_volume.rs` on the batch engine): one scene, so
//! the two engines' known answers and their agreement are about the same
//! hair.

use glam::DVec3;
use helixhair_physics::{NaturalShape, RootPose, StrandParams};

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

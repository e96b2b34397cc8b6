//! The GPU tests' adapter, by the workspace's one test policy
//! (`helixhair_gpu::context_or_skip`): skip where none exists, fail where
//! CI asks (`HELIXHAIR_REQUIRE_GPU=1`, set by `.ci/run`).

use helixhair_physics::gpu::GpuContext;

/// A headless context, or `None` (after saying why) on a machine without an
/// adapter; a missing adapter fails the test where CI requires a GPU.
pub fn context() -> Option<GpuContext> {
    helixhair_gpu::context_or_skip("physics GPU test")
}

/// The GPU engine tests' draping scene: strands of four kinds (30 cm
/// straight and wavy, 12 elements; 25 cm curls, 15; 12 cm tight curls, 10),
/// each on the two roots of the shake scene moved onto the sphere's
/// surface, stepped with `method` at one substep: (settings, one model per
/// strand, roots).
pub fn draping_strands(
    method: helixhair_physics::Method,
) -> (
    helixhair_physics::SimSettings,
    Vec<helixhair_physics::batch::layout::BatchModel>,
    Vec<helixhair_physics::RootPose>,
) {
    use super::shake_scene::{curly_25_cm, head_roots, straight_30_cm, wavy_30_cm};
    use super::sphere::RADIUS_M;
    use helixhair_physics::batch::layout::BatchModel;
    use helixhair_physics::{RootPose, SimSettings, StrandModel};
    let settings = SimSettings {
        method,
        substeps: 1,
        ..SimSettings::default()
    };
    let mut models = Vec::new();
    let mut roots = Vec::new();
    for params in [
        straight_30_cm(),
        wavy_30_cm(),
        curly_25_cm(),
        super::curl(10),
    ] {
        let model = StrandModel::new(&params, settings.quadrature_points).expect("valid params");
        for root in head_roots() {
            models.push(BatchModel::new(&model));
            roots.push(RootPose {
                position_m: root.position_m.normalize() * RADIUS_M,
                ..root
            });
        }
    }
    (settings, models, roots)
}

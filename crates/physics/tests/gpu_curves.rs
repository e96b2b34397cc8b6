//! The drawn centrelines the GPU engine writes on its device
//! (`stage_curves`, `shaders/physics/curves.wgsl`) against their CPU twin,
//! the batch engine's sweep at f32, and the twin against the known shape
//! of a Super-Helix: the f64 boundary points of `frames_and_points`, the
//! helix h(σ, k) inside each element, and a circle of radius 1/κ for a
//! strand of constant bend. Blended curves (a drawn strand between
//! guides, with a base of its own) against the f64 shape of the blended
//! strains, computed here from the engine's state.
//!
//! Policy: with no adapter the tests print why and pass, unless
//! `HELIXHAIR_REQUIRE_GPU=1` (set by `.ci/run`), where they fail.
#![cfg(feature = "gpu")]

use crate::common;

use common::gpu::context;
use common::shake;
use common::shake_scene::{curly_25_cm, head_roots, straight_30_cm};
use glam::DVec3;
use helixhair_physics::batch::layout::BatchModel;
use helixhair_physics::geometry::helix::centreline_and_jacobian;
use helixhair_physics::geometry::shape::frames_and_points;
use helixhair_physics::gpu::GpuEngine;
use helixhair_physics::gpu::curves::{BlendElement, CurveBlend, curve_point_count, stage_curves};
use helixhair_physics::{
    NaturalShape, RigidMotion, RootPose, SimSettings, StrandModel, StrandParams,
};

/// GPU against twin, on the same strains, metres: the same f32 operations
/// in another order, with the GPU's own cos and sin (lavapipe's are
/// llvmpipe's polynomials), over 12–15 elements of up to 16 pieces each.
const CURVE_TWIN_TOL_M: f32 = 2e-6;

/// Twin (f32) against the f64 shape, metres: f32 round-off carried over
/// the 30 cm strand's up to 12 × 16 pieces (about 200 steps of 6e-8 m).
const CURVE_F64_TOL_M: f64 = 1e-5;

/// Mean strain magnitude, relative: f32 round-off of a sum of a dozen
/// lengths (about 12 × 6e-8), with the GPU's own square root.
const STRAIN_TOL: f32 = 1e-5;

/// 30 cm straight and 25 cm curly strands, and a 10-element curl, each on
/// the two roots of the shake scene.
fn models() -> (Vec<StrandModel>, Vec<RootPose>) {
    let curl = StrandParams {
        elements: 10,
        natural_shape: NaturalShape::Helix {
            radius_m: 0.02,
            step_m: 0.05,
        },
        ..StrandParams::default()
    };
    let (mut models, mut roots) = (Vec::new(), Vec::new());
    for params in [straight_30_cm(), curly_25_cm(), curl] {
        let model = StrandModel::new(&params, 5).expect("valid params");
        for root in head_roots() {
            models.push(model.clone());
            roots.push(root);
        }
    }
    (models, roots)
}

/// The f64 shape of `model` at `root` with strains `q`, cut `samples`
/// times per element: p_Q + R_Q h(σ, k_Q) at each piece's start, then the
/// tip (head coordinates).
fn f64_curve(model: &StrandModel, root: &RootPose, q: &[DVec3], samples: u32) -> Vec<DVec3> {
    let motion = RigidMotion::at_rest(root.position_m, root.head_from_root);
    let (frames, points) = frames_and_points(model, q, &motion);
    let mut out = Vec::new();
    for (e, &k) in q.iter().enumerate() {
        let piece_m = model.lengths_m[e] / f64::from(samples);
        for j in 0..samples {
            let h = centreline_and_jacobian(f64::from(j) * piece_m, k).0;
            out.push(root.position_m + points[e] + frames[e] * h);
        }
    }
    out.push(root.position_m + points[q.len()]);
    out
}

#[test]
fn the_device_curves_match_their_twin_and_the_helix_shape() {
    let Some(ctx) = context() else { return };
    let (models, roots) = models();
    let batch: Vec<BatchModel> = models.iter().map(BatchModel::new).collect();
    let settings = SimSettings {
        substeps: 1,
        ..SimSettings::default()
    };
    let mut engine = GpuEngine::new(ctx.clone(), &settings, &batch, &roots, None).expect("engine");
    let head = shake();
    for _ in 0..30 {
        engine.step_frame(&head);
    }
    // Straight strands cut once per element, curls more: every count the
    // stage takes, including the CPU's most (16).
    let sampling: Vec<u32> = [1, 3, 16, 4, 7, 2].to_vec();
    let lengths: Vec<&[f64]> = models.iter().map(|m| m.lengths_m.as_slice()).collect();
    let mut blend = CurveBlend::engine_strands(&roots, &lengths, &sampling);
    // Two drawn strands: one between strands 0 and 2 (straight and curly,
    // 0.25 / 0.75) from strand 1's root, one with a base of its own on
    // strand 4's elements, each element reading its sources' element at
    // the same index (the curly model is shorter: its last).
    let (n0, n2, n4) = (
        models[0].elements(),
        models[2].elements(),
        models[4].elements(),
    );
    let starts: Vec<u32> = (0..batch.len())
        .map(|s| engine.elements_of(s).start as u32)
        .collect();
    let first = |s: usize| starts[s];
    let between = blend.push(
        &roots[1],
        5,
        (0..n0).map(|e| BlendElement {
            length_m: models[0].lengths_m[e],
            base: DVec3::ZERO,
            sources: [
                (first(0) + e as u32, 0.25),
                (first(2) + e.min(n2 - 1) as u32, 0.75),
            ],
        }),
    );
    let based = blend.push(
        &roots[0],
        3,
        (0..n4).map(|e| BlendElement {
            length_m: models[4].lengths_m[e],
            base: DVec3::new(2.0, -5.0, 1.0 + e as f64),
            sources: [(first(4) + e as u32, 1.0)],
        }),
    );
    let (points, strains, ranges) = {
        let stage = engine.write_curves(&blend).expect("curves");
        (
            stage.read_points(&ctx).expect("read"),
            stage.read_strains(&ctx).expect("read"),
            stage.ranges().to_vec(),
        )
    };
    assert_eq!(ranges.len(), batch.len() + 2);
    let (q, _) = engine.read_state().expect("state");
    let q64 = |i: usize| DVec3::new(q[i][0].into(), q[i][1].into(), q[i][2].into());
    // The f64 strains of every curve, blended here from the state.
    let mut curves: Vec<(StrandModel, RootPose, Vec<DVec3>, u32)> = (0..batch.len())
        .map(|s| {
            let k = engine.elements_of(s).map(q64).collect();
            (models[s].clone(), roots[s], k, sampling[s])
        })
        .collect();
    let f = |s: usize| first(s) as usize;
    let k_between = (0..n0)
        .map(|e| 0.25 * q64(f(0) + e) + 0.75 * q64(f(2) + e.min(n2 - 1)))
        .collect();
    curves.push((models[0].clone(), roots[1], k_between, 5));
    let k_based = (0..n4)
        .map(|e| DVec3::new(2.0, -5.0, 1.0 + e as f64) + q64(f(4) + e))
        .collect();
    curves.push((models[4].clone(), roots[0], k_based, 3));
    assert_eq!((between, based), (batch.len(), batch.len() + 1));

    let (mut worst_twin, mut worst_f64, mut worst_strain) = (0.0f32, 0.0f64, 0.0f32);
    for (c, (model, root, k64, samples)) in curves.iter().enumerate() {
        let mut twin = Vec::new();
        let strain = stage_curves(&blend, c, &q, &mut twin);
        assert_eq!(
            ranges[c].len(),
            curve_point_count(model.elements(), *samples)
        );
        assert_eq!(twin.len(), ranges[c].len());
        let device = &points[ranges[c].clone()];
        for (a, b) in device.iter().zip(&twin) {
            assert_eq!(a[3], 1.0, "w = 1");
            let d = (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f32::max);
            worst_twin = worst_twin.max(d);
        }
        let exact = f64_curve(model, root, k64, *samples);
        for (a, b) in twin.iter().zip(&exact) {
            let p = DVec3::new(a[0].into(), a[1].into(), a[2].into());
            worst_f64 = worst_f64.max(p.distance(*b));
        }
        let mean = k64.iter().map(|k| k.length()).sum::<f64>() / k64.len() as f64;
        worst_strain = worst_strain
            .max(((strains[c] - strain).abs()).max((strain - mean as f32).abs()) / mean as f32);
    }
    eprintln!(
        "curves: GPU vs twin {worst_twin:.2e} m, twin vs f64 {worst_f64:.2e} m, \
         mean strain {worst_strain:.2e} relative"
    );
    assert!(
        worst_twin <= CURVE_TWIN_TOL_M,
        "GPU vs twin {worst_twin:e} m"
    );
    assert!(worst_f64 <= CURVE_F64_TOL_M, "twin vs f64 {worst_f64:e} m");
    assert!(
        worst_strain <= STRAIN_TOL,
        "mean strain {worst_strain:e} relative"
    );
}

/// A strand bent by the same curvature κ in every element, with no twist,
/// lies on a circle of radius 1/κ: the known answer the twin's pieces must
/// keep, however finely they cut.
#[test]
fn a_constant_bend_draws_a_circle_of_radius_one_over_kappa() {
    let kappa = 10.0f32;
    let params = StrandParams {
        length_m: 0.3,
        elements: 8,
        ..StrandParams::default()
    };
    let model = StrandModel::new(&params, 5).expect("valid params");
    let root = RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Z);
    let n = model.elements();
    // One strand of n elements at the front of an engine's state.
    let q = vec![[0.0, kappa, 0.0, 0.0]; n];
    for samples in [1, 5, 16] {
        let blend = CurveBlend::engine_strands(&[root], &[&model.lengths_m], &[samples]);
        let mut curve = Vec::new();
        let strain = stage_curves(&blend, 0, &q, &mut curve);
        assert_eq!(strain, kappa);
        // The circle through the root, tangent to the root's direction,
        // bending about the frame's second axis.
        let frame = root.head_from_root.as_mat3();
        let (t, b) = (frame.x_axis, frame.y_axis);
        let normal = b.cross(t);
        let centre = normal / kappa;
        for p in &curve {
            let r = (glam::Vec3::new(p[0], p[1], p[2]) - centre).length();
            assert!(
                (r - 1.0 / kappa).abs() < 2e-6,
                "{samples} pieces: radius {r} m, expected {} m",
                1.0 / kappa
            );
        }
        assert_eq!(curve.len(), curve_point_count(n, samples));
    }
}

/// Blends are equal by their tables: a clone, or the same layout built
/// again; a push makes another. (The stage's build id, which spares the
/// per-frame comparison, must never make unequal blends equal.)
#[test]
fn blends_are_equal_by_their_tables() {
    let lengths = [0.02; 4];
    let root = RootPose::from_direction(DVec3::ZERO, DVec3::NEG_Y, DVec3::Z);
    let blend =
        |lengths: &[f64]| CurveBlend::engine_strands(&[root, root], &[lengths, lengths], &[1, 3]);
    let a = blend(&lengths);
    assert_eq!(a.clone(), a);
    assert_eq!(blend(&lengths), a);
    assert_ne!(blend(&[0.02; 5]), a);
    let mut c = a.clone();
    let element = BlendElement {
        length_m: 0.02,
        base: DVec3::ZERO,
        sources: [(0, 1.0)],
    };
    c.push(&root, 2, [element]);
    assert_ne!(c, a);
    // Strand 0: 4 × 1 + 1 points; strand 1: 4 × 3 + 1; the new curve 2 + 1.
    assert_eq!(c.ranges(), [0..5, 5..18, 18..21]);
    assert_eq!(c.elements_read(), 8);
}

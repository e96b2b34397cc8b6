//! Diagnostic: where the f32 batch path's Exact step parts from the f64
//! reference, and whether f32 round-off is the cause.
//!
//! `cargo run --release -p helixhair-physics --example f32_precision`
//!
//! One 30 cm straight strand (12 graded elements, as in
//! `assets/styles/straight.ron`) grows from a 10 cm head along each of a
//! few directions and falls under gravity (h = 1/240 s). For each it steps
//! the batch arithmetic with moments about the root
//! (`batch::exact::step_exact`) in f32 and, with the same f32 constants,
//! in f64 (`Real for f64`), and the batch path as it is
//! (`BatchSystem`: f32, moments about each element's own points), next to
//! the f64 reference `HairSystem`, and prints the largest relative
//! difference of max |q̇| over 45 frames for each.
//!
//! It is the diagnosis behind the batch path's local moments: about the
//! root, the mass block of an element 30 cm out is the small difference of
//! terms of size m|p|², and a straight strand's twist entries are the
//! smallest of all, so f32 (but not f64) parts from the reference on roots
//! out of the vertical plane through the head's centre. What the local
//! moments change: `docs/solvers.md`, "f32 on long straight strands".

use glam::DVec3;
use helixhair_physics::batch::layout::{BatchModel, ElementData, RootMotion, StepEnv};
use helixhair_physics::batch::step::exact::{Elimination, step_exact};
use helixhair_physics::batch::vec::V3;
use helixhair_physics::batch::{BatchSystem, Real};
use helixhair_physics::model::StrandModel;
use helixhair_physics::params::ElementLayout;
use helixhair_physics::{HairSystem, Method, RigidMotion, RootPose, SimSettings, StrandParams};

/// Frames stepped per direction.
const FRAMES: usize = 45;
/// Substeps per 60 Hz frame.
const SUBSTEPS: usize = 4;

/// max |q̇| after each frame of the batch Exact arithmetic in `T`, with
/// moments about the root (as the Dense kernel takes them).
fn batch_speeds<T: Real>(model: &BatchModel, env: &StepEnv, root: &RigidMotion) -> Vec<f64> {
    let n = model.elements();
    let mut q: Vec<V3<T>> = model.natural.iter().map(|k| V3::splat(*k)).collect();
    let mut v: Vec<V3<T>> = vec![V3::zero(); n];
    let mut scratch = vec![ElementData::zero(); n];
    let mut elimination = vec![Elimination::zero(); n];
    let root = RootMotion::<T>::gather(&[*root]);
    (0..FRAMES)
        .map(|_| {
            for _ in 0..SUBSTEPS {
                step_exact(
                    model,
                    env,
                    &root,
                    &mut q,
                    &mut v,
                    &mut scratch,
                    &mut elimination,
                );
            }
            v.iter()
                .flat_map(|x| [x.x.lane(0), x.y.lane(0), x.z.lane(0)])
                .map(|x| f64::from(x).abs())
                .fold(0.0, f64::max)
        })
        .collect()
}

fn main() {
    let params = StrandParams {
        length_m: 0.3,
        elements: 12,
        layout: ElementLayout::Graded {
            tip_to_root_ratio: 3.0,
        },
        radius_m: 40e-6,
        ellipticity: 1.0,
        youngs_modulus_pa: 3.9e9,
        shear_modulus_pa: 0.9e9,
        ..StrandParams::default()
    };
    let settings = SimSettings {
        method: Method::Exact,
        dt_secs: 1.0 / 60.0,
        substeps: SUBSTEPS as u32,
        ..SimSettings::default()
    };
    let model = StrandModel::new(&params, settings.quadrature_points).expect("valid strand");
    let model = BatchModel::new(&model);
    let env = StepEnv {
        h_secs: settings.substep_secs(),
        gravity_m_per_s2: settings.gravity_m_per_s2.to_array(),
        air_velocity_m_per_s: [0.0; 3],
    };
    let head = RigidMotion::default();
    println!(
        "direction, worst relative difference from the reference: \
         f32 root moments, f64 root moments, f32 local moments (BatchSystem)"
    );
    for d in [
        DVec3::new(0.0, 0.9659, 0.2588),
        DVec3::new(0.8192, 0.5736, 0.0),
        DVec3::new(0.7698, 0.5736, 0.2802),
        DVec3::new(0.9077, 0.2588, 0.3304),
    ] {
        let pose = RootPose::from_direction(d * 0.1, d, DVec3::Y);
        let root = head.carry(&pose);
        let in_f32 = batch_speeds::<f32>(&model, &env, &root);
        let in_f64 = batch_speeds::<f64>(&model, &env, &root);
        let mut batch = BatchSystem::new(settings.clone()).expect("valid settings");
        batch.set_guard(None);
        batch.add_group(&params, &[pose]).expect("valid strand");
        let mut reference = HairSystem::new(settings.clone()).expect("valid settings");
        reference.set_guard(None);
        reference.add_group(&params, &[pose]).expect("valid strand");
        let (mut worst_f32, mut worst_f64, mut worst_local) = (0.0f64, 0.0f64, 0.0f64);
        for f in 0..FRAMES {
            reference.step_frame(&head);
            let speed = reference.strands()[0]
                .v()
                .iter()
                .map(|x| x.abs().max_element())
                .fold(0.0, f64::max)
                .max(1.0);
            let rel = |x: f64| {
                if x.is_finite() {
                    (x - speed).abs() / speed
                } else {
                    f64::INFINITY
                }
            };
            worst_f32 = worst_f32.max(rel(in_f32[f]));
            worst_f64 = worst_f64.max(rel(in_f64[f]));
            batch.step_frame(&head);
            let local = batch
                .v(0)
                .iter()
                .map(|x| x.abs().max_element())
                .fold(0.0, f64::max);
            worst_local = worst_local.max(rel(local));
        }
        println!("{d:?}, {worst_f32:.2e}, {worst_f64:.2e}, {worst_local:.2e}");
    }
}

//! The guard's measure on the GPU (`stage_measure`,
//! `shaders/physics/measure.wgsl`) against a known answer (a straight
//! strand carried round by a spinning head) and against its CPU twin,
//! the batch engine's measure at f32 one strand wide, on strands of four
//! kinds draping over a sphere under a head shake (their own constants and
//! element counts, in contact and not, judged by either energy), and its
//! finiteness test on a state gone NaN or infinite.
//!
//! Policy: with no adapter the tests print why and pass, unless
//! `HELIXHAIR_REQUIRE_GPU=1` (set by `.ci/run`), where they fail.
#![cfg(feature = "gpu")]

use crate::common;

use common::gpu::{context, draping_strands};
use common::shake;
use common::sphere::sphere_field;
use glam::{DMat3, DVec3};
use helixhair_physics::batch::contact::NearCells;
use helixhair_physics::batch::layout::BatchModel;
use helixhair_physics::batch::vec::V3;
use helixhair_physics::frame_balance::{KineticEnergy, StrandMeasure};
use helixhair_physics::gpu::GpuEngine;
use helixhair_physics::gpu::measure::stage_measure;
use helixhair_physics::{HeadTrajectory, Method, RigidMotion, RootPose, SimSettings, StrandModel};

/// Kernel against twin, on the same state: each energy within this
/// fraction of the strand's size (kinetic + elastic + |gravitational|),
/// one tenth of the guard's own allowance for f32 round-off
/// (`batch::guard::F32_ENERGY_ROUND_OFF`, 1e-4), so that the device's
/// verdicts are the CPU's but at the allowance's very edge; every vector
/// and the other scalars within this fraction of their largest value
/// over the strands. Both sum the same f32 terms in the same order; they
/// differ in fused multiply-adds and the sample positions' round-off.
const MEASURE_TOL: f64 = 1e-5;

/// Frames of the shake before the measure: the hair is moving, bent and
/// partly on the sphere.
const FRAMES: usize = 20;

/// Known answers in f32: a few ulps of the sums.
const KNOWN_TOL: f64 = 1e-5;

fn to_v3(x: &[[f32; 4]]) -> Vec<V3<f32>> {
    x.iter().map(|a| V3::new(a[0], a[1], a[2])).collect()
}

/// Largest |a − b| of each of `values`' quantities over the strands,
/// over the largest |b|.
fn worst_relative(pairs: &[(StrandMeasure, StrandMeasure)]) -> Vec<(&'static str, f64)> {
    type Get = fn(&StrandMeasure) -> Vec<f64>;
    let quantities: [(&str, Get); 9] = [
        ("momentum", |m| m.momentum.to_array().to_vec()),
        ("angular momentum", |m| {
            m.angular_momentum.to_array().to_vec()
        }),
        ("force", |m| m.external_force_n.to_array().to_vec()),
        ("torque", |m| m.external_torque_n_m.to_array().to_vec()),
        ("power", |m| vec![m.external_power_w]),
        ("mass", |m| vec![m.mass_kg]),
        ("second moment", |m| vec![m.second_moment_kg_m2]),
        ("fastest", |m| vec![m.fastest_relative_m_per_s]),
        ("strain kinetic", |m| vec![m.strain_kinetic_j]),
    ];
    quantities
        .iter()
        .map(|(name, get)| {
            let (mut diff, mut size) = (0.0f64, 0.0f64);
            for (gpu, twin) in pairs {
                for (a, b) in get(gpu).into_iter().zip(get(twin)) {
                    diff = diff.max((a - b).abs());
                    size = size.max(b.abs());
                }
            }
            (*name, diff / size.max(f64::MIN_POSITIVE))
        })
        .collect()
}

#[test]
fn the_gpu_measure_is_its_twins() {
    let (field, _) = sphere_field();
    let near = NearCells::new(&field);
    let head = shake();
    let cases = [
        (Method::Exact, KineticEnergy::True),
        (Method::BlockDiagonal, KineticEnergy::BlockDiagonal),
    ];
    for ((method, judged_by), with_field) in cases.into_iter().flat_map(|c| [(c, true), (c, false)])
    {
        let Some(ctx) = context() else { return };
        let (settings, models, roots) = draping_strands(method);
        let collider = with_field.then_some(&field);
        let mut gpu =
            GpuEngine::new(ctx, &settings, &models, &roots, collider).expect("GPU engine");
        for _ in 0..FRAMES {
            gpu.step_frame(&head);
        }
        let end = head.motion_at(gpu.time_secs());
        let measured = gpu.measure(&end, judged_by).expect("measure");
        let (q, v) = gpu.read_state().expect("readback");
        let gravity = settings.gravity_m_per_s2;
        let mut pairs = Vec::new();
        let mut touching = 0;
        let mut worst_energy = 0.0f64;
        for (i, (model, root)) in models.iter().zip(&roots).enumerate() {
            let range = gpu.elements_of(i);
            let (q, v) = (to_v3(&q[range.clone()]), to_v3(&v[range]));
            let collider = with_field.then_some((&field, &near));
            let twin = stage_measure(&settings, model, root, &end, collider, (&q, &v), judged_by);
            let motion = end.carry(root);
            let (on_gpu, on_cpu) = (
                measured[i].strand(&motion, gravity),
                twin.strand(&motion, gravity),
            );
            assert!(measured[i].state_is_finite() && twin.state_is_finite());
            assert_eq!(
                on_gpu.in_contact, on_cpu.in_contact,
                "{method:?}: strand {i}: contact {} on the GPU, {} on the CPU",
                on_gpu.in_contact, on_cpu.in_contact
            );
            touching += usize::from(on_cpu.in_contact);
            let size = on_cpu.size_j;
            for (name, a, b) in [
                ("kinetic", on_gpu.kinetic_j, on_cpu.kinetic_j),
                (
                    "block kinetic",
                    on_gpu.block_kinetic_j,
                    on_cpu.block_kinetic_j,
                ),
                ("energy", on_gpu.energy_j, on_cpu.energy_j),
                ("size", on_gpu.size_j, on_cpu.size_j),
            ] {
                let off = (a - b).abs() / size;
                worst_energy = worst_energy.max(off);
                assert!(
                    off < MEASURE_TOL,
                    "{method:?}: strand {i}: {name} {a:.6e} on the GPU, {b:.6e} on the CPU \
                     ({off:.2e} of the strand's size)"
                );
            }
            if judged_by == KineticEnergy::BlockDiagonal {
                assert!(on_cpu.block_kinetic_j > 0.0, "strand {i}: no T_bd summed");
            }
            pairs.push((on_gpu, on_cpu));
        }
        println!(
            "{} (collider {with_field}): {touching} of {} strands on the sphere",
            method.label(),
            models.len()
        );
        println!(
            "{} (collider {with_field}): energies: GPU against twin {worst_energy:.2e} of the \
             strand's size",
            method.label()
        );
        // Rooted on the sphere, every strand touches it.
        assert_eq!(touching, if with_field { models.len() } else { 0 });
        for (name, off) in worst_relative(&pairs) {
            println!(
                "{} (collider {with_field}): {name}: GPU against twin {off:.2e}",
                method.label()
            );
            assert!(off < MEASURE_TOL, "{method:?}: {name} differs by {off:.2e}");
        }
    }
}

/// A straight strand (natural strains zero, at rest relative to its root)
/// rooted at the head's centre along x, the head spinning at ω about z:
/// every point moves at ω × r, so with m = ρS L and I = m L²/3 about the
/// root, T = ½ ω² I, p = ω × (m L/2) x, L_root = I ω, and nothing moves
/// relative to the root (strain kinetic, T_bd and the fastest relative
/// speed zero).
#[test]
fn the_gpu_measure_of_a_spinning_straight_strand_is_the_rigid_bodys() {
    let Some(ctx) = context() else { return };
    let settings = SimSettings::default();
    let params = helixhair_physics::StrandParams::default();
    let model = StrandModel::new(&params, settings.quadrature_points).expect("valid params");
    let batch_model = BatchModel::new(&model);
    let root = RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Y);
    let mut gpu = GpuEngine::new(
        ctx,
        &settings,
        std::slice::from_ref(&batch_model),
        &[root],
        None,
    )
    .expect("GPU engine");
    let omega = DVec3::new(0.0, 0.0, 2.0);
    let head = RigidMotion {
        angular_velocity_rad_per_s: omega,
        ..RigidMotion::at_rest(DVec3::ZERO, DMat3::IDENTITY)
    };
    let measured = gpu
        .measure(&head, KineticEnergy::BlockDiagonal)
        .expect("measure");
    let m = measured[0].strand(&head.carry(&root), settings.gravity_m_per_s2);
    let length = params.length_m;
    let mass = f64::from(batch_model.mass_per_length) * length;
    let inertia = mass * length * length / 3.0;
    let drag_per_mass = f64::from(batch_model.air_drag) / f64::from(batch_model.mass_per_length);
    let momentum = omega.cross(DVec3::X * mass * length / 2.0);
    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= KNOWN_TOL * scale;
    let close3 = |a: DVec3, b: DVec3, scale: f64| (a - b).abs().max_element() <= KNOWN_TOL * scale;
    println!("spinning strand: {m:?}");
    assert!(close(m.mass_kg, mass, mass), "mass {}", m.mass_kg);
    assert!(
        close(m.second_moment_kg_m2, inertia, inertia),
        "second moment"
    );
    let kinetic = 0.5 * omega.length_squared() * inertia;
    assert!(
        close(m.kinetic_j, kinetic, kinetic),
        "kinetic {}",
        m.kinetic_j
    );
    assert!(close3(m.momentum, momentum, momentum.length()), "momentum");
    assert!(
        close3(m.angular_momentum, omega * inertia, inertia * 2.0),
        "angular momentum"
    );
    let force = settings.gravity_m_per_s2 * mass - momentum * drag_per_mass;
    assert!(close3(m.external_force_n, force, force.length()), "force");
    let power = -2.0 * kinetic * drag_per_mass;
    assert!(close(m.external_power_w, power, power.abs()), "power");
    for (name, x) in [
        ("strain kinetic", m.strain_kinetic_j),
        ("block kinetic", m.block_kinetic_j),
    ] {
        assert!(x.abs() <= KNOWN_TOL * kinetic, "{name} {x:.3e}");
    }
    assert!(m.fastest_relative_m_per_s <= KNOWN_TOL * omega.length() * length);
    assert!(!m.in_contact);
}

/// A strand whose state holds a NaN or an infinity is found not finite
/// from its measure alone, and only that strand.
#[test]
fn the_gpu_measure_finds_a_state_that_is_not_finite() {
    let (settings, models, roots) = draping_strands(Method::Exact);
    for bad in [f32::NAN, f32::INFINITY] {
        for in_rates in [false, true] {
            let Some(ctx) = context() else { return };
            let mut gpu =
                GpuEngine::new(ctx, &settings, &models, &roots, None).expect("GPU engine");
            let (mut q, mut v) = gpu.read_state().expect("readback");
            let broken = 3;
            let element = gpu.elements_of(broken).start + 2;
            if in_rates {
                v[element][1] = bad;
            } else {
                q[element][1] = bad;
            }
            gpu.set_state(&q, &v);
            let measured = gpu
                .measure(
                    &RigidMotion::at_rest(DVec3::ZERO, DMat3::IDENTITY),
                    KineticEnergy::True,
                )
                .expect("measure");
            for (i, m) in measured.iter().enumerate() {
                assert_eq!(
                    m.state_is_finite(),
                    i != broken,
                    "strand {i} with {bad} in {}",
                    if in_rates { "q̇" } else { "q" }
                );
            }
        }
    }
}

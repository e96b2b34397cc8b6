//! Known answers of the hair–hair model (`helixhair_physics::volume`):
//! friction relaxes relative motion with time constant 1/μ and conserves
//! momentum; friction in a strand's step is air drag toward the grid
//! velocity; a block compressed above its rest density expands; the rest
//! pose feels no pressure; a shaken head with the model calms down without
//! guard events.

use crate::common;

use std::sync::Arc;

use common::shake_scene::ShakeThenStill;
use common::volume_scene::{assert_calms_down, kinetic_after_shake};
use glam::{DMat3, DVec3};
use helixhair_physics::volume::friction::HeadVelocity;
use helixhair_physics::volume::friction::implicit_velocity;
use helixhair_physics::volume::pair_points::points_per_element;
use helixhair_physics::volume::{InteractionSettings, RestDensity, SamplePoint, VolumeField};
use helixhair_physics::{HairSystem, Method, RigidMotion, SimSettings, Strand, StrandModel};

/// Points on a regular lattice filling a cube of edge `edge_m` about the
/// origin, `per_axis` to a side, each of `mass_kg`, all at `velocity`.
fn lattice(edge_m: f64, per_axis: usize, mass_kg: f64, velocity: DVec3) -> Vec<SamplePoint> {
    let step = edge_m / per_axis as f64;
    let mut out = Vec::new();
    for i in 0..per_axis {
        for j in 0..per_axis {
            for k in 0..per_axis {
                let p = (DVec3::new(i as f64, j as f64, k as f64) + 0.5) * step - 0.5 * edge_m;
                out.push(SamplePoint {
                    position_m: p,
                    velocity_m_per_s: velocity,
                    mass_kg,
                });
            }
        }
    }
    out
}

fn settings() -> InteractionSettings {
    InteractionSettings {
        enabled: true,
        ..InteractionSettings::default()
    }
}

/// Two populations of one block, masses 1 : 3, moving through each other
/// along x: the grid velocity is their mean, friction's implicit step
/// takes each to it by hμ/(1 + hμ), so the relative velocity falls by
/// (1 + hμ) per step (→ e^(−μt), time constant 1/μ) and the total momentum
/// stays.
#[test]
fn friction_damps_relative_motion_with_time_constant_one_over_mu() {
    let s = settings();
    let (h, mu) = (1.0 / 600.0, s.friction_per_s);
    let a = lattice(0.1, 10, 1e-6, DVec3::new(0.2, 0.0, 0.0));
    let b = lattice(0.1, 10, 3e-6, DVec3::new(-0.1, 0.0, 0.0));
    let rest = RestDensity::new(&[a.clone(), b.clone()].concat(), s.cell_m, 0.05).unwrap();
    let mut points = [a, b].concat();
    let momentum = |p: &[SamplePoint]| {
        p.iter()
            .map(|x| x.mass_kg * x.velocity_m_per_s)
            .sum::<DVec3>()
    };
    let start_momentum = momentum(&points);
    let mut field = VolumeField::default();
    let steps = (1.0 / (mu * h)).round() as i32; // t = 1/μ
    for _ in 0..steps {
        field.update(&rest, &[&points], &HeadVelocity::default(), false);
        let targets: Vec<DVec3> = points
            .iter()
            .map(|p| field.read(&rest, &s, p).relative_target_m_per_s)
            .collect();
        for (p, u) in points.iter_mut().zip(targets) {
            p.velocity_m_per_s = implicit_velocity(p.velocity_m_per_s, u, mu, h);
        }
    }
    let n = points.len() / 2;
    let relative = points[0].velocity_m_per_s.x - points[n].velocity_m_per_s.x;
    // Every pair alike: the block moves as one body of two populations.
    for i in 0..n {
        let r = points[i].velocity_m_per_s.x - points[n + i].velocity_m_per_s.x;
        assert!((r - relative).abs() < 1e-12, "pair {i}: {r} vs {relative}");
    }
    let discrete = 0.3 * (1.0 + h * mu).powi(-steps);
    assert!(
        (relative - discrete).abs() < 1e-12 * 0.3,
        "{relative} vs {discrete}"
    );
    // Backward Euler's e^(−1) within its first-order error hμ/2 (relative).
    let continuous = 0.3 * (-1.0f64).exp();
    assert!(
        ((relative - continuous) / continuous).abs() < h * mu,
        "relative velocity {relative} after 1/μ, e^-1 gives {continuous}"
    );
    let end = momentum(&points);
    assert!((end - start_momentum).length() < 1e-12 * start_momentum.length());
}

/// The friction in a strand's step is exactly air drag toward the grid
/// velocity: a strand on a head that translates (the head's velocity c the
/// same at every sample) pulled with rate μ toward a uniform u_rel
/// relative to the head steps like the same strand with drag
/// ν' = ν + μρS toward air of (ν v_air + μρS (u_rel + c))/ν'.
#[test]
fn friction_in_the_step_is_air_drag_toward_the_target() {
    let mut params = common::curl(8);
    params.air_drag = 2e-5;
    let model = Arc::new(StrandModel::new(&params, 4).unwrap());
    let (mu, u, air) = (7.0, DVec3::new(0.1, -0.2, 0.05), DVec3::new(0.3, 0.0, 0.0));
    let rho_s = model.mass_per_length;
    let mut dragged = params.clone();
    dragged.air_drag = params.air_drag + mu * rho_s;
    let air_dragged =
        |head: DVec3| (params.air_drag * air + mu * rho_s * (u + head)) / dragged.air_drag;
    let dragged_model = Arc::new(StrandModel::new(&dragged, 4).unwrap());
    let root = common::horizontal_root();
    let mut pulled = Strand::new(model.clone(), root, Method::Exact);
    let mut reference = Strand::new(dragged_model, root, Method::Exact);
    let points = model.elements() * points_per_element(4);
    pulled.set_volume_pull(mu, vec![u; points], vec![DVec3::ZERO; points]);
    let gravity = DVec3::new(0.0, -9.81, 0.0);
    for k in 0..60 {
        let head = common::side_to_side(k as f64 / 60.0);
        let motion = head.carry(&root);
        pulled.step(&motion, gravity, air, 1.0 / 60.0);
        let wind = air_dragged(head.velocity_m_per_s);
        reference.step(&motion, gravity, wind, 1.0 / 60.0);
    }
    let scale = reference.v().iter().map(|v| v.length()).fold(0.0, f64::max);
    assert!(scale > 0.1, "the strand moved: |v| = {scale}");
    assert!(common::max_diff(pulled.v(), reference.v()) < 1e-9 * scale);
    assert!(common::max_diff(pulled.q(), reference.q()) < 1e-9);
}

/// A block squeezed to 60% of its rest size (4.6 times its rest density)
/// is pushed outward everywhere and, moved by the push alone, spreads out
/// until its excess density has fallen.
#[test]
fn a_block_compressed_above_rest_density_expands() {
    let s = settings();
    let rest_points = lattice(0.1, 12, 1e-6, DVec3::ZERO);
    let rest = RestDensity::new(&rest_points, s.cell_m, 0.1).unwrap();
    let mut points: Vec<SamplePoint> = rest_points
        .iter()
        .map(|p| SamplePoint {
            position_m: 0.6 * p.position_m,
            ..*p
        })
        .collect();
    let rms = |p: &[SamplePoint]| {
        (p.iter().map(|x| x.position_m.length_squared()).sum::<f64>() / p.len() as f64).sqrt()
    };
    let mut field = VolumeField::default();
    field.update(&rest, &[&points], &HeadVelocity::default(), false);
    let start_excess = field.excess().iter().cloned().fold(0.0, f64::max);
    assert!(start_excess > 1.0, "squeezed: excess {start_excess}");
    let mut outward = 0.0;
    for p in &points {
        let push = field.read(&rest, &s, p).push_m_per_s2;
        // Within a cell of the centre the excess is flat up to how the
        // lattice falls on the grid; the outer layers must be pushed out.
        if p.position_m.abs().max_element() > s.cell_m {
            assert!(
                push.dot(p.position_m) > 0.0,
                "inward push {push} at {}",
                p.position_m
            );
        }
        outward += push.dot(p.position_m.normalize_or_zero());
    }
    assert!(outward > 0.0);
    let start_rms = rms(&points);
    let h = 1.0 / 60.0;
    for _ in 0..120 {
        field.update(&rest, &[&points], &HeadVelocity::default(), false);
        for p in &mut points {
            let r = field.read(&rest, &s, p);
            let v = implicit_velocity(
                p.velocity_m_per_s + h * r.push_m_per_s2,
                r.relative_target_m_per_s,
                s.friction_per_s,
                h,
            );
            p.velocity_m_per_s = v;
            p.position_m += h * v;
        }
    }
    field.update(&rest, &[&points], &HeadVelocity::default(), false);
    let end_excess = field.excess().iter().cloned().fold(0.0, f64::max);
    assert!(
        rms(&points) > 1.2 * start_rms,
        "rms {} from {start_rms}",
        rms(&points)
    );
    assert!(
        end_excess < 0.5 * start_excess,
        "excess {end_excess} from {start_excess}"
    );
}

fn head_system(interaction: bool, gravity: DVec3) -> HairSystem {
    let (params, roots) = common::volume_scene::small_head(12, 4);
    let mut sim = SimSettings {
        gravity_m_per_s2: gravity,
        ..SimSettings::default()
    };
    sim.interaction.enabled = interaction;
    let mut system = HairSystem::new(sim).unwrap();
    system.add_group(&params, &roots).unwrap();
    system
}

/// The rest pose splats to its own rest density: no node is in excess,
/// so with no gravity and a still (turned) head nothing moves, model on.
#[test]
fn rest_pose_feels_no_pressure() {
    let mut system = head_system(true, DVec3::ZERO);
    let head = RigidMotion::at_rest(DVec3::new(0.1, 1.6, -0.2), DMat3::from_rotation_y(0.7));
    for _ in 0..10 {
        system.step_frame(&head);
    }
    let volume = system.volume().expect("model on");
    assert!(volume.state().field().excess().iter().all(|e| *e == 0.0));
    for s in system.strands() {
        assert!(common::max_diff(s.q(), &s.model().natural) < 1e-12);
        assert!(s.v().iter().all(|v| v.length() < 1e-12));
    }
}

/// A head shaken for 4¼ periods and then held still: with the model the
/// hair's energy after the shake decays (each second below the last, and
/// faster than without the model, which it damps), and the guard never
/// steps in.
#[test]
fn energy_after_a_shake_decays_with_the_model_and_no_guard_events() {
    let gravity = DVec3::new(0.0, -9.81, 0.0);
    let head = ShakeThenStill::ordinary();
    let kinetic_after = |interaction: bool| {
        let mut system = head_system(interaction, gravity);
        let seconds = kinetic_after_shake(
            &mut system,
            &head,
            |s, head| s.step_frame(head),
            |s| s.energies().kinetic_j,
        );
        (seconds, system.guard_event_count())
    };
    let (with, events) = kinetic_after(true);
    let (without, _) = kinetic_after(false);
    assert_eq!(events, 0, "guard events with the model");
    assert_calms_down(&with, &without);
}

/// An 8-element curl (four quadrature nodes) in a random state (seed
/// `seed`) on a head caught mid-shake, so velocities and the head's turn
/// are all in play; with the generator, for more random numbers.
fn curl_mid_shake(seed: u64) -> (Strand, RigidMotion, common::Rng) {
    use helixhair_physics::HeadTrajectory;
    let model = Arc::new(StrandModel::new(&common::curl(8), 4).unwrap());
    let mut strand = Strand::new(model.clone(), common::horizontal_root(), Method::Exact);
    let mut rng = common::Rng::new(seed);
    let q: Vec<DVec3> = model.natural.iter().map(|k| *k + rng.vec3(4.0)).collect();
    let v: Vec<DVec3> = (0..q.len()).map(|_| rng.vec3(10.0)).collect();
    strand.set_state(&q, &v);
    (strand, common::shake().motion_at(0.3), rng)
}

/// The guard's start measure is the last frame's end measure, reused; the
/// model's new pull is exchanged into it (`volume::balance::PullWork`)
/// instead of measuring again. Known answer: the exchanged measure is the
/// measure taken afresh with the new pull, to round-off.
#[test]
fn exchanging_the_pull_in_a_cached_measure_equals_measuring_again() {
    use helixhair_physics::frame_balance::MeasureInputs;
    use helixhair_physics::volume::reference::strand_points;
    let (mut strand, head, mut rng) = curl_mid_shake(9);
    let model = strand.model().clone();
    let carried = head.carry(strand.root());
    let inputs = MeasureInputs {
        gravity_m_per_s2: DVec3::new(0.0, -9.81, 0.0),
        air_velocity_m_per_s: DVec3::ZERO,
        contact: None,
    };
    let points = model.elements() * points_per_element(4);
    let pull = |rng: &mut common::Rng| {
        let target = (0..points).map(|_| rng.vec3(0.5)).collect();
        let push = (0..points).map(|_| rng.vec3(5.0)).collect();
        (5.0 + 10.0 * rng.next(), target, push)
    };
    let (mu, target, push) = pull(&mut rng);
    strand.set_volume_pull(mu, target, push);
    let end = strand.measure(&carried, &inputs);
    strand.set_cached_measure(Some(end));
    let (mut samples, mut points) = (Vec::new(), Vec::new());
    let kin = strand.kinematics(&carried);
    strand_points(&strand, &kin, &head, &mut samples, &mut points);
    strand.exchange_volume_pull(pull(&mut rng), &samples, &head);
    let exchanged = strand.cached_measure().expect("kept");
    let fresh = strand.measure(&carried, &inputs);
    let size = fresh.external_force_n.length() + fresh.external_power_w.abs();
    assert!(size > 0.0);
    assert!((exchanged.external_force_n - fresh.external_force_n).length() < 1e-12 * size);
    assert!((exchanged.external_torque_n_m - fresh.external_torque_n_m).length() < 1e-12 * size);
    assert!((exchanged.external_power_w - fresh.external_power_w).abs() < 1e-12 * size);
    assert_ne!(exchanged.external_power_w, end.external_power_w);
    assert_eq!(exchanged.energy_j, fresh.energy_j);
}

/// The model's points (one per pair of quadrature nodes,
/// `volume::pair_points`) carry the strand's mass, momentum and centre of
/// mass: Σ m_p = ρS L, Σ m_p v_p = Σ ρS w_j ℓ v_j and Σ m_p x_p / Σ m_p
/// the quadrature's centre of mass, carried into head coordinates; at
/// four nodes per element there are two points per element. A curl in a
/// random state on a head caught mid-shake, so velocities and the head's
/// turn are all in play.
#[test]
fn the_points_carry_the_strands_mass_momentum_and_centre_of_mass() {
    use helixhair_physics::volume::reference::strand_points;
    let (strand, head, _) = curl_mid_shake(21);
    let model = strand.model().clone();
    let carried = head.carry(strand.root());
    let kin = strand.kinematics(&carried);
    let (mut samples, mut points) = (Vec::new(), Vec::new());
    strand_points(&strand, &kin, &head, &mut samples, &mut points);
    assert_eq!(points.len(), 2 * model.elements());
    assert_eq!(points_per_element(4), 2);
    let rho_s = model.mass_per_length;
    let length_m: f64 = model.lengths_m.iter().sum();
    let mass: f64 = points.iter().map(|p| p.mass_kg).sum();
    assert!(
        (mass - rho_s * length_m).abs() < 1e-13 * mass,
        "mass {mass}"
    );
    let momentum: DVec3 = points.iter().map(|p| p.mass_kg * p.velocity_m_per_s).sum();
    let expected: DVec3 = kin
        .samples
        .iter()
        .map(|s| rho_s * s.weight_m * s.velocity_m_per_s)
        .sum();
    assert!(expected.length() / mass > 0.1, "the strand moves");
    assert!((momentum - expected).length() < 1e-12 * expected.length());
    let centre: DVec3 = points
        .iter()
        .map(|p| p.mass_kg * p.position_m)
        .sum::<DVec3>()
        / mass;
    let world: DVec3 = kin
        .samples
        .iter()
        .map(|s| s.weight_m * s.position_m)
        .sum::<DVec3>()
        / length_m;
    let body_from_world = head.world_from_body.transpose();
    let expected = body_from_world * (carried.position_m + world - head.position_m);
    assert!(
        (centre - expected).length() < 1e-12,
        "{centre} against {expected}"
    );
}

/// The cell search on a 3 × 3 × 3-node grid of 1 m cells from the origin:
/// known cells, places in them and weights, the far face in the last
/// cell, and nothing outside or at NaN.
#[test]
fn a_point_finds_its_cell_and_weights() {
    let grid = helixhair_physics::volume::Grid {
        origin_m: DVec3::ZERO,
        cell_m: 1.0,
        dims: [3, 3, 3],
    };
    let cell = grid.locate(DVec3::new(1.25, 0.5, 1.75)).unwrap();
    // Node (1, 0, 1) is 1 + 0·3 + 1·9.
    assert_eq!(cell.first, 10);
    assert_eq!(cell.frac, [0.25, 0.5, 0.75]);
    let weights = cell.weights();
    // Corner 0 is (1 − 0.25)(1 − 0.5)(1 − 0.75); corner 7 is 0.25·0.5·0.75.
    assert_eq!(weights[0], 0.75 * 0.5 * 0.25);
    assert_eq!(weights[7], 0.25 * 0.5 * 0.75);
    assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-15);
    let far = grid.locate(DVec3::splat(2.0)).unwrap();
    assert_eq!((far.first, far.frac), (13, [1.0; 3]));
    assert!(grid.locate(DVec3::new(-0.1, 1.0, 1.0)).is_none());
    assert!(grid.locate(DVec3::new(1.0, 2.1, 1.0)).is_none());
    assert!(grid.locate(DVec3::new(1.0, f64::NAN, 1.0)).is_none());
}

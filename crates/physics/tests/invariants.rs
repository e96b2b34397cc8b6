//! Exact invariants (docs/physics.md section 7): a natural helix at rest stays
//! at rest; rotating the root frame and gravity together leaves q
//! unchanged; serial and parallel stepping agree bit for bit.

use crate::common;

use common::*;
use glam::{DMat3, DVec3};
use helixhair_physics::{HairSystem, Method, RigidMotion, RootPose, SimSettings};

/// A strand at its natural shape feels no force: q must not move at all
/// beyond round-off of a zero right-hand side.
const REST_DRIFT_TOL: f64 = 1e-12;
/// Rotating the whole problem changes only the order of round-off.
const ROTATION_TOL_REL: f64 = 1e-9;

#[test]
fn natural_helix_without_gravity_stays_at_rest_for_ten_thousand_steps() {
    let mut rng = Rng::new(7);
    for method in [Method::Dense, Method::BlockDiagonal] {
        for _ in 0..3 {
            let mut p = params(0.2, 8);
            p.natural_shape = helix_shape();
            p.internal_friction = 2e-10;
            p.air_drag = 1e-5;
            let mut s = strand(&p, method);
            let root = RigidMotion::at_rest(rng.vec3(0.2), rng.rotation());
            for _ in 0..10_000 {
                s.step(&root, DVec3::ZERO, DVec3::ZERO, 1.0 / 60.0);
            }
            let drift = max_diff(s.q(), &p.natural_shape.strains(8));
            assert!(drift < REST_DRIFT_TOL, "{method:?}: drift {drift}");
        }
    }
}

#[test]
fn rotating_root_and_gravity_together_leaves_q_unchanged() {
    let mut rng = Rng::new(11);
    for method in [Method::Dense, Method::BlockDiagonal] {
        let mut p = params(0.15, 7);
        p.natural_shape = helix_shape();
        p.internal_friction = 2e-10;
        p.air_drag = 1e-5;
        let gravity = DVec3::new(0.0, -9.81, 0.0);
        let root = rng.rotation();
        let turn = rng.rotation();
        let run = |frame: DMat3, g: DVec3| {
            let mut s = strand(&p, method);
            let motion = RigidMotion::at_rest(DVec3::ZERO, frame);
            for _ in 0..300 {
                s.step(&motion, g, DVec3::ZERO, 1.0 / 60.0);
            }
            s.q().to_vec()
        };
        let a = run(root, gravity);
        let b = run(turn * root, turn * gravity);
        let scale = a.iter().map(|q| q.abs().max_element()).fold(0.0, f64::max);
        assert!(
            max_diff(&a, &b) < ROTATION_TOL_REL * scale,
            "{method:?}: {}",
            max_diff(&a, &b)
        );
        // And the strand did move: gravity bent it away from its rest curl.
        assert!(max_diff(&a, &p.natural_shape.strains(7)) > 1e-2 * scale);
    }
}

#[test]
fn serial_and_parallel_stepping_are_bit_identical() {
    let head = helixhair_physics::Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    let build = |parallel: bool| {
        let settings = SimSettings {
            method: Method::BlockDiagonal,
            ..SimSettings::default()
        };
        let mut system = HairSystem::new(settings).expect("valid settings");
        let roots: Vec<RootPose> = (0..16)
            .map(|i| {
                let a = i as f64 * 0.4;
                let dir = DVec3::new(a.cos(), 0.5, a.sin());
                RootPose::from_direction(dir * 0.1, dir, DVec3::Y)
            })
            .collect();
        let p = helixhair_physics::StrandParams {
            natural_shape: helix_shape(),
            ..helixhair_physics::StrandParams::default()
        };
        system.add_group(&p, &roots).expect("valid params");
        system.set_parallel(parallel);
        for _ in 0..30 {
            system.step_frame(&head);
        }
        system
    };
    let (serial, parallel) = (build(false), build(true));
    assert!(
        serial.is_finite() && parallel.is_finite(),
        "non-finite states"
    );
    for (a, b) in serial.strands().iter().zip(parallel.strands()) {
        assert_eq!(a.q(), b.q());
        assert_eq!(a.v(), b.v());
    }
}

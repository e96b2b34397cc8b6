//! Where the methods fail, pinned so that a change is noticed (docs/physics.md
//! section 6). Each test opens with what goes wrong. The tests run the
//! solvers raw (a `HairSystem`'s guard switched off); `guards.rs` pins how
//! the guard catches each of these failures.

use crate::common;

use common::*;
use glam::{DMat3, DVec3};
use helixhair_physics::{HairSystem, Method, Oscillation, RootPose, SimSettings, StepScheme};

#[test]
fn own_element_blocks_blow_up_on_a_curly_strand_at_any_usable_step() {
    // What went wrong: the "own element" reading of the seed gives each
    // element only its own inertia while gravity and inertial forces still
    // gather the whole subtree; on a 3D curl (twist coupled to bending) the
    // explicit part then grows by a large factor every step, whatever h.
    // This pins the failure (blow-up within 20 steps for h from 1 to 10 ms)
    // so that a change to it is noticed; on a straight planar elastica
    // at α = 1 the same variant settles; it does not at α ≥ 5.
    let (p, root) = curl_on_oblique_root();
    for h in [0.001, 0.002, 0.005, 0.01] {
        let mut s = strand(&p, Method::BlockDiagonalOwnElement);
        let blew_up = (0..20).any(|_| {
            s.step(&root, DVec3::new(0.0, -9.81, 0.0), DVec3::ZERO, h);
            !s.is_finite()
        });
        assert!(blew_up, "h = {h}: own-element blocks stayed finite");
    }
}

#[test]
fn block_diagonal_without_friction_blows_up_under_a_head_shake() {
    // What goes wrong: with zero internal friction and a head shaking
    // 0.5 rad at 1.5 Hz, a curly 20 cm strand at 60 Hz goes non-finite
    // within a second under Block-diagonal with the velocity terms frozen
    // at the step's start (the whole system's, `VelocityExplicit`); with
    // the default friction it stays bounded, and Dense stays bounded
    // either way. With its own Lagrangian's terms taken implicitly (the
    // default scheme, docs/solvers.md) Block-diagonal stays finite
    // without friction too: explicit velocity terms were the cause.
    let head = Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    let run = |method: Method, scheme: StepScheme, friction: f64| -> bool {
        let settings = SimSettings {
            method,
            scheme,
            ..SimSettings::default()
        };
        let mut system = HairSystem::new(settings).expect("valid settings");
        system.set_guard(None);
        let dir = DVec3::new(1.0, 0.5, 0.0);
        let mut p = params(0.2, 10);
        p.natural_shape = helix_shape();
        p.internal_friction = friction;
        system
            .add_group(&p, &[RootPose::from_direction(dir * 0.1, dir, DVec3::Y)])
            .expect("valid params");
        (0..60).all(|_| {
            system.step_frame(&head);
            system.is_finite()
        })
    };
    let (explicit, implicit) = (StepScheme::VelocityExplicit, StepScheme::default());
    assert!(
        !run(Method::BlockDiagonal, explicit, 0.0),
        "block-diagonal stayed finite without friction, velocity terms explicit"
    );
    assert!(
        run(Method::BlockDiagonal, explicit, 2e-10),
        "block-diagonal failed with default friction, velocity terms explicit"
    );
    assert!(
        run(Method::BlockDiagonal, implicit, 0.0),
        "block-diagonal failed without friction, its own velocity terms implicit"
    );
    assert!(
        run(Method::Dense, implicit, 0.0),
        "dense failed without friction"
    );
}

#[test]
fn block_diagonal_blows_up_on_a_hanging_curl_at_sixty_hertz_with_the_whole_systems_velocity_terms()
{
    // What went wrong: a 20 cm curl (radius 2 cm, step 5 cm) hanging from
    // a still head, default friction and drag, went non-finite within two
    // seconds at h = 1/60 s under Block-diagonal from N = 8 (step 37), and
    // sooner as N grew (N = 10: step 19; N = 20: step 13); N = 5 stayed
    // finite. The truncated mass met the whole system's velocity terms,
    // which belong with the whole M, and the step pumped energy in; ten
    // substeps (h = 1/600 s) kept it finite. That old step is still the
    // velocity-explicit scheme, pinned here. With the velocity terms of
    // Block-diagonal's own Lagrangian (the default scheme,
    // `batch/block_terms.rs`) the same curl stays finite at every N:
    // its energy T_bd + V can no longer grow (tests/block_velocity_terms.rs).
    // Dense and Exact are finite at 60 Hz for N = 10 and 30.
    let run_with = |method: Method, n: usize, h: f64, scheme: StepScheme| -> bool {
        let mut p = params(0.2, n);
        p.natural_shape = helixhair_physics::NaturalShape::Helix {
            radius_m: 0.02,
            step_m: 0.05,
        };
        p.internal_friction = 2e-10;
        p.air_drag = 1e-5;
        let mut s = strand(&p, method);
        s.set_scheme(scheme);
        let root = at_rest(DMat3::IDENTITY);
        (0..(2.0 / h).round() as usize).all(|_| {
            s.step(&root, DVec3::new(0.0, -9.81, 0.0), DVec3::ZERO, h);
            s.is_finite()
        })
    };
    let run = |method, n, h| run_with(method, n, h, StepScheme::VelocityExplicit);
    assert!(
        run(Method::BlockDiagonal, 5, 1.0 / 60.0),
        "block-diagonal failed at N = 5"
    );
    for n in [8, 10, 20] {
        assert!(
            !run(Method::BlockDiagonal, n, 1.0 / 60.0),
            "block-diagonal stayed finite at N = {n}"
        );
        if n >= 10 {
            assert!(
                run(Method::BlockDiagonal, n, 1.0 / 600.0),
                "block-diagonal failed at N = {n}, h = 1/600 s"
            );
        }
    }
    for n in [5, 8, 10, 20] {
        assert!(
            run_with(Method::BlockDiagonal, n, 1.0 / 60.0, StepScheme::default()),
            "block-diagonal with its own velocity terms failed at N = {n}"
        );
    }
    for n in [10, 30] {
        assert!(run(Method::Dense, n, 1.0 / 60.0), "dense failed at N = {n}");
        assert!(run(Method::Exact, n, 1.0 / 60.0), "exact failed at N = {n}");
    }
}

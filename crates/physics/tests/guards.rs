//! The guard (`helixhair_physics::guard`) against the failures pinned in
//! `failure_modes.rs`: each failure is caught, recovered from and
//! reported, and a healthy run is left alone.

use crate::common;

use common::*;
use glam::DVec3;
use helixhair_physics::guard::speed_bound_m_per_s;
use helixhair_physics::{
    Guard, GuardAction, GuardCause, HairSystem, Method, Oscillation, RootPose, SimSettings,
    StepScheme, StrandParams,
};

fn system(method: Method, p: &StrandParams, guard: Option<Guard>) -> HairSystem {
    system_with(method, StepScheme::default(), p, guard)
}

fn system_with(
    method: Method,
    scheme: StepScheme,
    p: &StrandParams,
    guard: Option<Guard>,
) -> HairSystem {
    let settings = SimSettings {
        method,
        scheme,
        ..SimSettings::default()
    };
    let mut system = HairSystem::new(settings).expect("valid settings");
    system.set_guard(guard);
    system
        .add_group(p, &[horizontal_root()])
        .expect("valid params");
    system
}

/// Runs `frames` frames; returns whether every frame ended finite, and
/// every guard event.
fn run(
    system: &mut HairSystem,
    head: &dyn helixhair_physics::HeadTrajectory,
    frames: usize,
) -> (bool, Vec<helixhair_physics::GuardEvent>) {
    let mut events = Vec::new();
    let mut finite = true;
    for _ in 0..frames {
        system.step_frame(head);
        finite &= system.is_finite();
        events.extend_from_slice(system.last_guard_events());
    }
    (finite, events)
}

#[test]
fn the_speed_bound_bounds_every_point_relative_to_the_root() {
    // Σ ℓ_Q |q̇_Q| (L − s_Q) ≥ |ṙ(s)| relative to the root frame, for any
    // state: check it on random curled states with random rates.
    let mut rng = Rng::new(7);
    let p = hanging_curl(8);
    let m = model(&p, 4);
    let root = at_rest(glam::DMat3::IDENTITY);
    for _ in 0..50 {
        let q = random_strains(&mut rng, 8, 60.0);
        let v = random_strains(&mut rng, 8, 30.0);
        let bound = speed_bound_m_per_s(&m, &v);
        let kin = kinematics(&m, &q, &v, &root);
        let fastest = kin
            .samples
            .iter()
            .map(|s| s.velocity_m_per_s.length())
            .fold(0.0, f64::max);
        assert!(fastest <= bound * (1.0 + 1e-12), "{fastest} > {bound}");
    }
}

#[test]
fn a_block_diagonal_blow_up_on_a_hanging_curl_is_handed_to_exact() {
    // Block-diagonal with the whole system's velocity terms (the
    // velocity-explicit scheme): its own Lagrangian's terms, the default,
    // no longer blow up here (failure_modes.rs).
    let p = hanging_curl(10);
    let root = at_rest(glam::DMat3::IDENTITY);
    let old = StepScheme::VelocityExplicit;
    let mut raw = system_with(Method::BlockDiagonal, old, &p, None);
    assert!(
        !run(&mut raw, &root, 120).0,
        "the raw solver should blow up"
    );
    let guard = Guard::default();
    let mut guarded = system_with(Method::BlockDiagonal, old, &p, Some(guard));
    let mut events = Vec::new();
    for _ in 0..240 {
        guarded.step_frame(&root);
        let s = &guarded.strands()[0];
        assert!(s.is_finite(), "the guarded run went non-finite");
        assert!(speed_bound_m_per_s(s.model(), s.v()) <= guard.speed_limit_m_per_s);
        events.extend_from_slice(guarded.last_guard_events());
    }
    assert!(!events.is_empty(), "the guard never stepped in");
    assert!(
        matches!(
            events[0].action,
            GuardAction::Retried {
                method: Method::Exact,
                substeps: 1
            }
        ),
        "the first retry should hand the strand to Exact: {}",
        events[0]
    );
    assert!(events.iter().all(|e| e.strand == 0
        && matches!(
            e.action,
            GuardAction::Reset
                | GuardAction::Retried {
                    method: Method::Exact,
                    ..
                }
        )));
    assert_eq!(guarded.guard_event_count(), events.len());
}

#[test]
fn a_frame_no_retry_can_pass_resets_the_strand_at_rest() {
    // A guard whose speed limit is 1 mm/s cannot be satisfied by a strand
    // falling from rest: every retry fails and the strand is reset.
    let p = hanging_curl(6);
    let root = at_rest(glam::DMat3::IDENTITY);
    let strict = Guard {
        speed_limit_m_per_s: 1e-3,
        max_substeps: 4,
        ..Guard::default()
    };
    let mut guarded = system(Method::Exact, &p, Some(strict));
    let (finite, events) = run(&mut guarded, &root, 2);
    assert!(finite);
    assert_eq!(events.len(), 2, "every frame should trip the guard");
    assert!(events.iter().all(|e| e.action == GuardAction::Reset));
    // Reset to the start-of-frame shape (the natural one), at rest.
    let s = &guarded.strands()[0];
    assert_eq!(s.q(), s.model().natural.as_slice());
    assert!(s.v().iter().all(|v| *v == DVec3::ZERO));
}

#[test]
fn a_strand_that_keeps_failing_is_pinned_once_not_reset_every_frame() {
    // The window's old failure: a strand reset every frame, snapping back
    // and falling again, thousands of interventions. Now the third reset
    // within a second pins it at rest, with one event, and it stays there.
    let p = hanging_curl(6);
    let root = at_rest(glam::DMat3::IDENTITY);
    let strict = Guard {
        speed_limit_m_per_s: 1e-3,
        max_substeps: 4,
        ..Guard::default()
    };
    let mut guarded = system(Method::Exact, &p, Some(strict));
    let (finite, events) = run(&mut guarded, &root, 120);
    assert!(finite);
    let actions: Vec<GuardAction> = events.iter().map(|e| e.action).collect();
    assert_eq!(
        actions,
        [GuardAction::Reset, GuardAction::Reset, GuardAction::Pinned]
    );
    let s = &guarded.strands()[0];
    assert_eq!(s.q(), s.model().natural.as_slice());
    assert!(s.v().iter().all(|v| *v == DVec3::ZERO));
    assert!(events[2].to_string().contains("pinned"));
}

/// A real blow-up of Block-diagonal (the whole system's velocity terms,
/// frozen at the step's start, no friction: tests/failure_modes.rs) is
/// caught although the guard judges Block-diagonal by its own energy.
#[test]
fn a_frictionless_head_shake_is_caught_before_it_shows() {
    let head = Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    let dir = DVec3::new(1.0, 0.5, 0.0);
    let mut p = params(0.2, 10);
    p.natural_shape = helix_shape();
    let settings = SimSettings {
        method: Method::BlockDiagonal,
        scheme: StepScheme::VelocityExplicit,
        ..SimSettings::default()
    };
    let mut system = HairSystem::new(settings).expect("valid settings");
    system
        .add_group(&p, &[RootPose::from_direction(dir * 0.1, dir, DVec3::Y)])
        .expect("valid params");
    let (finite, events) = run(&mut system, &head, 60);
    assert!(finite);
    assert!(!events.is_empty(), "the guard never stepped in");
    assert!(events.iter().all(|e| matches!(
        e.cause,
        GuardCause::NotFinite | GuardCause::TooFast { .. } | GuardCause::EnergyGain { .. }
    )));
}

#[test]
fn a_healthy_run_is_left_alone_and_matches_the_unguarded_one() {
    // Dense on the hanging curl at 60 Hz is finite and slow: the guard
    // must not step in, and must not change a single bit.
    let p = hanging_curl(10);
    let root = at_rest(glam::DMat3::IDENTITY);
    let mut raw = system(Method::Dense, &p, None);
    let mut guarded = system(Method::Dense, &p, Some(Guard::default()));
    let (_, raw_events) = run(&mut raw, &root, 120);
    let (finite, events) = run(&mut guarded, &root, 120);
    assert!(finite && raw_events.is_empty() && events.is_empty());
    assert_eq!(raw.strands()[0].q(), guarded.strands()[0].q());
    assert_eq!(raw.strands()[0].v(), guarded.strands()[0].v());
}

#[test]
fn a_brush_push_is_work_the_guard_counts_not_energy_from_nowhere() {
    // A strong push on every sample (the external hook a brush drives:
    // twice gravity, sideways) puts real energy into the strand. The
    // guard's balance counts the push's work (the measure counts the step hook's force),
    // so it must not mistake that energy for a blow-up.
    let p = hanging_curl(10);
    let root = at_rest(glam::DMat3::IDENTITY);
    let mut guarded = system(Method::Exact, &p, Some(Guard::default()));
    let samples = guarded.strands()[0].kinematics(&root).samples.len();
    let rho_s = p.mass_per_length();
    let push = vec![DVec3::new(0.0, 0.0, 2.0 * 9.81 * rho_s); samples];
    guarded.strands_mut()[0].set_external_forces(&push);
    let tip_before = *guarded.strands()[0]
        .boundary_points_world(&root)
        .last()
        .unwrap();
    let (finite, events) = run(&mut guarded, &root, 60);
    let tip_after = *guarded.strands()[0]
        .boundary_points_world(&root)
        .last()
        .unwrap();
    assert!(finite);
    assert!(events.is_empty(), "the push's work was counted: {events:?}");
    // The push really moved the hair (the check above is not vacuous).
    assert!(
        tip_after.z - tip_before.z > 0.02,
        "the tip moved {} m along the push",
        tip_after.z - tip_before.z
    );
}

/// The rule of `frame_balance::KineticEnergy`: Block-diagonal with its own
/// velocity terms conserves T_bd + V, not T + V. From rest, its smaller
/// inertia turns a potential drop into more true kinetic energy than the
/// drop: judged by T + V the healthy first frame of a strand released
/// horizontally failed (every strand of the example styles did); judged
/// by its own energy it passes.
#[test]
fn block_diagonal_is_judged_by_the_energy_it_conserves() {
    use helixhair_physics::frame_balance::{KineticEnergy, MeasureInputs, SteppedFrame};
    let kinetic = KineticEnergy::of(Method::BlockDiagonal, StepScheme::default());
    assert_eq!(kinetic, KineticEnergy::BlockDiagonal);
    assert_eq!(
        KineticEnergy::of(Method::Exact, StepScheme::default()),
        KineticEnergy::True
    );
    let gravity = DVec3::new(0.0, -9.81, 0.0);
    let inputs = MeasureInputs {
        gravity_m_per_s2: gravity,
        air_velocity_m_per_s: DVec3::ZERO,
        contact: None,
    };
    let root = at_rest(glam::DMat3::IDENTITY);
    let dt_secs = 1.0 / 60.0;
    let frame = SteppedFrame {
        dt_secs,
        substeps: 1,
    };
    let guard = Guard::default();
    let mut s = strand(&params(0.3, 12), Method::BlockDiagonal);
    let start = s.measure(&root, &inputs);
    s.step(&root, gravity, DVec3::ZERO, dt_secs);
    let end = s.measure(&root, &inputs);
    let by_true = guard.check(s.q(), s.v(), &start, &end, frame);
    let by_own = guard.check(
        s.q(),
        s.v(),
        &start.judged_by(kinetic),
        &end.judged_by(kinetic),
        frame,
    );
    println!("judged by T + V: {by_true:?}; by T_bd + V: {by_own:?}");
    assert!(
        matches!(by_true, Some(GuardCause::EnergyGain { .. })),
        "T + V should grow"
    );
    assert_eq!(by_own, None);
}

/// Issue 33's strand: 9.8 cm straight, released horizontally, still
/// head, Block-diagonal at 60 Hz with one substep for 900 frames: with its
/// own velocity terms and judged by its own energy, the guard never steps
/// in (judged by T + V it re-stepped 10 frames with Exact).
#[test]
fn block_diagonal_holds_a_released_strand_without_the_guard() {
    let mut guarded = system(
        Method::BlockDiagonal,
        &params(0.098, 10),
        Some(Guard::default()),
    );
    let (finite, events) = run(&mut guarded, &at_rest(glam::DMat3::IDENTITY), 900);
    assert!(finite);
    assert!(events.is_empty(), "the guard stepped in: {}", events[0]);
}

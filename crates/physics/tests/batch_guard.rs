//! The guard on the f32 batch path (`batch::guard`): the Block-diagonal
//! blow-up of `guards.rs` and its energy gain are caught, reset and
//! reported by strand index, a strand that keeps failing is pinned once,
//! and a healthy run is bit-identical with and without the guard.

mod common;

use common::*;
use glam::DVec3;
use helixhair_physics::batch::BatchSystem;
use helixhair_physics::guard::speed_bound_m_per_s;
use helixhair_physics::{Guard, Method, Oscillation, RootPose, SimSettings, StrandParams};

/// Straight strands growing sideways from the origin, in a few directions.
fn straight_roots(count: usize) -> Vec<RootPose> {
    (0..count)
        .map(|i| {
            let a = i as f64;
            RootPose::from_direction(DVec3::ZERO, DVec3::new(a.cos(), 0.2, a.sin()), DVec3::Y)
        })
        .collect()
}

/// Three straight strands (indices 0..3), then two hanging curls (3..5),
/// stepped with `method` at 60 Hz, one substep.
fn mixed(method: Method, guard: Option<Guard>) -> BatchSystem {
    let settings = SimSettings {
        method,
        ..SimSettings::default()
    };
    let mut system = BatchSystem::new(settings).expect("valid settings");
    system.set_guard(guard);
    system
        .add_group(&StrandParams::default(), &straight_roots(3))
        .expect("valid params");
    system
        .add_group(&hanging_curl(10), &[horizontal_root(), horizontal_root()])
        .expect("valid params");
    system
}

/// A guard whose 1 mm/s speed limit fails every strand falling from rest.
fn strict() -> Guard {
    Guard {
        speed_limit_m_per_s: 1e-3,
        ..Guard::default()
    }
}

fn states(system: &BatchSystem, strands: std::ops::Range<usize>) -> Vec<(Vec<DVec3>, Vec<DVec3>)> {
    strands.map(|i| (system.q(i), system.v(i))).collect()
}

#[test]
fn a_block_diagonal_blow_up_on_a_hanging_curl_is_reset_and_reported() {
    let still = at_rest(glam::DMat3::IDENTITY);
    let mut raw = mixed(Method::BlockDiagonal, None);
    let blew_up = (0..120).any(|_| {
        raw.step_frame(&still);
        !raw.is_finite()
    });
    assert!(blew_up, "the raw f32 Block-diagonal should blow up");
    let guard = Guard::default();
    let mut guarded = mixed(Method::BlockDiagonal, Some(guard));
    let curl_model = model(&hanging_curl(10), 4);
    let mut resets = Vec::new();
    let mut pins = Vec::new();
    for _ in 0..240 {
        guarded.step_frame(&still);
        assert!(guarded.is_finite(), "the guarded run went non-finite");
        for i in 3..5 {
            let speed = speed_bound_m_per_s(&curl_model, &guarded.v(i));
            assert!(
                speed <= guard.speed_limit_m_per_s,
                "strand {i}: {speed} m/s"
            );
        }
        resets.extend_from_slice(guarded.last_guard_resets());
        pins.extend_from_slice(guarded.last_guard_pins());
    }
    println!(
        "{} resets, first frames: {:?}",
        resets.len(),
        &resets[..resets.len().min(8)]
    );
    assert!(!resets.is_empty(), "the guard never stepped in");
    assert_eq!(guarded.guard_reset_count(), resets.len() + pins.len());
    // Every strand that kept failing was pinned once, and is at its natural
    // shape at rest.
    pins.sort_unstable();
    let before = pins.len();
    pins.dedup();
    assert_eq!(pins.len(), before, "a strand was pinned twice: {pins:?}");
    for &i in &pins {
        assert!(
            guarded.v(i).iter().all(|v| *v == DVec3::ZERO),
            "strand {i} moves"
        );
    }
}

#[test]
fn a_reset_strand_is_at_its_natural_shape_at_rest() {
    let mut system = mixed(Method::Exact, Some(strict()));
    system.step_frame(&at_rest(glam::DMat3::IDENTITY));
    assert_eq!(system.last_guard_resets(), &[0, 1, 2, 3, 4]);
    let natural = model(&hanging_curl(10), 4).natural;
    let natural_f32: Vec<DVec3> = natural.iter().map(|k| k.as_vec3().as_dvec3()).collect();
    assert_eq!(system.q(4), natural_f32);
    assert!(system.v(4).iter().all(|v| *v == DVec3::ZERO));
}

/// A strand that rests away from its natural shape (an imported sag-free
/// strand rests in its groomed shape, `BatchSystem::set_rest_pose`) is
/// reset there, at rest, not to its natural shape, from which it would
/// swing back into its pose.
#[test]
fn a_reset_strand_is_at_its_rest_pose_at_rest() {
    let mut system = mixed(Method::Exact, Some(strict()));
    let natural = model(&hanging_curl(10), 4).natural;
    let pose: Vec<DVec3> = natural
        .iter()
        .enumerate()
        .map(|(e, k)| *k + DVec3::new(1.0, -2.0, 3.0) * (e as f64 + 1.0))
        .collect();
    system.set_rest_pose(4, &pose);
    system.step_frame(&at_rest(glam::DMat3::IDENTITY));
    assert_eq!(system.last_guard_resets(), &[0, 1, 2, 3, 4]);
    let pose_f32: Vec<DVec3> = pose.iter().map(|k| k.as_vec3().as_dvec3()).collect();
    let natural_f32: Vec<DVec3> = natural.iter().map(|k| k.as_vec3().as_dvec3()).collect();
    assert_eq!(system.q(4), pose_f32);
    assert!(system.v(4).iter().all(|v| *v == DVec3::ZERO));
    // Its batch-mate, told nothing, is at its natural shape.
    assert_eq!(system.q(3), natural_f32);
}

#[test]
fn a_healthy_run_is_left_alone_and_matches_the_unguarded_one() {
    // Exact on the hanging curl and straight strands under a head shake at
    // 60 Hz is finite and slow: the guard must not step in, nor change a bit.
    let shake = Oscillation {
        axis: DVec3::new(0.2, 1.0, 0.1),
        amplitude_rad: 0.3,
        frequency_hz: 1.0,
    };
    let mut guarded = mixed(Method::Exact, Some(Guard::default()));
    let mut unguarded = mixed(Method::Exact, None);
    assert!(unguarded.guard().is_none());
    for _ in 0..120 {
        guarded.step_frame(&shake);
        unguarded.step_frame(&shake);
        assert!(guarded.last_guard_resets().is_empty());
    }
    assert_eq!(guarded.guard_reset_count(), 0);
    assert_eq!(states(&guarded, 0..5), states(&unguarded, 0..5));
}

#[test]
fn a_guard_switched_back_on_judges_the_frame_it_sees_not_one_it_missed() {
    // The same healthy shake as above, its guard off for 45 frames in the
    // middle: switched back on, it judges the frames it sees, from the
    // state it starts from, and steps in no more than when it was on
    // throughout (nothing).
    let shake = Oscillation {
        axis: DVec3::new(0.2, 1.0, 0.1),
        amplitude_rad: 0.3,
        frequency_hz: 1.0,
    };
    let mut system = mixed(Method::Exact, Some(Guard::default()));
    for frame in 0..150 {
        match frame {
            30 => system.set_guard(None),
            75 => system.set_guard(Some(Guard::default())),
            _ => {}
        }
        system.step_frame(&shake);
        assert!(
            system.last_guard_events().is_empty(),
            "frame {frame}: {:?}",
            system.last_guard_events()
        );
    }
    assert_eq!(system.guard_reset_count(), 0);
}

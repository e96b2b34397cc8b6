//! A head motion whose acceleration jumps leaves healthy hair alone, and a
//! strand that keeps failing over a long span is pinned once.
//!
//! The soak's finding (docs/reliability.md): at the end of a nod whose
//! angular acceleration stops at once (about 15 rad/s² to 0 within a
//! frame), the batch guard reset 400–520 slowly moving curls, each gaining
//! a few 1e-10 J more than a quarter of its kinetic energy. The step holds
//! the root's acceleration over a step, so a jump inside the frame puts in
//! energy that the balance's trapezoid rule does not see; the guard now
//! allows for it ([`root_sampling_uncertainty_j`]), on both engines.
//!
//! [`root_sampling_uncertainty_j`]: helixhair_physics::frame_balance::root_sampling_uncertainty_j

use crate::common;

use common::*;
use glam::{DMat3, DVec3};
use helixhair_physics::batch::BatchSystem;
use helixhair_physics::{
    Guard, GuardAction, HairSystem, HeadTrajectory, NaturalShape, ResetMemory, RigidMotion,
    SimSettings, StrandParams,
};

/// A still head for [`AbruptNod::START_SECS`] (the hair settles), then
/// two nods of 20° about x at 1.5 Hz, angle A·(1 − cos ωt)/2, and then a
/// still head again: velocity continuous, angular acceleration A·ω²/2 ≈
/// 15.5 rad/s² at the clip's first and last instants and zero outside.
struct AbruptNod;

impl AbruptNod {
    const AMPLITUDE_RAD: f64 = 0.349_065_850_398_865_9; // 20°
    const OMEGA: f64 = std::f64::consts::TAU * 1.5;
    const START_SECS: f64 = 6.0;
    const END_SECS: f64 = 2.0 / 1.5;
}

impl HeadTrajectory for AbruptNod {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        let (a, w) = (Self::AMPLITUDE_RAD, Self::OMEGA);
        let t_secs = t_secs - Self::START_SECS;
        let t = t_secs.clamp(0.0, Self::END_SECS);
        let moving = (0.0..Self::END_SECS).contains(&t_secs);
        let angle = 0.5 * a * (1.0 - (w * t).cos());
        let rate = if moving {
            0.5 * a * w * (w * t).sin()
        } else {
            0.0
        };
        let accel = if moving {
            0.5 * a * w * w * (w * t).cos()
        } else {
            0.0
        };
        RigidMotion {
            position_m: DVec3::ZERO,
            world_from_body: DMat3::from_rotation_x(angle),
            velocity_m_per_s: DVec3::ZERO,
            angular_velocity_rad_per_s: DVec3::X * rate,
            acceleration_m_per_s2: DVec3::ZERO,
            angular_acceleration_rad_per_s2: DVec3::X * accel,
        }
    }
}

/// The soak's curls (assets/styles/groomed/full_head.ron): 25 cm ringlets
/// of radius 1.2 cm and 3 cm per turn, 15 elements.
fn soak_curl() -> StrandParams {
    StrandParams {
        natural_shape: NaturalShape::Helix {
            radius_m: 0.012,
            step_m: 0.03,
        },
        ..params(0.25, 15)
    }
}

/// Frames: six seconds still, the nod (80) and a second still after it.
const FRAMES: usize = 500;

#[test]
fn the_batch_guard_leaves_hair_alone_when_a_nod_stops_abruptly() {
    let mut hair = BatchSystem::new(SimSettings::default()).expect("valid settings");
    hair.add_group(&soak_curl(), &outward_roots(32))
        .expect("valid params");
    for frame in 0..FRAMES {
        hair.step_frame(&AbruptNod);
        check_frame(frame, hair.last_guard_events());
    }
    assert!(hair.is_finite());
}

#[test]
fn the_reference_guard_leaves_hair_alone_when_a_nod_stops_abruptly() {
    let mut hair = HairSystem::new(SimSettings::default()).expect("valid settings");
    hair.add_group(&soak_curl(), &outward_roots(8))
        .expect("valid params");
    for frame in 0..FRAMES {
        hair.step_frame(&AbruptNod);
        check_frame(frame, hair.last_guard_events());
    }
}

/// No guard event once the nod has started.
fn check_frame(frame: usize, events: &[helixhair_physics::GuardEvent]) {
    let nod_frame = (AbruptNod::START_SECS * 60.0).round() as usize;
    for e in events {
        println!("frame {frame}: {e}");
    }
    if frame >= nod_frame {
        assert!(events.is_empty(), "frame {frame}: {}", events[0]);
    }
}

#[test]
fn a_strand_failing_every_few_seconds_is_pinned_on_its_fifth_reset() {
    let guard = Guard::default();
    // One reset every 5 s at 60 Hz: never three within the hold window,
    // but five in a row within the long window.
    let mut memory = ResetMemory::default();
    let mut pinned_at = None;
    for reset in 1..=8 {
        for _ in 0..300 {
            memory.tick();
        }
        if memory.give_up(&guard) == GuardAction::Pinned {
            pinned_at = Some(reset);
            break;
        }
    }
    assert_eq!(pinned_at, Some(guard.long_resets_before_pinning));
    // One reset a minute is forgotten each time: never pinned.
    let mut memory = ResetMemory::default();
    for _ in 0..20 {
        for _ in 0..3600 {
            memory.tick();
        }
        assert_eq!(memory.give_up(&guard), GuardAction::Reset);
    }
    // Three within a second: pinned on the third.
    let mut memory = ResetMemory::default();
    let actions: Vec<GuardAction> = (0..3).map(|_| memory.give_up(&guard)).collect();
    use GuardAction::{Pinned, Reset};
    assert_eq!(actions, [Reset, Reset, Pinned]);
}

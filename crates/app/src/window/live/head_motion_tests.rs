//! Tests of [`super::head_motion`] (kept apart to keep the module short).

use helixhair_physics::Oscillation;

use super::*;

#[test]
fn differences_match_an_analytic_oscillation() {
    // A head shake written as the physics crate's Oscillation, and the
    // same shake through FrameHead's differences.
    let reference = Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    let head = FrameHead {
        start_secs: 0.0,
        pose: [0.0; 5],
        rate: [0.0; 5],
        accel: [0.0; 5],
        clip: None,
        pivot_m: DVec3::ZERO,
    };
    for t in [0.05, 0.2, 0.31] {
        let want = reference.motion_at(t);
        // Replace the clip by the exact sinusoid via the manual turn.
        let angle = 0.5 * (std::f64::consts::TAU * 1.5 * t).sin();
        let w = std::f64::consts::TAU * 1.5;
        let frame = FrameHead {
            start_secs: t,
            pose: [angle, 0.0, 0.0, 0.0, 0.0],
            rate: [0.5 * w * (w * t).cos(), 0.0, 0.0, 0.0, 0.0],
            accel: [-w * w * angle, 0.0, 0.0, 0.0, 0.0],
            ..head.clone()
        };
        let got = frame.motion_at(t);
        assert!((got.angular_velocity_rad_per_s - want.angular_velocity_rad_per_s).length() < 1e-6);
        assert!(
            (got.angular_acceleration_rad_per_s2 - want.angular_acceleration_rad_per_s2).length()
                < 1e-3
        );
        assert!((got.world_from_body.col(2) - want.world_from_body.col(2)).length() < 1e-12);
    }
}

#[test]
fn clips_start_and_end_at_rest_and_really_move() {
    for clip in Clip::ALL {
        let mut driver = HeadDriver::default();
        driver.play(clip, 1.0);
        let frame = driver.frame(1.0);
        for t in [1.0, 1.0 + clip.duration_secs()] {
            let m = frame.motion_at(t);
            assert!(m.position_m.length() < 1e-9, "{clip:?} {t}");
            // Zero to the differences' error: the nod starts with a
            // finite acceleration a, read as a·δ/4 at its first instant.
            assert!(
                m.angular_velocity_rad_per_s.length() < 5e-3,
                "{clip:?} {t} {m:?}"
            );
        }
        let peak = (0..100)
            .map(|k| {
                let m = frame.motion_at(1.0 + clip.duration_secs() * k as f64 / 100.0);
                m.angular_velocity_rad_per_s.length() + m.velocity_m_per_s.length()
            })
            .fold(0.0, f64::max);
        assert!(peak > 0.3, "{clip:?} peak speed {peak}");
        assert_eq!(Clip::from_name(clip.name()), Some(clip));
    }
}

#[test]
fn the_head_follows_the_user_smoothly_to_the_target() {
    let mut driver = HeadDriver::default();
    driver.target.turn_rad = 0.8;
    let mut peak_rate: f64 = 0.0;
    for k in 0..120 {
        let m = driver.frame(k as f64 / 60.0).motion_at(k as f64 / 60.0);
        peak_rate = peak_rate.max(m.angular_velocity_rad_per_s.y);
        driver.advance(1.0 / 60.0);
    }
    // Critically damped: arrives without overshoot, and moved fast
    // enough on the way for the hair to feel it (peak of a critically
    // damped step: target × ω / e).
    let m = driver.frame(2.0).motion_at(2.0);
    let (axis, angle) = glam::DQuat::from_mat3(&m.world_from_body).to_axis_angle();
    assert!((angle - 0.8).abs() < 1e-3 && (axis - DVec3::Y).length() < 1e-6);
    let expected_peak = 0.8 * FOLLOW_RAD_PER_S / std::f64::consts::E;
    assert!(
        (peak_rate - expected_peak).abs() / expected_peak < 0.05,
        "{peak_rate}"
    );
}

#[test]
fn the_clip_playing_is_named_with_its_time_until_it_ends() {
    let mut driver = HeadDriver::default();
    assert_eq!(driver.playing(0.0), None);
    driver.play(Clip::Shake, 1.0);
    let duration = Clip::Shake.duration_secs();
    assert_eq!(
        driver.playing(1.5),
        Some(format!("shake, 0.5 of {duration:.1} s"))
    );
    assert_eq!(driver.playing(1.0 + duration + 0.1), None);
}

//! A head drag recorded in the window, saved as a motion file and played
//! back by `helixhair sim --play FILE`'s code ([`parse_play`] and
//! [`Playback::load`]) gives back the window's head trajectory.

use glam::{DMat3, DVec3};
use helixhair_physics::HeadTrajectory;

use super::super::head_motion::{FrameHead, HeadDriver, ManualPose};
use super::*;
use crate::motion::playback::{Playback, parse_play};

const DT_SECS: f64 = 1.0 / 60.0;

/// Known keyframes of a drag: the user's target at frame k. A mouse drag
/// moves the target a little every frame (here along smooth curves), and
/// the head panel's "centre head" makes it jump (frame 90).
fn drag_target(frame: usize) -> ManualPose {
    let t = frame as f64 * DT_SECS;
    if frame >= 90 {
        return ManualPose::default();
    }
    ManualPose {
        turn_rad: 0.8 * (std::f64::consts::TAU * 0.5 * t).sin(),
        tilt_rad: 0.3 * (std::f64::consts::TAU * 0.7 * t).sin(),
        offset_m: DVec3::new(
            0.0,
            0.01 * t,
            0.02 * (std::f64::consts::TAU * 0.4 * t).sin(),
        ),
    }
}

fn angle_between(a: DMat3, b: DMat3) -> f64 {
    let (_, angle) = glam::DQuat::from_mat3(&(a.transpose() * b)).to_axis_angle();
    angle.abs()
}

#[test]
fn a_recorded_drag_played_by_sim_play_gives_the_windows_head_poses() {
    // The window's frames: the driver follows the drag, the recorder keeps
    // each frame's start pose; the window's poses at frame starts and at
    // mid-frame instants are kept to compare.
    let mut driver = HeadDriver::default();
    driver.recorder = Some(MotionRecorder::default());
    let start_secs = 2.0;
    let frames = 130;
    let mut window: Vec<(f64, (DMat3, DVec3))> = Vec::new();
    let mut middles: Vec<(f64, (DMat3, DVec3))> = Vec::new();
    let mut velocities = Vec::new();
    let mut largest_jump_rad: f64 = 0.0;
    for k in 0..frames {
        let target = drag_target(k);
        largest_jump_rad = largest_jump_rad
            .max((target.turn_rad - driver.target.turn_rad).abs())
            .max((target.tilt_rad - driver.target.tilt_rad).abs());
        driver.target = target;
        let t = start_secs + k as f64 * DT_SECS;
        let frame: FrameHead = driver.frame(t);
        driver.record(&frame);
        window.push((t, frame.pose_at(t)));
        velocities.push(frame.motion_at(t).angular_velocity_rad_per_s);
        middles.push((t + 0.5 * DT_SECS, frame.pose_at(t + 0.5 * DT_SECS)));
        driver.advance(DT_SECS);
    }
    let motion = driver.recorder.take().unwrap().motion("drag").unwrap();
    assert_eq!(motion.keys.len(), frames);

    let dir = std::env::temp_dir().join(format!("helixhair-motion-rec-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("drag.ron");
    motion.save(&path).unwrap();
    let Ok(Playback::File(parsed)) = parse_play(path.to_str().unwrap()) else {
        panic!("--play takes the file")
    };
    let played = Playback::File(parsed).load().unwrap();

    // At the recorded instants the file passes through the keys: the same
    // pose to rounding (the RON text keeps f64 in full).
    for (t, (rotation, offset)) in &window {
        let (r, o) = played.pose_at(t - start_secs);
        assert!(angle_between(r, *rotation) < 1e-9, "t {t}");
        assert!((o - *offset).length() < 1e-12, "t {t}");
    }
    // Between them the file's Hermite curve and the window's spring part
    // where the spring's acceleration jumps: by ω²Δ when the target jumps
    // by Δ at a frame start, which a cubic through the keys cannot follow
    // within the frame; its error is at most about ω²Δh²/8 (h the frame).
    // The smooth part of the drag (target steps of 0.04 rad a frame) stays
    // far inside that bound; the jump of "centre head" (0.8 rad) sets it.
    let w = super::super::head_motion::FOLLOW_RAD_PER_S;
    let bound_rad = w * w * largest_jump_rad * DT_SECS * DT_SECS / 8.0;
    let mut worst = (0.0f64, 0.0f64);
    for (t, (rotation, offset)) in middles.iter().take(frames - 1) {
        let (r, o) = played.pose_at(t - start_secs);
        worst.0 = worst.0.max(angle_between(r, *rotation));
        worst.1 = worst.1.max((o - *offset).length());
    }
    assert!(
        worst.0 < bound_rad && worst.1 < 1e-4,
        "worst between keys {worst:?}, bound {bound_rad} rad"
    );
    // And the head's velocity, which the hair feels, agrees mid-drag
    // (frame 30, inside the smooth part), to 2% of the window's.
    let t = start_secs + 30.0 * DT_SECS;
    let want = velocities[30];
    let got = played.motion_at(t - start_secs).angular_velocity_rad_per_s;
    assert!(
        (got - want).length() < 0.02 * want.length(),
        "{got} vs {want}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

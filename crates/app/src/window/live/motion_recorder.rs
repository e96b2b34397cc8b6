//! Recording the head's motion as a motion file: the user drags the head
//! (or plays clips) while recording, and the poses become keys that
//! `helixhair sim --play FILE` and the window play back
//! (docs/motion-format.md).
//!
//! # How it works
//!
//! While recording, the head's pose at the start of every displayed frame
//! (the pose the physics steps from: the spring following the user's drag,
//! composed with any playback) becomes one key, its time counted from the
//! first key. A motion file's rotation is Ry(turn) · Rx(tilt) · Rz(roll),
//! so each rotation is split into those three angles (Y-X-Z Euler angles);
//! turn and roll are unwrapped against the previous key, so a head turning
//! past 180° keeps turning instead of spinning back through the
//! interpolation. The file interpolates between keys with Catmull–Rom
//! Hermite curves, which pass through every key: at the recorded instants
//! the file gives back exactly the window's pose, and between them (one
//! frame apart) the curve differs from the window's spring by far less
//! than the drag's own detail.

use glam::{DMat3, DQuat, DVec3, EulerRot};

use crate::motion::file::{MOTION_VERSION, Motion, MotionKey};

/// The head's poses kept while recording.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MotionRecorder {
    start_secs: Option<f64>,
    keys: Vec<MotionKey>,
}

impl MotionRecorder {
    /// Keeps the head's `pose` (rotation world from head, offset in
    /// metres) at simulated time `time_secs`. A time not after the last
    /// key's (a paused frame) is skipped: a motion file's times increase.
    pub fn record(&mut self, time_secs: f64, pose: (DMat3, DVec3)) {
        let start = *self.start_secs.get_or_insert(time_secs);
        let time_secs = time_secs - start;
        if self.keys.last().is_some_and(|k| time_secs <= k.time_secs) {
            return;
        }
        let mut key = key_from_pose(time_secs, pose);
        if let Some(last) = self.keys.last() {
            key.turn_deg = unwrap_deg(key.turn_deg, last.turn_deg);
            key.roll_deg = unwrap_deg(key.roll_deg, last.roll_deg);
        }
        self.keys.push(key);
    }

    /// Keys recorded so far.
    pub fn key_count(&self) -> usize {
        self.keys.len()
    }

    /// Seconds recorded so far.
    pub fn duration_secs(&self) -> f64 {
        self.keys.last().map_or(0.0, |k| k.time_secs)
    }

    /// The recording as a motion called `name`; `None` before the first key.
    pub fn motion(&self, name: &str) -> Option<Motion> {
        (!self.keys.is_empty()).then(|| Motion {
            version: MOTION_VERSION,
            name: name.to_owned(),
            keys: self.keys.clone(),
        })
    }
}

/// The key at `time_secs` for a pose: turn, tilt and roll (degrees) with
/// Ry(turn) · Rx(tilt) · Rz(roll) = rotation, and the offset.
pub fn key_from_pose(time_secs: f64, (rotation, offset_m): (DMat3, DVec3)) -> MotionKey {
    let (turn, tilt, roll) = DQuat::from_mat3(&rotation).to_euler(EulerRot::YXZ);
    MotionKey {
        time_secs,
        turn_deg: turn.to_degrees(),
        tilt_deg: tilt.to_degrees(),
        roll_deg: roll.to_degrees(),
        offset_m,
    }
}

/// `angle_deg` plus the whole turns that bring it nearest `previous_deg`.
fn unwrap_deg(angle_deg: f64, previous_deg: f64) -> f64 {
    let turns = ((previous_deg - angle_deg) / 360.0 + 0.5).floor();
    angle_deg + 360.0 * turns
}

#[cfg(test)]
#[path = "motion_playback_tests.rs"]
mod playback_tests;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pose_comes_back_from_its_key() {
        let rotation = DMat3::from_rotation_y(0.7)
            * DMat3::from_rotation_x(-0.3)
            * DMat3::from_rotation_z(0.2);
        let key = key_from_pose(1.5, (rotation, DVec3::new(0.01, 0.0, -0.02)));
        assert!((key.turn_deg - 0.7f64.to_degrees()).abs() < 1e-9);
        assert!((key.tilt_deg + 0.3f64.to_degrees()).abs() < 1e-9);
        assert!((key.roll_deg - 0.2f64.to_degrees()).abs() < 1e-9);
    }

    #[test]
    fn a_turn_past_half_a_circle_is_unwrapped() {
        assert_eq!(unwrap_deg(-179.0, 178.0), 181.0);
        assert_eq!(unwrap_deg(10.0, 5.0), 10.0);
        assert_eq!(unwrap_deg(179.0, -178.0), -181.0);
    }

    #[test]
    fn paused_frames_add_no_key_and_times_start_at_zero() {
        let mut rec = MotionRecorder::default();
        let still = (DMat3::IDENTITY, DVec3::ZERO);
        rec.record(3.0, still);
        rec.record(3.0, still);
        rec.record(3.5, still);
        let motion = rec.motion("m").unwrap();
        let times: Vec<f64> = motion.keys.iter().map(|k| k.time_secs).collect();
        assert_eq!(times, vec![0.0, 0.5]);
        assert!(motion.validate().is_ok());
    }
}

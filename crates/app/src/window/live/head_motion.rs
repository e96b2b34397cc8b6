//! How the head moves: the user's pose and the built-in motions.
//!
//! The head's pose is the composition of two parts:
//!
//! - a **manual pose** (turn, tilt, offset) the user sets with Alt-drag or
//!   the head panel. The head does not jump to it: it follows through a
//!   critically damped spring (natural frequency [`FOLLOW_RAD_PER_S`]), so
//!   velocity and acceleration stay finite and the hair feels a real push;
//! - a **playback**: a built-in [`Clip`] (nod, shake, turn, quick jerk)
//!   or a motion file (docs/motion-format.md), the same
//!   [`HeadPlayback`] `helixhair sim --play` steps on, started at some
//!   simulated time.
//!
//! The head's pose can also be recorded as a motion file
//! ([`super::motion_recorder`]): [`HeadDriver::record`] keeps the pose at
//! the start of every frame while recording.
//!
//! The physics needs pose, velocity and acceleration at any instant of a
//! frame. [`HeadDriver::frame`] freezes the spring's state at the frame's
//! start (position, velocity and acceleration, so the manual pose moves as a
//! parabola over the frame) and returns a [`FrameHead`], which implements
//! [`HeadTrajectory`]: velocities and accelerations are central differences
//! of the pose, accurate to O(δ²) with δ = 0.5 ms, which is what keeps the
//! clips and the spring free of hand-derived formulas.

use std::sync::Arc;

use glam::{DMat3, DVec3};
use helixhair_physics::{HeadTrajectory, RigidMotion};

use super::motion_recorder::MotionRecorder;
use crate::motion::clip::ClipTrajectory;
use crate::motion::playback::HeadPlayback;

/// Natural frequency of the spring the head follows the user's pose with,
/// rad/s: it settles in about 0.4 s.
pub const FOLLOW_RAD_PER_S: f64 = 12.0;

pub use crate::motion::clip::Clip;
use crate::motion::clip::{about_pivot, motion_from_pose};

/// The user's pose: turn about the vertical, tilt about the sideways axis,
/// and an offset.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ManualPose {
    /// Turn (yaw) about +y, radians.
    pub turn_rad: f64,
    /// Tilt (pitch) about +x, radians; positive looks down.
    pub tilt_rad: f64,
    /// Offset of the head, metres.
    pub offset_m: DVec3,
}

impl ManualPose {
    fn to_array(self) -> [f64; 5] {
        [
            self.turn_rad,
            self.tilt_rad,
            self.offset_m.x,
            self.offset_m.y,
            self.offset_m.z,
        ]
    }

    fn from_array(a: [f64; 5]) -> Self {
        Self {
            turn_rad: a[0],
            tilt_rad: a[1],
            offset_m: DVec3::new(a[2], a[3], a[4]),
        }
    }

    fn rotation(self) -> DMat3 {
        DMat3::from_rotation_y(self.turn_rad) * DMat3::from_rotation_x(self.tilt_rad)
    }
}

/// A playback and the simulated time it started at, seconds.
type Playing = Option<(Arc<HeadPlayback>, f64)>;

/// Drives the head: the user's target pose, the spring following it, the
/// playback playing, and the recorder while recording.
#[derive(Clone, Debug, Default)]
pub struct HeadDriver {
    /// Where the user wants the head.
    pub target: ManualPose,
    pose: [f64; 5],
    rate: [f64; 5],
    clip: Playing,
    /// The head's poses being recorded, while recording.
    pub recorder: Option<MotionRecorder>,
    /// The point the head turns about, world, metres: the origin for the
    /// default head, an imported head's own ([`crate::head::of_style`]).
    pub pivot_m: DVec3,
}

impl HeadDriver {
    /// Starts `clip` at time `now_secs`.
    pub fn play(&mut self, clip: Clip, now_secs: f64) {
        self.play_motion(HeadPlayback::Clip(ClipTrajectory(clip)), now_secs);
    }

    /// Starts `playback` (a clip or a motion file) at time `now_secs`.
    pub fn play_motion(&mut self, playback: HeadPlayback, now_secs: f64) {
        self.clip = Some((Arc::new(playback), now_secs));
    }

    /// Whether a playback is still moving at `now_secs`.
    pub fn is_playing(&self, now_secs: f64) -> bool {
        self.clip
            .as_ref()
            .is_some_and(|(p, start)| now_secs - start <= p.duration_secs())
    }

    /// What plays at `now_secs`, in words ("shake, 1.2 of 3.0 s";
    /// "a motion file, …"), while it plays.
    pub fn playing(&self, now_secs: f64) -> Option<String> {
        let (playback, start) = self.clip.as_ref()?;
        let elapsed = now_secs - start;
        let duration = playback.duration_secs();
        if elapsed > duration {
            return None;
        }
        let name = match playback.as_ref() {
            HeadPlayback::Clip(clip) => clip.0.name(),
            HeadPlayback::Motion(_) => "a motion file",
        };
        Some(format!("{name}, {elapsed:.1} of {duration:.1} s"))
    }

    /// Keeps the pose at the start of `frame` while recording.
    pub fn record(&mut self, frame: &FrameHead) {
        if let Some(recorder) = &mut self.recorder {
            recorder.record(frame.start_secs, frame.pose_at(frame.start_secs));
        }
    }

    /// The head's motion over the frame starting at `start_secs`.
    pub fn frame(&self, start_secs: f64) -> FrameHead {
        let target = self.target.to_array();
        let w = FOLLOW_RAD_PER_S;
        let accel =
            std::array::from_fn(|i| w * w * (target[i] - self.pose[i]) - 2.0 * w * self.rate[i]);
        FrameHead {
            start_secs,
            pose: self.pose,
            rate: self.rate,
            accel,
            clip: self.clip.clone(),
            pivot_m: self.pivot_m,
        }
    }

    /// Advances the spring by `dt_secs` (in small exact-enough steps).
    pub fn advance(&mut self, dt_secs: f64) {
        let target = self.target.to_array();
        let w = FOLLOW_RAD_PER_S;
        let steps = (dt_secs / 1e-3).ceil().max(1.0) as usize;
        let h = dt_secs / steps as f64;
        for _ in 0..steps {
            for ((pose, rate), target) in self.pose.iter_mut().zip(&mut self.rate).zip(target) {
                let a = w * w * (target - *pose) - 2.0 * w * *rate;
                *rate += h * a;
                *pose += h * *rate;
            }
        }
    }

    /// Stops the head where it is now: the target becomes the current
    /// pose, at rest, and any playback ends (set as rest).
    pub fn hold(&mut self) {
        self.target = ManualPose::from_array(self.pose);
        self.rate = [0.0; 5];
        self.clip = None;
    }

    /// Puts the head at the target at once, at rest (e.g. on reset).
    pub fn snap(&mut self) {
        self.pose = self.target.to_array();
        self.rate = [0.0; 5];
        self.clip = None;
    }
}

/// The head's motion over one frame (see the module docs).
#[derive(Clone, Debug)]
pub struct FrameHead {
    start_secs: f64,
    pose: [f64; 5],
    rate: [f64; 5],
    accel: [f64; 5],
    clip: Playing,
    pivot_m: DVec3,
}

impl FrameHead {
    /// Rotation (world from head) and position of the head at `t_secs`,
    /// turning about the origin (as motion files record it; the
    /// simulation's motion turns it about the pivot).
    pub fn pose_at(&self, t_secs: f64) -> (DMat3, DVec3) {
        let dt = t_secs - self.start_secs;
        let manual = ManualPose::from_array(std::array::from_fn(|i| {
            self.pose[i] + self.rate[i] * dt + 0.5 * self.accel[i] * dt * dt
        }));
        let (clip_rotation, clip_offset) = match &self.clip {
            Some((playback, start)) => playback.pose_at(t_secs - start),
            None => (DMat3::IDENTITY, DVec3::ZERO),
        };
        (
            manual.rotation() * clip_rotation,
            manual.offset_m + clip_offset,
        )
    }
}

impl HeadTrajectory for FrameHead {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        motion_from_pose(|t| about_pivot(self.pose_at(t), self.pivot_m), t_secs)
    }
}

#[cfg(test)]
#[path = "head_motion_tests.rs"]
mod tests;

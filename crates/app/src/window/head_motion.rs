//! How the head moves: the user's pose and the built-in motions.
//!
//! The head's pose is the composition of two parts:
//!
//! - a **manual pose** (turn, tilt, offset) the user sets with Alt-drag or
//!   the head panel. The head does not jump to it: it follows through a
//!   critically damped spring (natural frequency [`FOLLOW_RAD_PER_S`]), so
//!   velocity and acceleration stay finite and the hair feels a real push;
//! - a **clip** from [`Clip`] (nod, shake, turn, quick jerk), a smooth
//!   function of time that starts and ends at rest.
//!
//! The physics needs pose, velocity and acceleration at any instant of a
//! frame. [`HeadDriver::frame`] freezes the spring's state at the frame's
//! start (position, velocity and acceleration, so the manual pose moves as a
//! parabola over the frame) and returns a [`FrameHead`], which implements
//! [`HeadTrajectory`]: velocities and accelerations are central differences
//! of the pose, accurate to O(δ²) with δ = 0.5 ms, which is what keeps the
//! clips and the spring free of hand-derived formulas.

use glam::{DMat3, DVec3};
use helixhair_physics::{HeadTrajectory, RigidMotion};

/// Natural frequency of the spring the head follows the user's pose with,
/// rad/s: it settles in about 0.4 s.
pub const FOLLOW_RAD_PER_S: f64 = 12.0;

/// Time step of the central differences, seconds.
const DIFF_SECS: f64 = 5e-4;

/// A built-in head motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clip {
    /// Two nods: 20° down and back at 1.5 Hz.
    Nod,
    /// A shake: 0.5 rad either way at 1.5 Hz for two cycles, eased in and out.
    Shake,
    /// A turn of 60° to the left, a hold, and back.
    Turn,
    /// A quick jerk: 6 cm sideways in 0.12 s, then back in 0.5 s.
    Jerk,
}

impl Clip {
    /// Every clip, for menus.
    pub const ALL: [Clip; 4] = [Clip::Nod, Clip::Shake, Clip::Turn, Clip::Jerk];

    /// Name for menus and the command line.
    pub fn name(self) -> &'static str {
        match self {
            Clip::Nod => "nod",
            Clip::Shake => "shake",
            Clip::Turn => "turn",
            Clip::Jerk => "jerk",
        }
    }

    /// The clip called `name`.
    pub fn from_name(name: &str) -> Option<Clip> {
        Clip::ALL.into_iter().find(|c| c.name() == name)
    }

    /// Length in seconds.
    pub fn duration_secs(self) -> f64 {
        match self {
            Clip::Nod | Clip::Shake => 2.0 / 1.5,
            Clip::Turn => 2.4,
            Clip::Jerk => 0.62,
        }
    }

    /// (rotation, offset) of the head at `t` seconds into the clip; the
    /// identity outside [0, duration].
    pub fn pose_at(self, t: f64) -> (DMat3, DVec3) {
        let d = self.duration_secs();
        if !(0.0..=d).contains(&t) {
            return (DMat3::IDENTITY, DVec3::ZERO);
        }
        let tau = std::f64::consts::TAU;
        match self {
            Clip::Nod => {
                let angle = 20f64.to_radians() * 0.5 * (1.0 - (tau * 1.5 * t).cos());
                (DMat3::from_rotation_x(angle), DVec3::ZERO)
            }
            Clip::Shake => {
                let ease = (std::f64::consts::PI * t / d).sin().powi(2);
                let angle = 0.5 * ease * (tau * 1.5 * t).sin();
                (DMat3::from_rotation_y(angle), DVec3::ZERO)
            }
            Clip::Turn => {
                let amount = if t < 0.8 {
                    smoothstep(t / 0.8)
                } else if t < 1.6 {
                    1.0
                } else {
                    1.0 - smoothstep((t - 1.6) / 0.8)
                };
                (
                    DMat3::from_rotation_y(60f64.to_radians() * amount),
                    DVec3::ZERO,
                )
            }
            Clip::Jerk => {
                let amount = if t < 0.12 {
                    smoothstep(t / 0.12)
                } else {
                    1.0 - smoothstep((t - 0.12) / 0.5)
                };
                (DMat3::IDENTITY, DVec3::new(0.06 * amount, 0.0, 0.0))
            }
        }
    }
}

/// Quintic smoothstep: 0 at 0, 1 at 1, first and second derivatives zero
/// at both ends (so a clip starts and stops without a jolt).
fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * x * (x * (6.0 * x - 15.0) + 10.0)
}

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

/// Drives the head: the user's target pose, the spring following it, and
/// the clip playing.
#[derive(Clone, Debug, Default)]
pub struct HeadDriver {
    /// Where the user wants the head.
    pub target: ManualPose,
    pose: [f64; 5],
    rate: [f64; 5],
    clip: Option<(Clip, f64)>,
}

impl HeadDriver {
    /// Starts `clip` at time `now_secs`.
    pub fn play(&mut self, clip: Clip, now_secs: f64) {
        self.clip = Some((clip, now_secs));
    }

    /// The clip playing at `now_secs`, if any.
    pub fn playing(&self, now_secs: f64) -> Option<Clip> {
        self.clip
            .filter(|(c, start)| now_secs - start <= c.duration_secs())
            .map(|(c, _)| c)
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
            clip: self.clip,
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

    /// Puts the head at the target at once, at rest (e.g. on reset).
    pub fn snap(&mut self) {
        self.pose = self.target.to_array();
        self.rate = [0.0; 5];
        self.clip = None;
    }
}

/// The head's motion over one frame (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct FrameHead {
    start_secs: f64,
    pose: [f64; 5],
    rate: [f64; 5],
    accel: [f64; 5],
    clip: Option<(Clip, f64)>,
}

impl FrameHead {
    /// Rotation (world from head) and position of the head at `t_secs`.
    pub fn pose_at(&self, t_secs: f64) -> (DMat3, DVec3) {
        let dt = t_secs - self.start_secs;
        let manual = ManualPose::from_array(std::array::from_fn(|i| {
            self.pose[i] + self.rate[i] * dt + 0.5 * self.accel[i] * dt * dt
        }));
        let (clip_rotation, clip_offset) = match self.clip {
            Some((clip, start)) => clip.pose_at(t_secs - start),
            None => (DMat3::IDENTITY, DVec3::ZERO),
        };
        (
            manual.rotation() * clip_rotation,
            manual.offset_m + clip_offset,
        )
    }
}

/// The rotation vector (axis × angle) of `r`, for small and large angles.
fn rotation_vector(r: DMat3) -> DVec3 {
    // atan2 keeps small angles accurate, where acos(w) loses half the
    // digits; q and −q are the same rotation, so take w ≥ 0.
    let mut q = glam::DQuat::from_mat3(&r);
    if q.w < 0.0 {
        q = -q;
    }
    let xyz = DVec3::new(q.x, q.y, q.z);
    let s = xyz.length();
    if s == 0.0 {
        DVec3::ZERO
    } else {
        xyz * (2.0 * s.atan2(q.w) / s)
    }
}

impl HeadTrajectory for FrameHead {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        let h = DIFF_SECS;
        let (r0, p0) = self.pose_at(t_secs);
        let (rm, pm) = self.pose_at(t_secs - h);
        let (rp, pp) = self.pose_at(t_secs + h);
        // World angular displacement over ±h: R(t ± h) R(t)ᵀ.
        let back = rotation_vector(rm * r0.transpose());
        let ahead = rotation_vector(rp * r0.transpose());
        RigidMotion {
            position_m: p0,
            world_from_body: r0,
            velocity_m_per_s: (pp - pm) / (2.0 * h),
            angular_velocity_rad_per_s: (ahead - back) / (2.0 * h),
            acceleration_m_per_s2: (pp - 2.0 * p0 + pm) / (h * h),
            angular_acceleration_rad_per_s2: (ahead + back) / (h * h),
        }
    }
}

#[cfg(test)]
#[path = "head_motion_tests.rs"]
mod tests;

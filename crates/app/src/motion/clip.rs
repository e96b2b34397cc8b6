//! The built-in head motions (nod, shake, turn, quick jerk), shared by the
//! window's head panel and `helixhair sim --play`, so a shot seen in the
//! window can be reproduced without one.
//!
//! A clip is a smooth pose as a function of time that starts and ends at
//! rest. The physics needs velocity and acceleration too:
//! [`motion_from_pose`] takes them as central differences of the pose, accurate
//! to O(δ²) with δ = [`DIFF_SECS`], which keeps every motion free of
//! hand-derived formulas.

use glam::{DMat3, DVec3};
use helixhair_physics::{HeadTrajectory, RigidMotion};

/// Time step of the central differences, seconds.
pub const DIFF_SECS: f64 = 5e-4;

/// A built-in head motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clip {
    /// Two nods: 20° down and back at 1.5 Hz, starting and stopping
    /// without a jump in acceleration.
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
                // (1 − cos)/2 squared: the same two 20° nods, but its
                // acceleration is zero at both ends, where the plain raised
                // cosine stopped from 15.5 rad/s² at once.
                let raised = 0.5 * (1.0 - (tau * 1.5 * t).cos());
                let angle = 20f64.to_radians() * raised * raised;
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

/// A clip played from time zero, then a still head: what `sim --play`
/// steps the hair on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClipTrajectory(pub Clip);

impl HeadTrajectory for ClipTrajectory {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        motion_from_pose(|t| self.0.pose_at(t), t_secs)
    }
}

/// A head pose (world from head, position) turned about `pivot_m` instead
/// of the origin: the clips and motion files turn the head about the
/// origin of head coordinates, which is the default head's skull; an
/// imported groom's head stands wherever its file put it (Sintel's bust
/// 1.5 m up), so its motion turns about its own pivot
/// ([`crate::head::of_style::head_pivot_m`]). A head point y goes to
/// o + c + R (y − c) = (o + c − R c) + R y: same rotation, shifted.
pub fn about_pivot((rotation, offset_m): (DMat3, DVec3), pivot_m: DVec3) -> (DMat3, DVec3) {
    (rotation, offset_m + pivot_m - rotation * pivot_m)
}

/// The head's motion at `t_secs` from its pose (world from head, position)
/// as a function of time: velocities and accelerations by central
/// differences over ±[`DIFF_SECS`].
pub fn motion_from_pose(pose_at: impl Fn(f64) -> (DMat3, DVec3), t_secs: f64) -> RigidMotion {
    let h = DIFF_SECS;
    let (r0, p0) = pose_at(t_secs);
    let (rm, pm) = pose_at(t_secs - h);
    let (rp, pp) = pose_at(t_secs + h);
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

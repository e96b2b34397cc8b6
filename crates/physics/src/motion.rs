//! Rigid motion of the head and of the root frames it carries.
//!
//! Every strand is clamped at its root to a rigid frame. The frame's pose
//! places the strand; its velocity and acceleration enter the dynamics as the
//! root's own motion (the strand is carried along, and feels the inertial
//! forces of an accelerating head). A [`RigidMotion`] is that full state at
//! one instant; a [`HeadTrajectory`] gives it at any time.
//!
//! Conventions: rotations are matrices whose columns are the body's axes in
//! world coordinates (`world_from_body`); angular velocity and acceleration
//! are world vectors. A root frame's first axis is the strand's tangent n₀ at
//! the root, the other two are the material directions n₁, n₂.

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

/// Pose of a root frame in the head's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RootPose {
    /// Root point in head coordinates, metres.
    pub position_m: DVec3,
    /// Columns (n₀, n₁, n₂) in head coordinates; n₀ is the growth direction.
    pub head_from_root: DMat3,
}

impl RootPose {
    /// A root at `position_m` growing along `direction`, with n₁ the part of
    /// `reference` orthogonal to the direction (any orthogonal vector when
    /// `reference` is parallel to it).
    pub fn from_direction(position_m: DVec3, direction: DVec3, reference: DVec3) -> Self {
        let n0 = direction.normalize();
        let mut n1 = reference - reference.dot(n0) * n0;
        if n1.length_squared() < 1e-12 {
            n1 = n0.any_orthonormal_vector();
        }
        let n1 = n1.normalize();
        let n2 = n0.cross(n1);
        Self {
            position_m,
            head_from_root: DMat3::from_cols(n0, n1, n2),
        }
    }
}

/// Pose, velocity and acceleration of a rigid body at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidMotion {
    /// Body origin in world coordinates, metres.
    pub position_m: DVec3,
    /// Rotation taking body coordinates to world coordinates.
    pub world_from_body: DMat3,
    /// Velocity of the body origin, m/s.
    pub velocity_m_per_s: DVec3,
    /// Angular velocity in world coordinates, rad/s.
    pub angular_velocity_rad_per_s: DVec3,
    /// Acceleration of the body origin, m/s².
    pub acceleration_m_per_s2: DVec3,
    /// Angular acceleration in world coordinates, rad/s².
    pub angular_acceleration_rad_per_s2: DVec3,
}

impl Default for RigidMotion {
    fn default() -> Self {
        Self::at_rest(DVec3::ZERO, DMat3::IDENTITY)
    }
}

impl RigidMotion {
    /// A body resting at a pose.
    pub fn at_rest(position_m: DVec3, world_from_body: DMat3) -> Self {
        Self {
            position_m,
            world_from_body,
            velocity_m_per_s: DVec3::ZERO,
            angular_velocity_rad_per_s: DVec3::ZERO,
            acceleration_m_per_s2: DVec3::ZERO,
            angular_acceleration_rad_per_s2: DVec3::ZERO,
        }
    }

    /// The velocity of the body's point at `offset_m` from its origin
    /// (world axes), m/s: v + ω × offset.
    pub fn velocity_at(&self, offset_m: DVec3) -> DVec3 {
        self.velocity_m_per_s + self.angular_velocity_rad_per_s.cross(offset_m)
    }

    /// The motion of a frame fixed to this body at `root` (body
    /// coordinates): same angular motion, and the rigid-body velocity and
    /// acceleration (with centripetal term) of the attachment point.
    pub fn carry(&self, root: &RootPose) -> RigidMotion {
        let offset = self.world_from_body * root.position_m;
        let w = self.angular_velocity_rad_per_s;
        let alpha = self.angular_acceleration_rad_per_s2;
        RigidMotion {
            position_m: self.position_m + offset,
            world_from_body: self.world_from_body * root.head_from_root,
            velocity_m_per_s: self.velocity_at(offset),
            angular_velocity_rad_per_s: w,
            acceleration_m_per_s2: self.acceleration_m_per_s2
                + alpha.cross(offset)
                + w.cross(w.cross(offset)),
            angular_acceleration_rad_per_s2: alpha,
        }
    }
}

/// Where the head is, and how it moves, at any time.
pub trait HeadTrajectory: Sync {
    /// The head's motion at time `t_secs`.
    fn motion_at(&self, t_secs: f64) -> RigidMotion;

    /// The head's motion as a step of `h_secs` from `t_secs` takes it: the
    /// pose and velocities at the step's start, and the accelerations that
    /// carry those velocities to the step's end, (v(t + h) − v(t))/h and
    /// likewise for the turn.
    ///
    /// Why the mean and not the start's: the step moves the hair's rates
    /// by h times the accelerations it is given, relative to the root, so
    /// with the start's acceleration held the root's velocity at the
    /// step's end is off by the acceleration's change over the step, and
    /// the hair's world momentum with it. Where the acceleration turns
    /// within a step (the jerk clip's, at 60 Hz with one substep) that
    /// put energy into the hair: Block-diagonal, which answers a load
    /// faster than the true strand, drew the guard twice on the wavy
    /// example; with the mean, on no example under any clip, on either
    /// engine (docs/physics.md section 6).
    fn step_motion_at(&self, t_secs: f64, h_secs: f64) -> RigidMotion {
        let start = self.motion_at(t_secs);
        let end = self.motion_at(t_secs + h_secs);
        RigidMotion {
            acceleration_m_per_s2: (end.velocity_m_per_s - start.velocity_m_per_s) / h_secs,
            angular_acceleration_rad_per_s2: (end.angular_velocity_rad_per_s
                - start.angular_velocity_rad_per_s)
                / h_secs,
            ..start
        }
    }
}

/// A head that never moves.
impl HeadTrajectory for RigidMotion {
    fn motion_at(&self, _t_secs: f64) -> RigidMotion {
        RigidMotion {
            velocity_m_per_s: DVec3::ZERO,
            angular_velocity_rad_per_s: DVec3::ZERO,
            acceleration_m_per_s2: DVec3::ZERO,
            angular_acceleration_rad_per_s2: DVec3::ZERO,
            ..*self
        }
    }
}

/// A head turning back and forth about a fixed axis through its origin:
/// angle(t) = amplitude · sin(2π f t). With a vertical axis this is a head
/// shake, with a sideways axis a nod.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Oscillation {
    /// Rotation axis in world coordinates (normalised on use).
    pub axis: DVec3,
    /// Peak angle in radians.
    pub amplitude_rad: f64,
    /// Frequency in hertz.
    pub frequency_hz: f64,
}

impl HeadTrajectory for Oscillation {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        let axis = self.axis.normalize();
        let w = std::f64::consts::TAU * self.frequency_hz;
        let angle = self.amplitude_rad * (w * t_secs).sin();
        let rate = self.amplitude_rad * w * (w * t_secs).cos();
        let accel = -self.amplitude_rad * w * w * (w * t_secs).sin();
        RigidMotion {
            position_m: DVec3::ZERO,
            world_from_body: DMat3::from_axis_angle(axis, angle),
            velocity_m_per_s: DVec3::ZERO,
            angular_velocity_rad_per_s: axis * rate,
            acceleration_m_per_s2: DVec3::ZERO,
            angular_acceleration_rad_per_s2: axis * accel,
        }
    }
}

/// A head moving back and forth along a fixed direction without turning:
/// offset(t) = amplitude · sin(2π f t) · direction. Vertical, it is a bounce
/// (a walk, a jump); sideways, a sway.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bounce {
    /// Direction of travel in world coordinates (normalised on use).
    pub direction: DVec3,
    /// Peak offset in metres.
    pub amplitude_m: f64,
    /// Frequency in hertz.
    pub frequency_hz: f64,
}

impl HeadTrajectory for Bounce {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        let d = self.direction.normalize();
        let w = std::f64::consts::TAU * self.frequency_hz;
        let (sin, cos) = (w * t_secs).sin_cos();
        RigidMotion {
            position_m: d * (self.amplitude_m * sin),
            world_from_body: DMat3::IDENTITY,
            velocity_m_per_s: d * (self.amplitude_m * w * cos),
            angular_velocity_rad_per_s: DVec3::ZERO,
            acceleration_m_per_s2: d * (-self.amplitude_m * w * w * sin),
            angular_acceleration_rad_per_s2: DVec3::ZERO,
        }
    }
}

//! The contact force per unit length on one sample near the head.
//!
//! With d the signed distance of the sample, n the field's gradient (both
//! moved into world coordinates with the head), and v_rel the sample's
//! velocity relative to the head's surface point under it, a sample with
//! d < skin feels
//!
//! f = min(k (skin − d) − c min(v_rel · n, 0), ρS a_max) n,
//!
//! a spring pushing out and a damper resisting approach (never pulling in).
//! k = α ρS / h² and c = 2 √α ρS / h make the spring-mass pair of one
//! sample critically damped at the step's stability edge scaled by α: an
//! explicit force in the linearly implicit step stays stable for α < 1.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::sdf::SignedDistanceField;
use crate::motion::RigidMotion;

/// How hair meets the head.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ContactSettings {
    /// Distance from the surface at which contact starts, metres. Default
    /// 2 mm: hair rests on the scalp a little above the mesh, which hides
    /// the penetration the penalty needs (about g h² / α, 0.5 mm at 240 Hz).
    pub skin_m: f64,
    /// α in k = α ρS / h². Default 0.25: a quarter of the explicit
    /// stability limit, so samples sharing an element's force stay stable.
    pub stiffness_ratio: f64,
    /// Cap on the contact acceleration, m/s². Default 300 (about 30 g): a
    /// head jumping into the hair pushes it aside without flinging it.
    pub max_acceleration_m_per_s2: f64,
}

impl Default for ContactSettings {
    fn default() -> Self {
        Self {
            skin_m: 0.002,
            stiffness_ratio: 0.25,
            max_acceleration_m_per_s2: 300.0,
        }
    }
}

/// What the forces stage needs for contact during one step.
#[derive(Clone, Copy, Debug)]
pub struct ContactInputs<'a> {
    /// The head's surface, in head coordinates.
    pub collider: &'a SignedDistanceField,
    /// The head's motion at the start of the step.
    pub head: &'a RigidMotion,
    /// Contact settings.
    pub settings: ContactSettings,
    /// Step length h, seconds (sets k and c).
    pub h_secs: f64,
}

impl ContactInputs<'_> {
    /// Force per unit length (N/m) on a sample at world position `p_m`
    /// moving at `v_m_per_s`, for a strand of mass per length `rho_s`.
    pub fn force(&self, p_m: DVec3, v_m_per_s: DVec3, rho_s: f64) -> DVec3 {
        let head = self.head;
        let offset = p_m - head.position_m;
        let local = head.world_from_body.transpose() * offset;
        let Some((d, gradient)) = self.collider.sample(local) else {
            return DVec3::ZERO;
        };
        let s = &self.settings;
        if d >= s.skin_m || gradient == DVec3::ZERO {
            return DVec3::ZERO;
        }
        let n = head.world_from_body * gradient;
        let surface_velocity =
            head.velocity_m_per_s + head.angular_velocity_rad_per_s.cross(offset);
        let approach = (v_m_per_s - surface_velocity).dot(n).min(0.0);
        let k = s.stiffness_ratio * rho_s / (self.h_secs * self.h_secs);
        let c = 2.0 * s.stiffness_ratio.sqrt() * rho_s / self.h_secs;
        let push = (k * (s.skin_m - d) - c * approach).min(rho_s * s.max_acceleration_m_per_s2);
        n * push.max(0.0)
    }
}

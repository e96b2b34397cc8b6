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
//! That is what the GPU kernels apply ([`ContactInputs::force`]).
//!
//! # Implicit contact (both CPU engines)
//!
//! An explicit penalty that stable is soft: hair resting on the head sinks
//! g h²/α into it (11 mm at 60 Hz with α = 0.25), and a bouncing head
//! pushes hair into the skull. Both CPU engines therefore treat contact in
//! the step matrix, as it treats the stiffness: over a step the sample's
//! normal distance moves by h (v_rel·n + n·J Δv), so the force at the
//! step's end is
//!
//! f = [k (skin − d − h v_rel·n) − c v_rel·n] − (h k + c) n nᵀ J Δv,
//!
//! the bracket (the predicted push, [`ContactInputs::implicit_force`]) on
//! the right-hand side and h (h k + c) Jᵀ n nᵀ J on the left, a
//! mass-like term the solvers take with the mass data
//! ([`crate::step::mass::add_sample_weights`]). Then α can be large
//! ([`ContactSettings::implicit_stiffness_ratio`]): the step stays stable
//! for any α, as it does for any K. A sample that will cross into the skin
//! during the step (d + h min(v_rel·n, 0) < skin) is in contact from the
//! step's start, so no sample ends a step deep in a spring it never
//! compressed. A sample whose predicted push is not positive (separating
//! faster than the spring pushes) is out of contact for the step: contact
//! never pulls.
//!
//! # The cap
//!
//! The predicted push is capped at ρS a_max
//! ([`ContactSettings::max_acceleration_m_per_s2`]). A sample the head
//! meets at speed needs the cap: at 1 m/s the predicted push is
//! (α/h + 2√α/h)·1 m/s = 480 m/s² at 60 Hz with α = 4. Capped, the
//! sample's spring and damper are scaled for the step by cap / spring:
//! f = cap − (cap / spring)(h k + c) n nᵀ J Δv. The push then still
//! falls as the sample moves out, as the uncapped law's does, and is the
//! same law at the cap. Capping the push alone, as a constant force with
//! no term in the step matrix, threw hair off the head: a free point
//! meeting the head at 1 m/s left the step at 4 m/s (h a_max = 5 m/s of
//! push, nothing taking it back as the point moved out), and
//! Block-diagonal, whose strands answer a push in joint motion lighter
//! than the true ones, turned it into points at 50–180 m/s (the straight
//! example settled on the default head, under the head's shake and nod
//! at 60 Hz, batch engine: 13 and 67 strand-frames handed to Exact; none
//! with the scaled law). With the scaled law that point, met at the
//! skin's edge, leaves the step still approaching at 0.17 m/s (uncapped:
//! 0.11 m/s), and the next step stops it.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::sdf::SignedDistanceField;
use crate::error::{ParamError, check_range};
use crate::motion::RigidMotion;

/// How hair meets the head.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ContactSettings {
    /// Distance from the surface at which contact starts, metres. Default
    /// 2 mm: hair rests on the scalp a little above the mesh, which hides
    /// the penetration the penalty needs (about g h² / α, 0.5 mm at 240 Hz).
    pub skin_m: f64,
    /// α in k = α ρS / h² of the explicit penalty the GPU kernels apply.
    /// Default 0.25: a quarter of the explicit
    /// stability limit, so samples sharing an element's force stay stable.
    pub stiffness_ratio: f64,
    /// Cap on the contact acceleration, m/s². Default 300 (about 30 g): a
    /// head jumping into the hair pushes it aside without flinging it.
    pub max_acceleration_m_per_s2: f64,
    /// α of the implicit contact both CPU engines step (see the module
    /// docs). Default 4: a sample held by contact alone sinks g h²/α =
    /// 0.7 mm at 60 Hz (16 times stiffer than the explicit penalty), and
    /// the contact is critically damped per sample. Stiffer is not better
    /// yet: the contact set is frozen over a step, and with both engines
    /// at the samples, α = 16 drew real blow-ups as 30 cm straight hair
    /// landed on the head (a point at 73 m/s on a still head), α = 32 4 to
    /// 12 guard events per clip on the straight and wavy examples; at
    /// α = 4 none. Where hair presses on the head harder than its weight
    /// (the groomed curly example's draped loops, about 2 mm into a 2 mm
    /// skin), a style sets a thicker skin (`examples/contact_depth.rs`
    /// measures the depths).
    pub implicit_stiffness_ratio: f64,
}

impl ContactSettings {
    /// Checks every field; the error names the offending one. A skin up to
    /// 2 cm (thicker would hold hair visibly off the head); stiffness
    /// ratios above zero, the explicit one to 1 (its stability edge) and
    /// the implicit one to 64; the cap from 1 to 10,000 m/s².
    pub fn validate(&self) -> Result<(), ParamError> {
        check_range("contact.skin_m", self.skin_m, 0.0, 0.02)?;
        check_range("contact.stiffness_ratio", self.stiffness_ratio, 1e-6, 1.0)?;
        check_range(
            "contact.max_acceleration_m_per_s2",
            self.max_acceleration_m_per_s2,
            1.0,
            1e4,
        )?;
        check_range(
            "contact.implicit_stiffness_ratio",
            self.implicit_stiffness_ratio,
            1e-6,
            64.0,
        )
    }
}

impl Default for ContactSettings {
    fn default() -> Self {
        Self {
            skin_m: 0.002,
            stiffness_ratio: 0.25,
            max_acceleration_m_per_s2: 300.0,
            implicit_stiffness_ratio: 4.0,
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
        let s = &self.settings;
        let Some(surface) = self.surface(p_m, v_m_per_s) else {
            return DVec3::ZERO;
        };
        if surface.distance_m >= s.skin_m {
            return DVec3::ZERO;
        }
        let approach = surface.approach_m_per_s.min(0.0);
        let k = s.stiffness_ratio * rho_s / (self.h_secs * self.h_secs);
        let c = 2.0 * s.stiffness_ratio.sqrt() * rho_s / self.h_secs;
        let push = (k * (s.skin_m - surface.distance_m) - c * approach)
            .min(rho_s * s.max_acceleration_m_per_s2);
        surface.normal * push.max(0.0)
    }

    /// The field at a sample at world position `p_m` moving at
    /// `v_m_per_s`: signed distance, outward normal (world) and the
    /// velocity along it relative to the moving surface; `None` outside the
    /// field or where its gradient vanishes. The one lookup every contact
    /// force and energy starts from.
    fn surface(&self, p_m: DVec3, v_m_per_s: DVec3) -> Option<SurfacePoint> {
        let head = self.head;
        let offset = p_m - head.position_m;
        let local = head.world_from_body.transpose() * offset;
        let (distance_m, gradient) = self.collider.sample(local)?;
        if gradient == DVec3::ZERO {
            return None;
        }
        let normal = head.world_from_body * gradient;
        let surface_velocity = head.velocity_at(offset);
        Some(SurfacePoint {
            distance_m,
            normal,
            approach_m_per_s: (v_m_per_s - surface_velocity).dot(normal),
        })
    }
}

/// The collider's field at one sample (see `ContactInputs::surface`).
#[derive(Clone, Copy, Debug)]
struct SurfacePoint {
    distance_m: f64,
    normal: DVec3,
    approach_m_per_s: f64,
}

/// A sample's implicit contact for one step (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImplicitContact {
    /// The predicted push at the step's end without the Δv term, N/m.
    pub force_n_per_m: DVec3,
    /// The outward normal n, world.
    pub normal: DVec3,
    /// h k + c, per unit length (N·s/m²): the step matrix gains
    /// h (h k + c) Jᵀ n nᵀ J times the sample's weight.
    pub gain: f64,
}

impl ContactInputs<'_> {
    /// The implicit contact of a sample at world position `p_m` moving at
    /// `v_m_per_s`, for a strand of mass per length `rho_s`; `None` out of
    /// contact.
    pub fn implicit_force(
        &self,
        p_m: DVec3,
        v_m_per_s: DVec3,
        rho_s: f64,
    ) -> Option<ImplicitContact> {
        let surface = self.surface(p_m, v_m_per_s)?;
        let s = &self.settings;
        let (d, n, approach) = (surface.distance_m, surface.normal, surface.approach_m_per_s);
        let h = self.h_secs;
        // A sample that will enter the skin during the step is in contact
        // already: otherwise it would end the step deep inside and be
        // pushed out by a spring it never compressed (energy from nowhere).
        let predicted_d = d + h * approach.min(0.0);
        if predicted_d >= s.skin_m {
            return None;
        }
        let alpha = s.implicit_stiffness_ratio;
        let k = alpha * rho_s / (h * h);
        let c = 2.0 * alpha.sqrt() * rho_s / h;
        let spring = k * (s.skin_m - d - h * approach) - c * approach;
        let cap = rho_s * s.max_acceleration_m_per_s2;
        // Capped, spring and damper are scaled by cap / spring for the
        // step, so the push still falls as the sample moves out (see
        // "The cap" in the module docs); at the cap both laws agree.
        let (push, gain) = if spring > cap {
            (cap, (h * k + c) * (cap / spring))
        } else {
            (spring, h * k + c)
        };
        (push > 0.0).then_some(ImplicitContact {
            force_n_per_m: n * push,
            normal: n,
            gain,
        })
    }
}

//! Stage "forces": generalized forces Q = ∫ Jᵀ F ds in O(N).
//!
//! The force per unit length at each sample is
//! F = ρS (g − r̈_free) − ν (ṙ_carried − v_air) + F_ext, where r̈_free is the
//! acceleration with q̈ = 0 (from the reconstruction's jets: moving this
//! inertial term to the right-hand side is what Lagrange's equations give)
//! and ṙ_carried = v_root + ω_root × r is the velocity the root's motion
//! alone gives the point. The drag on the strain rates, −ν J q̇, is treated
//! implicitly by the step (it is (ν/ρS) M q̇), so it is not counted here;
//! the hair–hair model's friction likewise adds only its known part
//! ([`VolumePull::known_n_per_m`]).
//!
//! For element Q, Q_Q = Σ_{own samples} w Gᵀ F + A_Qᵀ F_beyond + B_Qᵀ τ_beyond
//! with F_beyond = Σ w F and τ_beyond = Σ w r × F over all later samples:
//! two suffix sums, one sweep tip to root.

use glam::DVec3;

use crate::collision::ContactInputs;
use crate::model::StrandModel;
use crate::motion::RigidMotion;
use crate::step::reconstruct::Kinematics;
use crate::volume::VolumePull;

/// Environment of the forces stage.
#[derive(Clone, Copy, Debug)]
pub struct ForceInputs<'a> {
    /// Motion of the root frame.
    pub root: &'a RigidMotion,
    /// Gravity, m/s².
    pub gravity_m_per_s2: DVec3,
    /// Air velocity, m/s.
    pub air_velocity_m_per_s: DVec3,
    /// Extra force per unit length at each sample (N/m), or empty: the hook
    /// for user forces.
    pub external_n_per_m: &'a [DVec3],
    /// The head collider, if any (see [`crate::collision`]).
    pub contact: Option<ContactInputs<'a>>,
    /// The hair–hair model's pull on this strand, if on
    /// ([`crate::volume::friction`]).
    pub volume: Option<VolumePull<'a>>,
}

/// Force per unit length on sample `i` (N/m).
pub fn sample_force(
    model: &StrandModel,
    kin: &Kinematics,
    inputs: &ForceInputs,
    i: usize,
) -> DVec3 {
    let s = &kin.samples[i];
    let carried = inputs.root.velocity_at(s.position_m);
    let mut f = model.mass_per_length * (inputs.gravity_m_per_s2 - s.free_acceleration_m_per_s2)
        - model.air_drag * (carried - inputs.air_velocity_m_per_s);
    if let Some(extra) = inputs.external_n_per_m.get(i) {
        f += *extra;
    }
    if let Some(volume) = &inputs.volume {
        f += volume.known_n_per_m(i, model.mass_per_length);
    }
    if let Some(contact) = &inputs.contact {
        // Implicit contact: the predicted push; its Δv term is in the step
        // matrix (crate::collision::contact).
        let world = inputs.root.position_m + s.position_m;
        if let Some(push) = contact.implicit_force(world, s.velocity_m_per_s, model.mass_per_length)
        {
            f += push.force_n_per_m;
        }
    }
    f
}

/// Writes the generalized forces Q_Q (N·m², one triple per element) to `out`.
pub fn generalized_forces(
    model: &StrandModel,
    kin: &Kinematics,
    inputs: &ForceInputs,
    out: &mut [DVec3],
) {
    project_sample_forces(
        model,
        kin,
        |i| sample_force(model, kin, inputs, i) * kin.samples[i].weight_m,
        out,
    );
}

/// Σ_s Jᵀ(s) f_s per element for sample forces `f_s` (N: force per unit
/// length times the sample's weight), by the two suffix sums: the
/// projection every generalized force shares.
pub fn project_sample_forces(
    model: &StrandModel,
    kin: &Kinematics,
    weighted_force: impl Fn(usize) -> DVec3,
    out: &mut [DVec3],
) {
    let points = model.quadrature.len();
    let mut force_beyond = DVec3::ZERO;
    let mut torque_beyond = DVec3::ZERO;
    for e in (0..model.elements()).rev() {
        let jac = &kin.elements[e];
        let mut own = jac.a.transpose() * force_beyond + jac.b.transpose() * torque_beyond;
        for i in e * points..(e + 1) * points {
            let s = &kin.samples[i];
            let f = weighted_force(i);
            own += s.jacobian.transpose() * f;
            force_beyond += f;
            torque_beyond += s.position_m.cross(f);
        }
        out[e] = own;
    }
}

//! The friction term: each sample's velocity is pulled toward the grid's,
//! the mean velocity of the hair around it, and how the step takes it
//! implicitly.
//!
//! # The force
//!
//! Per unit length, F = μ ρS (u(x) − v), with μ the friction rate (1/s),
//! ρS the strand's mass per length, v the sample's world velocity and u(x)
//! = Σ w_n(x) u_n the grid velocity read back at the sample (PIC). Strands
//! moving through each other feel it; a lock moving as one does not
//! (u = v). It is a drag toward a velocity field, exactly like air drag
//! toward the wind: ν (v_air − v) with ν = μ ρS and v_air = u(x).
//!
//! # Why it is implicit, and how
//!
//! Taken explicitly, a drag of rate μ is stable only for hμ < 2. The step
//! already treats air drag implicitly: the part −ν J q̇ that depends on the
//! strain rates enters the step matrix through the mass scale
//! s = 1 + hν/ρS (`crate::step`, stage "solve"), the rest, ν (v_air −
//! ṙ_carried), is a known force. Friction enters the same way: its rate μ
//! joins ν/ρS in s and in the right-hand side's −(ν/ρS) M v, and the known
//! part μ ρS (u − ṙ_carried) joins the sample forces
//! ([`VolumePull::force_n_per_m`]). u is frozen over the frame (it is the
//! other strands' mean, splatted at the frame's start); for a free sample
//! the step is then v' = (v + hμ u)/(1 + hμ) ([`implicit_velocity`]), which
//! moves v toward u by the fraction hμ/(1 + hμ) < 1 for any h: it cannot
//! overshoot, and the relative velocity v − u decays as (1 + hμ)^(−t/h) →
//! e^(−μt), time constant 1/μ.
//!
//! μ is uniform over the hair (a sample with no neighbours has u ≈ its own
//! velocity and feels almost nothing), which is what lets it fold into s;
//! a density-weighted μ would need per-sample weights in the step matrix,
//! as contact has.

use glam::DVec3;
use wide::f64x4;

#[cfg(doc)]
use super::splat::NodeSums;

/// What the model hands one strand's step: the friction rate and, per
/// quadrature sample, the grid velocity and the pressure's push, frozen
/// over the frame.
#[derive(Clone, Copy, Debug)]
pub struct VolumePull<'a> {
    /// Friction rate μ, 1/s: the implicit part, added to the drag rate.
    pub friction_per_s: f64,
    /// Grid velocity u at each sample, world coordinates, m/s.
    pub target_m_per_s: &'a [DVec3],
    /// Pressure acceleration at each sample, world coordinates, m/s².
    pub push_m_per_s2: &'a [DVec3],
}

impl VolumePull<'_> {
    /// The known part of the model's force per unit length on sample `i`
    /// (N/m): μ ρS (u − ṙ_carried) + ρS a_push, with ṙ_carried the velocity
    /// the root's motion alone gives the sample. The rest, −μ ρS J q̇, is in
    /// the step matrix. A sample past the slices' ends feels nothing.
    pub fn force_n_per_m(&self, i: usize, carried_m_per_s: DVec3, mass_per_length: f64) -> DVec3 {
        let (Some(u), Some(a)) = (self.target_m_per_s.get(i), self.push_m_per_s2.get(i)) else {
            return DVec3::ZERO;
        };
        mass_per_length * (self.friction_per_s * (*u - carried_m_per_s) + *a)
    }
}

/// The grid velocity u(x) = Σ w_n u_n at a point of a cell whose nodes
/// are `around[offsets[c]]` with weights `weights[c]`
/// ([`super::cell::Locator::offsets`], [`super::cell::Cell::weights`]),
/// m/s, from the nodes' mean velocities u_n
/// ([`NodeSums::velocity_m_per_s`], found once per node and frame) in the
/// first three lanes of `around` (the fourth is not read): one four-lane
/// multiply and add per node, the sum of the scalar products in the same
/// order.
#[inline(always)]
pub fn grid_velocity(around: &[f64x4], offsets: &[usize; 8], weights: &[f64; 8]) -> DVec3 {
    let sum = offsets
        .iter()
        .zip(weights)
        .fold(f64x4::ZERO, |sum, (offset, w)| {
            sum + f64x4::splat(*w) * around[*offset]
        });
    let [x, y, z, _] = *sum.as_array();
    DVec3::new(x, y, z)
}

/// One implicit step of the friction alone for a free sample:
/// v' = (v + hμ u)/(1 + hμ), m/s.
pub fn implicit_velocity(v: DVec3, target: DVec3, friction_per_s: f64, h_secs: f64) -> DVec3 {
    let hm = h_secs * friction_per_s;
    (v + hm * target) / (1.0 + hm)
}

//! The friction term: each sample's velocity is pulled toward the grid's,
//! the mean velocity of the hair around it, and how the step takes it
//! implicitly.
//!
//! # The force
//!
//! Per unit length, F = μ ρS (u(x) − v), with μ the friction rate (1/s),
//! ρS the strand's mass per length, v the sample's world velocity and u(x)
//! = Σ w_n(x) u_n the grid velocity read back at the sample's point
//! ([`super::pair_points`], one per pair of quadrature nodes; PIC). Strands
//! moving through each other feel it; a lock moving as one does not
//! (u = v).
//!
//! # Relative to the head
//!
//! u is splatted once per frame, at its start, and frozen over the frame;
//! the head moves on. The grid is fixed in head coordinates, so what is
//! frozen is the hair's velocity *relative to the head's rigid motion*:
//! each sample keeps u_rel = u − c₀, with c₀ the velocity the head's rigid
//! motion gives the sample's place at the frame's start
//! ([`HeadVelocity`]; the field subtracts it at its nodes, which comes to
//! the same at every sample), and feels F = μ ρS (u_rel − (v − c)), c the
//! head's velocity there now. Hair that moves with the head feels nothing
//! however the head accelerates; a world-frozen u would drag it back
//! toward the head's velocity of the frame's start, a force the frame's
//! measure could not tell from energy gained (measured: the small head
//! shaken with μ = 200/s, 44 strands flagged in 120 frames).
//!
//! # Why it is implicit, and how
//!
//! Taken explicitly, a drag of rate μ is stable only for hμ < 2. v − c is
//! the velocity of the sample relative to the root's rigid motion, J q̇
//! (the strain rates' part of it), so F = μ ρS u_rel − μ ρS J q̇: a known
//! force ([`VolumePull::known_n_per_m`]) and a drag on the strain rates
//! exactly like air drag's −ν J q̇, which the step treats implicitly
//! through the mass scale s = 1 + hν/ρS (`crate::step`, stage "solve"):
//! μ joins ν/ρS in s and in the right-hand side's −(ν/ρS) M v. For a free
//! sample the step is then w' = (w + hμ u_rel)/(1 + hμ) for w = v − c
//! ([`implicit_velocity`]), which moves w toward u_rel by the fraction
//! hμ/(1 + hμ) < 1 for any h: it cannot overshoot, and the relative
//! velocity decays as (1 + hμ)^(−t/h) → e^(−μt), time constant 1/μ.
//!
//! μ is uniform over the hair (a sample with no neighbours has u ≈ its own
//! velocity and feels almost nothing), which is what lets it fold into s;
//! a density-weighted μ would need per-sample weights in the step matrix,
//! as contact has.

use glam::{DMat3, DVec3};
use wide::f64x4;

use super::pair_points::point_of;
use crate::motion::RigidMotion;

#[cfg(doc)]
use super::splat::NodeSums;

/// What the model hands one strand's step: the friction rate and, per
/// point (the model reads the field once per pair of quadrature nodes,
/// [`super::pair_points`]), the grid velocity relative to the head and
/// the pressure's push, frozen over the frame. Both samples of a pair
/// feel their point's known part; the drag on its own velocity is each
/// sample's.
#[derive(Clone, Copy, Debug)]
pub struct VolumePull<'a> {
    /// Friction rate μ, 1/s: the implicit part, added to the drag rate.
    pub friction_per_s: f64,
    /// Grid velocity at each point relative to the head's rigid motion
    /// there, u − c₀, at the frame's start, world axes, m/s.
    pub relative_target_m_per_s: &'a [DVec3],
    /// Pressure acceleration at each point, world coordinates, m/s².
    pub push_m_per_s2: &'a [DVec3],
    /// Quadrature samples per element: sample i is node i mod n of
    /// element i / n, and feels point [`point_of`] of them.
    pub samples_per_element: usize,
}

impl VolumePull<'_> {
    /// The known part of the model's force per unit length on sample `i`
    /// (N/m): ρS (μ u_rel + a), its point's. The rest, −μ ρS J q̇, is in
    /// the step matrix. A sample past the slices' ends feels nothing.
    pub fn known_n_per_m(&self, i: usize, mass_per_length: f64) -> DVec3 {
        self.known_at(i, mass_per_length).unwrap_or(DVec3::ZERO)
    }

    /// The whole force per unit length on sample `i` moving at `velocity`
    /// (world, m/s) where the head's rigid motion moves at `carried`
    /// (m/s): μ ρS (u_rel − (v − c)) + ρS a, N/m.
    pub fn force_n_per_m(
        &self,
        i: usize,
        velocity: DVec3,
        carried: DVec3,
        mass_per_length: f64,
    ) -> DVec3 {
        self.known_at(i, mass_per_length)
            .map_or(DVec3::ZERO, |known| {
                known - mass_per_length * self.friction_per_s * (velocity - carried)
            })
    }

    /// ρS (μ u_rel + a) at sample `i`'s point, or `None` past the slices'
    /// ends.
    fn known_at(&self, i: usize, mass_per_length: f64) -> Option<DVec3> {
        let p = self.point(i);
        let u = self.relative_target_m_per_s.get(p)?;
        let a = self.push_m_per_s2.get(p)?;
        Some(mass_per_length * (self.friction_per_s * *u + *a))
    }

    /// The point sample `i` feels.
    fn point(&self, i: usize) -> usize {
        let n = self.samples_per_element.max(1);
        point_of(i / n, i % n, n)
    }
}

/// The head's rigid velocity field, c(p) = v + ω × (R p) for a point p in
/// head coordinates, written c(p) = v + W p with W = \[ω\]× R, one
/// matrix–vector product per point. The field takes it at its nodes
/// ([`super::VolumeField::update`]): c is affine in p and trilinear
/// weights reproduce affine functions exactly, so the read-back of
/// u_n − c(x_n) is u(x) − c(x) with no per-sample work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadVelocity {
    /// The head origin's velocity v, m/s, world.
    pub origin_m_per_s: DVec3,
    /// W = \[ω\]× R, 1/s: world velocity per metre of head coordinates.
    pub per_body_m: DMat3,
}

impl Default for HeadVelocity {
    /// A still head: zero everywhere.
    fn default() -> Self {
        Self {
            origin_m_per_s: DVec3::ZERO,
            per_body_m: DMat3::ZERO,
        }
    }
}

impl HeadVelocity {
    /// The field of the head moving as `head`.
    pub fn of(head: &RigidMotion) -> Self {
        let w = head.angular_velocity_rad_per_s;
        let r = head.world_from_body;
        Self {
            origin_m_per_s: head.velocity_m_per_s,
            per_body_m: DMat3::from_cols(w.cross(r.x_axis), w.cross(r.y_axis), w.cross(r.z_axis)),
        }
    }

    /// The velocity at `body_m` (head coordinates), m/s, world.
    pub fn at(&self, body_m: DVec3) -> DVec3 {
        self.origin_m_per_s + self.per_body_m * body_m
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
/// v' = (v + hμ u)/(1 + hμ), m/s (velocities relative to the head, or a
/// still head).
pub fn implicit_velocity(v: DVec3, target: DVec3, friction_per_s: f64, h_secs: f64) -> DVec3 {
    let hm = h_secs * friction_per_s;
    (v + hm * target) / (1.0 + hm)
}

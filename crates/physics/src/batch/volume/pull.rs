//! The hair–hair model's pull on a batch's samples ([`crate::volume`]):
//! what the step adds at each quadrature sample, and how it rides the
//! step's hook.
//!
//! # The force, as the batch step takes it
//!
//! Per unit length, the model's force on a sample is
//! F = μρS (u_rel − (ṙ − c)) + ρS a ([`crate::volume::friction`]):
//! friction toward the grid velocity relative to the head, u_rel, a drag
//! on the sample's velocity relative to the root's rigid motion,
//! ṙ − c = J q̇ (c = v_root + ω × r), and the pressure's push a; u_rel and
//! a are frozen over the frame. The batch step takes air drag on the full
//! velocity, −ν(ṙ − v_air), with its implicit part (ν/ρS) M in the mass
//! scale s = 1 + hν/ρS ([`crate::batch::forward`], [`crate::batch::suffix::mass_scale`]);
//! the friction goes the same way: s gains hμ
//! ([`SampleHook::drag_rate_per_s`]) and each sample's force gains
//! μρS (u_rel − (ṙ − c)) + ρS a ([`SampleHook::sample_force`]). The f64
//! reference splits the same force into its known part and (μ) M q̇ on
//! the right-hand side ([`crate::step`]); since J q̇ = ṙ − c at every
//! sample, the two are one arithmetic up to round-off, as for air drag.
//!
//! Per point (one per pair of quadrature nodes,
//! [`crate::volume::pair_points`]) the pull keeps one vector, the known
//! part k = ρS (μ u_rel + a) read there (computed in f64, stored in f32),
//! and per lane the rate μρS, so the force on a sample of the pair moving
//! at ṙ − c relative to the root's rigid motion is k − μρS (ṙ − c).
//!
//! # The hook
//!
//! The step's sample hook ([`SampleHook`], threaded through every
//! batch step for the head's contact) carries it: [`WithPull`] wraps the
//! contact (or [`crate::batch::forward::NoContact`]) and adds the pull's drag rate
//! and sample forces. Without the model the hook's
//! [`SampleHook::SAMPLE_FORCES`] is false and the sample loop compiles
//! exactly as before (bit-identical steps).

use crate::batch::forward::SampleHook;
use crate::batch::lane_model::{Constants, LaneModel};
use crate::batch::lanes::{LANES, Lanes, Real};
use glam::DVec3;

use crate::batch::layout::RootMotion;
use crate::batch::vec::V3;
use crate::motion::{RigidMotion, RootPose};
use crate::volume::pair_points::point_of;

/// One batch's pull for a frame: what [`crate::batch::volume::BatchVolume`]
/// hands each batch.
#[derive(Clone, Copy, Debug)]
pub struct SamplePull<'a> {
    /// Friction rate μ, 1/s (the same for every lane).
    pub friction_per_s: f32,
    /// μρS per lane, kg/(m·s).
    pub rate: Lanes,
    /// Per point ([`point_of`]), the known part k = ρS (μ u_rel + a), N/m,
    /// world axes.
    pub known: &'a [V3<Lanes>],
    /// Quadrature nodes per element.
    pub nodes: usize,
}

impl SamplePull<'_> {
    /// The model's force per unit length on node `j` of element `e` moving
    /// at `relative` (m/s) relative to the root's rigid motion, ṙ − c:
    /// k − μρS (ṙ − c), N/m, k its point's.
    #[inline(always)]
    pub fn force(&self, e: usize, j: usize, relative: V3<Lanes>) -> V3<Lanes> {
        self.known[point_of(e, j, self.nodes)] - relative.scale(self.rate)
    }
}

/// The step's hook `H` with the model's pull added.
#[derive(Debug)]
pub struct WithPull<'a, H> {
    /// The hook it wraps (the head's contact, or none).
    pub inner: H,
    /// The pull.
    pub pull: SamplePull<'a>,
    /// The batch's roots' rigid velocity over the step, which the
    /// friction's drag is relative to.
    pub root: RootVelocity,
}

impl<H: SampleHook<Lanes>> SampleHook<Lanes> for WithPull<'_, H> {
    const SAMPLE_FORCES: bool = true;

    const SAMPLE_CONTACT: bool = H::SAMPLE_CONTACT;

    #[inline(always)]
    fn drag_rate_per_s(&self) -> f64 {
        f64::from(self.pull.friction_per_s)
    }

    #[inline(always)]
    fn sample_contact(
        &self,
        e: usize,
        j: usize,
        r: V3<Lanes>,
        velocity: V3<Lanes>,
    ) -> Option<(V3<Lanes>, V3<Lanes>)> {
        self.inner.sample_contact(e, j, r, velocity)
    }

    #[inline(always)]
    fn sample_force(&self, e: usize, j: usize, r: V3<Lanes>, velocity: V3<Lanes>) -> V3<Lanes> {
        self.pull.force(e, j, velocity - self.root.at(r))
    }
}

/// A batch's roots' rigid velocity field: each lane's root point velocity
/// and the root frame's angular velocity (f32 lanes, as
/// [`RootMotion::gather`] has them).
#[derive(Clone, Copy, Debug)]
pub struct RootVelocity {
    /// The root points' velocities, m/s.
    pub velocity_m_per_s: V3<Lanes>,
    /// The roots' angular velocity, rad/s.
    pub angular_velocity_rad_per_s: V3<Lanes>,
}

impl RootVelocity {
    /// The field of roots moving as `root`.
    #[inline(always)]
    pub fn of(root: &RootMotion<Lanes>) -> Self {
        Self {
            velocity_m_per_s: root.velocity_m_per_s,
            angular_velocity_rad_per_s: root.angular_velocity_rad_per_s,
        }
    }

    /// The field of `roots` (≤ [`LANES`]; padding lanes repeat the last)
    /// on a head moving as `head`: the velocities
    /// [`RigidMotion::carry`] gives them, rounded to f32 as
    /// [`RootMotion::gather`] rounds them, without the rest of their
    /// motion.
    pub fn carried_by(head: &RigidMotion, roots: &[RootPose]) -> Self {
        let velocity: [DVec3; LANES] = std::array::from_fn(|l| {
            let root = &roots[l.min(roots.len() - 1)];
            head.velocity_at(head.world_from_body * root.position_m)
        });
        let lanes = |f: fn(&DVec3) -> f64, values: &[DVec3; LANES]| {
            Lanes::from_fn(|l| f(&values[l]) as f32)
        };
        let v3 = |values: &[DVec3; LANES]| {
            V3::new(
                lanes(|v| v.x, values),
                lanes(|v| v.y, values),
                lanes(|v| v.z, values),
            )
        };
        Self {
            velocity_m_per_s: v3(&velocity),
            angular_velocity_rad_per_s: v3(&[head.angular_velocity_rad_per_s; LANES]),
        }
    }

    /// The velocity the roots' rigid motion gives a point `r` (relative
    /// to the root point), m/s.
    #[inline(always)]
    pub fn at(&self, r: V3<Lanes>) -> V3<Lanes> {
        self.velocity_m_per_s + self.angular_velocity_rad_per_s.cross(r)
    }
}

/// Per lane, the pull's work terms at node `j` of element `e`, of
/// quadrature length `w_len` (m) at `r` (relative to the root point)
/// moving at `velocity` (world), `relative` to the root's rigid motion:
/// adds its force, torque and power to the guard's sums, as
/// [`crate::volume::balance`] does on the reference.
#[inline(always)]
pub fn add_pull_work(
    pull: &SamplePull<'_>,
    e: usize,
    j: usize,
    r: V3<Lanes>,
    (velocity, relative): (V3<Lanes>, V3<Lanes>),
    w_len: Lanes,
    sums: (&mut V3<Lanes>, &mut V3<Lanes>, &mut Lanes),
) {
    let f = pull.force(e, j, relative).scale(w_len);
    let (force, torque, power) = sums;
    *force += f;
    *torque += r.cross(f);
    *power += f.dot(velocity);
}

/// μρS lane by lane from the friction rate and a batch's constants.
pub fn friction_rate(friction_per_s: f32, model: &LaneModel) -> Lanes {
    Lanes::splat(friction_per_s) * model.mass_per_length()
}

//! Stage "collide" on the fast path: the head collider's penalty force at
//! each element's end point, folded into the suffix sums.
//!
//! # How it works
//!
//! The f64 reference ([`crate::HairSystem`]) adds the contact force per
//! unit length of [`ContactInputs::force`] at every quadrature sample.
//! Here the signed distance field is looked up once per lane at each
//! element's END point only: the lookup is scalar (one grid cell per lane),
//! so it is kept to N lookups per strand and step instead of N × points,
//! and the end points are already computed by the forward sweep
//! ([`super::forward::advance`]: `point_m` relative to the root point, and
//! `point_velocity`). The world position is the lane's root position plus
//! `point_m`; the head's motion is the one at the step's start, as in the
//! reference.
//!
//! **From N/m to N.** The end point of element Q stands for the half of
//! each element beside it: it carries f · (ℓ_Q + ℓ_{Q+1})/2, and the tip
//! f · ℓ_{N−1}/2. (The half of element 0 next to the root is left out: a
//! force on the clamped root does no work.)
//!
//! **Where a point force enters the step.** Write p = p_{Q+1} for the end
//! point of element Q (relative to the root, like every sample's r) and F
//! for the force on it, in newtons. Its generalized force on element P is
//! (∂p/∂q_P)ᵀ F, and
//!
//! - P > Q: zero (moving a later element does not move p);
//! - P < Q: p lies beyond P, so ∂p/∂q_P = A_P − [p]×B_P, the "beyond"
//!   Jacobian every sample past P has (see [`super::suffix`]);
//! - P = Q: ∂p/∂q_Q = a_Q = R_Q ∂h(ℓ_Q, k)/∂k, the element's own end
//!   Jacobian. [`super::forward::advance`] builds A_Q = R_Q·J_end + [p]×B_Q
//!   with this same p, so a_Q = A_Q − [p]×B_Q: the beyond formula, read at
//!   r = p.
//!
//! So the end point acts exactly as a sample "beyond" every element up to
//! and including Q. The suffix sweep gives element P the terms
//! A_PᵀF_b + B_Pᵀτ_b over the samples strictly beyond P, with
//! (A_P − [r]×B_P)ᵀF = A_PᵀF + B_Pᵀ(r × F); hence [`add_end_point_force`]
//! adds, to element Q's data:
//!
//! - F to `force_sum` and p × F to `torque_sum`: the suffix sums carry it
//!   to every P < Q (they are added after element Q's own terms are read);
//! - a_QᵀF = A_QᵀF + B_Qᵀ(p × F) to `own_force`: element Q's own share.
//!
//! This is one rule for every element, the tip included (nothing lies
//! beyond the tip, so no element Q + 1 could carry its sums). Adding F and
//! p × F to element Q + 1's suffix sums instead, as a sample at σ = 0 of
//! element Q + 1 whose own Jacobian is zero, gives the same generalized
//! forces for Q < N − 1. `tests/batch_contact.rs` checks the result
//! against central differences of the f64 reconstruction.
//!
//! The force is explicit (its Jacobian is not in the step matrix), as in
//! the reference: the penalty's stiffness k = α ρS / h² is what keeps it
//! stable ([`crate::collision::contact`]).
//!
//! **Cost.** With no collider, [`super::BatchSystem`] branches once per
//! batch to the sweep without this stage ([`NoContact`], which compiles to
//! nothing). With one, each end point costs a lookup per lane, and the
//! three SIMD products above only when some lane is in contact.

use glam::{DVec3, Vec3};

use super::forward::FrameState;
use super::lanes::{LANES, Real};
use super::layout::{BatchModel, ElementData};
use super::vec::V3;
use crate::collision::ContactInputs;

/// A force applied at each element's end point during the forward sweep.
pub trait EndPointForce<T> {
    /// Called once element `e`'s data `el` is complete (own sums, A_Q,
    /// B_Q), with `end` the state at its end point.
    fn at_end(&mut self, e: usize, end: &FrameState<T>, el: &mut ElementData<T>);
}

/// No collider: nothing happens at the end points.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoContact;

impl<T> EndPointForce<T> for NoContact {
    #[inline(always)]
    fn at_end(&mut self, _e: usize, _end: &FrameState<T>, _el: &mut ElementData<T>) {}
}

/// Adds the point force `force_n` (newtons, world axes) at `point_m` (the
/// end point of the element `el` describes, relative to the root) to the
/// element's generalized force and suffix sums; see the module docs.
#[inline(always)]
pub fn add_end_point_force<T: Real>(el: &mut ElementData<T>, point_m: V3<T>, force_n: V3<T>) {
    let torque = point_m.cross(force_n);
    el.own_force += el.a.t_mul_vec(force_n) + el.b.t_mul_vec(torque);
    el.force_sum += force_n;
    el.torque_sum += torque;
}

/// The head collider for one batch during one step: the contact inputs and
/// each lane's root position.
#[derive(Clone, Copy, Debug)]
pub struct LaneContact<'a> {
    inputs: ContactInputs<'a>,
    root_positions_m: [DVec3; LANES],
    lengths_m: &'a [f32],
    mass_per_length: f64,
}

impl<'a> LaneContact<'a> {
    /// Contact for a batch of `model`'s strands whose lane i is rooted at
    /// `root_positions_m[i]` (world, metres, at the step's start).
    pub fn new(
        inputs: ContactInputs<'a>,
        model: &'a BatchModel,
        root_positions_m: [DVec3; LANES],
    ) -> Self {
        Self {
            inputs,
            root_positions_m,
            lengths_m: &model.lengths_m,
            mass_per_length: f64::from(model.mass_per_length),
        }
    }

    /// The length element `e`'s end point stands for, metres.
    fn point_length_m(&self, e: usize) -> f64 {
        let next = self.lengths_m.get(e + 1).copied().unwrap_or(0.0);
        0.5 * f64::from(self.lengths_m[e] + next)
    }
}

impl<T: Real> EndPointForce<T> for LaneContact<'_> {
    #[inline(always)]
    fn at_end(&mut self, e: usize, end: &FrameState<T>, el: &mut ElementData<T>) {
        let length_m = self.point_length_m(e);
        let lane_vec = |x: &V3<T>, i: usize| Vec3::new(x.x.lane(i), x.y.lane(i), x.z.lane(i));
        let mut forces_n = [Vec3::ZERO; LANES];
        let mut touching = false;
        for (i, force) in forces_n.iter_mut().enumerate().take(T::WIDTH) {
            let point_m = self.root_positions_m[i] + lane_vec(&end.point_m, i).as_dvec3();
            let velocity = lane_vec(&end.point_velocity, i).as_dvec3();
            let f = self.inputs.force(point_m, velocity, self.mass_per_length);
            if f != DVec3::ZERO {
                *force = (f * length_m).as_vec3();
                touching = true;
            }
        }
        if touching {
            let force_n = V3::new(
                T::from_fn(|i| forces_n[i].x),
                T::from_fn(|i| forces_n[i].y),
                T::from_fn(|i| forces_n[i].z),
            );
            add_end_point_force(el, end.point_m, force_n);
        }
    }
}

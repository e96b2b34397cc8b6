//! Stage "collide" on the fast path: the head collider's penalty force at
//! each element's end point, folded into the suffix sums.
//!
//! # How it works
//!
//! The f64 reference ([`crate::HairSystem`]) adds the contact force per
//! unit length of [`ContactInputs::force`](crate::collision::ContactInputs::force) at every quadrature sample.
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
//! - P < Q: p lies beyond P, so ∂p/∂q_P = A_P − \[p\]×B_P, the "beyond"
//!   Jacobian every sample past P has (see [`super::suffix`]);
//! - P = Q: ∂p/∂q_Q = a_Q = R_Q ∂h(ℓ_Q, k)/∂k, the element's own end
//!   Jacobian. [`super::forward::advance`] builds A_Q = R_Q·J_end + \[p\]×B_Q
//!   with this same p, so a_Q = A_Q − \[p\]×B_Q: the beyond formula, read at
//!   r = p.
//!
//! So the end point acts exactly as a sample "beyond" every element up to
//! and including Q. The suffix sweep gives element P the terms
//! A_PᵀF_b + B_Pᵀτ_b over the samples strictly beyond P, with
//! (A_P − \[r\]×B_P)ᵀF = A_PᵀF + B_Pᵀ(r × F); hence [`add_end_point_force`]
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
//! **Implicit on Exact, as in the reference.** On the Exact steps
//! ([`LaneContact::new`] with `implicit`), the force is the reference's
//! implicit one ([`ContactInputs::implicit_force`](crate::collision::ContactInputs::implicit_force)): the predicted push
//! k (skin − d − h v_rel·n) − c v_rel·n on the right-hand side, and its
//! derivative in Δv, h (h k + c) ℓ aᵀ n nᵀ a on the left, with α =
//! [`ContactSettings::implicit_stiffness_ratio`](crate::collision::ContactSettings)
//! (4, sixteen times the explicit penalty's). The end point is a point
//! "beyond" every element up to and including Q, so that term is a point
//! inertia K = a aᵀ at the end point, a = n √(h (h k + c) ℓ)
//! ([`ElementData::contact_axis`]): with local moments the tip-to-root
//! elimination of [`crate::batch::step::exact`] holds its articulated inertia about
//! that very point when it reaches element Q, and K enters it as H_aa −= K
//! (H carries the inertia with a minus sign). The elimination is then
//! still exact, O(N), and the velocity-implicit step's GMRES, whose
//! preconditioner is that elimination, gets the contact in its operator and
//! its preconditioner alike (A z = v + h G z holds as before, since P now
//! includes K). Block-diagonal keeps the explicit penalty k = α ρS / h²
//! with α = 0.25 ([`crate::collision::contact`]): its truncated inertia
//! has no articulated sweep to put K in.
//!
//! **Cost.** With no collider, [`super::BatchSystem`] branches once per
//! batch to the sweep without this stage ([`NoContact`], which compiles to
//! nothing). With one, each lane's end point is first taken into the
//! field's grid and tested against [`NearCells`], one bit per grid cell
//! that says whether any point of the cell can be within the skin; only
//! points that pass pay for the full lookup (eight grid values, the
//! gradient, the force). The test is exact: a point it skips has a force
//! of exactly zero, so results do not depend on it. The three SIMD
//! products above run only when some lane of the batch is in contact.
//! Measured (docs/gpu.md): about a third of the step's time with 6% of
//! end points in contact.

pub mod lane_screen;
pub mod near_cells;

use glam::{DVec3, Vec3};

use super::forward::{EndPointForce, FrameState};
use super::lane_model::LaneModel;
use super::lanes::{LANES, Real};
use super::layout::ElementData;
use super::vec::V3;
use crate::batch::contact::lane_screen::LaneScreen;
pub use crate::batch::contact::near_cells::{NearCells, SkinTest};

/// Adds the point force `force_n` (newtons, world axes) at `point_m` (the
/// end point of the element `el` describes, relative to the root) to the
/// element's generalized force and suffix sums; see the module docs.
#[inline(always)]
///
/// With `LOCAL` moments A_Q is about the end point itself, so the
/// generalized force is A_QᵀF alone (the same number:
/// (A − \[p\]×B)ᵀF = AᵀF + Bᵀ(p × F) about the root), and the torque is
/// about the element's start, `span` × F.
pub fn add_end_point_force<T: Real, const LOCAL: bool>(
    el: &mut ElementData<T>,
    point_m: V3<T>,
    force_n: V3<T>,
) {
    if LOCAL {
        el.own_force += el.a.t_mul_vec(force_n);
        el.torque_sum += el.span.cross(force_n);
    } else {
        let torque = point_m.cross(force_n);
        el.own_force += el.a.t_mul_vec(force_n) + el.b.t_mul_vec(torque);
        el.torque_sum += torque;
    }
    el.force_sum += force_n;
}

/// The head collider for one batch during one step: the contact inputs and
/// each lane's root position.
#[derive(Clone, Copy, Debug)]
pub struct LaneContact<'a> {
    test: SkinTest<'a>,
    /// The batch's screen ahead of `test` ([`crate::batch::contact::lane_screen`]).
    screen: LaneScreen,
    root_positions_m: [DVec3; LANES],
    model: &'a LaneModel,
    /// Whether the contact is implicit (Exact) or the explicit penalty.
    implicit: bool,
}

impl<'a> LaneContact<'a> {
    /// Contact for a batch of strands (lane i's constants: lane i of
    /// `model`) whose lane i is rooted at `root_positions_m[i]` (world,
    /// metres, at the step's start); `test` screens the points
    /// ([`SkinTest`]). `implicit`: the Exact steps' implicit contact (see
    /// the module docs); otherwise the explicit penalty.
    pub fn new(
        test: SkinTest<'a>,
        model: &'a LaneModel,
        root_positions_m: [DVec3; LANES],
        implicit: bool,
    ) -> Self {
        Self {
            test,
            screen: LaneScreen::new(&test, &root_positions_m),
            root_positions_m,
            model,
            implicit,
        }
    }

    /// The length element `e`'s end point stands for in lane `lane`,
    /// metres.
    fn point_length_m(&self, e: usize, lane: usize) -> f64 {
        let lengths = &self.model.lengths_m;
        let next = lengths.get(e + 1).map_or(0.0, |l| l.lane(lane));
        0.5 * f64::from(lengths[e].lane(lane) + next)
    }
}

impl<T: Real> EndPointForce<T> for LaneContact<'_> {
    #[inline(always)]
    fn at_end<const LOCAL: bool>(
        &mut self,
        e: usize,
        end: &FrameState<T>,
        el: &mut ElementData<T>,
    ) {
        let lane_vec = |x: &V3<T>, i: usize| Vec3::new(x.x.lane(i), x.y.lane(i), x.z.lane(i));
        // Implicit contact needs the elimination's frame at the end point.
        let implicit = self.implicit && LOCAL;
        let mut forces_n = [Vec3::ZERO; LANES];
        let mut axes = [Vec3::ZERO; LANES];
        let mut touching = false;
        let inputs = &self.test.inputs;
        let h = inputs.h_secs;
        let screened =
            self.screen
                .may_feel(self.test.near, end.point_m, end.point_velocity, implicit);
        if screened == 0 {
            return;
        }
        for (i, (force, axis)) in forces_n
            .iter_mut()
            .zip(&mut axes)
            .enumerate()
            .take(T::WIDTH)
        {
            if screened & (1 << i) == 0 {
                continue;
            }
            let point_m = self.root_positions_m[i] + lane_vec(&end.point_m, i).as_dvec3();
            let velocity = lane_vec(&end.point_velocity, i).as_dvec3();
            if !self.test.may_feel(point_m, velocity, implicit) {
                continue;
            }
            let rho_s = f64::from(self.model.mass_per_length.lane(i));
            let length_m = self.point_length_m(e, i);
            if implicit {
                if let Some(push) = inputs.implicit_force(point_m, velocity, rho_s) {
                    *force = (push.force_n_per_m * length_m).as_vec3();
                    *axis = (push.normal * (h * push.gain * length_m).sqrt()).as_vec3();
                    touching = true;
                }
            } else {
                let f = inputs.force(point_m, velocity, rho_s);
                if f != DVec3::ZERO {
                    *force = (f * length_m).as_vec3();
                    touching = true;
                }
            }
        }
        if touching {
            let lanes = |v: &[Vec3; LANES]| {
                V3::new(
                    T::from_fn(|i| v[i].x),
                    T::from_fn(|i| v[i].y),
                    T::from_fn(|i| v[i].z),
                )
            };
            add_end_point_force::<T, LOCAL>(el, end.point_m, lanes(&forces_n));
            el.contact_axis = lanes(&axes);
        }
    }
}

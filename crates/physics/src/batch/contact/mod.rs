//! Stage "collide" on the fast path: the head collider's implicit contact
//! at every quadrature sample, the reference's law.
//!
//! # How it works
//!
//! Both engines step one contact law: at each quadrature sample within
//! the skin (or about to enter it during the step), the predicted push of
//! [`ContactInputs::implicit_force`](crate::collision::ContactInputs::implicit_force)
//! on the right-hand side, k (skin − d − h v_rel·n) − c v_rel·n along the
//! field's normal n, and its derivative in Δv on the left: the step matrix
//! gains w ℓ h (h k + c) Jᵀ n nᵀ J for the sample, a point inertia a aᵀ
//! (a = n √(w ℓ h (h k + c))) that moves with the sample. α =
//! [`ContactSettings::implicit_stiffness_ratio`](crate::collision::ContactSettings)
//! sets k = α ρS / h² and c = 2 √α ρS / h.
//!
//! [`LaneContact`] is the forward sweep's hook ([`super::forward::EndPointForce`]):
//! [`super::forward::own_sums_into`] asks it at each sample (position
//! relative to the lane's root, world velocity) and adds the push to the
//! sample's force per unit length, like gravity's, so the suffix sums carry
//! it to every element before. The point inertia enters the step matrix in
//! three places, all from ψ = Jᵀ a and φ = (a, d × a) (d the sample's
//! offset from the element's start with local moments, else from the root):
//!
//! - element Q's own block D_Q gains ψ ψᵀ, and its couplings to the
//!   parent's rigid motion U_Q, V_Q gain a ψᵀ and (d × a) ψᵀ (taken over
//!   the mass scale s there, since the steps scale those by s and the
//!   contact is no mass);
//! - the rigid motion of element Q's start frame gains Σ φ φᵀ
//!   ([`ContactInertia`](super::layout::ContactInertia)): the Exact elimination subtracts it from the
//!   articulated inertia H (which holds inertia with a minus sign) once it
//!   has moved H to element Q's start, so every element before sees the
//!   sample as it sees the subtree's mass; Block-diagonal carries it tip
//!   to root beside the suffix sums and adds [A; B]ᵀ (Σ φ φᵀ) [A; B] to each
//!   block, keeping the diagonal blocks of the whole matrix as the
//!   reference's Block-diagonal does.
//!
//! The elimination stays exact and O(N), and the velocity-implicit step's
//! GMRES gets the contact in its operator and its preconditioner alike.
//! `tests/batch_contact.rs` checks one step against the f64 reference's
//! step, which adds the same terms at the same samples
//! ([`crate::step::mass::add_sample_weights`]).
//!
//! **Cost.** With no collider, [`super::BatchSystem`] branches once per
//! batch to the sweep without this stage ([`NoContact`](super::forward::NoContact), which compiles to
//! nothing). With one, each lane's sample is first taken into the field's
//! grid and tested against [`NearCells`], one bit per grid cell that says
//! whether any point of the cell can be within the skin; only points that
//! pass pay for the full lookup (eight grid values, the gradient, the
//! force). The test is exact: a point it skips has a force of exactly
//! zero, so results do not depend on it. The point-inertia products run
//! only for samples where some lane of the batch is in contact.

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

/// The head collider for one batch during one step: the contact inputs and
/// each lane's root position.
#[derive(Clone, Copy, Debug)]
pub struct LaneContact<'a> {
    test: SkinTest<'a>,
    /// The batch's screen ahead of `test` ([`crate::batch::contact::lane_screen`]).
    screen: LaneScreen,
    root_positions_m: [DVec3; LANES],
    model: &'a LaneModel,
}

impl<'a> LaneContact<'a> {
    /// Contact for a batch of strands (lane i's constants: lane i of
    /// `model`) whose lane i is rooted at `root_positions_m[i]` (world,
    /// metres, at the step's start); `test` screens the points
    /// ([`SkinTest`]).
    pub fn new(test: SkinTest<'a>, model: &'a LaneModel, root_positions_m: [DVec3; LANES]) -> Self {
        Self {
            test,
            screen: LaneScreen::new(&test, &root_positions_m),
            root_positions_m,
            model,
        }
    }
}

impl<T: Real> EndPointForce<T> for LaneContact<'_> {
    const SAMPLE_CONTACT: bool = true;

    #[inline(always)]
    fn at_end<const LOCAL: bool>(
        &mut self,
        _e: usize,
        _end: &FrameState<T>,
        _el: &mut ElementData<T>,
    ) {
    }

    #[inline(always)]
    fn sample_contact(
        &self,
        _e: usize,
        _j: usize,
        r: V3<T>,
        velocity: V3<T>,
    ) -> Option<(V3<T>, V3<T>)> {
        let screened = self.screen.may_feel(self.test.near, r, velocity, true);
        if screened == 0 {
            return None;
        }
        let lane_vec = |x: &V3<T>, i: usize| Vec3::new(x.x.lane(i), x.y.lane(i), x.z.lane(i));
        let mut pushes = [Vec3::ZERO; LANES];
        let mut axes = [Vec3::ZERO; LANES];
        let mut touching = false;
        let inputs = &self.test.inputs;
        let h = inputs.h_secs;
        for (i, (push, axis)) in pushes.iter_mut().zip(&mut axes).enumerate().take(T::WIDTH) {
            if screened & (1 << i) == 0 {
                continue;
            }
            let point_m = self.root_positions_m[i] + lane_vec(&r, i).as_dvec3();
            let point_velocity = lane_vec(&velocity, i).as_dvec3();
            if !self.test.may_feel(point_m, point_velocity, true) {
                continue;
            }
            let rho_s = f64::from(self.model.mass_per_length.lane(i));
            if let Some(contact) = inputs.implicit_force(point_m, point_velocity, rho_s) {
                *push = contact.force_n_per_m.as_vec3();
                *axis = (contact.normal * (h * contact.gain).sqrt()).as_vec3();
                touching = true;
            }
        }
        touching.then(|| {
            let lanes = |v: &[Vec3; LANES]| {
                V3::new(
                    T::from_fn(|i| v[i].x),
                    T::from_fn(|i| v[i].y),
                    T::from_fn(|i| v[i].z),
                )
            };
            (lanes(&pushes), lanes(&axes))
        })
    }
}

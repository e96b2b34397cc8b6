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
//! [`LaneContact`] is the forward sweep's hook ([`super::forward::SampleHook`]):
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
//! grid and tested against [`NearCells`], per grid cell the lowest distance
//! any point of it has from the surface, less the sample's reach over the
//! step; only points that can reach the skin pay for the full lookup (eight grid values, the gradient, the
//! force). The test is exact: a point it skips has a force of exactly
//! zero, so results do not depend on it. The point-inertia products run
//! only for samples where some lane of the batch is in contact.

pub mod lane_screen;
pub mod near_cells;

use glam::{DVec3, Vec3};

use super::forward::SampleHook;
use super::lanes::{LANES, Lanes, Real};
use super::vec::V3;
use crate::batch::contact::lane_screen::LaneScreen;
pub use crate::batch::contact::near_cells::{NearCells, SkinTest};
use crate::collision::contact::ImplicitContact;

/// The head collider for one batch during one step: the contact inputs,
/// each lane's root position and mass per length.
#[derive(Clone, Copy, Debug)]
pub struct LaneContact<'a> {
    test: SkinTest<'a>,
    /// The batch's screen ahead of `test` ([`crate::batch::contact::lane_screen`]).
    screen: LaneScreen,
    root_positions_m: [DVec3; LANES],
    /// ρS of each lane's strand, kg/m.
    mass_per_length: Lanes,
}

impl<'a> LaneContact<'a> {
    /// Contact for a batch of strands whose lane i has mass per length
    /// lane i of `mass_per_length` (kg/m) and is rooted at
    /// `root_positions_m[i]` (world, metres, at the step's start); `test`
    /// screens the points ([`SkinTest`]).
    pub fn new(
        test: SkinTest<'a>,
        mass_per_length: Lanes,
        root_positions_m: [DVec3; LANES],
    ) -> Self {
        Self {
            test,
            screen: LaneScreen::new(&test, &root_positions_m),
            root_positions_m,
            mass_per_length,
        }
    }

    /// The lanes among `lanes` (a bit mask) on whose point `r` (relative
    /// to the lane's root, metres) moving at `velocity` (world, m/s) the
    /// implicit contact acts, as a bit mask; `touch(i, contact)` gets each
    /// one's contact. Screened in lanes first, then lane by lane as exactly
    /// as the lookup ([`SkinTest::may_feel`]), so a skipped point has no
    /// contact at all. The step's hook and the guard's test of a frame's
    /// end both ask this.
    #[inline(always)]
    pub fn touching<T: Real>(
        &self,
        r: V3<T>,
        velocity: V3<T>,
        lanes: u32,
        mut touch: impl FnMut(usize, ImplicitContact),
    ) -> u32 {
        let screened = self.screen.may_feel(self.test.near, r, velocity, true) & lanes;
        if screened == 0 {
            return 0;
        }
        let lane_vec = |x: &V3<T>, i: usize| {
            DVec3::new(
                f64::from(x.x.lane(i)),
                f64::from(x.y.lane(i)),
                f64::from(x.z.lane(i)),
            )
        };
        let mut found = 0;
        for i in (0..T::WIDTH).filter(|i| screened & (1 << i) != 0) {
            let point_m = self.root_positions_m[i] + lane_vec(&r, i);
            let point_velocity = lane_vec(&velocity, i);
            if !self.test.may_feel(point_m, point_velocity, true) {
                continue;
            }
            let rho_s = f64::from(self.mass_per_length.lane(i));
            if let Some(contact) = self
                .test
                .inputs
                .implicit_force(point_m, point_velocity, rho_s)
            {
                touch(i, contact);
                found |= 1 << i;
            }
        }
        found
    }
}

impl<T: Real> SampleHook<T> for LaneContact<'_> {
    const SAMPLE_CONTACT: bool = true;

    #[inline(always)]
    fn sample_contact(
        &self,
        _e: usize,
        _j: usize,
        r: V3<T>,
        velocity: V3<T>,
    ) -> Option<(V3<T>, V3<T>)> {
        let mut pushes = [Vec3::ZERO; LANES];
        let mut axes = [Vec3::ZERO; LANES];
        let h = self.test.inputs.h_secs;
        let found = self.touching(r, velocity, u32::MAX, |i, contact| {
            pushes[i] = contact.force_n_per_m.as_vec3();
            axes[i] = (contact.normal * (h * contact.gain).sqrt()).as_vec3();
        });
        (found != 0).then(|| {
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

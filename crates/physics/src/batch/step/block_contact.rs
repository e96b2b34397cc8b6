//! The head's contact between elements, which Block-diagonal's blocks
//! leave out: the product (C − C_bd) x for its velocity-implicit GMRES.
//!
//! # Why
//!
//! The implicit contact adds C = Σ_samples h(hk + c) w Jᵀ n nᵀ J to the
//! step matrix ([`crate::batch::contact`]). Exact eliminates the whole of
//! it; Block-diagonal's blocks hold only its diagonal blocks C_bd, so for
//! the joint motion of several elements (a curl rolling over the scalp)
//! the contact is explicit, and its stiffness k · h² against the blocks'
//! mass is far past explicit stability: measured on the curly preset on
//! a still head, the guard stepped in on both engines (a strand reset at
//! t = 1.77 s on the batch engine). The seed keeps the diagonal blocks of
//! the *mass* matrix for speed; nothing in its argument asks to drop the
//! contact's coupling, which costs two light sweeps per GMRES product
//! and is zero wherever no sample touches.
//!
//! # How it works
//!
//! The samples of element k move with the twist of the elements before
//! it (their own element's share is left out of C, as the elimination
//! and the blocks leave it: [`crate::batch::layout::ElementData::contact`]).
//! Root to tip, the twist (u, ω) of x is carried from each element's
//! start point to its end (u += ω × span) and gains the element's own
//! (A x_e, B x_e); element k's samples turn the twist at its start into
//! a wrench through their point inertias, (f, τ) = H_k (u, ω). Tip to
//! root, the wrenches of the samples past each element are summed about
//! its end point (τ += span × f as the origin moves back), and
//! (C x)_e = Aᵀ f + Bᵀ τ. The diagonal share C_bd x_e is the element's
//! block of the contact past it (`ContactInertia::project`), the
//! matrix the blocks already hold, recorded as the blocks are made
//! ([`super::block_diagonal::blocks_tip_to_root`]).

use crate::batch::lanes::Real;
use crate::batch::layout::ElementData;
use crate::batch::vec::{M3, V3};

/// Whether any element of the batch has a sample in contact this step
/// (no coupling to add otherwise).
pub fn any_touching<T>(scratch: &[ElementData<T>]) -> bool {
    scratch.iter().any(|el| el.touching)
}

/// out_e += ((C − C_bd) x)_e · `scale` for every element (module docs);
/// `diagonal` each element's C_bd as
/// [`super::block_diagonal::blocks_tip_to_root`] hands it, `force` and
/// `torque` buffers of N entries for the wrench of each element's own
/// samples.
pub fn add_contact_coupling<T: Real>(
    scratch: &[ElementData<T>],
    diagonal: &[M3<T>],
    x: &[V3<T>],
    scale: T,
    force: &mut [V3<T>],
    torque: &mut [V3<T>],
    out: &mut [V3<T>],
) {
    // Root to tip: the twist of x at each element's start point, and the
    // wrench it makes at the element's own samples (about that point).
    let (mut linear, mut angular) = (V3::zero(), V3::zero());
    for (e, el) in scratch.iter().enumerate() {
        (force[e], torque[e]) = if el.touching {
            let [aa, ab, ba, bb] = &el.contact.blocks;
            (
                aa.mul_vec_add(linear, ab.mul_vec(angular)),
                ba.mul_vec_add(linear, bb.mul_vec(angular)),
            )
        } else {
            (V3::zero(), V3::zero())
        };
        linear = linear + angular.cross(el.span) + el.a.mul_vec(x[e]);
        angular += el.b.mul_vec(x[e]);
    }
    // Tip to root: the wrench of the samples past e about e's end point.
    let (mut f, mut tau) = (V3::zero(), V3::zero());
    for e in (0..scratch.len()).rev() {
        let el = &scratch[e];
        let whole = el.a.t_mul_vec_add(f, el.b.t_mul_vec(tau));
        let coupling = whole - diagonal[e].mul_vec(x[e]);
        out[e] = coupling.scale_add(scale, out[e]);
        tau = tau + el.span.cross(f) + torque[e];
        f += force[e];
    }
}

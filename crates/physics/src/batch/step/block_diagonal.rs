//! Block-diagonal step of a batch (the seed paper's method, "subtree"
//! reading; see [`crate::step::solve::block_diagonal`]): one root-to-tip sweep
//! ([`crate::batch::forward`]), then one tip-to-root sweep that accumulates the
//! suffix sums and, element by element, solves the 3×3 block
//! (s M_QQ + D) Δv = rhs and integrates. Two passes over the strand, no
//! third: each element's block needs only the sums past it. The head's
//! implicit contact at the samples past the element joins its block as
//! the reference's does (crate::batch::contact): Block-diagonal keeps the
//! diagonal blocks of the whole step matrix, contact included.

use crate::batch::forward::SampleHook;
use crate::batch::forward::forward_with;
use crate::batch::lane_model::Constants;
use crate::batch::lanes::Real;
use crate::batch::layout::{ContactInertia, ElementData, RootMotion, StepEnv};
use crate::batch::suffix::{Beyond, element_terms, integrate, mass_scale, step_terms};
use crate::batch::vec::V3;

/// One Block-diagonal step of every lane's strand (`scratch` has N
/// entries), with the hook's forces and the head's implicit contact at the
/// samples ([`crate::batch::contact`]), and with moments about the root or, with `LOCAL`,
/// about each element's own points ([`crate::batch::forward::forward_with`]; the
/// suffix sums then move by −span from each element to the next).
#[inline(always)]
pub fn step_block_diagonal_with<T: Real, const LOCAL: bool, H: SampleHook<T>>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    scratch: &mut [ElementData<T>],
    hook: &H,
) {
    forward_with::<T, false, LOCAL, H>(model, env, root, q, v, scratch, hook, None);
    let s =
        mass_scale(model, env) + T::splat_f64(env.h_secs) * T::splat_f64(hook.drag_rate_per_s());
    let mut beyond = Beyond::zero();
    // The implicit contact of the samples past the element, about the
    // same origin as `beyond` (crate::batch::contact); `None` until a
    // sample touches.
    let mut contact: Option<ContactInertia<T>> = None;
    for e in (0..q.len()).rev() {
        let el = &scratch[e];
        let terms = element_terms(el, &beyond);
        let (diagonal, rhs) = step_terms(model, env, e, terms.force, q[e], v[e]);
        let mut step_matrix = terms.mass_block.scale(s).add_diagonal(diagonal);
        if let Some(c) = &contact {
            step_matrix += c.project(&el.a, &el.b);
        }
        let delta_v = step_matrix.inverse() * rhs;
        integrate(env.h_secs, &mut q[e], &mut v[e], delta_v);
        if LOCAL {
            beyond.shift(-el.span);
            if let Some(c) = &mut contact {
                c.shift(-el.span);
            }
        }
        beyond.add(el);
        if el.touching {
            contact
                .get_or_insert_with(ContactInertia::zero)
                .add(&el.contact);
        }
    }
}

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
use crate::batch::step::load_stiffness::UniformLoad;
use crate::batch::suffix::{Beyond, element_terms, integrate, mass_scale, step_terms};
use crate::batch::vec::{M3, V3};

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
    let h_secs = env.h_secs;
    let drag = hook.drag_rate_per_s();
    blocks_tip_to_root::<T, LOCAL>(
        model,
        env,
        scratch,
        drag,
        q,
        v,
        None,
        None,
        |_, m, _, rhs, q, v| {
            integrate(h_secs, q, v, m.inverse() * rhs);
        },
    );
}

/// The tip-to-root sweep of a Block-diagonal step, after the forward sweep
/// filled `scratch`: element by element, from the suffix sums past it and
/// the head's contact there, its step matrix s M_QQ + D (+ contact; s with
/// the hook's extra drag rate `drag_rate_per_s`, 1/s) and
/// right-hand side (with `extra_force[e]` added to its generalized force:
/// Block-diagonal's own velocity terms, [`super::block_implicit`]) and,
/// with `loads` (`LOCAL` moments only), their stiffness in the matrix
/// ([`super::load_stiffness`]), handed
/// to `each(e, matrix, contact, rhs, q_e, v_e)` before the sums move on
/// to the element before it (`contact`: the contact's share of `matrix`,
/// C_bd, zero where no sample past the element touches;
/// [`super::block_contact`] subtracts it); moments about each element's own points with
/// `LOCAL` (the sums then move by −span from each element to the next).
#[expect(
    clippy::too_many_arguments,
    reason = "the sweep's inputs and its per-element callback"
)]
#[inline(always)]
pub fn blocks_tip_to_root<T: Real, const LOCAL: bool>(
    model: &impl Constants<T>,
    env: &StepEnv,
    scratch: &[ElementData<T>],
    drag_rate_per_s: f64,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    extra_force: Option<&[V3<T>]>,
    loads: Option<&UniformLoad<T>>,
    mut each: impl FnMut(usize, M3<T>, M3<T>, V3<T>, &mut V3<T>, &mut V3<T>),
) {
    let s = mass_scale(model, env) + T::splat_f64(env.h_secs) * T::splat_f64(drag_rate_per_s);
    // The loads' stiffness reads the suffix sums about each element's end
    // point, which only the local moments give.
    debug_assert!(
        LOCAL || loads.is_none(),
        "the loads' stiffness needs LOCAL moments"
    );
    let h_squared = T::splat_f64(env.h_secs * env.h_secs);
    let mut beyond = Beyond::zero();
    // The implicit contact of the samples past the element, about the
    // same origin as `beyond` (crate::batch::contact); `None` until a
    // sample touches.
    let mut contact: Option<ContactInertia<T>> = None;
    for e in (0..q.len()).rev() {
        let el = &scratch[e];
        let terms = element_terms(el, &beyond);
        let force = match extra_force {
            Some(extra) => terms.force + extra[e],
            None => terms.force,
        };
        let (diagonal, mut rhs) = step_terms(model, env, e, force, q[e], v[e]);
        let mut step_matrix = terms.mass_block.scale(s).add_diagonal(diagonal);
        if let Some(loads) = loads {
            let stiffness = loads.stiffness(el, &beyond).scale(h_squared);
            rhs = rhs - stiffness.mul_vec(v[e]);
            step_matrix += stiffness;
        }
        let contact_block = match &contact {
            Some(c) => {
                let block = c.project(&el.a, &el.b);
                step_matrix += block;
                block
            }
            None => M3::zero(),
        };
        each(e, step_matrix, contact_block, rhs, &mut q[e], &mut v[e]);
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

//! Exact step of a batch (and, at f64 one strand wide, of the reference
//! engine, [`crate::step::generic`]): the true step matrix solved in O(N)
//! by a tip-to-root recursion over articulated inertias, fused with the
//! suffix sums. Dense's Cholesky of the assembled matrix is its
//! independent check.
//!
//! Sweep 1 (root to tip, [`crate::batch::forward`] with U_Q and V_Q): element data.
//! Sweep 2 (tip to root): suffix sums give X_Q = U_Q + X_b, Y_Q = V_Q + Y_b
//! and M_QQ; the articulated inertia H (6×6, as four 3×3 blocks) eliminates
//! each element, W̃ = sW − H U, S̃ = sM_QQ + D − UᵀHU, H ← H + W̃ S̃⁻¹ W̃ᵀ,
//! and the right-hand side is folded the same way (r̃ = rhs − Uᵀ carried).
//! Sweep 3 (root to tip): x_Q = S̃⁻¹(r̃ − W̃ᵀ moved), moved += U x_Q, and
//! integrate. Three passes against Block-diagonal's two, and about twice the
//! arithmetic in the second.
//!
//! The pieces are public for the velocity-implicit step
//! ([`super::implicit`]): [`eliminate`] (sweeps 1 and 2),
//! [`back_substitute`] (sweep 3's solve, without integrating) and
//! [`solve_again`], which solves P x = b for a new right-hand side with
//! the elimination sweep 2 stored (b folded tip to root through W̃ and S̃⁻¹,
//! then back-substituted): two light sweeps, no 3×3 inverse, no H.

use crate::batch::forward::forward_with;
use crate::batch::forward::{NoContact, SampleHook};
use crate::batch::geometry::Coefficients;
use crate::batch::lane_model::Constants;
use crate::batch::lanes::Real;
use crate::batch::layout::{ElementData, RootMotion, StepEnv, shift_spatial_inertia};
use crate::batch::suffix::{Beyond, element_terms, integrate, mass_scale, step_terms};
use crate::batch::vec::{M3, V3};

/// What sweep 2 leaves for sweep 3, per element.
#[derive(Clone, Copy, Debug)]
pub struct Elimination<T> {
    /// W̃_Q top block (A side).
    pub w_top: M3<T>,
    /// W̃_Q bottom block (B side).
    pub w_bottom: M3<T>,
    /// S̃_Q⁻¹.
    pub s_inv: M3<T>,
    /// r̃_Q.
    pub rhs: V3<T>,
}

impl<T: Real> Elimination<T> {
    /// All zero.
    pub fn zero() -> Self {
        Self {
            w_top: M3::zero(),
            w_bottom: M3::zero(),
            s_inv: M3::zero(),
            rhs: V3::zero(),
        }
    }
}

/// One Exact step of every lane's strand; `scratch` and `elimination` have
/// N entries.
#[inline(always)]
pub fn step_exact<T: Real>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    scratch: &mut [ElementData<T>],
    elimination: &mut [Elimination<T>],
) {
    step_exact_with::<T, false, _>(model, env, root, q, v, scratch, elimination, &NoContact);
}

/// The articulated inertia H (twists to wrenches, as four 3×3 blocks) and
/// the carried wrench, moved to an origin `delta` from the current one
/// ([`shift_spatial_inertia`]; a wrench (f, τ) becomes (f, τ − δ × f)).
#[inline(always)]
fn shift_articulated<T: Real>(h: &mut [M3<T>; 4], carried: &mut [V3<T>; 2], delta: V3<T>) {
    shift_spatial_inertia(h, delta);
    carried[1] = carried[1] - delta.cross(carried[0]);
}

/// [`step_exact`] with the hook's forces and the head's implicit contact
/// at the samples ([`crate::batch::contact`]), and with moments about the root or, with
/// `LOCAL`, about each element's own points (see
/// [`crate::batch::forward::forward_with`]): then the suffix sums, H and the
/// carried wrench move by −span from each element to the next towards the
/// root, and the moved twist of sweep 3 by +span towards the tip.
#[expect(
    clippy::too_many_arguments,
    reason = "the step's buffers, as in `step_exact`, plus the hook"
)]
#[inline(always)]
pub fn step_exact_with<T: Real, const LOCAL: bool, H: SampleHook<T>>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    scratch: &mut [ElementData<T>],
    elimination: &mut [Elimination<T>],
    hook: &H,
) {
    eliminate::<T, LOCAL, H>(model, env, root, q, v, scratch, elimination, hook, None);
    back_substitute::<T, LOCAL>(scratch, elimination, |e, delta_v| {
        integrate(env.h_secs, &mut q[e], &mut v[e], delta_v);
    });
}

/// Sweeps 1 and 2 of [`step_exact_with`]: element data into `scratch`,
/// the elimination and the folded right-hand side into `elimination`.
/// Returns Σ|rhs|² per lane (the right-hand side before folding), for the
/// velocity-implicit step's stopping test. `coefficients`: the helix
/// coefficients of `q` if already evaluated ([`crate::batch::forward::forward_with`]).
#[expect(
    clippy::too_many_arguments,
    reason = "the step's buffers, as in `step_exact_with`"
)]
#[inline(always)]
pub fn eliminate<T: Real, const LOCAL: bool, H: SampleHook<T>>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    scratch: &mut [ElementData<T>],
    elimination: &mut [Elimination<T>],
    hook: &H,
    coefficients: Option<&[Coefficients<T>]>,
) -> T {
    forward_with::<T, true, LOCAL, H>(model, env, root, q, v, scratch, hook, coefficients);
    let s =
        mass_scale(model, env) + T::splat_f64(env.h_secs) * T::splat_f64(hook.drag_rate_per_s());
    let mut beyond = Beyond::zero();
    let mut h = [M3::zero(); 4];
    let mut carried = [V3::zero(); 2];
    let mut rhs_squared = T::splat(0.0);
    for e in (0..q.len()).rev() {
        let el = &scratch[e];
        let terms = element_terms(el, &beyond);
        // V_Q about the point A_Q refers to (its end, with LOCAL).
        let own_v = if LOCAL {
            el.v - M3::cross_cols(el.span, &el.u)
        } else {
            el.v
        };
        let [h_aa, h_ab, h_ba, h_bb] = &mut h;
        let [carried_a, carried_b] = &mut carried;
        let (diagonal, rhs) = step_terms(model, env, e, terms.force, q[e], v[e]);
        rhs_squared += rhs.dot(rhs);
        let hu_top = h_ab.mul_mat_add(&el.b, &h_aa.mul_mat(&el.a));
        let hu_bottom = h_bb.mul_mat_add(&el.b, &h_ba.mul_mat(&el.a));
        let w_top = (el.u + terms.x_beyond).scale_add(s, -hu_top);
        let w_bottom = (own_v + terms.y_beyond).scale_add(s, -hu_bottom);
        let hu_projected = el.b.t_mul_mat_add(&hu_bottom, &el.a.t_mul_mat(&hu_top));
        let s_tilde = terms
            .mass_block
            .scale_add(s, -hu_projected)
            .add_diagonal(diagonal);
        let s_inv = s_tilde.inverse();
        let p_top = w_top.mul_mat(&s_inv);
        let p_bottom = w_bottom.mul_mat(&s_inv);
        *h_aa = p_top.mul_mat_t_add(&w_top, h_aa);
        *h_ab = p_top.mul_mat_t_add(&w_bottom, h_ab);
        *h_ba = p_bottom.mul_mat_t_add(&w_top, h_ba);
        *h_bb = p_bottom.mul_mat_t_add(&w_bottom, h_bb);
        let r = rhs - el.b.t_mul_vec_add(*carried_b, el.a.t_mul_vec(*carried_a));
        let y = s_inv * r;
        *carried_a = w_top.mul_vec_add(y, *carried_a);
        *carried_b = w_bottom.mul_vec_add(y, *carried_b);
        elimination[e] = Elimination {
            w_top,
            w_bottom,
            s_inv,
            rhs: r,
        };
        if LOCAL {
            let delta = -el.span;
            shift_articulated(&mut h, &mut carried, delta);
            beyond.shift(delta);
        }
        if el.touching {
            // The implicit contact of this element's samples, about the
            // origin H has now (its start, or the root): point inertias
            // that move with the parent's frame as the rest of the subtree
            // does, which H holds with a minus sign (crate::batch::contact).
            for (block, contact) in h.iter_mut().zip(&el.contact.blocks) {
                *block = *block - *contact;
            }
        }
        beyond.add(el);
    }
    rhs_squared
}

/// Sweep 3 of [`step_exact_with`], root to tip: hands element e's Δv to
/// `out(e, Δv)` from the folded right-hand side in `elimination`.
#[inline(always)]
pub fn back_substitute<T: Real, const LOCAL: bool>(
    scratch: &[ElementData<T>],
    elimination: &[Elimination<T>],
    mut out: impl FnMut(usize, V3<T>),
) {
    let (mut moved_a, mut moved_b) = (V3::zero(), V3::zero());
    for (e, (el, x)) in scratch.iter().zip(elimination).enumerate() {
        if LOCAL {
            moved_a = moved_a - el.span.cross(moved_b);
        }
        let delta_v = x.s_inv
            * (x.rhs
                - x.w_bottom
                    .t_mul_vec_add(moved_b, x.w_top.t_mul_vec(moved_a)));
        moved_a = el.a.mul_vec_add(delta_v, moved_a);
        moved_b = el.b.mul_vec_add(delta_v, moved_b);
        out(e, delta_v);
    }
}

/// x = P⁻¹ b with the elimination of the last [`eliminate`] (P = s M + D,
/// the matrix it factored): the right-hand side `b` folded tip to root with
/// the stored W̃ and S̃⁻¹ (overwriting `elimination`'s folded right-hand
/// side), then [`back_substitute`]. Two light sweeps: the step matrix is
/// not formed again.
#[inline(always)]
pub fn solve_again<T: Real, const LOCAL: bool>(
    scratch: &[ElementData<T>],
    elimination: &mut [Elimination<T>],
    b: &[V3<T>],
    x: &mut [V3<T>],
) {
    let mut carried = [V3::zero(); 2];
    for e in (0..b.len()).rev() {
        let el = &scratch[e];
        let stored = &mut elimination[e];
        let [carried_a, carried_b] = &mut carried;
        let r = b[e] - el.b.t_mul_vec_add(*carried_b, el.a.t_mul_vec(*carried_a));
        let y = stored.s_inv * r;
        *carried_a = stored.w_top.mul_vec_add(y, *carried_a);
        *carried_b = stored.w_bottom.mul_vec_add(y, *carried_b);
        stored.rhs = r;
        if LOCAL {
            // The carried wrench's part of `shift_articulated`.
            carried[1] += el.span.cross(carried[0]);
        }
    }
    back_substitute::<T, LOCAL>(scratch, elimination, |e, delta_v| x[e] = delta_v);
}

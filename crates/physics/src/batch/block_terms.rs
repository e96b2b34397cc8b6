//! Block-diagonal's own velocity terms, written once for every width: the
//! correction F_true − F_bd that turns the step's forces into those of
//! Block-diagonal's own Lagrangian. Both engines run it, velocity-implicit
//! with the correction's derivative by polarisation
//! ([`crate::batch::step::block_implicit`]); the guard judges
//! Block-diagonal by T_bd + V ([`crate::batch::block_kinetic`]).
//! `tests/block_velocity_terms.rs` checks it at f64 against the truncated
//! energy's Lagrangian by differences, and at f32 against f64.
//!
//! # Why
//!
//! Block-diagonal solves with M_bd, the N diagonal 3×3 blocks M_QQ of the
//! mass matrix, but the forces stage gives it the true system's velocity
//! terms −∫ρS Jᵀ J̇q̇ ds, which belong with the whole M. The mix is no
//! mechanical system: on a strand released horizontally it gained energy
//! (docs/solvers.md). M_bd is itself symmetric positive definite, so the
//! Lagrangian with T_bd = ½ q̇ᵀ M_bd(q) q̇ and the same potential is a
//! mechanical system, and its equations
//!
//! M_bd q̈ + F_bd = Q_ext,  F_bd = Ṁ_bd q̇ − ∂T_bd/∂q,
//!
//! conserve T_bd + V with a still head (q̇ᵀF_bd = ½ q̇ᵀṀ_bd q̇ is exactly
//! what T_bd's own change needs).
//!
//! # The terms
//!
//! T_bd = Σ_Q ½ ∫_{Ω_Q} ρS |w_Q|² ds, with Ω_Q element Q and all beyond it
//! and w_Q = J_Q q̇_Q the motion element Q's rate alone gives. Then
//!
//! - Ṁ_QQ q̇_Q = ∫_{Ω_Q} ρS (J_Qᵀ J̇_Q q̇_Q + J̇_Qᵀ w_Q);
//! - ∂T_bd/∂q_Q = ∫_{Ω_Q} ρS (J_Qᵀ f_Q + (J̇_Q^own)ᵀ w_Q): an earlier
//!   element P < Q sees q_Q move its points, J_P = A_P − \[r\]×B_P changes
//!   by −\[δr\]×B_P, which gives f_Q = Σ_{P<Q} w_P × β_P (β_P = B_P q̇_P);
//!   a later element P > Q is turned rigidly by q_Q, which leaves |w_P|
//!   unchanged; and element Q itself gives J̇_Q^own = (∂J_Q/∂q_Q)[q̇_Q],
//!   the rate of J_Q from q̇_Q alone.
//!
//! Every rate is the strain rates' alone (the head's turn is taken out:
//! T_bd is defined in the root's frame). J̇_Q^own is J̇_Q
//! less the rigid turn Ω_Q × J_Q of element Q's start frame and, beyond
//! element Q, less −[v_{>Q}]× B_Q, v_{>Q} being the points' velocity
//! relative to element Q's end frame. f_Q = c_Q − (S_Q − t_Q I) r with the
//! prefix sums c_Q = Σ (A_P q̇_P) × β_P, S_Q = Σ β_P β_Pᵀ, t_Q = Σ |β_P|².
//!
//! The head's motion keeps the true system's terms (its accelerations,
//! the centrifugal ω × (ω × r) and the gyroscopic 2ω × J q̇, which does no
//! work). So the step's forces become Q + F_true − F_bd: the true
//! strain-rate terms, which Q holds as −F_true = −∫ρS Jᵀ J̇ˢq̇, are taken
//! out and Block-diagonal's own put in. This is the Lagrangian of
//! T = ½∫ρS|v_O + ω × r|² + ∫ρS (v_O + ω × r)·Jq̇ + T_bd: the true kinetic
//! energy with only its strain-strain part truncated; the head's terms all
//! come from the first two parts, which are the true system's.
//!
//! # How it works
//!
//! T_bd is defined in the root's frame, so F_bd and F_true's strain-rate
//! part depend on the strain rates alone, not on the head's motion: the
//! sweep here runs the forward kinematics ([`super::forward::advance_from_end`],
//! [`super::geometry::local_point_with`]) with the root held still (its
//! frame kept, its velocities and accelerations zero). Then at every
//! sample the acceleration with q̈ = 0 is J̇ˢq̇, the strain-rate
//! acceleration F_true projects; every velocity is a strain velocity; and
//! element Q's start frame turns at Ω_Q = Σ_{P<Q} β_P, so the
//! head terms (ω × w and the root's velocity) drop out of its formulas.
//!
//! Root to tip, per element Q, the sweep records
//!
//! - the prefix sums before Q: Ω_Q, c_Q = Σ α_P × β_P, S_Q = Σ β_P β_Pᵀ,
//!   t_Q = Σ |β_P|² (α_P = A_P q̇_P, β_P = B_P q̇_P, A about the root);
//! - A_Q, B_Q, α_Q, β_Q and their rates α̇_Q = Ȧ_Q q̇_Q (from the end
//!   point's local jet and β̇ × p + ṗ × β) and β̇_Q (the end frame's
//!   angular acceleration less the start's);
//! - its own samples' share: Jᵀ(J̇ˢq̇ − (ḧ − Rᵀ f)) with f = c_Q − S_Q r + t_Q r
//!   (own term of F_true less F_bd's, in the element's frame), the
//!   force and torque of ρS J̇ˢq̇ (F_true beyond), and the mass moments Σ m,
//!   Σ m r, Σ m ṙ, Σ m r rᵀ, Σ m ṙ rᵀ.
//!
//! Tip to root, the suffix sums give each element's beyond terms: F_true's
//! Aᵀ F + Bᵀ τ, and F_bd's Aᵀ (k₀ m + L Σr + \[β\]× Σṙ) + Bᵀ (turned), the
//! formulas of "The terms" with ω = 0 and a still root.
//!
//! Moments are taken about the root: the f32 instance's round-off is
//! measured against the f64 one in `tests/block_velocity_terms.rs`.

use super::forward::{FrameState, advance_from_end, root_jacobian};
use super::geometry::{Coefficients, local_end_with, local_point_with};
use super::lane_model::Constants;
use super::lanes::Real;
use super::layout::RootMotion;
use super::vec::{M3, V3};

/// What the root-to-tip pass leaves for element Q (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct BlockElement<T> {
    /// Ω_Q: the strain-induced turn rate of Q's start frame, rad/s.
    turn: V3<T>,
    /// c_Q = Σ_{P<Q} α_P × β_P.
    c: V3<T>,
    /// S_Q = Σ_{P<Q} β_P β_Pᵀ.
    s: M3<T>,
    /// t_Q = Σ_{P<Q} |β_P|².
    t: T,
    a: M3<T>,
    b: M3<T>,
    alpha: V3<T>,
    beta: V3<T>,
    alpha_rate: V3<T>,
    beta_rate: V3<T>,
    /// Q's end point relative to the root, m, and its strain velocity.
    end: V3<T>,
    end_velocity: V3<T>,
    /// Own samples: Σ Jᵀ(...) of F_true − F_bd, N·m².
    own: V3<T>,
    /// Own samples: Σ m J̇ˢq̇ and Σ r × m J̇ˢq̇ (F_true beyond).
    force: V3<T>,
    torque: V3<T>,
    /// Own samples' moments: Σ m, Σ m r, Σ m ṙ, Σ m r rᵀ, Σ m ṙ rᵀ.
    mass: T,
    first: V3<T>,
    velocity: V3<T>,
    second: M3<T>,
    mixed: M3<T>,
}

impl<T: Real> BlockElement<T> {
    /// All zero.
    pub fn zero() -> Self {
        let z = T::splat(0.0);
        Self {
            turn: V3::zero(),
            c: V3::zero(),
            s: M3::zero(),
            t: z,
            a: M3::zero(),
            b: M3::zero(),
            alpha: V3::zero(),
            beta: V3::zero(),
            alpha_rate: V3::zero(),
            beta_rate: V3::zero(),
            end: V3::zero(),
            end_velocity: V3::zero(),
            own: V3::zero(),
            force: V3::zero(),
            torque: V3::zero(),
            mass: z,
            first: V3::zero(),
            velocity: V3::zero(),
            second: M3::zero(),
            mixed: M3::zero(),
        }
    }
}

/// out = F_true − F_bd per element (N·m²) for the strands in state (`q`,
/// `v`) whose roots have the frame of `root`; `coefficients` are the helix
/// coefficients of `q` ([`super::velocity_terms::coefficients_of`]),
/// `buffer` holds N entries.
pub fn block_correction<T: Real>(
    model: &impl Constants<T>,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    coefficients: &[Coefficients<T>],
    buffer: &mut [BlockElement<T>],
    out: &mut [V3<T>],
) {
    let still = RootMotion {
        world_from_root: root.world_from_root,
        angular_velocity_rad_per_s: V3::zero(),
        angular_acceleration_rad_per_s2: V3::zero(),
        velocity_m_per_s: V3::zero(),
        acceleration_m_per_s2: V3::zero(),
    };
    let rho_s = model.mass_per_length();
    let per_element = model.node_count() + 1;
    let mut s = FrameState::at_root(&still);
    let (mut c, mut s_sum, mut t) = (V3::zero(), M3::zero(), T::splat(0.0));
    for ((e, el), co) in buffer
        .iter_mut()
        .enumerate()
        .zip(coefficients.chunks_exact(per_element))
    {
        let (co_nodes, co_end) = co.split_at(per_element - 1);
        let (k, k_dot) = (q[e], v[e]);
        let length_m = model.length_m(e);
        let mut sums = BlockElement::zero();
        sums.turn = s.angular_velocity;
        sums.c = c;
        sums.s = s_sum;
        sums.t = t;
        let mut own_local = V3::zero();
        for (j, co) in co_nodes.iter().enumerate() {
            let lp = local_point_with(model.node(j) * length_m, k, k_dot, *co);
            let [r, r_dot, acc] = s.carry(lp.h, lp.h_dot, lp.h_ddot);
            let m = model.weight(j) * length_m * rho_s;
            // f = c − S r + t r: the turn of the elements before, seen at r.
            let f = r.scale_add(t, c - s_sum * r);
            let own = s.frame.t_mul_vec(acc + f) - lp.h_ddot;
            own_local = lp.jacobian.t_mul_vec_add(own.scale(m), own_local);
            let acc_m = acc.scale(m);
            sums.force += acc_m;
            sums.torque += r.cross(acc_m);
            sums.mass += m;
            sums.first = r.scale_add(m, sums.first);
            sums.velocity = r_dot.scale_add(m, sums.velocity);
            sums.second = M3::outer_add(r.scale(m), r, sums.second);
            sums.mixed = M3::outer_add(r_dot.scale(m), r, sums.mixed);
        }
        sums.own = own_local;
        // The end point's local jet serves the advance and α's rate.
        let (end, turn) = local_end_with(length_m, k, k_dot, co_end[0]);
        let (next, a_end, b, _) = advance_from_end(&s, length_m, &end, &turn);
        let (p, p_dot) = (next.point_m, next.point_velocity);
        let a = root_jacobian(a_end, p, &b);
        let beta = next.angular_velocity - s.angular_velocity;
        let beta_rate = next.angular_acceleration - s.angular_acceleration;
        // α = R J_end k̇ + p × β; its rate with q̈ = 0.
        let local_velocity = s.frame * end.h_dot;
        let alpha = local_velocity + p.cross(beta);
        let alpha_rate = s.angular_velocity.cross(local_velocity)
            + s.frame * end.h_ddot
            + p_dot.cross(beta)
            + p.cross(beta_rate);
        sums.a = a;
        sums.b = b;
        sums.alpha = alpha;
        sums.beta = beta;
        sums.alpha_rate = alpha_rate;
        sums.beta_rate = beta_rate;
        sums.end = p;
        sums.end_velocity = p_dot;
        *el = sums;
        c += alpha.cross(beta);
        s_sum = M3::outer_add(beta, beta, s_sum);
        t = beta.dot_add(beta, t);
        s = next;
    }
    beyond_terms(buffer, out);
}

/// Tip to root: each element's own share plus its beyond terms from the
/// suffix sums (module docs).
fn beyond_terms<T: Real>(buffer: &[BlockElement<T>], out: &mut [V3<T>]) {
    let zero = T::splat(0.0);
    let (mut m, mut r_sum, mut v_sum) = (zero, V3::zero(), V3::zero());
    let (mut rr, mut vr) = (M3::zero(), M3::zero());
    let (mut force, mut torque) = (V3::zero(), V3::zero());
    for (el, o) in buffer.iter().zip(out.iter_mut()).rev() {
        let bx = M3::skew(el.beta);
        let k0 = el.alpha_rate - el.c - el.turn.cross(el.alpha);
        let l = (M3::skew(el.beta_rate) - M3::skew(el.turn).mul_mat(&bx) + el.s)
            .add_diagonal(V3::new(-el.t, -el.t, -el.t));
        let pulled = k0.scale(m) + l * r_sum + bx * v_sum;
        let end_turn = el.turn + el.beta;
        let d0 = end_turn.cross(el.end) - el.end_velocity;
        let nn = -M3::skew(end_turn);
        let turned = r_sum.cross(k0)
            + axial(l.mul_mat(&rr))
            + axial(bx.mul_mat(&vr))
            + v_sum.cross(el.alpha)
            + axial(bx.mul_mat_t(&vr))
            + d0.cross(el.alpha).scale(m)
            + d0.cross(bx * r_sum)
            + (nn * r_sum).cross(el.alpha)
            + axial(bx.mul_mat(&rr).mul_mat_t(&nn));
        // F_true beyond less F_bd beyond, through A_Q and B_Q.
        *o =
            el.b.t_mul_vec_add(torque - turned, el.a.t_mul_vec_add(force - pulled, el.own));
        m += el.mass;
        r_sum += el.first;
        v_sum += el.velocity;
        rr += el.second;
        vr += el.mixed;
        force += el.force;
        torque += el.torque;
    }
}

/// The axial vector of a matrix's antisymmetric part, doubled: for
/// C = M · YX · Pᵀ (YX = Σ y xᵀ), Σ (P x) × (M y).
#[inline(always)]
fn axial<T: Real>(c: M3<T>) -> V3<T> {
    V3::new(c.c1.z - c.c2.y, c.c2.x - c.c0.z, c.c0.y - c.c1.x)
}

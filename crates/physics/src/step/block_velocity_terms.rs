//! Velocity terms consistent with Block-diagonal's truncated inertia, so
//! that with a still head its own energy T_bd + V is a Lagrangian energy.
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
//! T_bd is defined in the root's frame). J̇_Q comes from the reconstruction's
//! rates ([`crate::step::reconstruct::reconstruct_with_rates`]); J̇_Q^own is J̇_Q
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
//! # Where it is used
//!
//! This is the terms' f64 statement on the assembled kinematics
//! ([`crate::step::reconstruct`]), checked against the truncated energy's
//! Lagrangian by differences (`tests/block_velocity_terms.rs`). The step
//! runs the generic code's arrangement of the same sums
//! ([`crate::batch::block_terms`], checked against this one to 2.4e-14 at
//! f64, `tests/block_terms.rs`) in both engines, velocity-implicit with the
//! correction's derivative by polarisation
//! ([`crate::batch::step::block_implicit`]). The guard judges
//! Block-diagonal by T_bd + V ([`crate::batch::block_kinetic`]).
//!
//! Cost: O(N). The sums over Ω_Q beyond element Q are polynomials of
//! degree two in r and ṙ, so five suffix moments of the samples, taken tip
//! to root, give them ([`BlockVelocityTerms::forces`]).

use glam::{DMat3, DVec3};

use crate::geometry::helix::{outer, skew};
use crate::model::StrandModel;
use crate::motion::RigidMotion;
use crate::step::forces::project_sample_forces;
use crate::step::reconstruct::Kinematics;
use crate::step::velocity_terms::jacobian_rate_times;

/// Buffers of [`BlockVelocityTerms::correction`], reused from step to step.
#[derive(Clone, Debug, Default)]
pub struct BlockVelocityTerms {
    accelerations: Vec<DVec3>,
    forces: Vec<DVec3>,
    /// Per element: Ω_Q, c_Q, S_Q, t_Q (see [`BlockVelocityTerms::forces`]).
    prefix: Vec<(DVec3, DVec3, DMat3, f64)>,
}

impl BlockVelocityTerms {
    /// out = F_bd = Ṁ_bd q̇ − ∂T_bd/∂q per element (N·m²), strain rates only,
    /// in O(N); `kin` from [`crate::step::reconstruct::reconstruct_with_rates`]: the sums over the samples beyond element Q
    /// are polynomials of degree two in r and ṙ, so five suffix moments of
    /// the samples (Σ ρSw, Σ ρSw r, Σ ρSw ṙ, Σ ρSw r rᵀ, Σ ρSw ṙ rᵀ), taken tip
    /// to root, give them. With u = k₀ + L r + \[β\]× ṙ the sample's term
    /// J̇ˢq̇_Q − f_Q − Ω_Q × w_Q and v_{>Q} = ṙ + d₀ + N r:
    /// Σu = m k₀ + L R + \[β\]× V, and Σ r × u + v_{>Q} × w_Q by `cross_sum`.
    pub fn forces(
        &mut self,
        model: &StrandModel,
        kin: &Kinematics,
        v: &[DVec3],
        root: &RigidMotion,
        out: &mut [DVec3],
    ) {
        let n = v.len();
        let points = model.quadrature.len();
        let rho_s = model.mass_per_length;
        let omega = root.angular_velocity_rad_per_s;
        // Root to tip: the prefix data of each element (Ω_Q, c_Q, S_Q, t_Q).
        let prefix = &mut self.prefix;
        prefix.clear();
        let (mut frame_turn, mut c, mut s_sum, mut t) =
            (DVec3::ZERO, DVec3::ZERO, DMat3::ZERO, 0.0);
        for (jac, v_q) in kin.elements.iter().zip(v) {
            prefix.push((frame_turn, c, s_sum, t));
            let beta = jac.b * *v_q;
            c += (jac.a * *v_q).cross(beta);
            s_sum += outer(beta, beta);
            t += beta.length_squared();
            frame_turn += beta;
        }
        // Tip to root: suffix moments of the samples beyond element Q.
        let (mut m, mut r_sum, mut v_sum) = (0.0, DVec3::ZERO, DVec3::ZERO);
        let (mut rr, mut vr) = (DMat3::ZERO, DMat3::ZERO);
        for q in (0..n).rev() {
            let (frame_turn, c, s_sum, t) = prefix[q];
            let jac = &kin.elements[q];
            let rates = &kin.element_rates[q];
            let v_q = v[q];
            let (alpha, beta) = (jac.a * v_q, jac.b * v_q);
            let (alpha_rate, beta_rate) = (rates.a * v_q, rates.b * v_q);
            let end = kin.points_m[q + 1];
            let end_velocity = strain_velocity(end, kin.point_velocities_m_per_s[q + 1], root);
            let end_turn = frame_turn + beta;
            let mut force = DVec3::ZERO;
            // Element Q's own samples, directly.
            for i in q * points..(q + 1) * points {
                let s = &kin.samples[i];
                let r = s.position_m;
                let f = c - s_sum * r + r * t;
                let j = s.jacobian;
                let w = j * v_q;
                let w_rate = kin.jacobian_rates[i] * v_q - omega.cross(w);
                force += j.transpose() * (w_rate - f - frame_turn.cross(w)) * (rho_s * s.weight_m);
            }
            // Beyond it, from the moments.
            let bx = skew(beta);
            let k0 = alpha_rate - omega.cross(alpha) - c - frame_turn.cross(alpha);
            let l = skew(beta_rate) - skew(omega + frame_turn) * bx + s_sum
                - DMat3::from_diagonal(DVec3::splat(t));
            let pulled = k0 * m + l * r_sum + bx * v_sum;
            let d0 = -root.velocity_m_per_s - end_velocity + end_turn.cross(end);
            let nn = -skew(omega + end_turn);
            let id = DMat3::IDENTITY;
            let turned = r_sum.cross(k0)
                + cross_sum(id, l, rr)
                + cross_sum(id, bx, vr)
                + v_sum.cross(alpha)
                + cross_sum(id, bx, vr.transpose())
                + d0.cross(alpha) * m
                + d0.cross(bx * r_sum)
                + (nn * r_sum).cross(alpha)
                + cross_sum(nn, bx, rr);
            force += jac.a.transpose() * pulled + jac.b.transpose() * turned;
            out[q] = force;
            for s in &kin.samples[q * points..(q + 1) * points] {
                let w = rho_s * s.weight_m;
                let (r, rd) = (s.position_m, s.velocity_m_per_s);
                m += w;
                r_sum += r * w;
                v_sum += rd * w;
                rr += outer(r, r) * w;
                vr += outer(rd, r) * w;
            }
        }
    }

    /// out = F_true − F_bd (N·m² per element): what turns the step's forces
    /// into Block-diagonal's Lagrangian ones. `kin` must come from
    /// [`crate::step::reconstruct::reconstruct_with_rates`] for rates `v`.
    pub fn correction(
        &mut self,
        model: &StrandModel,
        kin: &Kinematics,
        v: &[DVec3],
        root: &RigidMotion,
        out: &mut [DVec3],
    ) {
        let rho_s = model.mass_per_length;
        // F_true = ∫ρS Jᵀ J̇ˢq̇, J̇ˢq̇ = J̇q̇ − ω × Jq̇ (strain rates only).
        strain_rate_accelerations(model, kin, v, root, &mut self.accelerations);
        project_sample_forces(
            model,
            kin,
            |i| self.accelerations[i] * (rho_s * kin.samples[i].weight_m),
            out,
        );
        let mut forces = std::mem::take(&mut self.forces);
        forces.resize(v.len(), DVec3::ZERO);
        self.forces(model, kin, v, root, &mut forces);
        for (o, f) in out.iter_mut().zip(&forces) {
            *o -= *f;
        }
        self.forces = forces;
    }
}

/// J̇ˢ q̇ at every sample: the acceleration quadratic in the strain rates,
/// ½ (2J̇q̇) less the head's turn ω × Jq̇.
fn strain_rate_accelerations(
    model: &StrandModel,
    kin: &Kinematics,
    v: &[DVec3],
    root: &RigidMotion,
    out: &mut Vec<DVec3>,
) {
    jacobian_rate_times(model, kin, v, out);
    let omega = root.angular_velocity_rad_per_s;
    for (a, s) in out.iter_mut().zip(&kin.samples) {
        *a = 0.5 * *a - omega.cross(strain_velocity(s.position_m, s.velocity_m_per_s, root));
    }
}

/// J q̇ of a point: its velocity less the root's rigid motion.
fn strain_velocity(r: DVec3, r_dot: DVec3, root: &RigidMotion) -> DVec3 {
    r_dot - root.velocity_m_per_s - root.angular_velocity_rad_per_s.cross(r)
}

/// Σ (P x) × (M y) over samples, from the moment YX = Σ y xᵀ:
/// the axial vector of M · YX · Pᵀ.
fn cross_sum(p: DMat3, m: DMat3, yx: DMat3) -> DVec3 {
    let c = m * yx * p.transpose();
    DVec3::new(
        c.y_axis.z - c.z_axis.y,
        c.z_axis.x - c.x_axis.z,
        c.x_axis.y - c.y_axis.x,
    )
}

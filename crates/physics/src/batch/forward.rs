//! Stages "reconstruct", "forces" and "mass" (own-element part), fused into
//! one root-to-tip sweep.
//!
//! [`advance`] carries the frame state (R, ω, α and the point with its
//! velocity and acceleration) across one element and yields its beyond
//! Jacobians A_Q, B_Q; [`own_sums`] visits the element's quadrature samples
//! from its start state and sums what the element itself contributes:
//! Σ GᵀF, D_Q = Σ wρS GᵀG, mass moments, force and torque (and U_Q, V_Q
//! for Exact). [`forward`] runs both root to tip for a whole strand (or
//! batch of strands); the GPU kernels run them as separate stages, and
//! their CPU twins call these same functions.
//!
//! Forces. The force per unit length at a sample is
//! F = ρS (g − r̈_free) − ν (ṙ − v_air): the drag acts on the full velocity.
//! The f64 reference splits it into drag on the root-carried velocity plus
//! (ν/ρS) M q̇ on the right-hand side; since J q̇ = ṙ − ṙ_carried exactly at
//! every sample, the two agree to round-off, and this form needs no
//! matrix-free product M q̇ (one sweep fewer).

use super::contact::{EndPointForce, NoContact};
use super::geometry::{local_end, local_point};
use super::lanes::Real;
use super::layout::{BatchModel, ElementData, RootMotion, StepEnv};
use super::vec::{M3, V3};

/// The frame and point at an element boundary, with time derivatives.
#[derive(Clone, Copy, Debug)]
pub struct FrameState<T> {
    /// R_Q, world from material frame.
    pub frame: M3<T>,
    /// ω, rad/s, world.
    pub angular_velocity: V3<T>,
    /// α with q̈ = 0, rad/s², world.
    pub angular_acceleration: V3<T>,
    /// p_Q relative to the root point, metres.
    pub point_m: V3<T>,
    /// ṗ_Q, m/s.
    pub point_velocity: V3<T>,
    /// p̈_Q with q̈ = 0, m/s².
    pub point_acceleration: V3<T>,
}

impl<T: Real> FrameState<T> {
    /// The state at the root.
    pub fn at_root(root: &RootMotion<T>) -> Self {
        Self {
            frame: root.world_from_root,
            angular_velocity: root.angular_velocity_rad_per_s,
            angular_acceleration: root.angular_acceleration_rad_per_s2,
            point_m: V3::zero(),
            point_velocity: root.velocity_m_per_s,
            point_acceleration: root.acceleration_m_per_s2,
        }
    }

    /// Position, velocity and acceleration of the world point p + R h for a
    /// local point with derivatives (h, ḣ, ḧ).
    #[inline(always)]
    fn carry(&self, h: V3<T>, h_dot: V3<T>, h_ddot: V3<T>) -> [V3<T>; 3] {
        let w = self.angular_velocity;
        let d = self.frame * h;
        let rel_v = self.frame * h_dot;
        let w_rel_v = w.cross(rel_v);
        [
            self.point_m + d,
            self.point_velocity + w.cross(d) + rel_v,
            self.point_acceleration
                + self.angular_acceleration.cross(d)
                + w.cross(w.cross(d))
                + w_rel_v
                + w_rel_v
                + self.frame * h_ddot,
        ]
    }
}

/// Carries `s` across element `e` with strains `k` and rates `k_dot`;
/// returns the next boundary's state and the element's (A_Q, B_Q).
#[inline(always)]
pub fn advance<T: Real>(
    s: &FrameState<T>,
    length_m: f32,
    k: V3<T>,
    k_dot: V3<T>,
) -> (FrameState<T>, M3<T>, M3<T>) {
    let (end, turn) = local_end(length_m, k, k_dot);
    let [p, pv, pa] = s.carry(end.h, end.h_dot, end.h_ddot);
    let b = s
        .frame
        .mul_mat(&turn.left_jacobian)
        .scale(T::splat(length_m));
    let a = s.frame.mul_mat(&end.jacobian) + M3::cross_cols(p, &b);
    let spin = s.frame * turn.spin;
    let next = FrameState {
        frame: s.frame.mul_mat(&turn.rotation),
        angular_velocity: s.angular_velocity + spin,
        angular_acceleration: s.angular_acceleration
            + s.angular_velocity.cross(spin)
            + s.frame * turn.spin_dot,
        point_m: p,
        point_velocity: pv,
        point_acceleration: pa,
    };
    (next, a, b)
}

/// Element `e`'s own sums from its start state `s`; `a` and `b` are left
/// zero. With `OFF_DIAGONAL` it also sums U_Q and V_Q (Exact needs them).
#[inline(always)]
pub fn own_sums<T: Real, const OFF_DIAGONAL: bool>(
    model: &BatchModel,
    env: &StepEnv,
    e: usize,
    s: &FrameState<T>,
    k: V3<T>,
    k_dot: V3<T>,
) -> ElementData<T> {
    let length_m = model.lengths_m[e];
    let rho_s = T::splat(model.mass_per_length);
    let nu = T::splat(model.air_drag);
    let g = V3::splat(env.gravity_m_per_s2);
    let air = V3::splat(env.air_velocity_m_per_s);
    let mut el = ElementData::zero();
    for (node, weight) in model.nodes.iter().zip(&model.weights) {
        let lp = local_point(node * length_m, k, k_dot);
        let [r, vel, acc] = s.carry(lp.h, lp.h_dot, lp.h_ddot);
        let w_len = T::splat(weight * length_m);
        let w_mass = w_len * rho_s;
        let force = ((g - acc).scale(rho_s) - (vel - air).scale(nu)).scale(w_len);
        let jac = s.frame.mul_mat(&lp.jacobian);
        let jac_w = jac.scale(w_mass);
        el.own_force += jac.t_mul_vec(force);
        el.force_sum += force;
        el.torque_sum += r.cross(force);
        el.own_mass_block += jac_w.t_mul_mat(&jac);
        el.mass += w_mass;
        el.first_moment += r.scale(w_mass);
        let r_w = r.scale(w_mass);
        el.inertia += (M3::outer(r_w, r).scale(T::splat(-1.0))).add_diagonal(V3::new(
            r_w.dot(r),
            r_w.dot(r),
            r_w.dot(r),
        ));
        if OFF_DIAGONAL {
            el.u += jac_w;
            el.v += M3::cross_cols(r, &jac_w);
        }
    }
    el
}

/// The whole root-to-tip sweep: `out[e]` gets element e's data.
#[inline(always)]
pub fn forward<T: Real, const OFF_DIAGONAL: bool>(
    model: &BatchModel,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    out: &mut [ElementData<T>],
) {
    forward_with::<T, OFF_DIAGONAL, _>(model, env, root, q, v, out, &mut NoContact);
}

/// [`forward`] with a force at each element's end point (stage "collide",
/// [`super::contact`]).
#[inline(always)]
pub fn forward_with<T: Real, const OFF_DIAGONAL: bool, H: EndPointForce<T>>(
    model: &BatchModel,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    out: &mut [ElementData<T>],
    end_force: &mut H,
) {
    let mut s = FrameState::at_root(root);
    for (e, el) in out.iter_mut().enumerate() {
        *el = own_sums::<T, OFF_DIAGONAL>(model, env, e, &s, q[e], v[e]);
        let (next, a, b) = advance(&s, model.lengths_m[e], q[e], v[e]);
        el.a = a;
        el.b = b;
        end_force.at_end(e, &next, el);
        s = next;
    }
}

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

use super::geometry::{
    Coefficients, LocalPoint, LocalTurn, coefficients_at, local_end_with, local_point,
    local_point_with,
};
use super::lane_model::Constants;
use super::lanes::Real;
use super::layout::{ContactInertia, ElementData, RootMotion, StepEnv};
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
    pub fn carry(&self, h: V3<T>, h_dot: V3<T>, h_ddot: V3<T>) -> [V3<T>; 3] {
        let w = self.angular_velocity;
        let d = self.frame * h;
        let rel_v = self.frame * h_dot;
        let w_rel_v = w.cross(rel_v);
        [
            self.point_m + d,
            self.point_velocity + w.cross(d) + rel_v,
            self.frame.mul_vec_add(
                h_ddot,
                self.point_acceleration
                    + self.angular_acceleration.cross(d)
                    + w.cross(w.cross(d))
                    + w_rel_v
                    + w_rel_v,
            ),
        ]
    }
}

/// The quadrature samples of strands in state (`q`, `v`) with roots moving
/// as `root`, root to tip: for each element e, `sample(e, j, r, ṙ)` at its
/// node j (r relative to the root, ṙ world velocity), then
/// `element_end(e, s)` with the state at its end point. The guard's
/// measure ([`super::guard::measure_lanes`]) and the hair–hair model's
/// gather ([`super::volume::gather_batch`]) both sweep with it, so the
/// samples the measure keeps for the gather are the gather's own bits.
#[inline(always)]
pub fn sweep_samples<T: Real>(
    model: &impl Constants<T>,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    mut sample: impl FnMut(usize, usize, V3<T>, V3<T>),
    mut element_end: impl FnMut(usize, &FrameState<T>),
) {
    let mut s = FrameState::at_root(root);
    for (e, (k, k_dot)) in q.iter().zip(v).enumerate() {
        let length_m = model.length_m(e);
        for j in 0..model.node_count() {
            let lp = local_point(model.node(j) * length_m, *k, *k_dot);
            let [r, vel, _] = s.carry(lp.h, lp.h_dot, lp.h_ddot);
            sample(e, j, r, vel);
        }
        s = advance(&s, length_m, *k, *k_dot).0;
        element_end(e, &s);
    }
}

/// Carries `s` across element `e` with strains `k` and rates `k_dot`;
/// returns the next boundary's state and the element's (A_Q, B_Q).
#[inline(always)]
pub fn advance<T: Real>(
    s: &FrameState<T>,
    length_m: T,
    k: V3<T>,
    k_dot: V3<T>,
) -> (FrameState<T>, M3<T>, M3<T>) {
    let (next, a_local, b, _) = advance_local(s, length_m, k, k_dot);
    (next, root_jacobian(a_local, next.point_m, &b), b)
}

/// A_Q about the root from A_Q about the element's end point `end_m`
/// (relative to the root): moving the origin back by p_end gives
/// A = A_end + \[p_end\]×B.
#[inline(always)]
pub fn root_jacobian<T: Real>(a_local: M3<T>, end_m: V3<T>, b: &M3<T>) -> M3<T> {
    a_local + M3::cross_cols(end_m, b)
}

/// [`advance`] with A_Q taken about the element's end point instead of the
/// root: a_Q = R J_end (so J = a_Q − [r − p_end]×B_Q beyond the element);
/// the last value is the span R h(ℓ), end point minus start point, metres
/// (computed, not differenced, so it keeps f32's relative precision).
#[inline(always)]
pub fn advance_local<T: Real>(
    s: &FrameState<T>,
    length_m: T,
    k: V3<T>,
    k_dot: V3<T>,
) -> (FrameState<T>, M3<T>, M3<T>, V3<T>) {
    advance_local_with(s, length_m, k, k_dot, coefficients_at(length_m, k, true))
}

/// [`advance_local`] with the end's coefficients `co` already evaluated
/// ([`coefficients_at`] at σ = ℓ, with A): the same bits.
#[inline(always)]
pub fn advance_local_with<T: Real>(
    s: &FrameState<T>,
    length_m: T,
    k: V3<T>,
    k_dot: V3<T>,
    co: Coefficients<T>,
) -> (FrameState<T>, M3<T>, M3<T>, V3<T>) {
    let (end, turn) = local_end_with(length_m, k, k_dot, co);
    advance_from_end(s, length_m, &end, &turn)
}

/// [`advance_local_with`] from the end's local jet and turn
/// ([`local_end_with`]), for a caller that needs them too
/// ([`super::block_terms`]): the same bits.
#[inline(always)]
pub fn advance_from_end<T: Real>(
    s: &FrameState<T>,
    length_m: T,
    end: &LocalPoint<T>,
    turn: &LocalTurn<T>,
) -> (FrameState<T>, M3<T>, M3<T>, V3<T>) {
    let [p, pv, pa] = s.carry(end.h, end.h_dot, end.h_ddot);
    let b = s.frame.mul_mat(&turn.left_jacobian).scale(length_m);
    let a = s.frame.mul_mat(&end.jacobian);
    let spin = s.frame * turn.spin;
    let next = FrameState {
        frame: s.frame.mul_mat(&turn.rotation),
        angular_velocity: s.angular_velocity + spin,
        angular_acceleration: s.frame.mul_vec_add(
            turn.spin_dot,
            s.angular_acceleration + s.angular_velocity.cross(spin),
        ),
        point_m: p,
        point_velocity: pv,
        point_acceleration: pa,
    };
    let span = s.frame * end.h;
    (next, a, b, span)
}

/// Element `e`'s own sums from its start state `s`; `a` and `b` are left
/// zero. With `OFF_DIAGONAL` it also sums U_Q and V_Q (Exact needs them).
///
/// A sample's Jacobian is G = R J with R the element's start frame and J
/// the local ∂h/∂k, and R is a rotation, so the products with G are taken
/// in the element's frame and R is applied once per element, not once per
/// sample: GᵀG = JᵀJ (symmetric: six dot products), GᵀF = Jᵀ(RᵀF),
/// U = R Σ wρS J, and with r = p + R h,
/// V = Σ wρS \[r\]×G = \[p\]×U + R Σ wρS \[h\]×J.
#[inline(always)]
pub fn own_sums<T: Real, const OFF_DIAGONAL: bool>(
    model: &impl Constants<T>,
    env: &StepEnv,
    e: usize,
    s: &FrameState<T>,
    k: V3<T>,
    k_dot: V3<T>,
) -> ElementData<T> {
    let mut el = ElementData::zero();
    own_sums_into::<T, OFF_DIAGONAL, _>(
        model,
        env,
        e,
        s,
        k,
        k_dot,
        &mut el,
        (&NoContact, V3::zero()),
        None,
    );
    el
}

/// [`own_sums`] written into `el` in place, with `hook`'s force at each
/// quadrature sample (the hair–hair model's pull, [`crate::batch::volume::pull`];
/// nothing unless `H::SAMPLE_FORCES`; the hook sees each sample's place
/// relative to the root, `hook_origin_m` being where `s`'s point lies
/// relative to it: the element's start when `s` was moved there for local
/// moments, else zero): every field but `a` and `b` (and
/// `u`, `v` without `OFF_DIAGONAL`) is overwritten. The sweep uses this
/// form: an 8-lane [`ElementData`] is about 1.9 KB, and returning it by
/// value cost a copy and a zero fill per element (measured: 15% of a
/// Block-diagonal step).
#[expect(
    clippy::too_many_arguments,
    reason = "the element's inputs, its output and the hook"
)]
#[inline(always)]
pub fn own_sums_into<T: Real, const OFF_DIAGONAL: bool, H: SampleHook<T>>(
    model: &impl Constants<T>,
    env: &StepEnv,
    e: usize,
    s: &FrameState<T>,
    k: V3<T>,
    k_dot: V3<T>,
    el: &mut ElementData<T>,
    (hook, hook_origin_m): (&H, V3<T>),
    coefficients: Option<&[Coefficients<T>]>,
) {
    let length_m = model.length_m(e);
    let rho_s = model.mass_per_length();
    let nu = model.air_drag();
    let g = V3::splat_f64(env.gravity_m_per_s2);
    let air = V3::splat_f64(env.air_velocity_m_per_s);
    let zero = T::splat(0.0);
    let (mut force_sum, mut torque_sum, mut first_moment) = (V3::zero(), V3::zero(), V3::zero());
    let mut mass = zero;
    let mut second = [zero; 6];
    // Σ wρS JᵀJ by its upper triangle (00, 01, 02, 11, 12, 22).
    let mut gram = [zero; 6];
    let mut local_force = V3::zero();
    let mut u_local = M3::zero();
    let mut v_local = M3::zero();
    let mut contact = ContactInertia::zero();
    let mut touching = false;
    // The head's implicit contact adds h (h k + c) Jᵀ n nᵀ J to the step
    // matrix, which the steps scale by s with the mass: its own-element
    // share is taken over s here, so that it enters unscaled, as the
    // parent's share (`contact`) does (crate::batch::contact).
    let inverse_sqrt_scale = if H::SAMPLE_CONTACT {
        let drag = nu / rho_s + T::splat_f64(hook.drag_rate_per_s());
        T::splat(1.0) / (T::splat(1.0) + T::splat_f64(env.h_secs) * drag).sqrt()
    } else {
        T::splat(1.0)
    };
    for j in 0..model.node_count() {
        let sigma = model.node(j) * length_m;
        let co = match coefficients {
            Some(known) => known[j],
            None => coefficients_at(sigma, k, false),
        };
        let lp = local_point_with(sigma, k, k_dot, co);
        let [r, vel, acc] = s.carry(lp.h, lp.h_dot, lp.h_ddot);
        let w_len = model.weight(j) * length_m;
        let w_mass = w_len * rho_s;
        let mut per_length = (g - acc).scale_add(rho_s, (air - vel).scale(nu));
        if H::SAMPLE_FORCES {
            per_length += hook.sample_force(e, j, hook_origin_m + r, vel);
        }
        let jac = &lp.jacobian;
        if H::SAMPLE_CONTACT
            && let Some((push, gain_axis)) = hook.sample_contact(e, j, hook_origin_m + r, vel)
        {
            per_length += push;
            // a aᵀ = w ℓ h (h k + c) n nᵀ: this sample's point inertia.
            let a = gain_axis.scale(w_len.sqrt());
            contact.add_point(a, r);
            touching = true;
            let a_local = s.frame.t_mul_vec(a).scale(inverse_sqrt_scale);
            let psi = jac.t_mul_vec(a_local);
            add_upper_outer(&mut gram, psi);
            if OFF_DIAGONAL {
                u_local = M3::outer_add(a_local, psi, u_local);
                v_local = M3::outer_add(lp.h.cross(a_local), psi, v_local);
            }
        }
        let force = per_length.scale(w_len);
        local_force = jac.t_mul_vec_add(s.frame.t_mul_vec(force), local_force);
        let (c0, c1, c2) = (jac.c0, jac.c1, jac.c2);
        gram[0] = w_mass.mul_add(c0.dot(c0), gram[0]);
        gram[1] = w_mass.mul_add(c0.dot(c1), gram[1]);
        gram[2] = w_mass.mul_add(c0.dot(c2), gram[2]);
        gram[3] = w_mass.mul_add(c1.dot(c1), gram[3]);
        gram[4] = w_mass.mul_add(c1.dot(c2), gram[4]);
        gram[5] = w_mass.mul_add(c2.dot(c2), gram[5]);
        force_sum += force;
        torque_sum += r.cross(force);
        mass += w_mass;
        let r_w = r.scale(w_mass);
        first_moment += r_w;
        // Σ wρS r rᵀ by its upper triangle; I = tr(·)𝟙 − (·) after the loop.
        second[0] = r_w.x.mul_add(r.x, second[0]);
        second[1] = r_w.x.mul_add(r.y, second[1]);
        second[2] = r_w.x.mul_add(r.z, second[2]);
        second[3] = r_w.y.mul_add(r.y, second[3]);
        second[4] = r_w.y.mul_add(r.z, second[4]);
        second[5] = r_w.z.mul_add(r.z, second[5]);
        if OFF_DIAGONAL {
            let jac_w = jac.scale(w_mass);
            u_local += jac_w;
            v_local += M3::cross_cols(lp.h, &jac_w);
        }
    }
    el.force_sum = force_sum;
    el.torque_sum = torque_sum;
    el.mass = mass;
    el.first_moment = first_moment;
    let trace = second[0] + second[3] + second[5];
    el.inertia = M3::symmetric(second.map(|s| -s)).add_diagonal(V3::new(trace, trace, trace));
    el.own_force = local_force;
    el.own_mass_block = M3::symmetric(gram);
    el.contact = contact;
    el.touching = touching;
    if OFF_DIAGONAL {
        el.u = s.frame.mul_mat(&u_local);
        el.v = M3::cross_cols(s.point_m, &el.u) + s.frame.mul_mat(&v_local);
    }
}

/// Adds x xᵀ to a symmetric matrix held by its upper triangle (00, 01,
/// 02, 11, 12, 22).
#[inline(always)]
fn add_upper_outer<T: Real>(upper: &mut [T; 6], x: V3<T>) {
    let pairs = [
        (x.x, x.x),
        (x.x, x.y),
        (x.x, x.z),
        (x.y, x.y),
        (x.y, x.z),
        (x.z, x.z),
    ];
    for (u, (a, b)) in upper.iter_mut().zip(pairs) {
        *u = a.mul_add(b, *u);
    }
}

/// The whole root-to-tip sweep: `out[e]` gets element e's data.
#[inline(always)]
pub fn forward<T: Real, const OFF_DIAGONAL: bool>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    out: &mut [ElementData<T>],
) {
    forward_with::<T, OFF_DIAGONAL, false, _>(model, env, root, q, v, out, &NoContact, None);
}

/// [`forward`] with the hook's forces (the head's contact at the samples,
/// stage "collide", [`super::contact`]; the hair–hair model's pull), and with moments about the root (`LOCAL = false`,
/// as the Dense kernel takes them) or about each element's own points
/// (`LOCAL = true`).
///
/// # Local moments
///
/// About the root, the suffix sums of an element 30 cm out are terms of
/// size m|p|² whose small difference is its mass block; in f32 that loses
/// the small entries (a straight strand's twist ones first:
/// `examples/f32_precision.rs` measured 5% in one frame). With `LOCAL`,
/// element Q's own moments (first moment, inertia, torque, V_Q) are taken
/// about its start point, A_Q about its end point (so the suffix sums past
/// Q must be about that end point too), and `span` is end minus start: the
/// tip-to-root sweeps shift the sums by −span from one element to the next
/// ([`super::suffix::Beyond::shift`]), so every product involves only
/// distances of the size of what it describes.
///
/// `coefficients`, when given, are the helix coefficients of `q` as
/// [`super::velocity_terms::coefficients_of`] lays them out (a step that
/// needs them again evaluates them once); the same bits either way.
#[expect(
    clippy::too_many_arguments,
    reason = "the sweep's inputs, its output, the hook and the known coefficients"
)]
#[inline(always)]
pub fn forward_with<T: Real, const OFF_DIAGONAL: bool, const LOCAL: bool, H: SampleHook<T>>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    out: &mut [ElementData<T>],
    hook: &H,
    coefficients: Option<&[Coefficients<T>]>,
) {
    let per_element = model.node_count() + 1;
    let mut s = FrameState::at_root(root);
    for (e, el) in out.iter_mut().enumerate() {
        let co = coefficients
            .map(|c| c[e * per_element..(e + 1) * per_element].split_at(per_element - 1));
        // Own moments about the element's start (LOCAL) or the root.
        let moments_origin = if LOCAL {
            FrameState {
                point_m: V3::zero(),
                ..s
            }
        } else {
            s
        };
        own_sums_into::<T, OFF_DIAGONAL, H>(
            model,
            env,
            e,
            &moments_origin,
            q[e],
            v[e],
            el,
            (hook, s.point_m - moments_origin.point_m),
            co.map(|(nodes, _)| nodes),
        );
        let length_m = model.length_m(e);
        let end_co = match co {
            Some((_, end)) => end[0],
            None => coefficients_at(length_m, q[e], true),
        };
        let (next, a_local, b, span) = advance_local_with(&s, length_m, q[e], v[e], end_co);
        el.a = if LOCAL {
            a_local
        } else {
            root_jacobian(a_local, next.point_m, &b)
        };
        el.b = b;
        el.span = span;
        s = next;
    }
}

/// What the forward sweep adds at the quadrature samples to the strand's
/// own forces: the head's contact and the hair–hair model's pull.
pub trait SampleHook<T> {
    /// Whether [`Self::sample_force`] adds anything: a compile-time
    /// switch, so that without the hair–hair model ([`crate::batch::volume::pull`]) the
    /// sample loop is exactly as before.
    const SAMPLE_FORCES: bool = false;

    /// Whether [`Self::sample_contact`] can touch: a compile-time switch,
    /// so that without a collider the sample loop is exactly as before.
    const SAMPLE_CONTACT: bool = false;

    /// The head's implicit contact at quadrature node `j` of element `e`
    /// at `r` (relative to the root point, m) moving at `velocity` (world,
    /// m/s): `None` when no lane touches; else each lane's predicted push
    /// per unit length (N/m, zero for lanes out of contact) and its gain
    /// axis g, with g gᵀ = h (h k + c) n nᵀ (kg·s⁻¹·m⁻¹·s: the step
    /// matrix gains w ℓ g gᵀ through the sample's Jacobian), as
    /// [`crate::collision::ContactInputs::implicit_force`] gives them.
    #[inline(always)]
    fn sample_contact(
        &self,
        _e: usize,
        _j: usize,
        _r: V3<T>,
        _velocity: V3<T>,
    ) -> Option<(V3<T>, V3<T>)>
    where
        T: Real,
    {
        None
    }

    /// An extra drag rate, 1/s, taken implicitly through the mass scale
    /// (the hair–hair friction μ, [`crate::batch::volume::pull`]).
    #[inline(always)]
    fn drag_rate_per_s(&self) -> f64 {
        0.0
    }

    /// An extra force per unit length on quadrature node `j` of element
    /// `e` at `r` (relative to the root point, m) moving at `velocity`
    /// (world, m/s), N/m; read only when [`Self::SAMPLE_FORCES`].
    #[inline(always)]
    fn sample_force(&self, _e: usize, _j: usize, _r: V3<T>, _velocity: V3<T>) -> V3<T>
    where
        T: Real,
    {
        V3::zero()
    }
}

/// No collider and no hair–hair model: the samples feel only gravity,
/// inertia and the air.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoContact;

impl<T> SampleHook<T> for NoContact {}

//! Stage "velocity terms" on the fast path: the product G z of the
//! velocity-implicit step, in f32 lanes (see [`crate::step::velocity_terms`] for
//! the f64 reference and the physics).
//!
//! # How it works
//!
//! G = −∂Q/∂q̇ = ∫ ρS Jᵀ (∂r̈_free/∂q̇) ds, and r̈_free (the acceleration with
//! q̈ = 0) is a quadratic polynomial in the strain rates, so its
//! derivative along z is exactly
//!
//! (∂r̈_free/∂q̇) z = [r̈_free(q̇ + z) − r̈_free(q̇ − z)] / 2
//!
//! (polarisation). [`velocity_product`] runs the forward sweep's
//! kinematics ([`super::forward::advance_local`],
//! [`super::geometry::local_point`]) twice at once, root to tip, once with
//! rates q̇ + cz and once with q̇ − cz, and projects ρS w δr̈ at every
//! quadrature sample on the generalized forces the way the step projects
//! its forces: each element's own share Jᵀ(Rᵀ f) in its frame, and a
//! tip-to-root suffix sum of force and torque read through the A_Q, B_Q
//! that sweep 1 of the step left in the scratch (same q, so the same
//! Jacobians; moments about each element's own points, as the step takes
//! them).
//!
//! **Round-off in f32.** A difference of two accelerations loses the bits
//! of whatever the two share. So the root's linear and angular
//! accelerations, which add the same term to both and do not depend on q̇,
//! are left out of both sweeps (the difference is unchanged in exact
//! arithmetic), and z is scaled per lane by c = max(|q̇|∞, 1 m⁻¹/s)/|z|∞ so
//! that the shift is the size of the rates it perturbs (G is linear: the
//! result is scaled back by 1/c). A one-sided difference, which the f64
//! reference's O(N) solvers use (one sweep instead of two), would need a
//! shift of about √ε_f32 ≈ 3e-4 of q̇ and lose half of f32's digits; the
//! polarised one is exact up to round-off, which is what a GMRES
//! tolerance of 1e-3 needs.
//!
//! Air drag is not in G: its derivative (ν/ρS) M is already in the step
//! matrix through the mass scale s ([`super::suffix::mass_scale`]).

use super::forward::{FrameState, advance_local_with};
use super::geometry::{Coefficients, coefficients_at, local_point_with};
use super::lane_model::Constants;
use super::lanes::Real;
use super::layout::{ElementData, RootMotion};
use super::vec::V3;

/// One element's share of G z before the suffix sums: its own projection
/// and the force and torque (about its start point) of its samples.
#[derive(Clone, Copy, Debug)]
pub struct OwnProduct<T> {
    /// Σ_own Jᵀ f, N·m² per unit of z.
    pub own: V3<T>,
    /// Σ_own f, N.
    pub force: V3<T>,
    /// Σ_own (r − p_start) × f, N·m.
    pub torque: V3<T>,
}

impl<T: Real> OwnProduct<T> {
    /// All zero.
    pub fn zero() -> Self {
        Self {
            own: V3::zero(),
            force: V3::zero(),
            torque: V3::zero(),
        }
    }
}

/// The helix coefficients [`velocity_product`] needs for strains `q`, into
/// `out` (cleared first): per element, one per quadrature node, then the
/// end's (with A). They depend on q alone, not on the rates, so the two
/// sweeps of every product of a step share one evaluation (they were a
/// sixth of an imported groom's frame, with their sines and cosines
/// another tenth, when each product evaluated its own).
#[inline(always)]
pub fn coefficients_of<T: Real>(
    model: &impl Constants<T>,
    q: &[V3<T>],
    out: &mut Vec<Coefficients<T>>,
) {
    out.clear();
    for (e, k) in q.iter().enumerate() {
        let length_m = model.length_m(e);
        for j in 0..model.node_count() {
            out.push(coefficients_at(model.node(j) * length_m, *k, false));
        }
        out.push(coefficients_at(length_m, *k, true));
    }
}

/// Per lane, the largest |x_i| over every component of `x`.
#[inline(always)]
pub fn largest_abs<T: Real>(x: &[V3<T>]) -> T {
    let abs = |a: T| a.max(-a);
    x.iter().fold(T::splat(0.0), |m, e| {
        m.max(abs(e.x)).max(abs(e.y)).max(abs(e.z))
    })
}

/// Per lane, the scale c of the polarised difference along `z` at rates
/// `v`: c = max(|q̇|∞, 1 m⁻¹/s)/|z|∞, so that the shift cz is the size of
/// the rates it perturbs (module docs). A lane with z = 0 gets c = 1 and
/// an exact zero; a non-finite z stays so.
#[inline(always)]
pub fn polarisation_shift<T: Real>(v: &[V3<T>], z: &[V3<T>]) -> T {
    let one = T::splat(1.0);
    let z_size = largest_abs(z);
    let z_size = z_size.select_below(f32::MIN_POSITIVE, one, z_size);
    largest_abs(v).max(one) / z_size
}

/// out = G z per element (N·m²·s per unit of z) for the strands in state
/// (`q`, `v`) with roots moving as `root`; `scratch` holds sweep 1's data
/// for this state (A_Q about each element's end point, B_Q, span: the
/// step's `LOCAL` moments), `coefficients` the helix coefficients of `q`
/// ([`coefficients_of`]), `own` is a buffer of N entries.
#[expect(
    clippy::too_many_arguments,
    reason = "the step's state and buffers, named as the step names them"
)]
#[inline(always)]
pub fn velocity_product<T: Real>(
    model: &impl Constants<T>,
    root: &RootMotion<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    scratch: &[ElementData<T>],
    coefficients: &[Coefficients<T>],
    z: &[V3<T>],
    own: &mut [OwnProduct<T>],
    out: &mut [V3<T>],
) {
    let reach = polarisation_shift(v, z);
    let rho_s = model.mass_per_length();
    // Σ wρS δr̈ with δr̈ = (plus − minus)/2 in units of z: the factor 1/(2c).
    let factor = rho_s / (reach + reach);
    let still = RootMotion {
        angular_acceleration_rad_per_s2: V3::zero(),
        velocity_m_per_s: V3::zero(),
        acceleration_m_per_s2: V3::zero(),
        ..*root
    };
    let mut plus = FrameState::at_root(&still);
    let mut minus = plus;
    let per_element = model.node_count() + 1;
    for ((e, sums), co) in own
        .iter_mut()
        .enumerate()
        .zip(coefficients.chunks_exact(per_element))
    {
        let (co_nodes, co_end) = co.split_at(per_element - 1);
        let k = q[e];
        let shift = z[e].scale(reach);
        let (k_plus, k_minus) = (v[e] + shift, v[e] - shift);
        let length_m = model.length_m(e);
        // Moments about the element's start point.
        let origin_plus = FrameState {
            point_m: V3::zero(),
            ..plus
        };
        let origin_minus = FrameState {
            point_m: V3::zero(),
            ..minus
        };
        let mut result = OwnProduct::zero();
        let mut local = V3::zero();
        for (j, co) in co_nodes.iter().enumerate() {
            let sigma = model.node(j) * length_m;
            let lp = local_point_with(sigma, k, k_plus, *co);
            let lm = local_point_with(sigma, k, k_minus, *co);
            let [r, _, acc_plus] = origin_plus.carry(lp.h, lp.h_dot, lp.h_ddot);
            let [_, _, acc_minus] = origin_minus.carry(lm.h, lm.h_dot, lm.h_ddot);
            let f = (acc_plus - acc_minus).scale(factor * (model.weight(j) * length_m));
            local = lp.jacobian.t_mul_vec_add(plus.frame.t_mul_vec(f), local);
            result.force += f;
            result.torque += r.cross(f);
        }
        result.own = local;
        *sums = result;
        plus = advance_local_with(&plus, length_m, k, k_plus, co_end[0]).0;
        minus = advance_local_with(&minus, length_m, k, k_minus, co_end[0]).0;
        // The frame and the point depend on q alone, so the two sweeps'
        // are the same bits; sharing them lets the compiler compute each
        // product with them once for both sweeps.
        minus.frame = plus.frame;
        minus.point_m = plus.point_m;
    }
    // Tip to root: Q_e = own + a_eᵀ F_b + b_eᵀ τ_b, sums about e's end point.
    let (mut force, mut torque) = (V3::zero(), V3::zero());
    for e in (0..own.len()).rev() {
        let el = &scratch[e];
        out[e] =
            el.b.t_mul_vec_add(torque, el.a.t_mul_vec_add(force, own[e].own));
        // Move the moments to e's start point (by −span), then add e's own.
        torque = torque + el.span.cross(force) + own[e].torque;
        force += own[e].force;
    }
}

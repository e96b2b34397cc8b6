//! The tip-to-root half of stages "forces" and "mass": suffix sums of what
//! lies beyond each element, and the terms an element reads from them.
//!
//! With J = A_Q − \[r\]×B_Q for every sample past element Q, the diagonal
//! block and generalized force of element Q need only the suffix mass
//! moments (m, c, I) and the suffix force and torque (see [`crate::step::mass`],
//! [`crate::step::forces`]):
//!
//! X_b = m A − \[c\]×B,  Y_b = \[c\]×A + I B,
//! M_QQ = D_Q + AᵀX_b + BᵀY_b,  Q_Q = Σ_own GᵀF + AᵀF_b + Bᵀτ_b.
//!
//! The right-hand side and diagonal of the step (see [`crate::step`]) are
//! rhs = h[Q − K(q − qⁿ) − (γℓ + hK)q̇], D = hγℓ + h²K and the mass scale
//! s = 1 + hν/ρS.

use super::lane_model::Constants;
use super::lanes::Real;
use super::layout::{ElementData, StepEnv};
use super::vec::{M3, V3};

/// Sums over every sample past the current element.
#[derive(Clone, Copy, Debug)]
pub struct Beyond<T> {
    /// m, kg.
    pub mass: T,
    /// c = Σ wρS r, kg·m.
    pub first_moment: V3<T>,
    /// I = Σ wρS (|r|²𝟙 − rrᵀ), kg·m².
    pub inertia: M3<T>,
    /// Σ w F, N.
    pub force: V3<T>,
    /// Σ w r × F, N·m.
    pub torque: V3<T>,
}

impl<T: Real> Beyond<T> {
    /// Nothing beyond the tip.
    pub fn zero() -> Self {
        Self {
            mass: T::splat(0.0),
            first_moment: V3::zero(),
            inertia: M3::zero(),
            force: V3::zero(),
            torque: V3::zero(),
        }
    }

    /// Moves the moments' origin by `delta` (new origin minus old): the
    /// parallel-axis rule, c′ = c − mδ,
    /// I′ = I − 2(c·δ)𝟙 + m|δ|²𝟙 + cδᵀ + δcᵀ − mδδᵀ, τ′ = τ − δ × F.
    #[inline(always)]
    pub fn shift(&mut self, delta: V3<T>) {
        let c = self.first_moment;
        let m = self.mass;
        let m_delta = delta.scale(m);
        let diagonal = m_delta.dot(delta) - (c.dot(delta) + c.dot(delta));
        let inertia = M3::outer_add(-m_delta, delta, self.inertia);
        self.inertia = M3::outer_add(c, delta, M3::outer_add(delta, c, inertia))
            .add_diagonal(V3::new(diagonal, diagonal, diagonal));
        self.first_moment = c - m_delta;
        self.torque = self.torque - delta.cross(self.force);
    }

    /// Adds an element's own sums (moving one element towards the root).
    #[inline(always)]
    pub fn add(&mut self, el: &ElementData<T>) {
        self.mass += el.mass;
        self.first_moment += el.first_moment;
        self.inertia += el.inertia;
        self.force += el.force_sum;
        self.torque += el.torque_sum;
    }
}

/// What element Q reads from the suffix sums past it.
#[derive(Clone, Copy, Debug)]
pub struct ElementTerms<T> {
    /// X_b = m A − \[c\]×B, kg·m².
    pub x_beyond: M3<T>,
    /// Y_b = \[c\]×A + I B, kg·m³.
    pub y_beyond: M3<T>,
    /// M_QQ, kg·m³.
    pub mass_block: M3<T>,
    /// Q_Q, N·m².
    pub force: V3<T>,
}

/// The terms of element `el` given the sums `beyond` it.
#[inline(always)]
pub fn element_terms<T: Real>(el: &ElementData<T>, beyond: &Beyond<T>) -> ElementTerms<T> {
    let x_beyond =
        el.a.scale_add(beyond.mass, M3::cross_cols(-beyond.first_moment, &el.b));
    let y_beyond = beyond
        .inertia
        .mul_mat_add(&el.b, &M3::cross_cols(beyond.first_moment, &el.a));
    let mass_block = el.a.t_mul_mat_add(&x_beyond, &el.own_mass_block);
    let force = el.a.t_mul_vec_add(beyond.force, el.own_force);
    ElementTerms {
        mass_block: el.b.t_mul_mat_add(&y_beyond, &mass_block),
        force: el.b.t_mul_vec_add(beyond.torque, force),
        x_beyond,
        y_beyond,
    }
}

/// The step's per-element scalars: (D = hγℓ + h²K, rhs) for element `e`.
#[inline(always)]
pub fn step_terms<T: Real>(
    model: &impl Constants<T>,
    env: &StepEnv,
    e: usize,
    force: V3<T>,
    q: V3<T>,
    v: V3<T>,
) -> (V3<T>, V3<T>) {
    let h = T::splat_f64(env.h_secs);
    let h_squared = h * h;
    let kv = model.stiffness(e);
    let friction = model.friction(e);
    let n = model.natural(e);
    let h_friction = h * friction;
    let diagonal = V3::new(
        h_friction + h_squared * kv.x,
        h_friction + h_squared * kv.y,
        h_friction + h_squared * kv.z,
    );
    let damping = V3::new(
        friction + h * kv.x,
        friction + h * kv.y,
        friction + h * kv.z,
    );
    let elastic = q - n;
    let rhs = V3::new(
        force.x - kv.x * elastic.x - damping.x * v.x,
        force.y - kv.y * elastic.y - damping.y * v.y,
        force.z - kv.z * elastic.z - damping.z * v.z,
    )
    .scale(h);
    (diagonal, rhs)
}

/// s = 1 + hν/ρS, which folds the implicit drag into the mass term.
#[inline(always)]
pub fn mass_scale<T: Real>(model: &impl Constants<T>, env: &StepEnv) -> T {
    T::splat(1.0) + T::splat_f64(env.h_secs) * model.air_drag() / model.mass_per_length()
}

/// Stage "integrate": v ← v + Δv, q ← q + h v.
#[inline(always)]
pub fn integrate<T: Real>(h_secs: f64, q: &mut V3<T>, v: &mut V3<T>, delta_v: V3<T>) {
    *v += delta_v;
    *q += v.scale(T::splat_f64(h_secs));
}

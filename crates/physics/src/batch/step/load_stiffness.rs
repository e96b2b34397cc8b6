//! The loads' stiffness in Block-diagonal's step matrix: gravity and the
//! root's linear acceleration taken implicitly in position, block by block.
//!
//! # Why
//!
//! The step takes the elastic forces implicitly in position (h²K in its
//! matrix) but the loads, gravity and the inertial force −ρS a_O of a root
//! that accelerates, at the step's start. Their stiffness is that of a
//! pendulum: a strand hanging under g swings at ω² ≈ g·c / I about each
//! joint. Block-diagonal keeps only the diagonal blocks of the mass
//! matrix, so a strand swinging as one piece (every element turning the
//! same way) is lighter than it is, by the couplings it drops, and swings
//! faster: at 60 Hz with one substep, the explicit loads then gained
//! energy in the pendulum modes of the 30 cm example strands under a
//! shake or a jerk (measured: the guard caught 39 strand-frames in the
//! twenty runs of the four example styles under the five clips; with g
//! tripled, 15 on a still head; with g = 0 and a still head, none).
//! With the loads' stiffness in the block, the pendulum modes step as the
//! elastic ones do, backward in position, and lose energy rather than gain
//! it.
//!
//! # How
//!
//! For element Q, everything past it (the suffix sums, mass m and first
//! moment c about the element's end point) turns with the element's end
//! frame, δθ = B_Q δq. The end point moves too: an element bent by δκ
//! turns its end by ℓδκ and, to second order, draws it back along the
//! tangent by ℓ³δκ²/6, so under a load along the element the body past it
//! stores the energy of a turn about the point a third of the element
//! from its end. A uniform load g_e = g − a_O per unit mass, turning a body
//! of first moment c′ about that point, changes the potential −g_e·Σ m r
//! by ½ δθᵀ[(g_e·c′)𝟙 − sym(g_e c′ᵀ)]δθ to second order. On turns about
//! axes perpendicular to g_e that is (g_e·c′)|δθ|² exactly, whatever the
//! lever's direction; about g_e itself it is zero. The element's own
//! samples, bent with it, store ρS g ℓ⁴δκ²/24: a sixth of their first
//! moment about the element's start. So with
//! c′ = c + m·span/3 + c_own/6 the block takes
//!
//! K_Q = max(0, g_e·c′) Bᵀ(𝟙 − ĝĝᵀ)B,
//!
//! symmetric and never negative: the cross term (tilted levers, not at
//! equilibrium) and a lever above its pivot (an unstable pendulum, which
//! the explicit loads already step as it is) are left to the explicit
//! forces, so the step matrix stays positive definite. The step adds
//! h²K_Q to the block and −h²K_Q q̇ to its right-hand side, as it takes
//! h²K for the elastic forces: the linearisation of the loads at the
//! step's end position q + h q̇⁺.
//!
//! It approximates the loads' Hessian: the step stays consistent (first
//! order in h), with the error moved from energy the pendulum gains to
//! energy it loses.

use crate::batch::lanes::Real;
use crate::batch::layout::ElementData;
use crate::batch::suffix::Beyond;
use crate::batch::vec::{M3, V3};

/// The uniform load per unit mass every sample feels, g − a_O (world,
/// m/s²), and its direction (zero where it vanishes).
#[derive(Clone, Copy, Debug)]
pub struct UniformLoad<T> {
    per_kg: V3<T>,
    direction: V3<T>,
}

impl<T: Real> UniformLoad<T> {
    /// The load of gravity `gravity_m_per_s2` on a strand whose root point
    /// accelerates at `root_acceleration_m_per_s2` (per lane, world).
    pub fn new(gravity_m_per_s2: [f64; 3], root_acceleration_m_per_s2: V3<T>) -> Self {
        let per_kg = V3::splat_f64(gravity_m_per_s2) - root_acceleration_m_per_s2;
        let size = per_kg.dot(per_kg).sqrt();
        // 1/|g_e|, or 0 for no load (1e-30 keeps the division finite).
        let inverse = T::splat(1.0) / size.max(T::splat(1e-30));
        Self {
            per_kg,
            direction: per_kg.scale(inverse),
        }
    }

    /// K_Q for element `el` with the sums `beyond` past it (about its end
    /// point), N·m³: see the module's docs.
    #[inline(always)]
    pub fn stiffness(&self, el: &ElementData<T>, beyond: &Beyond<T>) -> M3<T> {
        // About the point a third of the element from its end, plus the
        // own samples' sixth (see the module's docs).
        let lever = beyond.first_moment
            + el.span.scale(beyond.mass * T::splat(1.0 / 3.0))
            + el.first_moment.scale(T::splat(1.0 / 6.0));
        let strength = self.per_kg.dot(lever).max(T::splat(0.0));
        let b = &el.b;
        let across = b.t_mul_vec(self.direction);
        M3::outer_add(-across, across, b.t_mul_mat(b)).scale(strength)
    }
}

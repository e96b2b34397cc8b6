//! Stage "velocity terms": how the generalized forces change with the
//! strain rates, for the velocity-implicit step.
//!
//! # Why
//!
//! The inertial part of the generalized forces, Q_in = −∫ ρS Jᵀ r̈_free ds,
//! holds the centrifugal and Coriolis terms: r̈_free (the acceleration with
//! q̈ = 0) is quadratic in the strain rates q̇, plus terms linear in q̇ from
//! the root's rotation. Frozen at the start of a step, they make the step
//! explicit in q̇, and a long strand whipping under a head shake blows up
//! at 1/60 s (measured: a 30 cm straight strand, shake 0.5 rad at 1.5 Hz,
//! non-finite after 1.3 s with every solver). Putting their derivative in
//! the step matrix, as the stiffness already is, cures it:
//!
//! (s M̃ + D + h G) Δv = rhs,  G = −∂Q/∂q̇ = 2 ∫ ρS Jᵀ J̇ ds.
//!
//! G is not symmetric (its skew part is gyroscopic: it does no work; its
//! symmetric part is Ṁ), and keeping either part alone does not cure the
//! blow-up (measured on the same strand: both blow up within 2.6 s).
//!
//! # How
//!
//! The step needs G only as a product G x, never as a matrix. Since
//! r̈_free = J̇ q̇ + (root terms), with J̇ the whole time derivative of J
//! (strains and the root's turn), its derivative along x is exactly
//!
//! (∂r̈_free/∂q̇) x = 2 J̇ x
//!
//! (J = ∂r/∂q, so ∂J_j/∂q_k = ∂J_k/∂q_j: the two ways q̇ enters J̇ q̇
//! count equally; the root's turn enters as ω × J x twice, once through J̇
//! and once through the Coriolis term ω × ṙ). Writing J as the
//! reconstruction does, J_Q(s) = A_Q − \[r\]× B_Q beyond element Q and the
//! sample's own R_Q ∂h(σ)/∂k inside it, gives for a sample of element e
//!
//! J̇ x = Σ_{Q<e} Ȧ_Q x_Q − ṙ × Σ_{Q<e} B_Q x_Q − r × Σ_{Q<e} Ḃ_Q x_Q + j̇ x_e,
//!
//! three prefix sums root to tip, then the forces stage's projection
//! ([`project_sample_forces`]) of 2ρS w J̇ x tip to root: O(N) with no
//! helix function evaluated ([`Derivative::JacobianRates`]). The rates Ȧ,
//! Ḃ, j̇ come from [`crate::step::reconstruct::reconstruct_with_rates`], once per
//! step, however many products the solve asks for.
//!
//! The first form, kept as the check ([`Derivative::Polarisation`]):
//! r̈_free is quadratic in q̇, so [r̈_free(q̇ + x) − r̈_free(q̇ − x)] / 2 is
//! its derivative along x exactly, from two jet sweeps of the
//! reconstruction ([`free_accelerations`]), each re-evaluating the helix
//! functions: about 0.7 of a whole explicit step per product, which would
//! make the velocity-implicit step cost about three explicit ones.

use glam::DVec3;

use crate::model::StrandModel;
use crate::motion::RigidMotion;
use crate::step::forces::project_sample_forces;
use crate::step::reconstruct::{Kinematics, free_accelerations};

/// How [`VelocityTerms::apply`] forms (∂r̈_free/∂q̇) x.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Derivative {
    /// 2 J̇ x from the Jacobians' rates: three prefix sums, no helix
    /// function evaluated. Needs `kin` from
    /// [`crate::step::reconstruct::reconstruct_with_rates`].
    JacobianRates,
    /// Polarisation of two jet sweeps, exact to round-off (the check).
    Polarisation,
}

/// Buffers of [`VelocityTerms::apply`], reused from step to step.
#[derive(Clone, Debug, Default)]
pub struct VelocityTerms {
    shifted: Vec<DVec3>,
    plus: Vec<DVec3>,
    minus: Vec<DVec3>,
}

/// 2 J̇ x at every sample (m/s² per unit of x), root to tip: see the module
/// doc's prefix sums.
pub(crate) fn jacobian_rate_times(
    model: &StrandModel,
    kin: &Kinematics,
    x: &[DVec3],
    out: &mut Vec<DVec3>,
) {
    assert!(
        kin.element_rates.len() == x.len() && kin.jacobian_rates.len() == kin.samples.len(),
        "the product needs reconstruct_with_rates"
    );
    let points = model.quadrature.len();
    let (mut carried, mut turned, mut turn_rate) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    out.clear();
    for (e, x_e) in x.iter().enumerate() {
        for i in e * points..(e + 1) * points {
            let s = &kin.samples[i];
            let u = carried - s.velocity_m_per_s.cross(turned) - s.position_m.cross(turn_rate)
                + kin.jacobian_rates[i] * *x_e;
            out.push(2.0 * u);
        }
        carried += kin.element_rates[e].a * *x_e;
        turned += kin.elements[e].b * *x_e;
        turn_rate += kin.element_rates[e].b * *x_e;
    }
}

impl VelocityTerms {
    /// out = G x = −(∂Q/∂q̇) x (N·m²·s per element and unit of x) for the
    /// strand in state (`q`, `v`) with its root moving as `root`; `kin` is
    /// the reconstruction of that state.
    #[allow(clippy::too_many_arguments)] // the step's state, named as the step names it
    pub fn apply(
        &mut self,
        derivative: Derivative,
        model: &StrandModel,
        kin: &Kinematics,
        q: &[DVec3],
        v: &[DVec3],
        root: &RigidMotion,
        x: &[DVec3],
        out: &mut [DVec3],
    ) {
        let factor = match derivative {
            Derivative::JacobianRates => {
                jacobian_rate_times(model, kin, x, &mut self.plus);
                1.0
            }
            Derivative::Polarisation => {
                let largest =
                    |y: &[DVec3]| y.iter().map(|e| e.abs().max_element()).fold(0.0, f64::max);
                let x_size = largest(x);
                if x_size == 0.0 || !x_size.is_finite() {
                    let fill = if x_size == 0.0 {
                        DVec3::ZERO
                    } else {
                        DVec3::NAN
                    };
                    out.fill(fill);
                    return;
                }
                // x scaled to the size of q̇ (G is linear, the result is
                // scaled back): the difference's cancellation stays at
                // round-off.
                let reach = largest(v).max(1.0) / x_size;
                for (sign, buffer) in [(1.0, &mut self.plus), (-1.0, &mut self.minus)] {
                    self.shifted.clear();
                    self.shifted
                        .extend(v.iter().zip(x).map(|(v, x)| *v + *x * (sign * reach)));
                    free_accelerations(model, q, &self.shifted, root, buffer);
                }
                for (p, m) in self.plus.iter_mut().zip(&self.minus) {
                    *p -= *m;
                }
                0.5 / reach
            }
        };
        // G x = ∫ ρS Jᵀ (∂r̈/∂q̇) x ds, with (∂r̈/∂q̇) x = plus · factor.
        let factor = model.mass_per_length * factor;
        project_sample_forces(
            model,
            kin,
            |i| self.plus[i] * (factor * kin.samples[i].weight_m),
            out,
        );
    }
}

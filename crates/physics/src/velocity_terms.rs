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
//! The step needs G only as a product G x, never as a matrix. r̈_free is a
//! quadratic polynomial in q̇, r̈_free(q̇) = B(q̇, q̇) + L q̇ + c, so
//! polarisation gives its derivative along x exactly, not as a finite
//! difference:
//!
//! (∂r̈_free/∂q̇) x = [r̈_free(q̇ + x) − r̈_free(q̇ − x)] / 2.
//!
//! Two jet sweeps of the reconstruction ([`free_accelerations`]) give it at
//! every sample, and the projection of the forces stage
//! ([`project_sample_forces`]) turns ρS w δr̈ into G x: O(N) in all. x is
//! scaled to the size of q̇ first (G is linear, so the result is scaled
//! back), which keeps the cancellation in the difference at round-off.
//! Dense, the reference, uses this exact form ([`Difference::Central`]);
//! the O(N) solvers' corrections use a forward difference from the step's
//! own r̈_free, one sweep instead of two ([`Difference::Forward`]).

use glam::DVec3;

use crate::forces::project_sample_forces;
use crate::model::StrandModel;
use crate::motion::RigidMotion;
use crate::reconstruct::{Kinematics, free_accelerations};

/// How [`VelocityTerms::apply`] differentiates r̈_free along x.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Difference {
    /// Polarisation, exact to round-off: two jet sweeps.
    Central,
    /// [r̈_free(q̇ + εx) − r̈_free(q̇)] / ε with |εx| = 1e-6 |q̇|, reusing the
    /// step's own r̈_free(q̇): one sweep, relative error about 1e-6 (the
    /// quadratic term ε B(x, x)), far below what a first-order step makes.
    Forward,
}

/// Relative size of the forward difference's shift, |εx| / max(|q̇|, 1).
pub const FORWARD_SHIFT: f64 = 1e-6;

/// Buffers of [`VelocityTerms::apply`], reused from step to step.
#[derive(Clone, Debug, Default)]
pub struct VelocityTerms {
    shifted: Vec<DVec3>,
    plus: Vec<DVec3>,
    minus: Vec<DVec3>,
}

impl VelocityTerms {
    /// out = G x = −(∂Q/∂q̇) x (N·m²·s per element and unit of x) for the
    /// strand in state (`q`, `v`) with its root moving as `root`; `kin` is
    /// the reconstruction of that state.
    #[allow(clippy::too_many_arguments)] // the step's state, named as the step names it
    pub fn apply(
        &mut self,
        difference: Difference,
        model: &StrandModel,
        kin: &Kinematics,
        q: &[DVec3],
        v: &[DVec3],
        root: &RigidMotion,
        x: &[DVec3],
        out: &mut [DVec3],
    ) {
        let largest = |y: &[DVec3]| y.iter().map(|e| e.abs().max_element()).fold(0.0, f64::max);
        let x_size = largest(x);
        if x_size == 0.0 || !x_size.is_finite() {
            out.fill(if x_size == 0.0 {
                DVec3::ZERO
            } else {
                DVec3::NAN
            });
            return;
        }
        let reach = largest(v).max(1.0) / x_size;
        let (scale, factor) = match difference {
            Difference::Central => {
                for (sign, buffer) in [(1.0, &mut self.plus), (-1.0, &mut self.minus)] {
                    self.shifted.clear();
                    self.shifted
                        .extend(v.iter().zip(x).map(|(v, x)| *v + *x * (sign * reach)));
                    free_accelerations(model, q, &self.shifted, root, buffer);
                }
                (reach, 0.5 / reach)
            }
            Difference::Forward => {
                let scale = FORWARD_SHIFT * reach;
                self.shifted.clear();
                self.shifted
                    .extend(v.iter().zip(x).map(|(v, x)| *v + *x * scale));
                free_accelerations(model, q, &self.shifted, root, &mut self.plus);
                self.minus.clear();
                self.minus
                    .extend(kin.samples.iter().map(|s| s.free_acceleration_m_per_s2));
                (scale, 1.0 / scale)
            }
        };
        debug_assert!(scale > 0.0);
        // δr̈ = (plus − minus) · factor; G x = ∫ ρS Jᵀ (∂r̈/∂q̇) x ds.
        let factor = model.mass_per_length * factor;
        project_sample_forces(
            model,
            kin,
            |i| (self.plus[i] - self.minus[i]) * (factor * kin.samples[i].weight_m),
            out,
        );
    }
}

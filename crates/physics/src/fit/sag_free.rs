//! The sag-free rest shape: natural strains that make a given shape a
//! static equilibrium.
//!
//! A strand is at rest where the elastic force balances the applied ones.
//! With the elastic energy ½(q − q⁰)ᵀK(q − q⁰) (K diagonal,
//! `docs/physics.md` section 3) and the generalized gravity
//! Q(q) = ∫ Jᵀ ρS g ds, equilibrium at q reads
//!
//! K (q − q⁰) = Q(q),
//!
//! and since K is diagonal and q is given (the fitted shape), the natural
//! strains follow exactly, one element at a time: q⁰ = q − K⁻¹ Q(q). No
//! iteration: this is the inverse of the statics problem, not the problem.
//!
//! Head support. Where the strand lies on the head, the head's contact
//! pushes on it, and the rest shape must hold the shape against that push
//! too: Q(q) then includes the contact's generalized force at rest,
//! exactly as the engine that will hold the strand applies it
//! ([`crate::engine::rest_contact`], which explains why nothing less will do).
//!
//! Two things can go wrong, and both are reported ([`SagFreeStatus`]):
//!
//! - **Absurd curvature.** A long strand held out horizontally needs a rest
//!   curvature near the root of order ρS g L²/(2EI); beyond
//!   [`MAX_NATURAL_STRAIN_PER_M`] (a 1 mm curl radius) the style would not
//!   validate. Such strains are clamped to the limit; the strand then sags
//!   where it was clamped.
//! - **Unstable equilibrium.** Holding the shape is not enough: a strand
//!   standing up beyond its buckling length is at rest, but the smallest
//!   push makes it fall over. The test is the energy's Hessian,
//!   H = K − ∂Q/∂q (symmetric, gravity being conservative), scaled to
//!   K^{-1/2} H K^{-1/2}: its smallest eigenvalue is 1 for a weightless
//!   strand, falls as gravity loads it, and is negative where the
//!   equilibrium is unstable. ∂Q/∂q is taken by central differences
//!   (3N evaluations of Q, each O(N)). Unstable strands keep their sag-free
//!   strains (still the best rest shape the model has for them) and are
//!   counted, so the caller can report them, or stiffened just enough to
//!   hold ([`super::stiffen`]).

use glam::DVec3;
use nalgebra::{DMatrix, SymmetricEigen};

use crate::model::StrandModel;
use crate::motion::RigidMotion;
use crate::natural_shape::MAX_NATURAL_STRAIN_PER_M;
use crate::step::forces::project_sample_forces;

use crate::engine::rest_contact::RestContact;
use crate::step::reconstruct::{Kinematics, reconstruct};

/// Step of the central differences of Q, m⁻¹: Q is smooth in q on the
/// scale of the strains themselves (1–1000 m⁻¹), so the O(h²) error is
/// ~1e-8 relative while round-off stays far below.
const DIFFERENCE_STEP_PER_M: f64 = 1e-3;

/// What the rest shape is solved for.
#[derive(Clone, Copy, Debug)]
pub struct SagFreeInputs<'a> {
    /// The strand's root, at rest, in world coordinates.
    pub root: &'a RigidMotion,
    /// Gravity, m/s².
    pub gravity_m_per_s2: DVec3,
    /// The head and its contact law, if the strand may rest on it.
    pub support: Option<RestContact<'a>>,
}

/// How the sag-free solve went for one strand.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SagFreeStatus {
    /// Exact equilibrium, stable.
    Held,
    /// Exact equilibrium, made stable by stiffening the strand
    /// ([`super::stiffen`]).
    Stiffened,
    /// Some strains exceeded the natural-strain limit and were clamped.
    Clamped,
    /// The equilibrium is unstable (the Hessian has a negative eigenvalue).
    Unstable,
}

/// The natural strains of one strand and the checks on them.
#[derive(Clone, Debug, PartialEq)]
pub struct SagFree {
    /// Natural strains q⁰ per element, m⁻¹ (clamped to the limit).
    pub natural_per_m: Vec<DVec3>,
    /// The outcome.
    pub status: SagFreeStatus,
    /// Smallest eigenvalue of K^{-1/2}(K − ∂Q/∂q)K^{-1/2}: 1 weightless,
    /// below 0 unstable.
    pub stability: f64,
    /// Largest |q⁰| component before clamping, m⁻¹.
    pub max_strain_per_m: f64,
}

/// The generalized gravity (plus the head's push at rest) on shape `q`,
/// N·m².
pub fn applied_forces(model: &StrandModel, q: &[DVec3], inputs: &SagFreeInputs) -> Vec<DVec3> {
    let kin = shape(model, q, inputs.root);
    let mut out = gravity_load(model, &kin, inputs.gravity_m_per_s2);
    if let Some(support) = &inputs.support {
        support.add_load(model, &kin, inputs.root, &mut out);
    }
    out
}

/// The shape `q` at rest on `root`.
fn shape(model: &StrandModel, q: &[DVec3], root: &RigidMotion) -> Kinematics {
    let mut kin = Kinematics::default();
    reconstruct(model, q, &vec![DVec3::ZERO; q.len()], root, &mut kin);
    kin
}

/// The generalized gravity on shape `kin`, N·m².
fn gravity_load(model: &StrandModel, kin: &Kinematics, gravity_m_per_s2: DVec3) -> Vec<DVec3> {
    let weight = model.mass_per_length * gravity_m_per_s2;
    let mut out = vec![DVec3::ZERO; model.elements()];
    project_sample_forces(model, kin, |i| weight * kin.samples[i].weight_m, &mut out);
    out
}

/// Natural strains holding `q` (the fitted shape of a strand with `model`'s
/// lengths and stiffness) at rest; see the module docs.
pub fn sag_free(model: &StrandModel, q: &[DVec3], inputs: &SagFreeInputs) -> SagFree {
    let load = applied_forces(model, q, inputs);
    let mut natural: Vec<DVec3> = q
        .iter()
        .zip(&load)
        .zip(&model.stiffness)
        .map(|((q, f), k)| *q - *f / *k)
        .collect();
    let max_strain = natural
        .iter()
        .map(|k| k.abs().max_element())
        .fold(0.0, f64::max);
    let limit = MAX_NATURAL_STRAIN_PER_M;
    for k in &mut natural {
        *k = k.clamp(DVec3::splat(-limit), DVec3::splat(limit));
    }
    let stability = stability(model, q, inputs);
    let status = if stability.is_nan() || stability < 0.0 {
        SagFreeStatus::Unstable
    } else if max_strain > limit {
        SagFreeStatus::Clamped
    } else {
        SagFreeStatus::Held
    };
    SagFree {
        natural_per_m: natural,
        status,
        stability,
        max_strain_per_m: max_strain,
    }
}

/// Smallest eigenvalue of K^{-1/2}(K − ∂Q/∂q)K^{-1/2} at `q`, the head's
/// contact taken with its normals frozen at `q`.
pub fn stability(model: &StrandModel, q: &[DVec3], inputs: &SagFreeInputs) -> f64 {
    let dim = 3 * q.len();
    let scale: Vec<f64> = model
        .stiffness
        .iter()
        .flat_map(|k| k.to_array())
        .map(f64::sqrt)
        .collect();
    // The contact's push with its normals frozen at q (see
    // `RestContact::linearize`): differentiable where the exact one is not.
    let springs = inputs
        .support
        .map(|support| support.linearize(model, &shape(model, q, inputs.root), inputs.root));
    let smooth_forces = |q: &[DVec3]| {
        let kin = shape(model, q, inputs.root);
        let mut out = gravity_load(model, &kin, inputs.gravity_m_per_s2);
        if let Some(springs) = &springs {
            springs.add_load(model, &kin, inputs.root, &mut out);
        }
        out
    };
    let mut h = DMatrix::<f64>::identity(dim, dim);
    let mut probe = q.to_vec();
    for col in 0..dim {
        let (e, c) = (col / 3, col % 3);
        probe[e][c] = q[e][c] + DIFFERENCE_STEP_PER_M;
        let plus = smooth_forces(&probe);
        probe[e][c] = q[e][c] - DIFFERENCE_STEP_PER_M;
        let minus = smooth_forces(&probe);
        probe[e][c] = q[e][c];
        for row in 0..dim {
            let dq =
                (plus[row / 3][row % 3] - minus[row / 3][row % 3]) / (2.0 * DIFFERENCE_STEP_PER_M);
            h[(row, col)] -= dq / (scale[row] * scale[col]);
        }
    }
    let sym = (&h + h.transpose()) * 0.5;
    SymmetricEigen::new(sym).eigenvalues.min()
}

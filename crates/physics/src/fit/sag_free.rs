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
//! Head support. Where the strand lies on the head (samples within the
//! contact skin of the collider's surface) the head carries the part of
//! the sample's weight that presses into it: the reaction −(ρS g·n) n is
//! added wherever ρS g·n < 0, n the outward normal. The strand's
//! stiffness then only has to hold the rest. In simulation the penalty
//! contact supplies that reaction after sinking a little into the skin
//! (`collision/contact.rs`), a fraction of a millimetre.
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

use crate::collision::SignedDistanceField;
use crate::forces::project_sample_forces;
use crate::model::StrandModel;
use crate::motion::RigidMotion;
use crate::natural_shape::MAX_NATURAL_STRAIN_PER_M;
use crate::reconstruct::{Kinematics, reconstruct};

/// Step of the central differences of Q, m⁻¹: Q is smooth in q on the
/// scale of the strains themselves (1–1000 m⁻¹), so the O(h²) error is
/// ~1e-8 relative while round-off stays far below.
const DIFFERENCE_STEP_PER_M: f64 = 1e-3;

/// The head as a support: its surface and where it is.
#[derive(Clone, Copy, Debug)]
pub struct Support<'a> {
    /// The head's signed distance field, head coordinates.
    pub collider: &'a SignedDistanceField,
    /// The head's pose (at rest).
    pub head: &'a RigidMotion,
    /// Samples closer to the surface than this rest on it, metres (the
    /// contact skin, `ContactSettings::skin_m`).
    pub skin_m: f64,
}

/// What the rest shape is solved for.
#[derive(Clone, Copy, Debug)]
pub struct SagFreeInputs<'a> {
    /// The strand's root, at rest, in world coordinates.
    pub root: &'a RigidMotion,
    /// Gravity, m/s².
    pub gravity_m_per_s2: DVec3,
    /// The head, if the strand may rest on it.
    pub support: Option<Support<'a>>,
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

/// The generalized gravity (plus head support) on shape `q`, N·m².
pub fn applied_forces(model: &StrandModel, q: &[DVec3], inputs: &SagFreeInputs) -> Vec<DVec3> {
    let mut kin = Kinematics::default();
    let v = vec![DVec3::ZERO; q.len()];
    reconstruct(model, q, &v, inputs.root, &mut kin);
    let weight = model.mass_per_length * inputs.gravity_m_per_s2;
    let mut out = vec![DVec3::ZERO; q.len()];
    project_sample_forces(
        model,
        &kin,
        |i| {
            let s = &kin.samples[i];
            let world = inputs.root.position_m + s.position_m;
            (weight + support_force(inputs.support.as_ref(), world, weight)) * s.weight_m
        },
        &mut out,
    );
    out
}

/// The head's reaction on a sample of weight `weight` (N/m) at `world`.
fn support_force(support: Option<&Support>, world: DVec3, weight: DVec3) -> DVec3 {
    let Some(support) = support else {
        return DVec3::ZERO;
    };
    let head = support.head;
    let local = head.world_from_body.transpose() * (world - head.position_m);
    let Some((distance, gradient)) = support.collider.sample(local) else {
        return DVec3::ZERO;
    };
    if distance >= support.skin_m || gradient == DVec3::ZERO {
        return DVec3::ZERO;
    }
    let n = (head.world_from_body * gradient).normalize();
    let pressing = weight.dot(n);
    if pressing < 0.0 {
        -pressing * n
    } else {
        DVec3::ZERO
    }
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

/// Smallest eigenvalue of K^{-1/2}(K − ∂Q/∂q)K^{-1/2} at `q`.
pub fn stability(model: &StrandModel, q: &[DVec3], inputs: &SagFreeInputs) -> f64 {
    let dim = 3 * q.len();
    let scale: Vec<f64> = model
        .stiffness
        .iter()
        .flat_map(|k| k.to_array())
        .map(f64::sqrt)
        .collect();
    let mut h = DMatrix::<f64>::identity(dim, dim);
    let mut probe = q.to_vec();
    for col in 0..dim {
        let (e, c) = (col / 3, col % 3);
        probe[e][c] = q[e][c] + DIFFERENCE_STEP_PER_M;
        let plus = applied_forces(model, &probe, inputs);
        probe[e][c] = q[e][c] - DIFFERENCE_STEP_PER_M;
        let minus = applied_forces(model, &probe, inputs);
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

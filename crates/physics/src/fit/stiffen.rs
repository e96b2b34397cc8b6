//! Holding strands that cannot hold themselves: the least stiffening that
//! makes a sag-free equilibrium stable.
//!
//! The sag-free solve ([`super::sag_free`](mod@super::sag_free)) makes any fitted shape an
//! equilibrium, but a strand standing up past its buckling length (or
//! reaching out too far for its stiffness) is at an *unstable* one: in
//! simulation it falls away from the imported shape (on the Sintel groom,
//! 430 of 11,241 strands, by up to 19 cm). Peer tools hold such hair with
//! per-strand stiffness; here the stiffening is the least that does it, and
//! it has a closed form.
//!
//! The stability measure is the smallest eigenvalue μ of
//! K^{-1/2}(K − ∂Q/∂q)K^{-1/2} = I − A, with A = K^{-1/2}(∂Q/∂q)K^{-1/2}
//! (symmetric part). ∂Q/∂q (gravity and head support) does not depend on
//! the stiffness, so scaling the moduli by s scales K by s and gives
//! μ(s) = 1 − λ_max(A)/s, with λ_max(A) = 1 − μ(1). The equilibrium is
//! stable with margin m (μ ≥ m) exactly when
//!
//! s ≥ (1 − μ(1)) / (1 − m).
//!
//! Greenhill's column is the check (crates/physics/tests/fit.rs): upright,
//! λ_max is the load ratio α/α_c, so a column at twice its buckling load
//! needs s = 2/(1 − m).
//!
//! The stiffer strand also needs milder natural strains to hold the same
//! shape (q⁰ = q − Q/(sK)), so the sag-free solve is redone at the new
//! stiffness, and its stability computed again (it equals m to the
//! central differences' accuracy). The scale is capped
//! ([`StiffenOptions::max_scale`]): a strand that would need more stays
//! unstable, and is reported so.

use glam::DVec3;

use super::sag_free::{SagFree, SagFreeInputs, SagFreeStatus, sag_free};
use crate::model::StrandModel;
use crate::{ParamError, StrandParams};

/// The largest scale of the moduli a style accepts; the moduli's own
/// range ([`crate::params::MAX_MODULUS_PA`]) caps it further per material
/// ([`max_stiffness_scale`]): 256× for the default hair.
pub const MAX_STIFFNESS_SCALE: f64 = 1000.0;

/// The largest scale of `params`' moduli that keeps both inside their
/// valid range, capped at [`MAX_STIFFNESS_SCALE`] (≥ 1 for valid params).
pub fn max_stiffness_scale(params: &StrandParams) -> f64 {
    let max = crate::params::MAX_MODULUS_PA;
    (max / params.youngs_modulus_pa)
        .min(max / params.shear_modulus_pa)
        .min(MAX_STIFFNESS_SCALE)
}

/// How unstable strands are stiffened.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StiffenOptions {
    /// The stability a stiffened strand gets, μ in (0, 1). Default 0.2: the
    /// strand's softest mode keeps a fifth of the stiffness it would have
    /// without gravity, enough that round-off and a head shake cannot tip
    /// it, while the stiffening stays the least that holds (μ = 0 would be
    /// neutral, μ → 1 needs infinite stiffness).
    pub margin: f64,
    /// Largest scale of the moduli, ≥ 1. Default: as far as the moduli's
    /// valid range allows ([`max_stiffness_scale`]; 256× for the default
    /// hair, [`StiffenOptions::for_material`] for another). A groom holds
    /// strands standing well past their buckling length (Sintel's
    /// stiffest needs 159×): the artist shaped them so, and the price, a
    /// strand stiffer than its material, is counted in the report.
    pub max_scale: f64,
}

impl Default for StiffenOptions {
    fn default() -> Self {
        Self::for_material(&StrandParams::default())
    }
}

impl StiffenOptions {
    /// The default margin, and the cap the moduli of `params` allow.
    pub fn for_material(params: &StrandParams) -> Self {
        Self {
            margin: 0.2,
            max_scale: max_stiffness_scale(params),
        }
    }

    /// No strand is stiffened (a cap of 1): [`sag_free_stiffened`] is then
    /// the plain sag-free solve.
    pub fn none() -> Self {
        Self {
            max_scale: 1.0,
            ..Self::default()
        }
    }
}

/// A sag-free rest shape, stiffened where it had to be.
#[derive(Clone, Debug, PartialEq)]
pub struct StiffenedRest {
    /// The rest shape at the final stiffness. Its status is
    /// [`SagFreeStatus::Stiffened`] when the scale is above 1.
    pub rest: SagFree,
    /// The scale of the moduli (1: unchanged).
    pub stiffness_scale: f64,
}

impl StiffenedRest {
    /// The scale of the moduli that would make this rest shape stable with
    /// margin `margin`, from its stability at the scale it got: μ at scale
    /// s is 1 − (1 − μ₁)/s (module docs), so μ₁ = 1 − (1 − μ(s)) s. 1 if it
    /// already is, `None` if μ is not a number. For a strand left
    /// [`SagFreeStatus::Unstable`], what holding it would take.
    pub fn needed_scale(&self, margin: f64) -> Option<f64> {
        let unit_stability = 1.0 - (1.0 - self.rest.stability) * self.stiffness_scale;
        stiffness_scale_for_margin(unit_stability, margin)
    }
}

/// The scale of the moduli that makes an equilibrium of stability
/// `stability` (μ at scale 1) stable with margin `margin`: 1 if it already
/// is, `None` if μ is not a number.
pub fn stiffness_scale_for_margin(stability: f64, margin: f64) -> Option<f64> {
    if !stability.is_finite() {
        return None;
    }
    if stability >= margin {
        return Some(1.0);
    }
    Some((1.0 - stability) / (1.0 - margin))
}

/// `params` with both moduli scaled by `scale`.
pub fn stiffened_params(params: &StrandParams, scale: f64) -> StrandParams {
    StrandParams {
        youngs_modulus_pa: params.youngs_modulus_pa * scale,
        shear_modulus_pa: params.shear_modulus_pa * scale,
        ..params.clone()
    }
}

/// The sag-free rest shape of shape `q` for a strand of `params` (its
/// model built with `samples_per_element` quadrature samples), stiffened
/// as `options` allow if its equilibrium is unstable.
pub fn sag_free_stiffened(
    params: &StrandParams,
    samples_per_element: usize,
    q: &[DVec3],
    inputs: &SagFreeInputs,
    options: &StiffenOptions,
) -> Result<StiffenedRest, ParamError> {
    let model = StrandModel::new(params, samples_per_element)?;
    let rest = sag_free(&model, q, inputs);
    if rest.status != SagFreeStatus::Unstable {
        return Ok(StiffenedRest {
            rest,
            stiffness_scale: 1.0,
        });
    }
    let Some(scale) = stiffness_scale_for_margin(rest.stability, options.margin)
        .filter(|s| *s <= options.max_scale)
    else {
        return Ok(StiffenedRest {
            rest,
            stiffness_scale: 1.0,
        });
    };
    let stiff = StrandModel::new(&stiffened_params(params, scale), samples_per_element)?;
    let mut stiff_rest = sag_free(&stiff, q, inputs);
    if stiff_rest.status == SagFreeStatus::Held {
        stiff_rest.status = SagFreeStatus::Stiffened;
    }
    Ok(StiffenedRest {
        rest: stiff_rest,
        stiffness_scale: scale,
    })
}

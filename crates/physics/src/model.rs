//! What the solver needs to know about a strand, derived once from its
//! parameters: element lengths, the stiffness diagonal K, the natural
//! strains qⁿ, the friction diagonal and the quadrature rule.

use glam::DVec3;

use crate::error::ParamError;
use crate::geometry::quadrature::Quadrature;
use crate::params::StrandParams;

/// Per-element constants of a strand, shared by every strand of a group.
#[derive(Clone, Debug, PartialEq)]
pub struct StrandModel {
    /// The parameters this model was built from.
    pub params: StrandParams,
    /// Element lengths ℓ_Q in metres, root first.
    pub lengths_m: Vec<f64>,
    /// K_Q = ((EI)₀ℓ_Q, (EI)₁ℓ_Q, (EI)₂ℓ_Q) in N·m³: U = ½ Σ (q − qⁿ)ᵀK(q − qⁿ).
    pub stiffness: Vec<DVec3>,
    /// Natural strains qⁿ_Q = (τ, κ₁, κ₂) in m⁻¹.
    pub natural: Vec<DVec3>,
    /// Friction diagonal γ ℓ_Q in N·m³·s.
    pub friction: Vec<f64>,
    /// Mass per unit length ρS in kg/m.
    pub mass_per_length: f64,
    /// Air drag ν in N·s/m².
    pub air_drag: f64,
    /// Quadrature rule used on every element.
    pub quadrature: Quadrature,
}

impl StrandModel {
    /// Validates `params` and derives the per-element constants, with a
    /// `quadrature_points`-point Gauss rule per element.
    pub fn new(params: &StrandParams, quadrature_points: usize) -> Result<Self, ParamError> {
        params.validate()?;
        if quadrature_points == 0 || quadrature_points > 8 {
            return Err(ParamError::new(
                "quadrature_points",
                quadrature_points as f64,
                "must lie in 1..=8",
            ));
        }
        let lengths_m = params.element_lengths();
        let ei = DVec3::from_array(params.stiffness());
        Ok(Self {
            params: params.clone(),
            stiffness: lengths_m.iter().map(|&l| ei * l).collect(),
            natural: params.natural_shape.strains(params.elements),
            friction: lengths_m
                .iter()
                .map(|&l| params.internal_friction * l)
                .collect(),
            mass_per_length: params.mass_per_length(),
            air_drag: params.air_drag,
            quadrature: Quadrature::gauss_legendre(quadrature_points),
            lengths_m,
        })
    }

    /// Number of elements N.
    pub fn elements(&self) -> usize {
        self.lengths_m.len()
    }

    /// Number of quadrature samples on the strand, N × points per element.
    pub fn samples(&self) -> usize {
        self.elements() * self.quadrature.len()
    }
}

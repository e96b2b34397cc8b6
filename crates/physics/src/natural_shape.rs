//! The natural (rest) shape of a strand: its curl and twist.
//!
//! A Super-Helix element at rest is a helix with constant Darboux vector
//! (τ, κ₁, κ₂) in the material frame. Artists think in curl radius and helix
//! step (the distance between turns); the conversion is exact: a helix of
//! radius R and step P, with c = P/2π, has curvature κ = R/(R² + c²) and
//! torsion τ = c/(R² + c²), and conversely R = κ/(κ² + τ²),
//! P = 2πτ/(κ² + τ²). The sign of the step is the handedness.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::error::ParamError;
use crate::error::check_range;

/// Largest natural curvature or twist magnitude in m⁻¹ (a 1 mm curl radius).
pub const MAX_NATURAL_STRAIN_PER_M: f64 = 1000.0;

/// The rest twist and curvatures, q = (τ, κ₁, κ₂) per element, in m⁻¹.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum NaturalShape {
    /// Straight: all natural strains zero.
    Straight,
    /// The same strains in every element.
    Uniform {
        /// Natural twist τ in m⁻¹.
        twist_per_m: f64,
        /// Natural curvature κ₁ about n₁ in m⁻¹.
        curvature1_per_m: f64,
        /// Natural curvature κ₂ about n₂ in m⁻¹.
        curvature2_per_m: f64,
    },
    /// A helix given as artists measure it, converted exactly.
    Helix {
        /// Curl radius R in metres (> 0).
        radius_m: f64,
        /// Helix step P in metres: the rise per turn along the axis; the sign
        /// gives the handedness, 0 gives a flat circle.
        step_m: f64,
    },
    /// One (τ, κ₁, κ₂) triple per element, root first, in m⁻¹.
    PerElement(Vec<[f64; 3]>),
}

/// Natural strains (τ, κ₁, κ₂) in m⁻¹ of a helix of radius `radius_m` and
/// step `step_m`.
pub fn helix_strains(radius_m: f64, step_m: f64) -> DVec3 {
    let c = step_m / std::f64::consts::TAU;
    let denom = radius_m * radius_m + c * c;
    DVec3::new(c / denom, radius_m / denom, 0.0)
}

/// Radius and step (metres) of the helix an element with strains
/// `(τ, κ₁, κ₂)` follows; a straight element has infinite radius.
pub fn helix_radius_and_step(strains: DVec3) -> (f64, f64) {
    let kappa = strains.y.hypot(strains.z);
    let omega2 = strains.length_squared();
    if omega2 == 0.0 {
        return (f64::INFINITY, 0.0);
    }
    (kappa / omega2, std::f64::consts::TAU * strains.x / omega2)
}

impl NaturalShape {
    /// Natural strains qⁿ for `elements` elements.
    pub fn strains(&self, elements: usize) -> Vec<DVec3> {
        match self {
            NaturalShape::Straight => vec![DVec3::ZERO; elements],
            NaturalShape::Uniform {
                twist_per_m,
                curvature1_per_m,
                curvature2_per_m,
            } => vec![DVec3::new(*twist_per_m, *curvature1_per_m, *curvature2_per_m); elements],
            NaturalShape::Helix { radius_m, step_m } => {
                vec![helix_strains(*radius_m, *step_m); elements]
            }
            NaturalShape::PerElement(list) => list.iter().map(|k| DVec3::from_array(*k)).collect(),
        }
    }

    /// Checks the shape for NaN, out-of-range strains and, for
    /// `PerElement`, a length that matches `elements`.
    pub fn validate(&self, elements: usize) -> Result<(), ParamError> {
        let limit = MAX_NATURAL_STRAIN_PER_M;
        match self {
            NaturalShape::Straight => Ok(()),
            NaturalShape::Uniform {
                twist_per_m,
                curvature1_per_m,
                curvature2_per_m,
            } => {
                check_range("natural_shape.twist_per_m", *twist_per_m, -limit, limit)?;
                check_range(
                    "natural_shape.curvature1_per_m",
                    *curvature1_per_m,
                    -limit,
                    limit,
                )?;
                check_range(
                    "natural_shape.curvature2_per_m",
                    *curvature2_per_m,
                    -limit,
                    limit,
                )
            }
            NaturalShape::Helix { radius_m, step_m } => {
                check_range("natural_shape.radius_m", *radius_m, 1e-3, 1.0)?;
                check_range("natural_shape.step_m", *step_m, -1.0, 1.0)
            }
            NaturalShape::PerElement(list) => {
                if list.len() != elements {
                    return Err(ParamError::new(
                        "natural_shape",
                        list.len() as f64,
                        format!(
                            "lists {} elements but the strand has {elements}",
                            list.len()
                        ),
                    ));
                }
                for k in list.iter().flatten() {
                    check_range("natural_shape", *k, -limit, limit)?;
                }
                Ok(())
            }
        }
    }
}

//! Physical parameters of a strand, with units, ranges and the reason for
//! each default.
//!
//! A [`StrandParams`] describes one strand, or a group of strands that share
//! their physics. Everything the solver needs per element (lengths, the
//! stiffness diagonal `K`, the natural strains `qⁿ`) is derived from it by
//! [`crate::StrandModel::new`], after [`StrandParams::validate`] has checked
//! every field. Defaults describe an average human hair 20 cm long, from the
//! measurements quoted in `docs/physics.md` section 3.

use serde::{Deserialize, Serialize};

use crate::error::{ParamError, check_range};
use crate::natural_shape::NaturalShape;

/// How the strand's length is cut into elements.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ElementLayout {
    /// All elements the same length, `length_m / elements`.
    Uniform,
    /// Element lengths grow geometrically from root to tip, so curvature,
    /// which piles up within the elasto-gravity length of the root, gets
    /// more resolution there.
    Graded {
        /// Tip element length over root element length (≥ 1; 1 is uniform).
        tip_to_root_ratio: f64,
    },
}

/// The largest Young's or shear modulus a strand may have, Pa: a hundred
/// times the stiffest keratin fibres, far past any hair; steel is 2e11.
pub const MAX_MODULUS_PA: f64 = 1e12;

/// Physical parameters shared by a group of strands.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StrandParams {
    /// Strand length L in metres, range (0, 2]. Default 0.2: shoulder-length
    /// hair, long enough that gravity bends it (4× the elasto-gravity length).
    pub length_m: f64,
    /// Number of Super-Helix elements N, range 1..=200. Default 10: Bertails
    /// 2006 used 5 per guide; 10 halves the discretisation error of a swing
    /// (first-mode error 0.19% instead of 0.78%).
    pub elements: usize,
    /// How the length is divided among the elements. Default uniform.
    pub layout: ElementLayout,
    /// Fibre radius r in metres (the radius of a circle of the same area),
    /// range [5e-6, 5e-4]. Default 35e-6, typical human hair.
    pub radius_m: f64,
    /// Ellipticity e = a/b of the cross-section, range [1, 4]. Default 1.0
    /// (round, straight Asian hair); African curly hair reaches 1.6 and more.
    pub ellipticity: f64,
    /// Mass density ρ in kg/m³, range [100, 10000]. Default 1300, keratin.
    pub density_kg_per_m3: f64,
    /// Young's modulus E in pascals (bending), range [1e6,
    /// [`MAX_MODULUS_PA`]]. Default
    /// 3.9e9, measured on human hair.
    pub youngs_modulus_pa: f64,
    /// Shear modulus G in pascals (twisting), range [1e5,
    /// [`MAX_MODULUS_PA`]]. Default
    /// 0.9e9, measured on human hair.
    pub shear_modulus_pa: f64,
    /// The rest shape: natural twist and curvatures (the curl).
    pub natural_shape: NaturalShape,
    /// Internal friction γ in N·m²·s: the generalized force −γ ℓ_Q q̇_Q
    /// resists strain rates. Range [0, 1e-6]. Default 2e-10, which gives
    /// the first bending mode of a default strand a damping ratio of a few
    /// percent, so a swing settles in a few seconds as real hair does.
    pub internal_friction: f64,
    /// Air drag ν in N·s/m² (force per unit length per unit velocity
    /// relative to the air), range [0, 1e-2]. Default 1e-5: about a tenth of
    /// Stokes drag on an isolated fibre, as a strand in a groom shares its
    /// air with its neighbours.
    pub air_drag: f64,
}

impl Default for StrandParams {
    fn default() -> Self {
        Self {
            length_m: 0.2,
            elements: 10,
            layout: ElementLayout::Uniform,
            radius_m: 35e-6,
            ellipticity: 1.0,
            density_kg_per_m3: 1300.0,
            youngs_modulus_pa: 3.9e9,
            shear_modulus_pa: 0.9e9,
            natural_shape: NaturalShape::Straight,
            internal_friction: 2e-10,
            air_drag: 1e-5,
        }
    }
}

/// Largest element count a strand may have; dense solves grow as N³.
pub const MAX_ELEMENTS: usize = 200;

impl StrandParams {
    /// Checks every field for NaN, infinities and values outside the
    /// documented range; the error names the offending field.
    pub fn validate(&self) -> Result<(), ParamError> {
        let l = self.length_m;
        if !l.is_finite() || l <= 0.0 || l > 2.0 {
            return Err(ParamError::new("length_m", l, "must lie in (0, 2]"));
        }
        if self.elements == 0 || self.elements > MAX_ELEMENTS {
            return Err(ParamError::new(
                "elements",
                self.elements as f64,
                format!("must lie in 1..={MAX_ELEMENTS}"),
            ));
        }
        if let ElementLayout::Graded { tip_to_root_ratio } = self.layout {
            check_range("layout.tip_to_root_ratio", tip_to_root_ratio, 1.0, 100.0)?;
        }
        check_range("radius_m", self.radius_m, 5e-6, 5e-4)?;
        check_range("ellipticity", self.ellipticity, 1.0, 4.0)?;
        check_range("density_kg_per_m3", self.density_kg_per_m3, 100.0, 1e4)?;
        check_range(
            "youngs_modulus_pa",
            self.youngs_modulus_pa,
            1e6,
            MAX_MODULUS_PA,
        )?;
        check_range(
            "shear_modulus_pa",
            self.shear_modulus_pa,
            1e5,
            MAX_MODULUS_PA,
        )?;
        check_range("internal_friction", self.internal_friction, 0.0, 1e-6)?;
        check_range("air_drag", self.air_drag, 0.0, 1e-2)?;
        self.natural_shape.validate(self.elements)
    }

    /// Cross-section area πr² in m².
    pub fn area_m2(&self) -> f64 {
        std::f64::consts::PI * self.radius_m * self.radius_m
    }

    /// Mass per unit length ρS in kg/m.
    pub fn mass_per_length(&self) -> f64 {
        self.density_kg_per_m3 * self.area_m2()
    }

    /// Stiffnesses ((EI)₀ = G·J_t, (EI)₁ = E·I₁, (EI)₂ = E·I₂) in N·m², for
    /// an elliptic section of area πr² and ellipticity e:
    /// I₁ = πr⁴/(4e), I₂ = πr⁴e/4, J_t = πr⁴/(e + 1/e).
    pub fn stiffness(&self) -> [f64; 3] {
        let r4 = self.radius_m.powi(4);
        let e = self.ellipticity;
        let pi = std::f64::consts::PI;
        [
            self.shear_modulus_pa * pi * r4 / (e + 1.0 / e),
            self.youngs_modulus_pa * pi * r4 / (4.0 * e),
            self.youngs_modulus_pa * pi * r4 * e / 4.0,
        ]
    }

    /// Element lengths ℓ_Q in metres, root first; they sum to `length_m`.
    pub fn element_lengths(&self) -> Vec<f64> {
        let n = self.elements;
        match self.layout {
            ElementLayout::Uniform => vec![self.length_m / n as f64; n],
            ElementLayout::Graded { tip_to_root_ratio } => {
                if n == 1 {
                    return vec![self.length_m];
                }
                let growth = tip_to_root_ratio.powf(1.0 / (n - 1) as f64);
                let raw: Vec<f64> = (0..n).map(|i| growth.powi(i as i32)).collect();
                let total: f64 = raw.iter().sum();
                raw.iter().map(|w| w / total * self.length_m).collect()
            }
        }
    }
}

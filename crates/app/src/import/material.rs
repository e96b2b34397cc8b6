//! The hair's material at import: what the fibre is made of, which the
//! groom file does not say.
//!
//! A groom carries curves, not physics: its strands' radius, cross-section,
//! density and moduli come from the artist. They matter at import, not only
//! later: the sag-free rest shape balances each strand's weight (ρ π r² e g
//! per metre) against its bending stiffness (E I), so hair twice as heavy
//! needs other natural curvatures to hang in the groom's shape, and a strand
//! that stands on stiff hair may fall on fine hair. `import` therefore
//! takes the material first: copied from a style (`--material STYLE`, its
//! first group's), then any of the single values on top, then the defaults
//! of [`StrandParams`] for what is left; the fit supplies each strand's
//! length, elements and natural shape.

use std::path::PathBuf;

use anyhow::{Context as _, bail};
use clap::Args;
use helixhair_physics::StrandParams;

use crate::style::Style;

/// The material flags of `helixhair import`.
#[derive(Args, Clone, Debug, Default)]
pub struct MaterialArgs {
    /// Copy the hair's material (radius, ellipticity, density, moduli,
    /// internal friction, air drag) from this style's first group; the
    /// flags below override single values
    #[arg(long, value_name = "STYLE")]
    pub material: Option<PathBuf>,
    /// Fibre radius in metres (the major semi-axis) [default: 35e-6]
    #[arg(long, value_name = "M")]
    pub radius_m: Option<f64>,
    /// Cross-section ellipticity, major over minor axis (1 is round)
    #[arg(long, value_name = "E")]
    pub ellipticity: Option<f64>,
    /// Fibre density in kg/m³ [default: 1300]
    #[arg(long, value_name = "KG_PER_M3")]
    pub density_kg_per_m3: Option<f64>,
    /// Young's modulus in pascals [default: 3.9e9]
    #[arg(long, value_name = "PA")]
    pub youngs_modulus_pa: Option<f64>,
    /// Shear modulus in pascals [default: 0.9e9]
    #[arg(long, value_name = "PA")]
    pub shear_modulus_pa: Option<f64>,
    /// A material given in memory (the window's open style), in place of
    /// `--material`'s file; the single values still go over it.
    #[arg(skip)]
    pub from_params: Option<Box<StrandParams>>,
}

impl MaterialArgs {
    /// The strand parameters the import starts every strand from: the
    /// style's material, the single values over it, checked; an error
    /// names the style file (with its line) or the flag.
    pub fn params(&self) -> anyhow::Result<StrandParams> {
        let mut params = StrandParams::default();
        if let Some(path) = &self.material {
            let style = Style::load(path)?;
            let Some(group) = style.groups.first() else {
                bail!(
                    "--material {}: the style has no group to copy the material from",
                    path.display()
                );
            };
            copy_material(&group.params, &mut params);
        }
        if let Some(from) = &self.from_params {
            copy_material(from, &mut params);
        }
        let flags = [
            ("--radius-m", self.radius_m, &mut params.radius_m),
            ("--ellipticity", self.ellipticity, &mut params.ellipticity),
            (
                "--density-kg-per-m3",
                self.density_kg_per_m3,
                &mut params.density_kg_per_m3,
            ),
            (
                "--youngs-modulus-pa",
                self.youngs_modulus_pa,
                &mut params.youngs_modulus_pa,
            ),
            (
                "--shear-modulus-pa",
                self.shear_modulus_pa,
                &mut params.shear_modulus_pa,
            ),
        ];
        let mut given = Vec::new();
        for (flag, value, field) in flags {
            if let Some(value) = value {
                *field = value;
                given.push(flag);
            }
        }
        params.validate().with_context(|| {
            if given.is_empty() {
                "the material the import starts from".to_owned()
            } else {
                format!("the material given by {}", given.join(", "))
            }
        })?;
        Ok(params)
    }
}

/// Copies what the fibre is made of (not its length, elements or shape)
/// from `from` into `into`.
fn copy_material(from: &StrandParams, into: &mut StrandParams) {
    into.radius_m = from.radius_m;
    into.ellipticity = from.ellipticity;
    into.density_kg_per_m3 = from.density_kg_per_m3;
    into.youngs_modulus_pa = from.youngs_modulus_pa;
    into.shear_modulus_pa = from.shear_modulus_pa;
    into.internal_friction = from.internal_friction;
    into.air_drag = from.air_drag;
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    #[test]
    fn flags_override_the_style_which_overrides_the_defaults() {
        let defaults = MaterialArgs::default().params().expect("the defaults hold");
        assert_eq!(defaults, StrandParams::default());
        let curly =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/styles/groomed/curly.ron");
        let args = MaterialArgs {
            material: Some(curly.clone()),
            density_kg_per_m3: Some(1100.0),
            ..MaterialArgs::default()
        };
        let params = args.params().expect("holds");
        let style = Style::load(&curly).expect("the example loads");
        let from = &style.groups[0].params;
        assert_eq!(params.radius_m, from.radius_m);
        assert_eq!(params.ellipticity, from.ellipticity);
        assert_eq!(params.internal_friction, from.internal_friction);
        assert_eq!(params.density_kg_per_m3, 1100.0);
        // The shape is the fit's, not the style's.
        assert_eq!(params.natural_shape, StrandParams::default().natural_shape);
        // A material in memory (the window's open style) copies the same.
        let in_memory = MaterialArgs {
            from_params: Some(Box::new(from.clone())),
            density_kg_per_m3: Some(1100.0),
            ..MaterialArgs::default()
        };
        assert_eq!(in_memory.params().expect("holds"), params);
    }

    #[test]
    fn an_impossible_value_names_its_flag_and_field() {
        let args = MaterialArgs {
            radius_m: Some(-1.0),
            ..MaterialArgs::default()
        };
        let error = format!("{:#}", args.params().expect_err("a negative radius"));
        assert!(error.contains("--radius-m"), "{error}");
        assert!(error.contains("radius_m"), "{error}");
        let args = MaterialArgs {
            shear_modulus_pa: Some(f64::NAN),
            ..MaterialArgs::default()
        };
        let error = format!("{:#}", args.params().expect_err("NaN"));
        assert!(error.contains("--shear-modulus-pa"), "{error}");
        let args = MaterialArgs {
            material: Some("no/such/style.ron".into()),
            ..MaterialArgs::default()
        };
        let error = format!("{:#}", args.params().expect_err("no file"));
        assert!(error.contains("no/such/style.ron"), "{error}");
    }
}

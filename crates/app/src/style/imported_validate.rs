//! The checks an imported groom's strands pass in a style
//! ([`crate::style::imported`]): counts, lengths, finite strains within the
//! format's limits, roots, and each strand's parameters as the physics
//! checks them.

use helixhair_physics::StrandParams;
use helixhair_physics::natural_shape::MAX_NATURAL_STRAIN_PER_M;
use helixhair_physics::params::MAX_ELEMENTS;

use crate::style::checks::{MAX_ROOT_COORDINATE_M, invalid as issue, param_issue};
use crate::style::error::StyleIssue;
use crate::style::field_path::FieldPath;
use crate::style::imported::{ImportedStrands, MAX_IMPORTED_STRANDS};
use helixhair_physics::fit::stiffen::MAX_STIFFNESS_SCALE;

/// Checks every strand; issues name `at.strands[i].field`.
pub fn validate_imported(
    imported: &ImportedStrands,
    material: &StrandParams,
    at: &FieldPath,
) -> Result<(), StyleIssue> {
    let strands = at.field("strands");
    if imported.strands.is_empty() || imported.strands.len() > MAX_IMPORTED_STRANDS {
        return Err(issue(
            strands,
            format!(
                "must list 1 to {MAX_IMPORTED_STRANDS} strands, not {}",
                imported.strands.len()
            ),
        ));
    }
    if imported.guides().next().is_none() {
        return Err(issue(
            strands,
            "needs at least one strand with `guide: true`",
        ));
    }
    for (i, strand) in imported.strands.iter().enumerate() {
        let at = strands.index(i);
        let n = strand.strains.len();
        if n == 0 || n > MAX_ELEMENTS {
            return Err(issue(
                at.field("strains"),
                format!("must list 1 to {MAX_ELEMENTS} elements, not {n}"),
            ));
        }
        if strand.natural.len() != n {
            return Err(issue(
                at.field("natural"),
                format!(
                    "lists {} elements but `strains` lists {n}",
                    strand.natural.len()
                ),
            ));
        }
        let length = strand.element_length_m * n as f64;
        if !(strand.element_length_m.is_finite() && length > 0.0 && length <= 2.0) {
            return Err(issue(
                at.field("element_length_m"),
                format!(
                    "times the element count must give a length in (0, 2] m; found {}",
                    strand.element_length_m
                ),
            ));
        }
        for (field, list) in [("strains", &strand.strains), ("natural", &strand.natural)] {
            if let Some(e) = list
                .iter()
                .position(|k| !k.is_finite() || k.abs().max_element() > MAX_NATURAL_STRAIN_PER_M)
            {
                return Err(issue(
                    at.field(field).index(e),
                    format!("must be finite and within ±{MAX_NATURAL_STRAIN_PER_M} m⁻¹"),
                ));
            }
        }
        let root = &strand.root;
        if !(root.position_m.is_finite()
            && root.position_m.abs().max_element() <= MAX_ROOT_COORDINATE_M)
        {
            return Err(issue(
                at.field("root").field("position_m"),
                "must be finite and within 10 m",
            ));
        }
        if !root.direction.is_finite()
            || root.direction.length() < 1e-9
            || !root.reference.is_finite()
        {
            return Err(issue(
                at.field("root").field("direction"),
                "must be finite and non-zero",
            ));
        }
        if !(1.0..=MAX_STIFFNESS_SCALE).contains(&strand.stiffness_scale) {
            return Err(issue(
                at.field("stiffness_scale"),
                format!(
                    "must be 1 to {MAX_STIFFNESS_SCALE}; found {}",
                    strand.stiffness_scale
                ),
            ));
        }
        strand
            .params(material)
            .validate()
            .map_err(|e| param_issue(&at, &e))?;
    }
    Ok(())
}

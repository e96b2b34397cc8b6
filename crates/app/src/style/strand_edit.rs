//! Per-strand changes over a group's shared parameters: what the styling
//! tools leave behind (a cut, a painted curl, a combed shape frozen as the
//! strand's rest shape) and what "set current shape as rest" keeps.
//!
//! A procedural group shares one [`StrandParams`] among its strands. A
//! brush touches some of them: those strands then differ from the group
//! in a few values, and only those values are written, strand by strand,
//! so the file stays readable and the group keeps everything else it had
//! (its placement, drawn strands, curl and length controls):
//!
//! ```ron
//! edits: [
//!     (strand: 3, length_m: 0.15),
//!     (strand: 7, natural_shape: Helix(radius_m: 0.01, step_m: 0.03)),
//!     (strand: 9, rest: (strains: [(0.0, 1.5, 0.0), …], natural: [(0.0, 2.1, 0.3), …])),
//! ]
//! ```
//!
//! `strand` counts the group's simulated strands from 0 in the order the
//! engine adds them: the listed roots, then the roots its `scalp`
//! placement grows (the same on every run: the placement is seeded).
//! Changing the placement's count or seed re-deals the roots, and edits
//! then apply to whichever strands now carry those numbers.
//!
//! # How an edit becomes a strand
//!
//! [`StrandEdit::params`] starts from the group's parameters and replaces
//! what the edit gives: a new length keeps the group's element size (the
//! element count scales with the length, at least one element of at least
//! [`MIN_ELEMENT_LENGTH_M`]); a painted natural shape replaces the group's;
//! a `rest` shape gives natural strains per element (the sag-free solve of
//! the shape the strand was frozen in) and the strains it starts in, which
//! is also the shape the guard resets it to. A stiffness scale multiplies
//! both moduli, as the import's stiffening does. A root direction (a
//! parting) turns the strand's root frame; a kept rest shape turns with it.

use glam::DVec3;
use helixhair_physics::fit::stiffen::stiffened_params;
use helixhair_physics::natural_shape::MAX_NATURAL_STRAIN_PER_M;
use helixhair_physics::{NaturalShape, StrandParams};
use serde::{Deserialize, Serialize};

use crate::style::StrandGroup;
use crate::style::checks::{check_finite, invalid, param_issue};
use crate::style::error::StyleIssue;
use crate::style::field_path::FieldPath;
use crate::style::root::Root;

/// Stiffness scales a painted or frozen strand may carry: a tenth of the
/// group's moduli to a hundred times.
pub const STIFFNESS_SCALE_RANGE: (f64, f64) = (0.1, 100.0);

/// The shortest element a cut may leave, metres: a strand is never cut
/// below one element of this length. 5 mm is under the shortest element
/// any bundled style uses (the fringe's 2 cm), and well above the length
/// at which an element's helix series lose accuracy.
pub const MIN_ELEMENT_LENGTH_M: f64 = 0.005;

/// One strand's changes over its group's parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrandEdit {
    /// The strand: its place among the group's simulated strands, from 0
    /// (listed roots, then scalp-grown roots).
    pub strand: usize,
    /// Its length, metres, where a cut or growth changed it; the element
    /// count follows (the group's element size kept).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::style::groom::inline_option"
    )]
    pub length_m: Option<f64>,
    /// Its natural shape where one was painted (curl, twist), instead of
    /// the group's.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::style::groom::inline_option"
    )]
    pub natural_shape: Option<NaturalShape>,
    /// Factor on the group's Young's and shear moduli, in [0.1, 100]
    /// (painted stiffness, or the least stiffening that holds a frozen
    /// shape). Default 1.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::style::groom::inline_option"
    )]
    pub stiffness_scale: Option<f64>,
    /// Its root's growth direction, head coordinates, where a parting
    /// turned it (any non-zero length; normalised).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::style::groom::inline_option"
    )]
    pub root_direction: Option<DVec3>,
    /// The shape the strand rests in, where a comb, a grab or a freeze
    /// left it: it starts there, rests there, and is reset there.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::style::groom::inline_option"
    )]
    pub rest: Option<RestShape>,
}

/// A shape kept as a strand's rest shape: the strains it is in, and the
/// natural strains that make it a static equilibrium under gravity (and
/// the head's support where it lies on the head).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RestShape {
    /// Strains (τ, κ₁, κ₂) per element, root first, m⁻¹: the shape.
    pub strains: Vec<DVec3>,
    /// Natural strains per element, m⁻¹ (as many as `strains`).
    pub natural: Vec<DVec3>,
}

impl StrandEdit {
    /// An edit of strand `strand` that changes nothing yet.
    pub fn new(strand: usize) -> Self {
        Self {
            strand,
            length_m: None,
            natural_shape: None,
            stiffness_scale: None,
            root_direction: None,
            rest: None,
        }
    }

    /// Whether the edit changes nothing (and can be dropped).
    pub fn is_empty(&self) -> bool {
        self.length_m.is_none()
            && self.natural_shape.is_none()
            && self.stiffness_scale.is_none()
            && self.root_direction.is_none()
            && self.rest.is_none()
    }

    /// The strand's parameters: `group`'s with this edit's changes (see
    /// the module docs).
    pub fn params(&self, group: &StrandParams) -> StrandParams {
        let mut params = stiffened_params(group, self.stiffness_scale.unwrap_or(1.0));
        if let Some(length_m) = self.length_m {
            params.elements = elements_for_length(group, length_m);
            params.length_m = length_m;
        }
        if let Some(shape) = &self.natural_shape {
            params.natural_shape = shape.clone();
        }
        if let Some(rest) = &self.rest {
            params.elements = rest.natural.len();
            params.natural_shape =
                NaturalShape::PerElement(rest.natural.iter().map(|k| k.to_array()).collect());
        }
        params
    }

    /// The strand's root: `root` with this edit's growth direction.
    pub fn root(&self, root: &Root) -> Root {
        Root {
            direction: self.root_direction.unwrap_or(root.direction),
            ..*root
        }
    }

    /// The strains the strand starts in and rests in, when the edit keeps a
    /// shape.
    pub fn rest_strains(&self) -> Option<&[DVec3]> {
        self.rest.as_ref().map(|r| r.strains.as_slice())
    }
}

/// The element count of a strand of `length_m` cut or grown from a group
/// with parameters `group`: the group's element size kept (so resolution
/// per metre does not change), at least one element.
pub fn elements_for_length(group: &StrandParams, length_m: f64) -> usize {
    let per_element_m = group.length_m / group.elements as f64;
    let count = (length_m / per_element_m).round() as usize;
    count.clamp(1, helixhair_physics::params::MAX_ELEMENTS)
}

/// The edit of strand `strand` in `edits` (sorted by strand, as a valid
/// style's are) and its place in the list, if any.
pub fn edit_of(edits: &[StrandEdit], strand: usize) -> Option<(usize, &StrandEdit)> {
    let at = edits.binary_search_by_key(&strand, |e| e.strand).ok()?;
    Some((at, &edits[at]))
}

/// The edit of strand `strand` in `edits`, made if missing (kept sorted by
/// strand).
pub fn edit_mut(edits: &mut Vec<StrandEdit>, strand: usize) -> &mut StrandEdit {
    let at = match edits.binary_search_by_key(&strand, |e| e.strand) {
        Ok(at) => at,
        Err(at) => {
            edits.insert(at, StrandEdit::new(strand));
            at
        }
    };
    &mut edits[at]
}

/// Checks `group`'s edits; issues name `at[i].field`. The strand numbers
/// are bounded where the group's strand count is known (no scalp
/// placement still to grow), and each edit is checked against its
/// strand's own parameters where they are known
/// ([`StrandGroup::base_params`]).
pub fn validate_edits(group: &StrandGroup, at: &FieldPath) -> Result<(), StyleIssue> {
    let edits = &group.edits;
    let strands = group.scalp.is_none().then(|| group.simulated_count());
    for (i, edit) in edits.iter().enumerate() {
        let at = at.index(i);
        if i > 0 && edits[i - 1].strand >= edit.strand {
            return Err(invalid(
                at.field("strand"),
                format!(
                    "edits must name each strand once, in increasing order; {} follows {}",
                    edit.strand,
                    edits[i - 1].strand
                ),
            ));
        }
        if let Some(count) = strands
            && edit.strand >= count
        {
            return Err(invalid(
                at.field("strand"),
                format!(
                    "the group has {count} strands (0 to {}); found {}",
                    count.saturating_sub(1),
                    edit.strand
                ),
            ));
        }
        if let Some(length_m) = edit.length_m
            && !(length_m.is_finite() && (MIN_ELEMENT_LENGTH_M..=2.0).contains(&length_m))
        {
            return Err(invalid(
                at.field("length_m"),
                format!("must lie in [{MIN_ELEMENT_LENGTH_M}, 2] metres; found {length_m}"),
            ));
        }
        if let Some(scale) = edit.stiffness_scale {
            let (low, high) = STIFFNESS_SCALE_RANGE;
            if !(scale.is_finite() && (low..=high).contains(&scale)) {
                return Err(invalid(
                    at.field("stiffness_scale"),
                    format!("must lie in [{low}, {high}]; found {scale}"),
                ));
            }
        }
        if let Some(direction) = edit.root_direction {
            check_finite(direction, &at.field("root_direction"), None)?;
            if direction.length() < 1e-9 {
                return Err(invalid(at.field("root_direction"), "must not be zero"));
            }
        }
        let Some(base) = group.base_params(edit.strand) else {
            continue;
        };
        if let Some(rest) = &edit.rest {
            let expected = match edit.length_m {
                Some(length_m) => elements_for_length(&base, length_m),
                None => base.elements,
            };
            for (name, list) in [("strains", &rest.strains), ("natural", &rest.natural)] {
                let list_at = at.field("rest").field(name);
                if list.len() != expected {
                    return Err(invalid(
                        list_at,
                        format!(
                            "must hold one strain triple per element ({expected}); found {}",
                            list.len()
                        ),
                    ));
                }
                for (k, strain) in list.iter().enumerate() {
                    check_finite(*strain, &list_at.index(k), Some(MAX_NATURAL_STRAIN_PER_M))?;
                }
            }
        }
        edit.params(&base)
            .validate()
            .map_err(|e| param_issue(&at, &e))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::style::Style;

    const STYLE: &str = "(version: 1, name: \"s\", groups: [(\n    name: \"g\",\n    params: (length_m: 0.3, elements: 6),\n    roots: [(position_m: (0.0, 0.1, 0.0), direction: (0.0, 1.0, 0.0))],\n    edits: [EDIT],\n)])\n";

    fn load(edit: &str) -> Result<Style, String> {
        Style::from_ron(&STYLE.replace("EDIT", edit), Path::new("e.ron")).map_err(|e| e.to_string())
    }

    #[test]
    fn a_cut_keeps_the_element_size_and_a_curl_replaces_the_shape() {
        let style =
            load("(strand: 0, length_m: 0.15, natural_shape: Helix(radius_m: 0.01, step_m: 0.03))")
                .unwrap();
        let group = &style.groups[0];
        let params = group.edits[0].params(&group.params);
        // 5 cm elements kept: 0.15 m is 3 of them.
        assert_eq!((params.length_m, params.elements), (0.15, 3));
        assert_eq!(
            params.natural_shape,
            helixhair_physics::NaturalShape::Helix {
                radius_m: 0.01,
                step_m: 0.03
            }
        );
    }

    #[test]
    fn an_imported_strand_is_edited_over_its_own_parameters() {
        // Two elements of 5 cm: the group's params (default element count)
        // are not this strand's.
        let src = "(version: 1, name: \"s\", groups: [(\n    name: \"i\",\n    imported: (source: \"x.tfx\", strands: [(\n        root: (position_m: (0.0, 0.1, 0.0), direction: (0.0, 1.0, 0.0)),\n        element_length_m: 0.05,\n        strains: [(0.0, 1.0, 0.0), (0.0, 1.0, 0.0)],\n        natural: [(0.0, 1.0, 0.0), (0.0, 1.0, 0.0)],\n    )]),\n    edits: [(strand: 0, rest: (strains: [(0.0, 2.0, 0.0), (0.0, 2.0, 0.0)], natural: [(0.0, 3.0, 0.0), (0.0, 3.0, 0.0)]))],\n)])\n";
        let style = Style::from_ron(src, Path::new("i.ron")).unwrap_or_else(|e| panic!("{e}"));
        let group = &style.groups[0];
        let base = group.base_params(0).unwrap();
        assert_eq!((base.elements, base.length_m), (2, 0.1));
        assert_eq!(group.edits[0].params(&base).elements, 2);
        // Past the last strand: refused.
        let past = src.replace("(strand: 0,", "(strand: 1,");
        let error = Style::from_ron(&past, Path::new("i.ron"))
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("field `groups[0].edits[0].strand`"),
            "{error}"
        );
    }

    #[test]
    fn bad_edits_name_their_field() {
        let wrong_count =
            load("(strand: 0, rest: (strains: [(0.0, 1.0, 0.0)], natural: [(0.0, 1.0, 0.0)]))")
                .unwrap_err();
        assert!(
            wrong_count.contains("field `groups[0].edits[0].rest.strains`")
                && wrong_count.contains("one strain triple per element (6)"),
            "{wrong_count}"
        );
        let no_strand = load("(strand: 3, length_m: 0.1)").unwrap_err();
        assert!(
            no_strand.contains("field `groups[0].edits[0].strand`"),
            "{no_strand}"
        );
        let too_short = load("(strand: 0, length_m: 0.001)").unwrap_err();
        assert!(
            too_short.contains("field `groups[0].edits[0].length_m`"),
            "{too_short}"
        );
        let nan = load("(strand: 0, stiffness_scale: NaN)").unwrap_err();
        assert!(nan.contains("stiffness_scale"), "{nan}");
    }
}

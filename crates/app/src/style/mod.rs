//! Hair styles: groups of strands with their physics and their roots on the
//! head, read from and written to versioned RON files.
//!
//! The format is documented field by field in `docs/style-format.md`. The
//! physics types ([`SimSettings`], [`StrandParams`]) are embedded as they
//! are, so a style can set every parameter the solver has, with the
//! solver's defaults for what it leaves out.
//!
//! Loading is three passes over the text: a version probe (so that a file
//! from a newer format says so instead of failing on its new fields), the
//! strict parse (`deny_unknown_fields` everywhere), and
//! [`Style::validate`]. Errors of all three name the file, line and field
//! ([`StyleError::Located`]); see [`crate::style::source_map`] for how positions
//! are found for values rejected after parsing.

pub mod checks;
pub mod error;
pub mod field_path;
pub mod groom;
pub mod groom_validate;
pub mod imported;
pub mod imported_validate;
pub mod ron_file;
pub mod root;
pub mod source_map;
pub mod strand_edit;
pub mod validate;

#[cfg(test)]
mod groom_tests;
#[cfg(test)]
mod tests;

use std::path::Path;

use helixhair_physics::engine::EngineKind;
use helixhair_physics::{RootPose, SimSettings, StrandParams};
use serde::{Deserialize, Serialize};

use crate::atomic_write::write_atomically;
use crate::style::error::{StyleError, StyleErrorKind, StyleIssue};
use crate::style::field_path::FieldPath;
use crate::style::groom::{RenderStrands, ScalpPlacement};
use crate::style::imported::ImportedStrands;
pub use crate::style::root::{DEFAULT_REFERENCE, Root};
use crate::style::source_map::{SourceMap, TextPosition};
use crate::style::strand_edit::StrandEdit;

/// The style format version this build reads and writes. Files with any
/// other version are refused (see "Version policy" in the format docs).
pub const STYLE_VERSION: u32 = 1;

/// A hair style: simulation settings and groups of strands.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Style {
    /// Format version; must be [`STYLE_VERSION`].
    pub version: u32,
    /// Display name of the style.
    pub name: String,
    /// Solver, time step, gravity; every field has a default.
    #[serde(default)]
    pub sim: SimSettings,
    /// The physics engine: `Reference` (the f64 `HairSystem`, every solver,
    /// guard and collider; the default) or `Batch` (the f32 SIMD
    /// `BatchSystem` on all cores, `sim.method` `Exact` or `BlockDiagonal`
    /// only). See [`helixhair_physics::engine`].
    #[serde(default)]
    pub engine: EngineKind,
    /// Accuracy target for the automatic choice of solver and element
    /// count (`crate::sim::auto_choice`): the tip-position RMS error allowed, as
    /// a fraction of each strand's length, in [1e-4, 1]. When set, each
    /// group's `elements` and the solver are chosen, not read. Default:
    /// absent (use the style's own).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy_target: Option<f64>,
    /// The strand groups; at least one.
    pub groups: Vec<StrandGroup>,
}

/// Strands that share their physical parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrandGroup {
    /// Name of the group (non-empty), carried into simulation output.
    pub name: String,
    /// Physical parameters of every strand of the group; every field has a
    /// default.
    #[serde(default)]
    pub params: StrandParams,
    /// One root per strand, listed; at least one unless `scalp` places
    /// roots instead (both together: the listed ones first).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub roots: Vec<Root>,
    /// Roots spread evenly on the head's scalp, combed in a direction.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::style::groom::inline_option"
    )]
    pub scalp: Option<ScalpPlacement>,
    /// The strands drawn for this group: count, interpolation from the
    /// guides, colour. Without it, the guides themselves are drawn.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::style::groom::inline_option"
    )]
    pub render: Option<RenderStrands>,
    /// Strands fitted from an imported groom, each with its own length,
    /// elements and natural strains (`helixhair import`; see
    /// [`crate::style::imported`]). Simulated after the listed roots.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::style::groom::inline_option"
    )]
    pub imported: Option<ImportedStrands>,
    /// Per-strand changes the styling tools made over `params` (cut,
    /// painted curl or stiffness, a shape kept as rest), one entry per
    /// changed strand in increasing strand order ([`StrandEdit`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub edits: Vec<StrandEdit>,
}

/// What the version probe reads: only the version, ignoring every other
/// field, so that files of any version get this far.
#[derive(Deserialize)]
#[serde(rename = "Style")]
struct VersionProbe {
    version: u32,
}

impl Style {
    /// The groups' names, in order.
    pub fn group_names(&self) -> Vec<String> {
        self.groups.iter().map(|g| g.name.clone()).collect()
    }

    /// Reads, parses and validates the style file at `path`.
    pub fn load(path: &Path) -> Result<Style, StyleError> {
        let src = std::fs::read_to_string(path).map_err(|error| StyleError::Read {
            path: path.to_owned(),
            error,
        })?;
        Self::from_ron(&src, path)
    }

    /// Parses and validates a style from RON text; `path` is only used to
    /// name the file in errors.
    pub fn from_ron(src: &str, path: &Path) -> Result<Style, StyleError> {
        if let Ok(probe) = ron::from_str::<VersionProbe>(src)
            && let Err(issue) = check_version(probe.version)
        {
            return Err(locate_issue(src, path, issue));
        }
        let style: Style =
            ron::from_str(src).map_err(|error| locate_ron_error(src, path, &error))?;
        style
            .validate()
            .map_err(|issue| locate_issue(src, path, issue))?;
        Ok(style)
    }

    /// The style as pretty RON text, with a header comment naming the
    /// format. Comments of a loaded file are not kept.
    pub fn to_ron(&self) -> Result<String, StyleError> {
        let body = ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::default())
            .map_err(StyleError::Serialize)?;
        Ok(format!(
            "// HelixHair style, format version {STYLE_VERSION}: see docs/style-format.md.\n{body}\n"
        ))
    }

    /// Writes the style to `path` as pretty RON, atomically: the file holds
    /// either its old content or the whole new style, never a part.
    pub fn save(&self, path: &Path) -> Result<(), StyleError> {
        let text = self.to_ron()?;
        write_atomically(path, text.as_bytes()).map_err(|error| StyleError::Write {
            path: path.to_owned(),
            error,
        })
    }

    /// Strands the simulation runs over all groups: listed roots and
    /// imported guides (scalp placements not counted: they need a head,
    /// see [`crate::head::groom`]).
    pub fn strand_count(&self) -> usize {
        self.groups.iter().map(StrandGroup::simulated_count).sum()
    }
}

impl StrandGroup {
    /// The physics root frames of the group's strands.
    pub fn root_poses(&self) -> Vec<RootPose> {
        self.roots.iter().map(Root::pose).collect()
    }

    /// The parameters simulated strand `n` has before its edit: the
    /// group's for a root, its own for an imported guide. `None` past the
    /// listed roots of a group whose scalp placement is not grown yet (its
    /// roots come between the listed ones and the imported guides), and
    /// past the last strand.
    pub fn base_params(&self, n: usize) -> Option<StrandParams> {
        let Some(k) = n.checked_sub(self.roots.len()) else {
            return Some(self.params.clone());
        };
        if self.scalp.is_some() {
            return None;
        }
        let imported = self.imported.as_ref()?.guides().nth(k)?;
        Some(imported.params(&self.params))
    }

    /// Strands the simulation runs for this group (once grown): its listed
    /// roots, then its imported guides.
    pub fn simulated_count(&self) -> usize {
        self.roots.len() + self.imported.as_ref().map_or(0, |i| i.guides().count())
    }
}

/// Ties a validation issue to the line of its field in `src`.
fn locate_issue(src: &str, path: &Path, issue: StyleIssue) -> StyleError {
    let (position, _) = SourceMap::new(src).locate(&issue.field);
    StyleError::Located {
        path: path.to_owned(),
        position,
        field: issue.field,
        kind: issue.kind,
        message: issue.message,
    }
}

/// Names the field of a `ron` error from the position `ron` reports.
pub(crate) fn locate_ron_error(
    src: &str,
    path: &Path,
    error: &ron::error::SpannedError,
) -> StyleError {
    let map = SourceMap::new(src);
    let position = map.skip_whitespace(TextPosition {
        line: error.span.start.line,
        col: error.span.start.col,
    });
    let mut field = map.path_at(position);
    match &error.code {
        // ron reports a missing field somewhere in or just after the struct
        // that lacks it; the struct's start is where a reader looks.
        ron::Error::MissingStructField { field: name, .. } => {
            if let Some((parent, start)) = map.enclosing_struct(&field) {
                return located_ron(path, start, parent.field(name), error);
            }
            field = field.field(name);
        }
        // An unknown or repeated field is reported on its name, which the
        // path then already ends with.
        ron::Error::DuplicateStructField { field: name, .. } if !field.ends_with_field(name) => {
            field = field.field(name);
        }
        ron::Error::NoSuchStructField { found, .. } if !field.ends_with_field(found) => {
            field = field.field(found);
        }
        _ => {}
    }
    located_ron(path, position, field, error)
}

fn located_ron(
    path: &Path,
    position: TextPosition,
    field: FieldPath,
    error: &ron::error::SpannedError,
) -> StyleError {
    StyleError::Located {
        path: path.to_owned(),
        position,
        field,
        kind: StyleErrorKind::of_ron(&error.code),
        message: error.code.to_string(),
    }
}

/// Refuses every format version but [`STYLE_VERSION`].
pub(crate) fn check_version(version: u32) -> Result<(), StyleIssue> {
    if version == STYLE_VERSION {
        return Ok(());
    }
    Err(StyleIssue {
        field: FieldPath::root().field("version"),
        kind: StyleErrorKind::Version,
        message: format!(
            "version {version} is not supported: this build reads version {STYLE_VERSION}"
        ),
    })
}

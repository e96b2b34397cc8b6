//! The checks a style passes after parsing: ranges, NaN, and lists that
//! must not be empty.
//!
//! Physical parameters are checked by the physics crate itself
//! ([`StrandParams::validate`](helixhair_physics::StrandParams::validate), [`SimSettings::validate`](helixhair_physics::SimSettings::validate)), whose field
//! names are prefixed here with where the parameters sit in the file.

use glam::DVec3;
use helixhair_physics::ParamError;
use helixhair_physics::engine::EngineKind;

pub use crate::style::checks::{MAX_ROOT_COORDINATE_M, param_issue};
use crate::style::checks::{check_finite, invalid};
use crate::style::error::StyleIssue;
use crate::style::field_path::FieldPath;
use crate::style::groom_validate::{validate_render, validate_scalp};
use crate::style::imported_validate::validate_imported;
use crate::style::strand_edit::validate_edits;
use crate::style::{Root, Style, check_version};

/// Shortest accepted root direction (it is normalised, so any unit works;
/// only a zero or vanishing vector has no direction).
pub const MIN_DIRECTION_LENGTH: f64 = 1e-9;

impl Style {
    /// Checks the whole style; the first problem found is returned, naming
    /// its field (e.g. `groups[1].roots[4].direction`).
    pub fn validate(&self) -> Result<(), StyleIssue> {
        check_version(self.version)?;
        let sim = FieldPath::root().field("sim");
        self.sim.validate().map_err(|e| param_issue(&sim, &e))?;
        check_engine(self)?;
        if let Some(target) = self.accuracy_target {
            check_accuracy_target(target).map_err(|e| param_issue(&FieldPath::root(), &e))?;
        }
        let groups = FieldPath::root().field("groups");
        if self.groups.is_empty() {
            return Err(invalid(groups, "must list at least one strand group"));
        }
        for (i, group) in self.groups.iter().enumerate() {
            let at = groups.index(i);
            if group.name.trim().is_empty() {
                return Err(invalid(at.field("name"), "must not be empty"));
            }
            group
                .params
                .validate()
                .map_err(|e| param_issue(&at.field("params"), &e))?;
            let roots = at.field("roots");
            if group.roots.is_empty() && group.scalp.is_none() && group.imported.is_none() {
                return Err(invalid(
                    roots,
                    "must list at least one root (one per strand), or give a `scalp` placement",
                ));
            }
            if let Some(scalp) = &group.scalp {
                validate_scalp(scalp, &at.field("scalp"))?;
            }
            if let Some(render) = &group.render {
                validate_render(render, &at.field("render"))?;
            }
            if let Some(imported) = &group.imported {
                validate_imported(imported, &group.params, &at.field("imported"))?;
            }
            validate_edits(group, &at.field("edits"))?;
            for (j, root) in group.roots.iter().enumerate() {
                validate_root(root, &roots.index(j))?;
            }
        }
        Ok(())
    }
}

/// The batch engine runs two solvers and no automatic choice: a style
/// that asks it for more is refused at its `engine` field.
fn check_engine(style: &Style) -> Result<(), StyleIssue> {
    let engine = FieldPath::root().field("engine");
    let kind = style.engine.label();
    if !style.engine.runs(style.sim.method) {
        return Err(invalid(
            engine,
            format!(
                "the {kind} engine runs `sim.method` `Exact` or `BlockDiagonal` only, not `{}`; \
                 pick one of those, or `engine: Reference` for every solver",
                method_spelling(style.sim.method)
            ),
        ));
    }
    if style.engine != EngineKind::Reference && style.accuracy_target.is_some() {
        return Err(invalid(
            engine,
            format!(
                "the {kind} engine cannot run an `accuracy_target` (it may choose any solver \
                 per group); remove the target, or use `engine: Reference`"
            ),
        ));
    }
    Ok(())
}

/// A solver as a style spells it (`Dense`, `Iterative(iterations:4)`).
pub(crate) fn method_spelling(method: helixhair_physics::Method) -> String {
    ron::to_string(&method).unwrap_or_else(|_| method.label())
}

fn validate_root(root: &Root, at: &FieldPath) -> Result<(), StyleIssue> {
    let limit = MAX_ROOT_COORDINATE_M;
    check_finite(root.position_m, &at.field("position_m"), Some(limit))?;
    let direction = at.field("direction");
    check_finite(root.direction, &direction, None)?;
    if root.direction.length() < MIN_DIRECTION_LENGTH {
        return Err(invalid(
            direction,
            format!(
                "must not be zero (length at least {MIN_DIRECTION_LENGTH:e}); found {}",
                format_vec(root.direction)
            ),
        ));
    }
    check_finite(root.reference, &at.field("reference"), None)
}

fn format_vec(v: DVec3) -> String {
    format!("({}, {}, {})", v.x, v.y, v.z)
}

/// Allowed accuracy targets (fraction of strand length): below 1e-4 no
/// measured setting reaches it; above 1 it means nothing.
pub const ACCURACY_TARGET_RANGE: (f64, f64) = (1e-4, 1.0);

/// Checks an accuracy target (style field or `--accuracy`).
pub fn check_accuracy_target(target: f64) -> Result<(), ParamError> {
    helixhair_physics::error::check_range(
        "accuracy_target",
        target,
        ACCURACY_TARGET_RANGE.0,
        ACCURACY_TARGET_RANGE.1,
    )
}

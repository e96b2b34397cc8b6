//! The small checks every section of a style shares (the top level in
//! [`crate::style::validate`], the scalp and render sections in
//! [`crate::style::groom_validate`]): finite vectors, and the issue they
//! raise. Kept apart so that neither checker depends on the other for them.

use glam::DVec3;
use helixhair_physics::ParamError;

use crate::style::error::{StyleErrorKind, StyleIssue};
use crate::style::field_path::FieldPath;

/// Every component finite and, with `limit`, inside `[-limit, limit]`.
pub fn check_finite(v: DVec3, at: &FieldPath, limit: Option<f64>) -> Result<(), StyleIssue> {
    for (k, x) in v.to_array().into_iter().enumerate() {
        if !x.is_finite() {
            return Err(invalid(
                at.index(k),
                format!("must be a finite number; found {x}"),
            ));
        }
        if let Some(limit) = limit
            && x.abs() > limit
        {
            return Err(invalid(
                at.index(k),
                format!("must lie in [-{limit}, {limit}]; found {x}"),
            ));
        }
    }
    Ok(())
}

/// An issue of `kind` at `field`.
pub fn issue(field: FieldPath, kind: StyleErrorKind, message: String) -> StyleIssue {
    StyleIssue {
        field,
        kind,
        message,
    }
}

/// An [`StyleErrorKind::InvalidValue`] issue at `field`.
pub fn invalid(field: FieldPath, message: impl Into<String>) -> StyleIssue {
    issue(field, StyleErrorKind::InvalidValue, message.into())
}

/// Largest distance of a root coordinate from the head's origin, metres:
/// a head is a tenth of that, so anything beyond is a typo.
pub const MAX_ROOT_COORDINATE_M: f64 = 10.0;

/// A physics parameter error, its field placed under `prefix`.
pub fn param_issue(prefix: &FieldPath, error: &ParamError) -> StyleIssue {
    invalid(
        prefix.join(&FieldPath::parse(&error.field)),
        format!("{}; found {}", error.reason, error.value),
    )
}

//! Errors of the physics crate.

use thiserror::Error;

/// A parameter outside its documented range, NaN, or inconsistent.
#[derive(Clone, Debug, PartialEq, Error)]
#[error("field `{field}` = {value}: {reason}")]
pub struct ParamError {
    /// The field's name as it appears in a style file (dotted for nested
    /// fields, e.g. `natural_shape.radius_m`).
    pub field: String,
    /// The offending value (a count or length for list fields).
    pub value: f64,
    /// What the value must be.
    pub reason: String,
}

impl ParamError {
    /// A new error for `field`.
    pub fn new(field: &str, value: f64, reason: impl Into<String>) -> Self {
        Self {
            field: field.to_owned(),
            value,
            reason: reason.into(),
        }
    }
}

/// Checks that `value` is finite and inside `[min, max]`, naming `field`.
pub fn check_range(field: &str, value: f64, min: f64, max: f64) -> Result<(), ParamError> {
    if !value.is_finite() {
        return Err(ParamError::new(field, value, "must be a finite number"));
    }
    if value < min || value > max {
        return Err(ParamError::new(
            field,
            value,
            format!("must lie in [{min}, {max}]"),
        ));
    }
    Ok(())
}

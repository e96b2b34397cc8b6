//! Checks every writer makes before writing a byte, so a writer never
//! leaves half a file for curves it cannot express.

use crate::curve_set::{Curve, CurveSet, StrandValue};
use crate::error::WriteError;
use crate::format::Format;

/// Every point finite, every per-point width and colour list as long as its
/// curve's points.
pub(crate) fn finite_points(format: Format, curves: &CurveSet) -> Result<(), WriteError> {
    for (index, curve) in curves.curves.iter().enumerate() {
        if let Some(point) = curve.points_m.iter().position(|p| !p.is_finite()) {
            return Err(WriteError::invalid(
                format,
                format!("curve {index} point {point} is not finite"),
            ));
        }
        let n = curve.points_m.len();
        let width_len = match &curve.width_m {
            Some(StrandValue::PerPoint(widths)) => Some(widths.len()),
            _ => None,
        };
        let colour_len = match &curve.colour {
            Some(StrandValue::PerPoint(colours)) => Some(colours.len()),
            _ => None,
        };
        for (what, len) in [("widths", width_len), ("colours", colour_len)] {
            if let Some(len) = len.filter(|&len| len != n) {
                return Err(WriteError::invalid(
                    format,
                    format!("curve {index} has {n} points but {len} per-point {what}"),
                ));
            }
        }
    }
    Ok(())
}

/// Whether every curve has the attribute (`true`) or none has (`false`);
/// an error names the first curve that breaks the rule, since a format
/// with one array for all strands cannot hold it for some only.
pub(crate) fn all_or_none(
    format: Format,
    curves: &CurveSet,
    what: &str,
    has: impl Fn(&Curve) -> bool,
) -> Result<bool, WriteError> {
    let Some(first) = curves.curves.first() else {
        return Ok(false);
    };
    let expected = has(first);
    match curves
        .curves
        .iter()
        .position(|curve| has(curve) != expected)
    {
        None => Ok(expected),
        Some(index) => Err(WriteError::invalid(
            format,
            format!(
                "curve 0 {} a {what} but curve {index} {}: give every curve a {what} or none",
                if expected { "has" } else { "has no" },
                if expected { "has none" } else { "has one" },
            ),
        )),
    }
}

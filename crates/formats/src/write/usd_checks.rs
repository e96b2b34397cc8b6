//! Checks every USD writer (`.usda`, `.usdc`, `.usdz`) and the Alembic
//! writer make before their first byte: the curves (as every writer checks them), the frames, the
//! head and its poses.

use crate::animation::Animation;
use crate::curve_set::CurveSet;
use crate::error::WriteError;
use crate::format::Format;
use crate::mesh::{MeshPose, TriangleMesh};
use crate::write::checks::{all_or_none, finite_points};

/// Checks what a USD layer would hold; returns whether the curves carry
/// widths and colours (every curve, or none).
pub(crate) fn usd_inputs(
    format: Format,
    curves: &CurveSet,
    animation: Option<&Animation>,
    head: Option<&TriangleMesh>,
    head_poses: &[MeshPose],
) -> Result<(bool, bool), WriteError> {
    let invalid = |message: String| WriteError::invalid(format, message);
    finite_points(format, curves)?;
    let with_width = all_or_none(format, curves, "width", |c| c.width_m.is_some())?;
    let with_colour = all_or_none(format, curves, "colour", |c| c.colour.is_some())?;
    let point_count = curves.point_count();
    if let Some(animation) = animation {
        if !(animation.time_codes_per_second.is_finite() && animation.time_codes_per_second > 0.0) {
            return Err(invalid(format!(
                "time codes per second must be positive, not {}",
                animation.time_codes_per_second
            )));
        }
        for (index, frame) in animation.frames.iter().enumerate() {
            if frame.points_m.len() != point_count {
                return Err(invalid(format!(
                    "frame {index} has {} points, the curves {point_count}",
                    frame.points_m.len()
                )));
            }
            if !frame.time_code.is_finite() || frame.points_m.iter().any(|p| !p.is_finite()) {
                return Err(invalid(format!(
                    "frame {index} has a non-finite time or point"
                )));
            }
            if index > 0 && frame.time_code <= animation.frames[index - 1].time_code {
                return Err(invalid(format!(
                    "frame {index}'s time code does not increase"
                )));
            }
        }
    }
    if let Some(head) = head {
        let n = head.vertices_m.len();
        if let Some(index) = head
            .triangles
            .iter()
            .position(|t| t.iter().any(|&v| v as usize >= n))
        {
            return Err(invalid(format!(
                "head triangle {index} names a vertex past the {n} vertices"
            )));
        }
        if head.vertices_m.iter().any(|v| !v.is_finite()) {
            return Err(invalid("a head vertex is not finite".to_string()));
        }
    }
    check_head_poses(format, head.is_some(), head_poses)?;
    Ok((with_width, with_colour))
}

/// Refuses head poses without a head, non-finite ones, and time codes that
/// do not increase.
fn check_head_poses(format: Format, has_head: bool, poses: &[MeshPose]) -> Result<(), WriteError> {
    let invalid = |message: String| Err(WriteError::invalid(format, message));
    if !has_head && !poses.is_empty() {
        return invalid("head poses were given without a head".to_string());
    }
    for (index, pose) in poses.iter().enumerate() {
        let finite = pose.time_code.is_finite()
            && pose.rotation.is_finite()
            && pose.translation_m.is_finite();
        if !finite {
            return invalid(format!("head pose {index} is not finite"));
        }
        if index > 0 && pose.time_code <= poses[index - 1].time_code {
            return invalid(format!("head pose {index}'s time code does not increase"));
        }
    }
    Ok(())
}

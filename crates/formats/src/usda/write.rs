//! Writing a groom (and optionally its animation and head) as `.usda`.

use std::fmt::Write as _;
use std::io::Write;

use glam::Vec3;

use crate::animation::Animation;
use crate::curve_set::{CurveSet, StrandValue, bounds_of};
use crate::error::WriteError;
use crate::format::Format;
use crate::mesh::{MeshPose, TriangleMesh};
use crate::write::usd_checks::usd_inputs;

/// Writes one layer:
///
/// - layer metadata `metersPerUnit = 1`, `upAxis = "Y"`, and for an
///   animation `startTimeCode`, `endTimeCode`, and `timeCodesPerSecond`
///   (also for an animation of no frames: a still frame at that rate);
/// - `def Xform "HelixHair"` (the default prim) holding
///   `def BasisCurves "hair"`: `type = "linear"`, `wrap = "nonperiodic"`,
///   `curveVertexCounts`, `points` (or `points.timeSamples` for an
///   animation, one sample per frame, with `extent` sampled alike), `widths`
///   when every curve has one (`uniform` when all are per strand, else
///   `vertex`), `primvars:displayColor` likewise;
/// - `def Mesh "head"` when a head is given (`faceVertexCounts` of 3,
///   `faceVertexIndices`, `points`, `subdivisionScheme = "none"`).
///
/// Numbers are the shortest decimals that read back as the same `f32`.
/// Everything is checked before the first byte is written: non-finite
/// points, widths or colours on some curves only, frames of the wrong
/// length, head indices out of range.
pub fn write_usda(
    out: &mut impl Write,
    curves: &CurveSet,
    animation: Option<&Animation>,
    head: Option<&TriangleMesh>,
) -> Result<(), WriteError> {
    write_usda_with_head_poses(out, curves, animation, head, &[])
}

/// [`write_usda`], with the head moving: `head_poses` become the head
/// `Mesh`'s `xformOp:transform` time samples (`matrix4d`, USD's row-vector
/// convention: the rotation's columns are the matrix's first three rows,
/// the translation its last), so the head turns with the hair in
/// usdview, Blender or Houdini. Empty: a still head, as [`write_usda`].
/// Refused (before writing) without a head, with non-finite poses or
/// with time codes that do not increase.
pub fn write_usda_with_head_poses(
    out: &mut impl Write,
    curves: &CurveSet,
    animation: Option<&Animation>,
    head: Option<&TriangleMesh>,
    head_poses: &[MeshPose],
) -> Result<(), WriteError> {
    let (with_width, with_colour) = usd_inputs(Format::Usda, curves, animation, head, head_poses)?;
    let point_count = curves.point_count();
    let animated = animation.filter(|a| !a.frames.is_empty());

    let mut text = String::with_capacity(64 * point_count + 1024);
    text.push_str("#usda 1.0\n(\n    defaultPrim = \"HelixHair\"\n");
    text.push_str("    doc = \"Written by helixhair-formats\"\n");
    text.push_str("    metersPerUnit = 1\n    upAxis = \"Y\"\n");
    if let Some(animation) = animated {
        let first = animation.frames.first().map_or(0.0, |f| f.time_code);
        let last = animation.frames.last().map_or(0.0, |f| f.time_code);
        let _ = writeln!(
            text,
            "    startTimeCode = {first}\n    endTimeCode = {last}"
        );
    }
    // The rate even for a still frame (an animation of no frames): a reader
    // then places its head pose and its frame at the simulation's rate, not
    // USD's fallback of 24.
    if let Some(animation) = animation {
        let _ = writeln!(
            text,
            "    timeCodesPerSecond = {}",
            animation.time_codes_per_second
        );
    }
    text.push_str(")\n\ndef Xform \"HelixHair\"\n{\n");
    text.push_str("    def BasisCurves \"hair\"\n    {\n");
    text.push_str("        uniform token type = \"linear\"\n");
    text.push_str("        uniform token wrap = \"nonperiodic\"\n");
    text.push_str("        int[] curveVertexCounts = [");
    join(
        &mut text,
        curves.curves.iter().map(|c| c.points_m.len()),
        |t, n| {
            let _ = write!(t, "{n}");
        },
    );
    text.push_str("]\n");
    match animated {
        None => {
            text.push_str("        point3f[] points = ");
            vec3_array(
                &mut text,
                curves
                    .curves
                    .iter()
                    .flat_map(|c| c.points_m.iter().copied()),
            );
            text.push('\n');
            text.push_str("        float3[] extent = ");
            extent(
                &mut text,
                curves.curves.iter().flat_map(|c| c.points_m.iter()),
            );
            text.push('\n');
        }
        Some(animation) => {
            text.push_str("        point3f[] points.timeSamples = {\n");
            for frame in &animation.frames {
                let _ = write!(text, "            {}: ", frame.time_code);
                vec3_array(&mut text, frame.points_m.iter().copied());
                text.push_str(",\n");
            }
            text.push_str("        }\n        float3[] extent.timeSamples = {\n");
            for frame in &animation.frames {
                let _ = write!(text, "            {}: ", frame.time_code);
                extent(&mut text, frame.points_m.iter());
                text.push_str(",\n");
            }
            text.push_str("        }\n");
        }
    }
    if with_width {
        let uniform = curves
            .curves
            .iter()
            .all(|c| matches!(c.width_m, Some(StrandValue::PerStrand(_))));
        text.push_str("        float[] widths = [");
        let widths = curves.curves.iter().flat_map(|curve| {
            let count = if uniform { 1 } else { curve.points_m.len() };
            (0..count).map(move |index| {
                curve
                    .width_m
                    .as_ref()
                    .and_then(|w| w.at(index))
                    .unwrap_or(0.0)
            })
        });
        join(&mut text, widths, |t, w| {
            let _ = write!(t, "{w}");
        });
        let interpolation = if uniform { "uniform" } else { "vertex" };
        let _ = writeln!(
            text,
            "] (\n            interpolation = \"{interpolation}\"\n        )"
        );
    }
    if with_colour {
        let uniform = curves
            .curves
            .iter()
            .all(|c| matches!(c.colour, Some(StrandValue::PerStrand(_))));
        text.push_str("        color3f[] primvars:displayColor = ");
        let colours = curves.curves.iter().flat_map(|curve| {
            let count = if uniform { 1 } else { curve.points_m.len() };
            (0..count).map(move |index| {
                Vec3::from_array(
                    curve
                        .colour
                        .as_ref()
                        .and_then(|c| c.at(index))
                        .unwrap_or([1.0; 3]),
                )
            })
        });
        vec3_array(&mut text, colours);
        let interpolation = if uniform { "uniform" } else { "vertex" };
        let _ = writeln!(
            text,
            " (\n            interpolation = \"{interpolation}\"\n        )"
        );
    }
    text.push_str("    }\n");
    if let Some(head) = head {
        text.push_str("\n    def Mesh \"head\"\n    {\n");
        text.push_str("        uniform token subdivisionScheme = \"none\"\n");
        text.push_str("        int[] faceVertexCounts = [");
        join(&mut text, head.triangles.iter(), |t, _| t.push('3'));
        text.push_str("]\n        int[] faceVertexIndices = [");
        join(&mut text, head.triangles.iter().flatten(), |t, v| {
            let _ = write!(t, "{v}");
        });
        text.push_str("]\n        point3f[] points = ");
        vec3_array(&mut text, head.vertices_m.iter().copied());
        text.push_str("\n        float3[] extent = ");
        extent(&mut text, head.vertices_m.iter());
        text.push('\n');
        head_transform(&mut text, head_poses);
        text.push_str("    }\n");
    }
    text.push_str("}\n");
    out.write_all(text.as_bytes())
        .map_err(WriteError::io(Format::Usda))
}

/// The head's `xformOp:transform` time samples (nothing for no poses).
fn head_transform(text: &mut String, poses: &[MeshPose]) {
    if poses.is_empty() {
        return;
    }
    text.push_str("        uniform token[] xformOpOrder = [\"xformOp:transform\"]\n");
    text.push_str("        matrix4d xformOp:transform.timeSamples = {\n");
    for pose in poses {
        let (r, t) = (pose.rotation, pose.translation_m);
        let _ = write!(text, "            {}: (", pose.time_code);
        for column in [r.x_axis, r.y_axis, r.z_axis] {
            let _ = write!(text, "({}, {}, {}, 0), ", column.x, column.y, column.z);
        }
        let _ = writeln!(text, "({}, {}, {}, 1)),", t.x, t.y, t.z);
    }
    text.push_str("        }\n");
}

fn join<T>(
    text: &mut String,
    items: impl Iterator<Item = T>,
    mut write: impl FnMut(&mut String, T),
) {
    for (index, item) in items.enumerate() {
        if index > 0 {
            text.push_str(", ");
        }
        write(text, item);
    }
}

fn vec3_array(text: &mut String, points: impl Iterator<Item = Vec3>) {
    text.push('[');
    join(text, points, |t, p| {
        let _ = write!(t, "({}, {}, {})", p.x, p.y, p.z);
    });
    text.push(']');
}

fn extent<'a>(text: &mut String, points: impl Iterator<Item = &'a Vec3>) {
    let (min, max) = bounds_of(points).unwrap_or((Vec3::ZERO, Vec3::ZERO));
    vec3_array(text, [min, max].into_iter());
}

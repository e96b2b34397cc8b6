//! Writing a groom (and optionally its animation and head) as a binary
//! crate file: the same prims, fields and values [`crate::write_usda`]
//! writes as text, so the two encodings read back alike in USD.

use std::io::Write;

use glam::Vec3;

use crate::animation::Animation;
use crate::curve_set::{CurveSet, StrandValue, bounds_of};
use crate::error::WriteError;
use crate::format::Format;
use crate::mesh::{MeshPose, TriangleMesh};
use crate::usdc::builder::{Builder, Node};
use crate::write::usd_checks::usd_inputs;

type Fields = Vec<(String, u64)>;

fn field(name: &str, value: u64) -> (String, u64) {
    (name.to_owned(), value)
}

/// Writes one crate layer holding what [`crate::write_usda_with_head_poses`]
/// writes for the same arguments (`/HelixHair/hair` linear `BasisCurves`
/// in metres, Y up, with widths, colours and time samples; the head
/// `Mesh` with its `xformOp:transform` samples), checked the same way
/// before the first byte.
pub fn write_usdc(
    out: &mut impl Write,
    curves: &CurveSet,
    animation: Option<&Animation>,
    head: Option<&TriangleMesh>,
    head_poses: &[MeshPose],
) -> Result<(), WriteError> {
    let (with_width, with_colour) = usd_inputs(Format::Usdc, curves, animation, head, head_poses)?;
    if curves.point_count() > i32::MAX as usize {
        return Err(WriteError::invalid(Format::Usdc, "more than 2^31 points"));
    }
    let animated = animation.filter(|a| !a.frames.is_empty());
    let mut b = Builder::new();
    let mut layer: Fields = vec![
        field("defaultPrim", b.token_value("HelixHair")),
        field(
            "documentation",
            b.string_value("Written by helixhair-formats"),
        ),
        field("metersPerUnit", b.double(1.0)),
        field("upAxis", b.token_value("Y")),
    ];
    if let Some(animation) = animated {
        let first = animation.frames.first().map_or(0.0, |f| f.time_code);
        let last = animation.frames.last().map_or(0.0, |f| f.time_code);
        layer.push(field("startTimeCode", b.double(first)));
        layer.push(field("endTimeCode", b.double(last)));
    }
    // The rate even for a still frame, as the `.usda` writer does.
    if let Some(animation) = animation {
        layer.push(field(
            "timeCodesPerSecond",
            b.double(animation.time_codes_per_second),
        ));
    }
    let mut children = vec![hair(&mut b, curves, animated, with_width, with_colour)];
    if let Some(head) = head {
        children.push(head_mesh(&mut b, head, head_poses));
    }
    let names: Vec<&str> = children.iter().map(|c| c.name.as_str()).collect();
    let root_fields = vec![
        field("specifier", b.specifier_def()),
        field("typeName", b.token_value("Xform")),
        field("primChildren", b.token_vector(&names)),
    ];
    layer.push(field("primChildren", b.token_vector(&["HelixHair"])));
    let root = Node::prim("HelixHair", root_fields, children);
    let bytes = b.finish(layer, vec![root]);
    out.write_all(&bytes).map_err(WriteError::io(Format::Usdc))
}

/// An attribute node: its type name, uniform or not, and fields.
fn attribute(b: &mut Builder, name: &str, type_name: &str, uniform: bool, more: Fields) -> Node {
    let mut fields = vec![field("typeName", b.token_value(type_name))];
    if uniform {
        fields.push(field("variability", b.uniform()));
    }
    fields.extend(more);
    Node::attribute(name, fields)
}

fn prim_with(b: &mut Builder, name: &str, type_name: &str, properties: Vec<Node>) -> Node {
    let names: Vec<&str> = properties.iter().map(|p| p.name.as_str()).collect();
    let fields = vec![
        field("specifier", b.specifier_def()),
        field("typeName", b.token_value(type_name)),
        field("properties", b.token_vector(&names)),
    ];
    Node::prim(name, fields, properties)
}

fn points(b: &mut Builder, points: &[Vec3]) -> u64 {
    b.vec3fs(points.iter().map(|p| p.to_array()))
}

fn extent<'a>(b: &mut Builder, points: impl Iterator<Item = &'a Vec3>) -> u64 {
    let (min, max) = bounds_of(points).unwrap_or((Vec3::ZERO, Vec3::ZERO));
    b.vec3fs([min.to_array(), max.to_array()].into_iter())
}

fn hair(
    b: &mut Builder,
    curves: &CurveSet,
    animated: Option<&Animation>,
    with_width: bool,
    with_colour: bool,
) -> Node {
    let mut properties = Vec::new();
    let linear = b.token_value("linear");
    properties.push(attribute(
        b,
        "type",
        "token",
        true,
        vec![field("default", linear)],
    ));
    let open = b.token_value("nonperiodic");
    properties.push(attribute(
        b,
        "wrap",
        "token",
        true,
        vec![field("default", open)],
    ));
    let counts = b.ints(curves.curves.iter().map(|c| c.points_m.len() as i32));
    properties.push(attribute(
        b,
        "curveVertexCounts",
        "int[]",
        false,
        vec![field("default", counts)],
    ));
    let (points_field, extent_field) = match animated {
        None => {
            let all: Vec<Vec3> = curves
                .curves
                .iter()
                .flat_map(|c| c.points_m.iter().copied())
                .collect();
            let value = points(b, &all);
            let bounds = extent(b, all.iter());
            (field("default", value), field("default", bounds))
        }
        Some(animation) => {
            let mut point_samples = Vec::new();
            let mut extent_samples = Vec::new();
            for frame in &animation.frames {
                point_samples.push((frame.time_code, points(b, &frame.points_m)));
                extent_samples.push((frame.time_code, extent(b, frame.points_m.iter())));
            }
            (
                field("timeSamples", b.time_samples(&point_samples)),
                field("timeSamples", b.time_samples(&extent_samples)),
            )
        }
    };
    properties.push(attribute(
        b,
        "points",
        "point3f[]",
        false,
        vec![points_field],
    ));
    properties.push(attribute(
        b,
        "extent",
        "float3[]",
        false,
        vec![extent_field],
    ));
    if with_width {
        let uniform = curves
            .curves
            .iter()
            .all(|c| matches!(c.width_m, Some(StrandValue::PerStrand(_))));
        let widths: Vec<f32> = per_strand_or_point(curves, uniform, |curve, index| {
            curve
                .width_m
                .as_ref()
                .and_then(|w| w.at(index))
                .unwrap_or(0.0)
        });
        let value = b.floats(widths.into_iter());
        let interpolation = b.token_value(if uniform { "uniform" } else { "vertex" });
        properties.push(attribute(
            b,
            "widths",
            "float[]",
            false,
            vec![
                field("default", value),
                field("interpolation", interpolation),
            ],
        ));
    }
    if with_colour {
        let uniform = curves
            .curves
            .iter()
            .all(|c| matches!(c.colour, Some(StrandValue::PerStrand(_))));
        let colours: Vec<[f32; 3]> = per_strand_or_point(curves, uniform, |curve, index| {
            curve
                .colour
                .as_ref()
                .and_then(|c| c.at(index))
                .unwrap_or([1.0; 3])
        });
        let value = b.vec3fs(colours.into_iter());
        let interpolation = b.token_value(if uniform { "uniform" } else { "vertex" });
        properties.push(attribute(
            b,
            "primvars:displayColor",
            "color3f[]",
            false,
            vec![
                field("default", value),
                field("interpolation", interpolation),
            ],
        ));
    }
    prim_with(b, "hair", "BasisCurves", properties)
}

/// One value per strand (`uniform`) or per point (`vertex`).
fn per_strand_or_point<T>(
    curves: &CurveSet,
    uniform: bool,
    value: impl Fn(&crate::curve_set::Curve, usize) -> T,
) -> Vec<T> {
    curves
        .curves
        .iter()
        .flat_map(|curve| {
            let count = if uniform { 1 } else { curve.points_m.len() };
            (0..count)
                .map(|index| value(curve, index))
                .collect::<Vec<_>>()
        })
        .collect()
}

fn head_mesh(b: &mut Builder, head: &TriangleMesh, poses: &[MeshPose]) -> Node {
    let mut properties = Vec::new();
    let none = b.token_value("none");
    properties.push(attribute(
        b,
        "subdivisionScheme",
        "token",
        true,
        vec![field("default", none)],
    ));
    let counts = b.ints(head.triangles.iter().map(|_| 3));
    properties.push(attribute(
        b,
        "faceVertexCounts",
        "int[]",
        false,
        vec![field("default", counts)],
    ));
    let indices: Vec<i32> = head.triangles.iter().flatten().map(|&v| v as i32).collect();
    let indices = b.ints(indices.into_iter());
    properties.push(attribute(
        b,
        "faceVertexIndices",
        "int[]",
        false,
        vec![field("default", indices)],
    ));
    let value = points(b, &head.vertices_m);
    properties.push(attribute(
        b,
        "points",
        "point3f[]",
        false,
        vec![field("default", value)],
    ));
    let bounds = extent(b, head.vertices_m.iter());
    properties.push(attribute(
        b,
        "extent",
        "float3[]",
        false,
        vec![field("default", bounds)],
    ));
    if !poses.is_empty() {
        let order = b.token_array(&["xformOp:transform"]);
        properties.push(attribute(
            b,
            "xformOpOrder",
            "token[]",
            true,
            vec![field("default", order)],
        ));
        let samples: Vec<(f64, u64)> = poses
            .iter()
            .map(|pose| {
                let (r, t) = (pose.rotation, pose.translation_m);
                let rows = [
                    [r.x_axis.x, r.x_axis.y, r.x_axis.z, 0.0],
                    [r.y_axis.x, r.y_axis.y, r.y_axis.z, 0.0],
                    [r.z_axis.x, r.z_axis.y, r.z_axis.z, 0.0],
                    [t.x, t.y, t.z, 1.0],
                ];
                (pose.time_code, b.matrix4d(rows))
            })
            .collect();
        let value = b.time_samples(&samples);
        properties.push(attribute(
            b,
            "xformOp:transform",
            "matrix4d",
            false,
            vec![field("timeSamples", value)],
        ));
    }
    prim_with(b, "head", "Mesh", properties)
}

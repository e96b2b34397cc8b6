//! A crate file's specs as the layer model the `.usda` reader builds
//! ([`crate::usda::parse::Layer`]), so both USD encodings share one
//! path from prims to curves (counts, interpolation, transforms, units,
//! axes, time samples: [`crate::usda`]).
//!
//! The pseudo-root spec gives the layer metadata; prim specs, taken in the
//! path tree's depth-first order (parents first), give the prims; attribute
//! specs give their values. Where the text reader keeps a line, this keeps
//! the byte offset of the value in question. Prims under something other
//! than a prim (a variant) are not read, as the text reader does not read
//! variants; classes and `active = false` prims hold no curves.

use crate::error::ReadErrorKind;
use crate::usda::parse::{ArrayValue, CurvesPrim, Layer, Prim};
use crate::usdc::cursor::error;
use crate::usdc::sections::{PathNode, Spec, spec_type};
use crate::usdc::values::{Rep, Values, kind};
use crate::warnings::short;

type Result<T> = std::result::Result<T, crate::ReadError>;

/// `SdfSpecifierClass`.
const SPECIFIER_CLASS: u64 = 2;

/// Builds the layer model from the decoded sections.
pub(crate) fn layer_from_crate(values: &Values) -> Result<Layer> {
    let file = values.file;
    let mut layer = Layer::default();
    let mut spec_at: Vec<Option<Spec>> = vec![None; file.paths.len()];
    for spec in &file.specs {
        let slot = spec_at.get_mut(spec.path).ok_or_else(|| {
            error(
                0,
                ReadErrorKind::BadValue,
                format!(
                    "a spec names path {}, past the {} paths",
                    spec.path,
                    file.paths.len()
                ),
            )
        })?;
        *slot = Some(*spec);
    }
    if let Some(root) = file
        .specs
        .iter()
        .find(|s| s.spec_type == spec_type::PSEUDO_ROOT)
    {
        layer_metadata(values, root, &mut layer)?;
    }
    // Path index → (prim index, skipped) for prims read.
    let mut prim_of: Vec<Option<(usize, bool)>> = vec![None; file.paths.len()];
    for &path in &file.path_order {
        let (Some(node), Some(spec)) = (file.paths[path], spec_at[path]) else {
            continue;
        };
        if node.property || spec.spec_type != spec_type::PRIM {
            continue;
        }
        let parent = match node.parent {
            None => continue,
            Some(parent) if file.paths[parent].is_some_and(|p| p.parent.is_none()) => None,
            Some(parent) => match prim_of[parent] {
                Some(found) => Some(found),
                None => {
                    let name = short(file.tokens.get(node.token).map_or("", String::as_str));
                    layer.warnings.push(|| {
                        format!("prim {name} under a variant or an unknown parent is not read")
                    });
                    continue;
                }
            },
        };
        let index = layer.prims.len();
        let skipped = read_prim(values, &spec, &node, parent, &mut layer)?;
        prim_of[path] = Some((index, skipped));
    }
    let mut curves_of: Vec<Option<usize>> = vec![None; layer.prims.len()];
    for (index, curves) in layer.curves.iter().enumerate() {
        curves_of[curves.prim] = Some(index);
    }
    for &path in &file.path_order {
        let (Some(node), Some(spec)) = (file.paths[path], spec_at[path]) else {
            continue;
        };
        if !node.property || spec.spec_type != spec_type::ATTRIBUTE {
            continue;
        }
        let Some((prim, _)) = node.parent.and_then(|parent| prim_of[parent]) else {
            continue;
        };
        let name = file.token(node.token as u64, 0)?.to_owned();
        read_attribute(values, &spec, &name, prim, curves_of[prim], &mut layer)?;
    }
    Ok(layer)
}

fn field_name<'a>(values: &'a Values, name: u32) -> &'a str {
    values
        .file
        .tokens
        .get(name as usize)
        .map_or("", String::as_str)
}

fn layer_metadata(values: &Values, root: &Spec, layer: &mut Layer) -> Result<()> {
    for (name, rep) in values.file.fields_of(root.field_set) {
        let rep = Rep(rep);
        let at = rep.payload() as usize;
        match field_name(values, name) {
            "metersPerUnit" => {
                if let Some(value) = values.number(rep)? {
                    layer.metadata.meters_per_unit = Some((at, value));
                }
            }
            "upAxis" => {
                if let Some(axis) = values.token(rep)? {
                    layer.metadata.up_axis = Some((at, axis));
                }
            }
            "timeCodesPerSecond" => layer.metadata.time_codes_per_second = values.number(rep)?,
            "framesPerSecond" => layer.metadata.frames_per_second = values.number(rep)?,
            _ => {}
        }
    }
    Ok(())
}

/// Adds a prim; returns whether it is skipped (a class, inactive, or
/// under one).
fn read_prim(
    values: &Values,
    spec: &Spec,
    node: &PathNode,
    parent: Option<(usize, bool)>,
    layer: &mut Layer,
) -> Result<bool> {
    values.budget.charge(256, 0, "the prims")?;
    let name = short(
        values
            .file
            .tokens
            .get(node.token)
            .map_or("", String::as_str),
    );
    let mut skipped = parent.is_some_and(|(_, skipped)| skipped);
    let mut type_name = None;
    let mut offset = 0usize;
    for (field, rep) in values.file.fields_of(spec.field_set) {
        let rep = Rep(rep);
        match field_name(values, field) {
            "specifier" if rep.kind() == kind::SPECIFIER => {
                skipped |= rep.payload() == SPECIFIER_CLASS;
            }
            "active" => skipped |= values.number(rep)? == Some(0.0),
            "typeName" => {
                offset = rep.payload() as usize;
                type_name = values.token(rep)?;
            }
            key @ ("references" | "payload" | "inheritPaths" | "specializes"
            | "variantSelection") => {
                layer
                    .warnings
                    .push(|| format!("<{name}>: {key} (composition) are not followed"));
            }
            _ => {}
        }
    }
    let index = layer.prims.len();
    layer.prims.push(Prim {
        name,
        parent: parent.map(|(index, _)| index),
        xform_op_order: None,
        xform_ops: Vec::new(),
        animated_xform: false,
    });
    if type_name.as_deref() == Some("BasisCurves") && !skipped {
        layer.curves.push(CurvesPrim {
            prim: index,
            line: offset,
            ..CurvesPrim::default()
        });
    }
    Ok(skipped)
}

/// An attribute's fields: type name, default, time samples, interpolation.
struct Attribute {
    type_name: String,
    default: Option<Rep>,
    samples: Option<Rep>,
    interpolation: Option<String>,
}

fn read_attribute(
    values: &Values,
    spec: &Spec,
    name: &str,
    prim: usize,
    curves: Option<usize>,
    layer: &mut Layer,
) -> Result<()> {
    let mut attribute = Attribute {
        type_name: String::new(),
        default: None,
        samples: None,
        interpolation: None,
    };
    for (field, rep) in values.file.fields_of(spec.field_set) {
        let rep = Rep(rep);
        match field_name(values, field) {
            "typeName" => attribute.type_name = values.token(rep)?.unwrap_or_default(),
            "default" if rep.kind() != kind::VALUE_BLOCK => attribute.default = Some(rep),
            "timeSamples" => attribute.samples = Some(rep),
            "interpolation" => attribute.interpolation = values.token(rep)?,
            _ => {}
        }
    }
    if name.starts_with("xformOp") {
        return xform_attribute(values, name, &attribute, &mut layer.prims[prim]);
    }
    let Some(curves) = curves.and_then(|index| layer.curves.get_mut(index)) else {
        return Ok(());
    };
    let interpolation = &attribute.interpolation;
    if let Some(rep) = attribute.default {
        match name {
            "type" => curves.curve_type = values.token(rep)?,
            "basis" => curves.basis = values.token(rep)?,
            "wrap" => curves.wrap = values.token(rep)?,
            "curveVertexCounts" => {
                curves.counts = values.numbers(rep)?.map(|v| array(rep, v, interpolation))
            }
            "points" => curves.points = values.vec3s(rep)?.map(|v| array(rep, v, interpolation)),
            "widths" | "primvars:widths" if attribute.type_name == "float[]" => {
                curves.widths = values.numbers(rep)?.map(|v| array(rep, v, interpolation));
            }
            "primvars:displayColor" if attribute.type_name == "color3f[]" => {
                curves.colours = values.vec3s(rep)?.map(|v| array(rep, v, interpolation));
            }
            _ => {}
        }
    }
    if let Some(rep) = attribute.samples {
        let Some(samples) = values.time_samples(rep)? else {
            return Ok(());
        };
        if name != "points" {
            let name = short(name);
            layer.warnings.push(|| {
                format!(
                    "byte {}: time samples of {name} are not read (only points move)",
                    rep.payload()
                )
            });
            return Ok(());
        }
        for (time, sample) in samples {
            let at = sample.payload() as usize;
            let points = if sample.kind() == kind::VALUE_BLOCK {
                None
            } else {
                let points = values.vec3s(sample)?.ok_or_else(|| {
                    error(
                        sample.payload(),
                        ReadErrorKind::BadValue,
                        format!("the points sample at time {time} is not a 3-vector array"),
                    )
                })?;
                Some(points)
            };
            curves.point_samples.push((time, at, points));
        }
    }
    Ok(())
}

fn xform_attribute(
    values: &Values,
    name: &str,
    attribute: &Attribute,
    prim: &mut Prim,
) -> Result<()> {
    if attribute.samples.is_some() {
        prim.animated_xform = true;
    }
    let Some(rep) = attribute.default else {
        return Ok(());
    };
    if name == "xformOpOrder" {
        prim.xform_op_order = values.tokens(rep)?;
    } else if let Some(numbers) = values.flat(rep)? {
        prim.xform_ops
            .push((name.to_owned(), rep.payload() as usize, numbers));
    }
    Ok(())
}

/// An array value with its offset and interpolation.
fn array<T>(rep: Rep, values: Vec<T>, interpolation: &Option<String>) -> ArrayValue<T> {
    ArrayValue {
        line: rep.payload() as usize,
        values,
        interpolation: interpolation.clone(),
    }
}

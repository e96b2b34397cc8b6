//! Alembic curves (`AbcGeom_Curve_v2` objects) to strands: the object
//! tree walked with its transforms, each curves object's `.geom`
//! properties read, time samples made frames.
//!
//! What is read: `P` (points, every sample), `nVertices` (the counts,
//! which may not change over time), `curveBasisAndType` (linear curves
//! exactly, cubic ones as their control polylines, with a warning) and
//! `width` (or Unreal's `groom_width`; a plain array or an indexed
//! geometry parameter, per point, per curve or one for all, matched by its
//! length). Other groom attributes (guides, ids, root UVs) are not read. Points go through
//! their `Xform` ancestors (every op: scale, translate, rotate, the three
//! axis rotations, matrix; `.inherits = false` drops the parents'); an
//! animated transform uses its first sample, with a warning. Alembic
//! declares no unit or up axis: metres and Y up unless the caller says
//! otherwise. Several curves objects concatenate in file order; animated
//! ones must share their sample times, static ones repeat in every frame.

use glam::{DMat4, DVec3, Vec3};

use crate::abc::archive::{Archive, Kind, MAX_DEPTH, Object, Property, metadata_value, pod};
use crate::abc::ogawa::{Child, error};
use crate::animation::Frame;
use crate::curve_set::{Curve, StrandValue};
use crate::error::{ReadError, ReadErrorKind};
use crate::format::Format;
use crate::imported::{Imported, Units, finish};
use crate::options::ReadOptions;
use crate::warnings::{Warnings, short};

/// The frame rate used when the samples are not evenly spaced (USD's
/// fallback too).
const FALLBACK_FRAMES_PER_SECOND: f64 = 24.0;

/// One curves object's strands, with its frames when animated.
struct ObjectCurves {
    curves: Vec<Curve>,
    /// (time in seconds, every strand's points) per sample.
    samples: Option<Vec<(f64, Vec<Vec3>)>>,
    /// The frame rate its time sampling implies.
    rate: Option<f64>,
    name: String,
}

/// Reads every curves object of an archive.
pub(crate) fn read_curves(
    archive: &Archive,
    options: &ReadOptions,
    file_bytes: usize,
) -> Result<Imported, ReadError> {
    let units = Units::resolve(Format::Abc, options, None)?;
    let mut warnings = Warnings::default();
    let mut found = Vec::new();
    let top = Place {
        world: DMat4::IDENTITY,
        animated_by: None,
        depth: 0,
    };
    walk(
        archive,
        archive.top,
        &top,
        &units,
        &mut found,
        &mut warnings,
    )?;
    if found.is_empty() {
        warnings.push(|| "the archive has no curves object with points".to_string());
    }
    let (rate, frames) = merge_frames(&found, file_bytes)?;
    let curves = found.into_iter().flat_map(|object| object.curves).collect();
    let animation = (!frames.is_empty()).then_some((rate, frames));
    Ok(finish(
        Format::Abc,
        &units,
        curves,
        animation,
        warnings.into_vec(),
    ))
}

/// Where an object sits: its parents' transform, the animated transform
/// above it (whose first sample is used), its depth.
struct Place {
    world: DMat4,
    animated_by: Option<String>,
    depth: usize,
}

fn walk(
    archive: &Archive,
    group: Child,
    place: &Place,
    units: &Units,
    found: &mut Vec<ObjectCurves>,
    warnings: &mut Warnings,
) -> Result<(), ReadError> {
    if place.depth > MAX_DEPTH {
        let (Child::Group(at) | Child::Data(at)) = group;
        return Err(error(
            at,
            ReadErrorKind::TooLarge,
            format!("objects nest deeper than {MAX_DEPTH} levels"),
        ));
    }
    for object in archive.children(group)? {
        let schema = metadata_value(&object.metadata, "schema").unwrap_or("");
        let mut child = Place {
            world: place.world,
            animated_by: place.animated_by.clone(),
            depth: place.depth + 1,
        };
        if schema.starts_with("AbcGeom_Xform") {
            let (local, inherits, animated) = xform(archive, &object, warnings)?;
            child.world = if inherits { place.world * local } else { local };
            if animated {
                child.animated_by = Some(short(&object.name));
            }
        } else if schema.starts_with("AbcGeom_Curve")
            && let Some(curves) = curves_object(archive, &object, place.world, units, warnings)?
        {
            if let Some(xform) = &place.animated_by {
                let name = short(&object.name);
                warnings.push(|| {
                    format!("{name}: its transform {xform} is animated; the first sample is used")
                });
            }
            found.push(curves);
        }
        walk(archive, object.group, &child, units, found, warnings)?;
    }
    Ok(())
}

fn find<'p>(properties: &'p [Property], name: &str) -> Option<&'p Property> {
    properties.iter().find(|p| p.name == name)
}

/// An `Xform` object's local matrix (column vectors, its first sample),
/// whether it inherits its parents' and whether it is animated.
fn xform(
    archive: &Archive,
    object: &Object,
    warnings: &mut Warnings,
) -> Result<(DMat4, bool, bool), ReadError> {
    let properties = archive.object_properties(object.group)?;
    let Some(compound) = find(&properties, ".xform").filter(|p| p.kind == Kind::Compound) else {
        return Ok((DMat4::IDENTITY, true, false));
    };
    let properties = archive.properties(compound.group)?;
    let first = |name: &str| -> Result<Option<Vec<f64>>, ReadError> {
        match find(&properties, name) {
            Some(p) if p.samples > 0 && p.kind != Kind::Compound => archive.numbers(p, 0).map(Some),
            _ => Ok(None),
        }
    };
    let inherits = first(".inherits")?.is_none_or(|v| v.first() != Some(&0.0));
    let ops = first(".ops")?.unwrap_or_default();
    let values = first(".vals")?.unwrap_or_default();
    let animated = find(&properties, ".vals")
        .is_some_and(|p| p.samples > 1 && !(p.first_changed == 0 && p.last_changed == 0));
    let mut local = DMat4::IDENTITY;
    let mut at = 0usize;
    for op in ops {
        let kind = (op as u8) >> 4;
        let channels = match kind {
            0..=1 => 3,
            2 => 4,
            3 => 16,
            4..=6 => 1,
            _ => {
                let name = short(&object.name);
                warnings.push(|| {
                    format!("{name}: transform op {kind} is not one Alembic defines; skipped")
                });
                continue;
            }
        };
        let Some(v) = values.get(at..at + channels) else {
            let name = short(&object.name);
            warnings.push(|| {
                format!("{name}: transform ops need more values than .vals holds; the rest skipped")
            });
            break;
        };
        at += channels;
        // Every op with three or four channels starts with a vector.
        let vec3 = || DVec3::new(v[0], v[1], v[2]);
        let matrix = match kind {
            0 => DMat4::from_scale(vec3()),
            1 => DMat4::from_translation(vec3()),
            2 if vec3().length_squared() > 0.0 => {
                DMat4::from_axis_angle(vec3().normalize(), v[3].to_radians())
            }
            2 => DMat4::IDENTITY,
            // Imath's row-vector rows are glam's columns.
            3 => DMat4::from_cols_slice(v),
            4 => DMat4::from_rotation_x(v[0].to_radians()),
            5 => DMat4::from_rotation_y(v[0].to_radians()),
            _ => DMat4::from_rotation_z(v[0].to_radians()),
        };
        // The first op is outermost, as in USD.
        local *= matrix;
    }
    Ok((local, inherits, animated))
}

/// A curves object's strands.
fn curves_object(
    archive: &Archive,
    object: &Object,
    world: DMat4,
    units: &Units,
    warnings: &mut Warnings,
) -> Result<Option<ObjectCurves>, ReadError> {
    let name = short(&object.name);
    let properties = archive.object_properties(object.group)?;
    let Some(geom) = find(&properties, ".geom").filter(|p| p.kind == Kind::Compound) else {
        warnings.push(|| format!("{name}: a curves object without .geom; skipped"));
        return Ok(None);
    };
    let geom = archive.properties(geom.group)?;
    let (Some(p), Some(counts)) = (find(&geom, "P"), find(&geom, "nVertices")) else {
        warnings.push(|| format!("{name}: curves without P or nVertices; skipped"));
        return Ok(None);
    };
    if p.kind != Kind::Array || p.extent != 3 || !matches!(p.pod, pod::F32 | pod::F64 | pod::F16) {
        return Err(error(
            0,
            ReadErrorKind::BadValue,
            format!("{name}: P is not an array of 3-vectors"),
        ));
    }
    if p.samples == 0 {
        warnings.push(|| format!("{name}: P has no samples; skipped"));
        return Ok(None);
    }
    if let Some(kind) = find(&geom, "curveBasisAndType").filter(|p| p.samples > 0) {
        let values = archive.numbers(kind, 0)?;
        match values.first().copied() {
            Some(1.0) => {}
            Some(t) => warnings.push(|| {
                format!(
                    "{name}: {} curves are read as their control polylines",
                    if t == 0.0 { "cubic" } else { "variable-order" }
                )
            }),
            None => {}
        }
        if values.get(1) == Some(&1.0) {
            warnings.push(|| format!("{name}: periodic (closed) curves are read open"));
        }
    }
    let sizes: Vec<usize> = archive
        .numbers(counts, 0)?
        .into_iter()
        .map(|c| {
            if c >= 0.0 && c.fract() == 0.0 {
                Ok(c as usize)
            } else {
                Err(error(
                    0,
                    ReadErrorKind::BadValue,
                    format!("{name}: curve vertex count {c} is not a count"),
                ))
            }
        })
        .collect::<Result<_, _>>()?;
    let total = sizes.iter().fold(0usize, |sum, &n| sum.saturating_add(n));
    let constant_counts = counts.first_changed == 0 && counts.last_changed == 0;
    let stored_points = archive.stored(p)?;
    let stored_counts = archive.stored(counts)?;
    let identity = world == DMat4::IDENTITY;
    let points_at = |index: u32| -> Result<Vec<Vec3>, ReadError> {
        if !constant_counts && index > 0 {
            let at = index.min(counts.samples - 1);
            let now: Vec<f64> = archive.numbers_in(counts, &stored_counts, at)?;
            if now.len() != sizes.len() || now.iter().zip(&sizes).any(|(a, &b)| *a != b as f64) {
                return Err(error(
                    0,
                    ReadErrorKind::Unsupported,
                    format!(
                        "{name}: the curve counts change at sample {index}; changing topology is not read"
                    ),
                ));
            }
        }
        let values = archive.numbers_in(p, &stored_points, index)?;
        if total.checked_mul(3) != Some(values.len()) {
            return Err(error(
                0,
                ReadErrorKind::CountMismatch,
                format!(
                    "{name}: sample {index} of P has {} points but nVertices add up to {total}",
                    values.len() / 3
                ),
            ));
        }
        Ok(values
            .chunks_exact(3)
            .map(|c| {
                let q = if identity {
                    DVec3::new(c[0], c[1], c[2])
                } else {
                    world.transform_point3(DVec3::new(c[0], c[1], c[2]))
                };
                units.point(q.x, q.y, q.z)
            })
            .collect())
    };
    let base = points_at(0)?;
    let sampling = archive.time_sampling(p)?;
    let (samples, rate) = if p.samples > 1 {
        // The count is the file's word: charged before anything is sized by it.
        let samples = p.samples as usize;
        archive
            .ogawa
            .budget
            .charge(samples.saturating_mul(64), 0, "P's samples")?;
        let mut list = Vec::with_capacity(samples);
        for index in 0..p.samples {
            list.push((sampling.time(index), points_at(index)?));
        }
        let uniform = !sampling.acyclic() && sampling.times.len() == 1;
        let rate =
            (uniform && sampling.time_per_cycle > 0.0).then(|| 1.0 / sampling.time_per_cycle);
        (Some(list), rate)
    } else {
        (None, None)
    };
    // `width`, or Unreal's `groom_width` among the arbitrary parameters.
    let arbitrary = match find(&geom, ".arbGeomParams").filter(|p| p.kind == Kind::Compound) {
        Some(compound) => archive.properties(compound.group)?,
        None => Vec::new(),
    };
    let width = find(&geom, "width").or_else(|| find(&arbitrary, "groom_width"));
    let widths = match width {
        Some(width) => widths_of(archive, width, &sizes, total, &name, units, warnings)?,
        None => None,
    };
    let mut curves = Vec::with_capacity(sizes.len());
    let mut first = 0;
    for (index, &size) in sizes.iter().enumerate() {
        let range = first..first + size;
        first = range.end;
        curves.push(Curve {
            points_m: base[range.clone()].to_vec(),
            width_m: widths.as_ref().map(|w: &Vec<f32>| match w.len() {
                1 => StrandValue::PerStrand(w[0]),
                n if n == sizes.len() && n != total => StrandValue::PerStrand(w[index]),
                _ => StrandValue::PerPoint(w[range.clone()].to_vec()),
            }),
            colour: None,
        });
    }
    Ok(Some(ObjectCurves {
        curves,
        samples,
        rate,
        name: object.name.clone(),
    }))
}

/// The first sample of `width` (a plain array, or an indexed parameter:
/// `.vals` looked up by `.indices`), in metres; `None` (with a warning)
/// when its length fits neither the points, the curves nor one value.
fn widths_of(
    archive: &Archive,
    width: &Property,
    sizes: &[usize],
    total: usize,
    name: &str,
    units: &Units,
    warnings: &mut Warnings,
) -> Result<Option<Vec<f32>>, ReadError> {
    let values = match width.kind {
        Kind::Compound => {
            let parts = archive.properties(width.group)?;
            let Some(vals) = find(&parts, ".vals").filter(|p| p.samples > 0) else {
                return Ok(None);
            };
            let vals = archive.numbers(vals, 0)?;
            match find(&parts, ".indices").filter(|p| p.samples > 0) {
                Some(indices) => {
                    let mut looked_up = Vec::new();
                    for index in archive.numbers(indices, 0)? {
                        match vals.get(index as usize) {
                            Some(&v) if index >= 0.0 => looked_up.push(v),
                            _ => {
                                return Err(error(
                                    0,
                                    ReadErrorKind::BadValue,
                                    format!(
                                        "{name}: width index {index} is past the {} widths",
                                        vals.len()
                                    ),
                                ));
                            }
                        }
                    }
                    looked_up
                }
                None => vals,
            }
        }
        _ if width.samples > 0 => archive.numbers(width, 0)?,
        _ => return Ok(None),
    };
    let len = values.len();
    if len == total || len == sizes.len() || len == 1 {
        Ok(Some(values.into_iter().map(|v| units.length(v)).collect()))
    } else {
        warnings.push(|| {
            format!(
                "{name}: width has {len} values, which fits neither {} curves nor their {total} points; ignored",
                sizes.len()
            )
        });
        Ok(None)
    }
}

/// Frames over all curves objects (their time codes at the rate the first
/// animated object's sampling implies, or 24 per second).
fn merge_frames(
    objects: &[ObjectCurves],
    file_bytes: usize,
) -> Result<(f64, Vec<Frame>), ReadError> {
    let Some(first) = objects.iter().find(|o| o.samples.is_some()) else {
        return Ok((FALLBACK_FRAMES_PER_SECOND, Vec::new()));
    };
    let rate = first.rate.unwrap_or(FALLBACK_FRAMES_PER_SECOND);
    let times: Vec<f64> = first.samples.iter().flatten().map(|(t, _)| *t).collect();
    for object in objects {
        if let Some(samples) = &object.samples
            && (samples.len() != times.len() || samples.iter().zip(&times).any(|(s, t)| s.0 != *t))
        {
            return Err(error(
                0,
                ReadErrorKind::Unsupported,
                format!(
                    "{}: curves objects with different sample times are not read together",
                    short(&object.name)
                ),
            ));
        }
    }
    let total: usize = objects
        .iter()
        .map(|o| o.curves.iter().map(|c| c.points_m.len()).sum::<usize>())
        .sum();
    let frame_points = total.saturating_mul(times.len());
    if frame_points > file_bytes {
        return Err(error(
            0,
            ReadErrorKind::TooLarge,
            format!(
                "{} frames of {total} points (static objects repeated in every frame) make {frame_points} points, more than the file's {file_bytes} bytes justify",
                times.len()
            ),
        ));
    }
    let frames = times
        .iter()
        .enumerate()
        .map(|(index, &time)| {
            let mut points_m = Vec::with_capacity(total);
            for object in objects {
                match &object.samples {
                    Some(samples) => points_m.extend_from_slice(&samples[index].1),
                    None => points_m.extend(
                        object
                            .curves
                            .iter()
                            .flat_map(|c| c.points_m.iter().copied()),
                    ),
                }
            }
            // Seconds to time codes, rounded off the last bits so whole
            // frames stay whole.
            let time_code = (time * rate * 1e9).round() / 1e9;
            Frame {
                time_code,
                points_m,
            }
        })
        .collect();
    Ok((rate, frames))
}

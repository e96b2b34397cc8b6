//! Parsed `BasisCurves` prims to strands: counts checked, units and axes
//! applied, primvars matched to curves, time samples to frames.

use glam::{DMat4, DVec3, Vec3};

use crate::animation::Frame;
use crate::curve_set::{Curve, StrandValue, UpAxis};
use crate::error::{Location, ReadError, ReadErrorKind};
use crate::format::Format;
use crate::imported::{Imported, Units, finish};
use crate::options::ReadOptions;
use crate::usda::parse::{ArrayValue, CurvesPrim, Layer, PrimPath};
use crate::usda::transform::world_transforms;
use crate::warnings::{Warnings, short};

/// USD's `metersPerUnit` when a layer does not author one (centimetres).
pub const USD_FALLBACK_METERS_PER_UNIT: f64 = 0.01;
/// USD's time codes per second when a layer authors neither
/// `timeCodesPerSecond` nor `framesPerSecond`.
pub const USD_FALLBACK_TIME_CODES_PER_SECOND: f64 = 24.0;

/// Where a value is: a line of a `.usda` layer, a byte of a `.usdc` file
/// (the layer model keeps one number for either).
fn location(format: Format, at: usize) -> Location {
    match format {
        Format::Usda => Location::Line(at),
        _ => Location::Byte(at as u64),
    }
}

fn error(format: Format, at: usize, kind: ReadErrorKind, message: String) -> ReadError {
    ReadError::new(format, location(format, at), kind, message)
}

/// One prim's strands, with its frames when animated.
struct PrimCurves {
    curves: Vec<Curve>,
    /// Points of every strand per sample time, when time-sampled.
    samples: Option<Vec<(f64, Vec<Vec3>)>>,
    line: usize,
}

/// Turns a parsed layer into the imported groom.
/// `file_bytes` bounds the frames: repeating static prims in every frame
/// may not make more points than the file has bytes.
pub(crate) fn curves_from_layer(
    format: Format,
    layer: Layer,
    options: &ReadOptions,
    file_bytes: usize,
) -> Result<Imported, ReadError> {
    let Layer {
        metadata,
        prims,
        curves: curve_prims,
        mut warnings,
    } = layer;
    let meters_per_unit = match metadata.meters_per_unit {
        Some((line, value)) if !(value.is_finite() && value > 0.0) => {
            return Err(error(
                format,
                line,
                ReadErrorKind::BadValue,
                format!("metersPerUnit must be positive, not {value}"),
            ));
        }
        Some((_, value)) => value,
        None => {
            if options.metres_per_unit.is_none() {
                warnings.push(|| {
                    "the layer authors no metersPerUnit: read in centimetres, USD's fallback \
                     (0.01 m per unit); a groom modelled in metres reads 100 times too small \
                     (`helixhair import --metres-per-unit 1`)"
                        .to_owned()
                });
            }
            USD_FALLBACK_METERS_PER_UNIT
        }
    };
    let up_axis = match metadata.up_axis {
        None => UpAxis::Y,
        Some((_, axis)) if axis == "Y" => UpAxis::Y,
        Some((_, axis)) if axis == "Z" => UpAxis::Z,
        Some((line, axis)) => {
            return Err(error(
                format,
                line,
                ReadErrorKind::BadValue,
                format!("upAxis must be \"Y\" or \"Z\", not {axis:?}"),
            ));
        }
    };
    let units = Units::resolve(format, options, Some((meters_per_unit, up_axis)))?;
    let time_codes_per_second = metadata
        .time_codes_per_second
        .or(metadata.frames_per_second)
        .filter(|rate| rate.is_finite() && *rate > 0.0)
        .unwrap_or(USD_FALLBACK_TIME_CODES_PER_SECOND);
    let world = world_transforms(&prims, &mut warnings);
    let mut per_prim = Vec::with_capacity(curve_prims.len());
    for prim in curve_prims {
        let path = PrimPath {
            prims: &prims,
            index: prim.prim,
        };
        let transform = world[prim.prim];
        if let Some(read) = prim_curves(format, prim, &path, transform, &units, &mut warnings)? {
            per_prim.push(read);
        }
    }
    if per_prim.is_empty() {
        warnings.push(|| "the layer has no BasisCurves prim with points".to_string());
    }
    let frames = merge_frames(format, &per_prim, file_bytes)?;
    let curves = per_prim.into_iter().flat_map(|prim| prim.curves).collect();
    let animation = (!frames.is_empty()).then_some((time_codes_per_second, frames));
    Ok(finish(
        format,
        &units,
        curves,
        animation,
        warnings.into_vec(),
    ))
}

fn prim_curves(
    format: Format,
    prim: CurvesPrim,
    path: &PrimPath,
    world: DMat4,
    units: &Units,
    warnings: &mut Warnings,
) -> Result<Option<PrimCurves>, ReadError> {
    match prim.curve_type.as_deref() {
        Some("linear") => {}
        Some("cubic") | None => warnings.push(|| {
            format!(
                "<{path}>: {} curves (basis {}) are read as their control polylines",
                prim.curve_type
                    .as_deref()
                    .unwrap_or("cubic (USD's fallback type)"),
                prim.basis.as_deref().unwrap_or("bezier"),
            )
        }),
        Some(other) => {
            return Err(error(
                format,
                prim.line,
                ReadErrorKind::BadValue,
                format!("<{path}>: curve type {other:?} is neither linear nor cubic"),
            ));
        }
    }
    if prim.wrap.as_deref() == Some("periodic") {
        warnings.push(|| format!("<{path}>: periodic (closed) curves are read open"));
    }
    let mut samples: Vec<(f64, usize, Vec<[f64; 3]>)> = Vec::new();
    for (time, line, values) in prim.point_samples {
        if !time.is_finite() {
            return Err(error(
                format,
                line,
                ReadErrorKind::BadValue,
                format!("time code {time} is not finite"),
            ));
        }
        match values {
            Some(values) => samples.push((time, line, values)),
            None => warnings.push(|| {
                format!(
                    "{}: <{path}>: the blocked points sample at time {time} is skipped",
                    location(format, line)
                )
            }),
        }
    }
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    if let Some(pair) = samples.windows(2).find(|pair| pair[0].0 == pair[1].0) {
        return Err(error(
            format,
            pair[1].1,
            ReadErrorKind::BadValue,
            format!("<{path}>: time code {} has two samples", pair[1].0),
        ));
    }
    let Some(counts) = prim.counts else {
        if prim.points.is_some() || !samples.is_empty() {
            return Err(error(
                format,
                prim.line,
                ReadErrorKind::CountMismatch,
                format!("<{path}> has points but no curveVertexCounts"),
            ));
        }
        warnings.push(|| format!("<{path}> has no curveVertexCounts and no points; skipped"));
        return Ok(None);
    };
    let mut sizes = Vec::with_capacity(counts.values.len());
    for &count in &counts.values {
        if !(count.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&count)) {
            return Err(error(
                format,
                counts.line,
                ReadErrorKind::BadValue,
                format!("<{path}>: curve vertex count {count} is not a count"),
            ));
        }
        sizes.push(count as usize);
    }
    let total = sizes
        .iter()
        .fold(0usize, |sum, &size| sum.saturating_add(size));
    // Without a transform the numbers go straight to metres (no -0 + 0).
    let identity = world == DMat4::IDENTITY;
    let transform = |point: &[f64; 3]| {
        let p = if identity {
            DVec3::from_array(*point)
        } else {
            world.transform_point3(DVec3::from_array(*point))
        };
        units.point(p.x, p.y, p.z)
    };
    let check = |line: usize, len: usize, what: &str| {
        if len == total {
            Ok(())
        } else {
            Err(error(
                format,
                line,
                ReadErrorKind::CountMismatch,
                format!(
                    "<{path}>: {what} has {len} points but curveVertexCounts add up to {total}"
                ),
            ))
        }
    };
    let base: Vec<Vec3> = match (samples.first(), &prim.points) {
        (Some((_, line, values)), _) => {
            check(*line, values.len(), "the first points sample")?;
            values.iter().map(transform).collect()
        }
        (None, Some(points)) => {
            check(points.line, points.values.len(), "points")?;
            points.values.iter().map(transform).collect()
        }
        (None, None) => {
            warnings.push(|| format!("<{path}> has no points; skipped"));
            return Ok(None);
        }
    };
    let mut frames = None;
    if !samples.is_empty() {
        let mut list = Vec::with_capacity(samples.len());
        for (time, line, values) in &samples {
            check(
                *line,
                values.len(),
                &format!("the points sample at time {time}"),
            )?;
            list.push((*time, values.iter().map(transform).collect()));
        }
        frames = Some(list);
    }
    let widths = prim
        .widths
        .and_then(|widths| per_curve(format, widths, &sizes, path, "widths", warnings));
    let colours = prim.colours.and_then(|colours| {
        per_curve(
            format,
            colours,
            &sizes,
            path,
            "primvars:displayColor",
            warnings,
        )
    });
    let mut curves = Vec::with_capacity(sizes.len());
    let mut first = 0;
    for (index, &size) in sizes.iter().enumerate() {
        let range = first..first + size;
        first = range.end;
        curves.push(Curve {
            points_m: base[range.clone()].to_vec(),
            width_m: widths
                .as_ref()
                .map(|w| w.for_curve(index, range.clone(), |v| units.length(v))),
            colour: colours
                .as_ref()
                .map(|c| c.for_curve(index, range.clone(), |v| v.map(|x| x as f32))),
        });
    }
    Ok(Some(PrimCurves {
        curves,
        samples: frames,
        line: prim.line,
    }))
}

/// A primvar's values matched to curves by interpolation.
struct Matched<T> {
    values: Vec<T>,
    interpolation: Interpolation,
}

#[derive(Clone, Copy)]
enum Interpolation {
    Constant,
    Uniform,
    Vertex,
}

impl<T: Copy> Matched<T> {
    fn for_curve<U>(
        &self,
        index: usize,
        range: std::ops::Range<usize>,
        convert: impl Fn(T) -> U,
    ) -> StrandValue<U> {
        match self.interpolation {
            Interpolation::Constant => StrandValue::PerStrand(convert(self.values[0])),
            Interpolation::Uniform => StrandValue::PerStrand(convert(self.values[index])),
            Interpolation::Vertex => {
                StrandValue::PerPoint(self.values[range].iter().map(|&v| convert(v)).collect())
            }
        }
    }
}

/// Checks a primvar's length against its interpolation (authored, or
/// inferred from the length); a mismatch is warned about and the primvar
/// ignored, as USD ignores it.
fn per_curve<T>(
    format: Format,
    array: ArrayValue<T>,
    sizes: &[usize],
    path: &PrimPath,
    what: &str,
    warnings: &mut Warnings,
) -> Option<Matched<T>> {
    let total = sizes
        .iter()
        .fold(0usize, |sum, &size| sum.saturating_add(size));
    let len = array.values.len();
    let interpolation = match array.interpolation.as_deref() {
        Some("constant") => Some(Interpolation::Constant),
        Some("uniform") => Some(Interpolation::Uniform),
        Some("vertex" | "varying") => Some(Interpolation::Vertex),
        Some(_) => None,
        None if len == total => Some(Interpolation::Vertex),
        None if len == sizes.len() => Some(Interpolation::Uniform),
        None if len == 1 => Some(Interpolation::Constant),
        None => None,
    };
    let expected = match interpolation {
        Some(Interpolation::Constant) => 1,
        Some(Interpolation::Uniform) => sizes.len(),
        Some(Interpolation::Vertex) => total,
        None => usize::MAX,
    };
    if interpolation.is_none() || len < expected || (len != expected && expected != 1) {
        warnings.push(|| format!(
            "{}: <{path}>: {what} has {len} values, which fits neither its interpolation ({}) nor {} curves of {total} points; ignored",
            location(format, array.line),
            short(array.interpolation.as_deref().unwrap_or("none authored")),
            sizes.len()
        ));
        return None;
    }
    Some(Matched {
        values: array.values,
        interpolation: interpolation.unwrap_or(Interpolation::Constant),
    })
}

/// Frames over all prims: animated prims must share their sample times;
/// static prims repeat their points in every frame.
fn merge_frames(
    format: Format,
    per_prim: &[PrimCurves],
    file_bytes: usize,
) -> Result<Vec<Frame>, ReadError> {
    let Some(times) = per_prim
        .iter()
        .find_map(|prim| prim.samples.as_ref())
        .map(|samples| samples.iter().map(|(time, _)| *time).collect::<Vec<_>>())
    else {
        return Ok(Vec::new());
    };
    for prim in per_prim {
        if let Some(samples) = &prim.samples
            && (samples.len() != times.len() || samples.iter().zip(&times).any(|(s, t)| s.0 != *t))
        {
            return Err(error(
                format,
                prim.line,
                ReadErrorKind::Unsupported,
                "BasisCurves prims with different sample times are not read together".to_string(),
            ));
        }
    }
    let total: usize = per_prim
        .iter()
        .map(|prim| prim.curves.iter().map(|c| c.points_m.len()).sum::<usize>())
        .sum();
    let frame_points = total.saturating_mul(times.len());
    if frame_points > file_bytes {
        let line = per_prim.first().map_or(1, |prim| prim.line);
        return Err(error(
            format,
            line,
            ReadErrorKind::TooLarge,
            format!(
                "{} frames of {total} points (static prims repeated in every frame) make {frame_points} points, more than the file's {file_bytes} bytes justify",
                times.len()
            ),
        ));
    }
    Ok(times
        .iter()
        .enumerate()
        .map(|(index, &time_code)| {
            let mut points_m = Vec::with_capacity(total);
            for prim in per_prim {
                match &prim.samples {
                    Some(samples) => points_m.extend_from_slice(&samples[index].1),
                    None => {
                        points_m.extend(prim.curves.iter().flat_map(|c| c.points_m.iter().copied()))
                    }
                }
            }
            Frame {
                time_code,
                points_m,
            }
        })
        .collect())
}

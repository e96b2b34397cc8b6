//! Cem Yuksel's binary `.hair` format (the public hair model library's).
//!
//! # Layout (little-endian)
//!
//! A 128-byte header: `"HAIR"`, `u32` strand count, `u32` total point
//! count, `u32` bit flags of the arrays present (1 segments, 2 points,
//! 4 thickness, 8 transparency, 16 colours), `u32` default segments per
//! strand, `f32` default thickness, `f32` default transparency, `f32 × 3`
//! default colour, 88 bytes of free text. Then the arrays present, in that
//! order: segments per strand (`u16`, a strand has segments + 1 points),
//! points (`f32 × 3`), thickness (`f32` per point), transparency (`f32` per
//! point), colours (`f32 × 3` per point). A missing array takes the
//! header's default.
//!
//! # What is read and written
//!
//! Points, thickness (as the width, a diameter) and colours; transparency
//! is checked to lie in the file, then ignored. Without a thickness array
//! every strand gets the default thickness, without a colour array the
//! default colour. The points array is required. Counts must agree exactly
//! (the segments, or strands × (default segments + 1), sum to the point
//! count) and the arrays must end where the file does.
//!
//! The format declares no unit or up axis. The default is metres, Y up;
//! the library's models are Z up in their own units, so pass
//! [`ReadOptions`] for them.
//!
//! The writer writes metres, Y up: segments, points, thickness when every
//! strand has a width (else a default of [`DEFAULT_WIDTH_M`]) and colours
//! when every strand has one. A strand has at most 65,536 points.

use std::io::Write;

use crate::bytes::{LeBytes, f32_in, put_f32, put_u32};
use crate::curve_set::{Curve, CurveSet, StrandValue};
use crate::error::{ReadError, ReadErrorKind, WriteError};
use crate::format::Format;
use crate::imported::{Imported, Units, finish};
use crate::options::ReadOptions;

/// The header's size in bytes.
pub const HAIR_HEADER_BYTES: u64 = 128;
/// The header's default thickness when the written strands have no width:
/// 80 µm, a typical human hair's diameter.
pub const DEFAULT_WIDTH_M: f32 = 80e-6;

const SEGMENTS_BIT: u32 = 1;
const POINTS_BIT: u32 = 2;
const THICKNESS_BIT: u32 = 4;
const TRANSPARENCY_BIT: u32 = 8;
const COLOURS_BIT: u32 = 16;
const INFO_BYTES: usize = 88;

/// Reads a `.hair` file.
pub fn read_hair(bytes: &[u8], options: &ReadOptions) -> Result<Imported, ReadError> {
    let file = LeBytes::new(bytes, Format::Hair);
    if bytes.get(..4) != Some(b"HAIR") {
        return Err(file.error(
            0,
            ReadErrorKind::BadMagic,
            "a .hair file starts with \"HAIR\"".to_string(),
        ));
    }
    file.require_fixed(0, HAIR_HEADER_BYTES, "the 128-byte header")?;
    let strands = u64::from(file.u32_at(4, "the strand count")?);
    let points = u64::from(file.u32_at(8, "the point count")?);
    let flags = file.u32_at(12, "the array flags")?;
    let default_segments = u64::from(file.u32_at(16, "the default segments")?);
    let default_thickness = file.f32_at(20, "the default thickness")?;
    let default_colour = [
        file.f32_at(32, "the default colour")?,
        file.f32_at(36, "the default colour")?,
        file.f32_at(40, "the default colour")?,
    ];
    if flags & POINTS_BIT == 0 {
        return Err(file.error(
            12,
            ReadErrorKind::Unsupported,
            format!("array flags {flags:#x} say there is no points array"),
        ));
    }
    let has = |bit: u32| flags & bit != 0;
    let sizes = [
        (SEGMENTS_BIT, "segment counts", 4, strands * 2),
        (POINTS_BIT, "points", 8, points * 12),
        (THICKNESS_BIT, "thicknesses", 8, points * 4),
        (TRANSPARENCY_BIT, "transparencies", 8, points * 4),
        (COLOURS_BIT, "colours", 8, points * 12),
    ];
    let mut offsets = [0u64; 5];
    let mut end = HAIR_HEADER_BYTES;
    for (slot, &(bit, what, field, size)) in sizes.iter().enumerate() {
        if has(bit) {
            let what = format!("the {what} of {strands} strands, {points} points");
            file.require(end, Some(size), field, &what)?;
            offsets[slot] = end;
            end += size;
        }
    }
    if end != file.len() {
        return Err(file.error(
            end,
            ReadErrorKind::CountMismatch,
            format!(
                "the header's counts make the arrays end at byte {end}, but the file has {} bytes",
                file.len()
            ),
        ));
    }
    let counts: Vec<u64> = if has(SEGMENTS_BIT) {
        let segments = file.slice(offsets[0], (strands * 2) as usize);
        segments
            .chunks_exact(2)
            .map(|pair| u64::from(u16::from_le_bytes([pair[0], pair[1]])) + 1)
            .collect()
    } else {
        let per_strand = default_segments + 1;
        if strands.checked_mul(per_strand) != Some(points) {
            return Err(file.error(
                16,
                ReadErrorKind::CountMismatch,
                format!(
                    "{strands} strands of {default_segments} default segments need {} points, the header says {points}",
                    u128::from(strands) * u128::from(per_strand)
                ),
            ));
        }
        vec![per_strand; strands as usize]
    };
    let total: u64 = counts.iter().sum();
    if total != points {
        return Err(file.error(
            offsets[0],
            ReadErrorKind::CountMismatch,
            format!("the segment counts give {total} points, the header says {points}"),
        ));
    }
    let units = Units::resolve(Format::Hair, options, None)?;
    let array = |slot: usize, bit: u32, per_point: usize| {
        has(bit).then(|| file.slice(offsets[slot], points as usize * per_point * 4))
    };
    let coordinates = array(1, POINTS_BIT, 3).unwrap_or_default();
    let thickness = array(2, THICKNESS_BIT, 1);
    let colours = array(4, COLOURS_BIT, 3);
    let mut curves = Vec::with_capacity(counts.len());
    let mut first = 0usize;
    for &count in &counts {
        let range = first..first + count as usize;
        first = range.end;
        let points_m = range
            .clone()
            .map(|point| {
                let at = |axis: usize| f64::from(f32_in(coordinates, 3 * point + axis));
                units.point(at(0), at(1), at(2))
            })
            .collect();
        let width_m = Some(match thickness {
            Some(values) => StrandValue::PerPoint(
                range
                    .clone()
                    .map(|point| units.length(f64::from(f32_in(values, point))))
                    .collect(),
            ),
            None => StrandValue::PerStrand(units.length(f64::from(default_thickness))),
        });
        let colour = Some(match colours {
            Some(values) => StrandValue::PerPoint(
                range
                    .map(|point| std::array::from_fn(|channel| f32_in(values, 3 * point + channel)))
                    .collect(),
            ),
            None => StrandValue::PerStrand(default_colour),
        });
        curves.push(Curve {
            points_m,
            width_m,
            colour,
        });
    }
    Ok(finish(Format::Hair, &units, curves, None, Vec::new()))
}

/// Writes one frame as a `.hair` file (see the module docs).
pub fn write_hair(out: &mut impl Write, curves: &CurveSet) -> Result<(), WriteError> {
    let invalid = |message: String| WriteError::invalid(Format::Hair, message);
    crate::write::checks::finite_points(Format::Hair, curves)?;
    let with_width =
        crate::write::checks::all_or_none(Format::Hair, curves, "width", |c| c.width_m.is_some())?;
    let with_colour =
        crate::write::checks::all_or_none(Format::Hair, curves, "colour", |c| c.colour.is_some())?;
    if let Some(index) = curves
        .curves
        .iter()
        .position(|c| c.points_m.is_empty() || c.points_m.len() > usize::from(u16::MAX) + 1)
    {
        return Err(invalid(format!(
            "curve {index} has {} points; a .hair strand has 1 to 65536",
            curves.curves[index].points_m.len()
        )));
    }
    let strands = u32::try_from(curves.curves.len())
        .map_err(|_| invalid("more strands than a u32 counts".to_string()))?;
    let points = u32::try_from(curves.point_count())
        .map_err(|_| invalid("more points than a u32 counts".to_string()))?;
    let mut flags = SEGMENTS_BIT | POINTS_BIT;
    if with_width {
        flags |= THICKNESS_BIT;
    }
    if with_colour {
        flags |= COLOURS_BIT;
    }
    let mut bytes = Vec::with_capacity(128 + curves.curves.len() * 2 + points as usize * 28);
    bytes.extend_from_slice(b"HAIR");
    put_u32(&mut bytes, strands);
    put_u32(&mut bytes, points);
    put_u32(&mut bytes, flags);
    put_u32(&mut bytes, 0); // default segments: every strand has its count
    put_f32(&mut bytes, DEFAULT_WIDTH_M);
    put_f32(&mut bytes, 0.0); // default transparency
    for _ in 0..3 {
        put_f32(&mut bytes, 1.0); // default colour
    }
    let mut info = b"helixhair-formats: metres, Y up".to_vec();
    info.resize(INFO_BYTES, 0);
    bytes.extend_from_slice(&info);
    for curve in &curves.curves {
        bytes.extend_from_slice(&((curve.points_m.len() - 1) as u16).to_le_bytes());
    }
    for point in curves.curves.iter().flat_map(|c| c.points_m.iter()) {
        for value in point.to_array() {
            put_f32(&mut bytes, value);
        }
    }
    if with_width {
        for curve in &curves.curves {
            for index in 0..curve.points_m.len() {
                let width = curve.width_m.as_ref().and_then(|w| w.at(index));
                put_f32(&mut bytes, width.unwrap_or(DEFAULT_WIDTH_M));
            }
        }
    }
    if with_colour {
        for curve in &curves.curves {
            for index in 0..curve.points_m.len() {
                let colour = curve.colour.as_ref().and_then(|c| c.at(index));
                for value in colour.unwrap_or([1.0; 3]) {
                    put_f32(&mut bytes, value);
                }
            }
        }
    }
    out.write_all(&bytes).map_err(WriteError::io(Format::Hair))
}

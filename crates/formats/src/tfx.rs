//! AMD TressFX binary `.tfx`: versions 4.x and 3.x read, 4.0 written.
//!
//! # Layout (little-endian)
//!
//! **4.x** (`TressFXTFXFileHeader`, 160 bytes): `f32` version, `u32` strand
//! count, `u32` points per strand (the same for every strand), then byte
//! offsets from the start of the file of: positions (`f32 × 4` per point,
//! x y z w, strand after strand, root first), per-strand UVs (`f32 × 2`),
//! per-point UVs (`f32 × 2`), per-strand thickness (`f32`) and per-point
//! colours (`f32 × 4`, RGBA), 0 meaning absent; then 32 reserved words.
//! `w` is the point's inverse mass to TressFX (0 pins it); it is ignored on
//! reading and written as 0 for roots and 1 elsewhere.
//!
//! **3.x** (`TressFXFileObject` of TressFX 3.1, 296 bytes): `f32` version,
//! `u32` strand count, `u32` points per strand, `u32` follow hairs per
//! guide, a `bool` (padded to 4 bytes), 31 reserved words, then offsets of
//! positions (`f32 × 3` per point), per-strand thickness, per-strand UVs,
//! per-point colours (`f32 × 4`), guide-strand indices (`u32`) and per-point
//! UVs, then 32 reserved words. The version field tells the two apart. No
//! real 3.x file was at hand: this layout is tested against files written
//! by this crate's tests only.
//!
//! # What is read and written
//!
//! Positions and per-point colours (RGB; alpha ignored). TressFX's
//! thickness is a relative scale, not a width, and UVs have no place in a
//! [`crate::CurveSet`]: both are checked to lie inside the file, then
//! ignored. The format declares no unit or up axis: TressFX assets are Y up
//! and, like the Sintel groom, usually metres, which is the default
//! (override with [`ReadOptions`]).
//!
//! The writer writes 4.0 in metres with Y up, positions and colours (when
//! every strand has one), no widths. TressFX needs every strand to have the
//! same number of points, a power of two from 4 to 64; the writer refuses
//! other curves (resample first).

use std::io::Write;

use crate::bytes::{LeBytes, f32_in, put_f32, put_u32};
use crate::curve_set::{Curve, CurveSet, StrandValue};
use crate::error::{ReadError, ReadErrorKind, WriteError};
use crate::format::Format;
use crate::imported::{Imported, Units, finish};
use crate::options::ReadOptions;

/// The 4.x header's size in bytes.
pub const TFX_V4_HEADER_BYTES: u64 = 160;
/// The 3.x header's size in bytes.
pub const TFX_V3_HEADER_BYTES: u64 = 296;

/// Where one file's arrays are, whichever version.
struct Layout {
    strands: u64,
    points_per_strand: u64,
    positions_offset: u64,
    floats_per_position: u64,
    colours_offset: u64,
}

/// Reads a TressFX 3.x or 4.x file.
pub fn read_tfx(bytes: &[u8], options: &ReadOptions) -> Result<Imported, ReadError> {
    let file = LeBytes::new(bytes, Format::Tfx);
    let version = file.f32_at(0, "the version field")?;
    let layout = if (4.0..5.0).contains(&version) {
        layout_v4(&file)?
    } else if (3.0..4.0).contains(&version) {
        layout_v3(&file)?
    } else {
        return Err(file.error(
            0,
            ReadErrorKind::UnsupportedVersion,
            format!(
                "version field reads {version}; TressFX 3.x and 4.x files start with 3.0 to 4.x"
            ),
        ));
    };
    if layout.points_per_strand == 0 {
        // Found by fuzzing: strands of no points take no bytes, so a tiny
        // file could ask for millions of empty strands.
        return Err(file.error(
            8,
            ReadErrorKind::BadValue,
            format!("{} strands of 0 points each", layout.strands),
        ));
    }
    let units = Units::resolve(Format::Tfx, options, None)?;
    let point_count = (layout.strands * layout.points_per_strand) as usize;
    let per_strand = layout.points_per_strand as usize;
    let floats = layout.floats_per_position as usize;
    let positions = file.slice(layout.positions_offset, point_count * floats * 4);
    let colours =
        (layout.colours_offset != 0).then(|| file.slice(layout.colours_offset, point_count * 16));
    let mut curves = Vec::with_capacity(layout.strands as usize);
    for strand in 0..layout.strands as usize {
        let first = strand * per_strand;
        let points_m = (first..first + per_strand)
            .map(|point| {
                let at = |axis: usize| f64::from(f32_in(positions, point * floats + axis));
                units.point(at(0), at(1), at(2))
            })
            .collect();
        let colour = colours.map(|colours| {
            StrandValue::PerPoint(
                (first..first + per_strand)
                    .map(|point| {
                        std::array::from_fn(|channel| f32_in(colours, point * 4 + channel))
                    })
                    .collect(),
            )
        });
        curves.push(Curve {
            points_m,
            width_m: None,
            colour,
        });
    }
    Ok(finish(Format::Tfx, &units, curves, None, Vec::new()))
}

fn layout_v4(file: &LeBytes) -> Result<Layout, ReadError> {
    file.require_fixed(0, TFX_V4_HEADER_BYTES, "the TressFX 4 header")?;
    let strands = u64::from(file.u32_at(4, "the strand count")?);
    let points_per_strand = u64::from(file.u32_at(8, "the points per strand")?);
    let points = strands * points_per_strand;
    let positions = format!("positions of {strands} strands × {points_per_strand} points");
    let colours = format!("colours of {strands} strands × {points_per_strand} points");
    let arrays = [
        (12, positions.as_str(), points.checked_mul(16)),
        (16, "per-strand UVs", strands.checked_mul(8)),
        (20, "per-point UVs", points.checked_mul(8)),
        (24, "per-strand thicknesses", strands.checked_mul(4)),
        (28, colours.as_str(), points.checked_mul(16)),
    ];
    let offsets = check_arrays(file, &arrays, TFX_V4_HEADER_BYTES, 12)?;
    Ok(Layout {
        strands,
        points_per_strand,
        positions_offset: offsets[0],
        floats_per_position: 4,
        colours_offset: offsets[4],
    })
}

fn layout_v3(file: &LeBytes) -> Result<Layout, ReadError> {
    file.require_fixed(0, TFX_V3_HEADER_BYTES, "the TressFX 3 header")?;
    let strands = u64::from(file.u32_at(4, "the strand count")?);
    let points_per_strand = u64::from(file.u32_at(8, "the points per strand")?);
    let points = strands * points_per_strand;
    let positions = format!("positions of {strands} strands × {points_per_strand} points");
    let colours = format!("colours of {strands} strands × {points_per_strand} points");
    let arrays = [
        (144, positions.as_str(), points.checked_mul(12)),
        (148, "per-strand thicknesses", strands.checked_mul(4)),
        (152, "per-strand UVs", strands.checked_mul(8)),
        (156, colours.as_str(), points.checked_mul(16)),
        (160, "guide strand indices", strands.checked_mul(4)),
        (164, "per-point UVs", points.checked_mul(8)),
    ];
    let offsets = check_arrays(file, &arrays, TFX_V3_HEADER_BYTES, 144)?;
    Ok(Layout {
        strands,
        points_per_strand,
        positions_offset: offsets[0],
        floats_per_position: 3,
        colours_offset: offsets[3],
    })
}

/// Reads each array's offset and checks the array lies in the file, after
/// the header. The array whose offset field is at `required_field` must be
/// present (non-zero offset). Returns the offsets in order.
fn check_arrays(
    file: &LeBytes,
    arrays: &[(u64, &str, Option<u64>)],
    header_bytes: u64,
    required_field: u64,
) -> Result<Vec<u64>, ReadError> {
    let mut offsets = Vec::with_capacity(arrays.len());
    for &(field, what, size) in arrays {
        let offset = u64::from(file.u32_at(field, what)?);
        if offset == 0 && field != required_field {
            offsets.push(0);
            continue;
        }
        if offset < header_bytes {
            return Err(file.error(
                field,
                ReadErrorKind::BadValue,
                format!("the {what} start at byte {offset}, inside the {header_bytes}-byte header"),
            ));
        }
        file.require(offset, size, field, &format!("the {what}"))?;
        offsets.push(offset);
    }
    Ok(offsets)
}

/// Writes one frame as a TressFX 4.0 file (see the module docs).
pub fn write_tfx(out: &mut impl Write, curves: &CurveSet) -> Result<(), WriteError> {
    let invalid = |message: String| WriteError::invalid(Format::Tfx, message);
    let per_strand = curves
        .curves
        .first()
        .map_or(4, |curve| curve.points_m.len());
    if !(4..=64).contains(&per_strand) || !per_strand.is_power_of_two() {
        return Err(invalid(format!(
            "TressFX needs 4, 8, 16, 32 or 64 points per strand; curve 0 has {per_strand}"
        )));
    }
    if let Some(index) = curves
        .curves
        .iter()
        .position(|c| c.points_m.len() != per_strand)
    {
        return Err(invalid(format!(
            "TressFX needs the same number of points on every strand: curve 0 has {per_strand}, curve {index} has {}",
            curves.curves[index].points_m.len()
        )));
    }
    crate::write::checks::finite_points(Format::Tfx, curves)?;
    let with_colour =
        crate::write::checks::all_or_none(Format::Tfx, curves, "colour", |c| c.colour.is_some())?;
    let strands = u32::try_from(curves.curves.len()).map_err(|_| {
        invalid(format!(
            "{} strands do not fit a u32 count",
            curves.curves.len()
        ))
    })?;
    let points = curves.point_count() as u64;
    let colours_offset = TFX_V4_HEADER_BYTES + points * 16;
    let end = colours_offset + if with_colour { points * 16 } else { 0 };
    if end > u64::from(u32::MAX) {
        return Err(invalid(format!(
            "{points} points make a file past the 4 GiB its u32 offsets reach"
        )));
    }
    let mut bytes = Vec::with_capacity(end as usize);
    put_f32(&mut bytes, 4.0);
    put_u32(&mut bytes, strands);
    put_u32(&mut bytes, per_strand as u32);
    put_u32(&mut bytes, TFX_V4_HEADER_BYTES as u32);
    for _ in 0..3 {
        put_u32(&mut bytes, 0); // strand UVs, point UVs, thickness
    }
    put_u32(
        &mut bytes,
        if with_colour {
            colours_offset as u32
        } else {
            0
        },
    );
    bytes.resize(TFX_V4_HEADER_BYTES as usize, 0);
    for curve in &curves.curves {
        for (index, point) in curve.points_m.iter().enumerate() {
            for value in point.to_array() {
                put_f32(&mut bytes, value);
            }
            put_f32(&mut bytes, if index == 0 { 0.0 } else { 1.0 });
        }
    }
    if with_colour {
        for curve in &curves.curves {
            for index in 0..curve.points_m.len() {
                let rgb = curve
                    .colour
                    .as_ref()
                    .and_then(|c| c.at(index))
                    .unwrap_or([1.0; 3]);
                for value in rgb {
                    put_f32(&mut bytes, value);
                }
                put_f32(&mut bytes, 1.0);
            }
        }
    }
    out.write_all(&bytes).map_err(WriteError::io(Format::Tfx))
}

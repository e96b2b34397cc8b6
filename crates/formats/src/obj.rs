//! Wavefront OBJ polylines: `v` and `l` lines, as Blender exports curves.
//!
//! # What is read
//!
//! - `v x y z` lines (extra numbers, such as `w` or a vertex colour, are
//!   ignored);
//! - `l i j k …` lines, one polyline each; an index is 1-based, or negative
//!   to count back from the last vertex defined so far (`-1` is the last),
//!   and may carry a texture index (`l 1/1 2/2`), which is ignored. An index
//!   must name a vertex defined above its line (OBJ writers, Blender's
//!   included, write vertices first).
//! - **Chaining**: an `l` line that starts at the vertex where the previous
//!   `l` line ended continues that polyline. Blender writes a curve
//!   converted to a mesh as one two-point `l` line per edge, so this joins
//!   them back into strands. Only consecutive `l` lines chain (an `o` or
//!   `g` line in between breaks the chain); branching edges start new
//!   polylines, nothing is reordered.
//! - Everything else (faces, normals, texture coordinates, groups,
//!   materials, comments) is skipped, so a head mesh in the same file does
//!   not disturb the hair.
//!
//! OBJ declares no unit or up axis: metres and Y up by default (Blender's
//! exporter writes Y up), overridable with [`ReadOptions`].
//!
//! # What is written
//!
//! A comment line, every point as a `v` line (shortest `f32` decimals, so
//! reading back is exact), then one `l` line per curve. Widths and colours
//! have no OBJ form and are not written.

use std::io::Write;

use glam::Vec3;

use crate::curve_set::{Curve, CurveSet};
use crate::error::{Location, ReadError, ReadErrorKind, WriteError};
use crate::format::Format;
use crate::imported::{Imported, Units, finish};
use crate::options::ReadOptions;

/// Reads an OBJ file's polylines.
pub fn read_obj(bytes: &[u8], options: &ReadOptions) -> Result<Imported, ReadError> {
    let units = Units::resolve(Format::Obj, options, None)?;
    let mut vertices: Vec<Vec3> = Vec::new();
    let mut polylines: Vec<Vec<u32>> = Vec::new();
    let mut chain_open = false;
    for (line_index, raw_line) in bytes.split(|&byte| byte == b'\n').enumerate() {
        let line_number = line_index + 1;
        let error = |kind, message: String| {
            ReadError::new(Format::Obj, Location::Line(line_number), kind, message)
        };
        let trimmed = raw_line.trim_ascii();
        if trimmed.is_empty() || trimmed[0] == b'#' {
            continue;
        }
        let Ok(text) = std::str::from_utf8(trimmed) else {
            return Err(error(
                ReadErrorKind::Syntax,
                "the line is not UTF-8 text".to_string(),
            ));
        };
        let mut tokens = text.split_ascii_whitespace();
        let keyword = tokens.next().unwrap_or_default();
        match keyword {
            "v" => {
                let mut xyz = [0.0f64; 3];
                for (axis, slot) in xyz.iter_mut().enumerate() {
                    let Some(token) = tokens.next() else {
                        return Err(error(
                            ReadErrorKind::Syntax,
                            format!(
                                "a vertex needs x, y and z; coordinate {} is missing",
                                axis + 1
                            ),
                        ));
                    };
                    *slot = token.parse().map_err(|_| {
                        error(ReadErrorKind::Syntax, format!("{token:?} is not a number"))
                    })?;
                }
                vertices.push(units.point(xyz[0], xyz[1], xyz[2]));
            }
            "l" => {
                let mut indices = Vec::new();
                for token in tokens {
                    let vertex_part = token.split('/').next().unwrap_or_default();
                    let index: i64 = vertex_part.parse().map_err(|_| {
                        error(
                            ReadErrorKind::Syntax,
                            format!("{token:?} is not a vertex index"),
                        )
                    })?;
                    let defined = vertices.len() as i64;
                    let resolved = if index > 0 {
                        index - 1
                    } else {
                        defined + index
                    };
                    if index == 0 || resolved < 0 || resolved >= defined {
                        return Err(error(
                            ReadErrorKind::BadValue,
                            format!(
                                "vertex index {index} is out of range: {defined} vertices are defined above this line"
                            ),
                        ));
                    }
                    indices.push(resolved as u32);
                }
                let chains = chain_open
                    && polylines
                        .last()
                        .and_then(|last| last.last())
                        .is_some_and(|&end| indices.first() == Some(&end));
                match polylines.last_mut() {
                    Some(last) if chains => last.extend_from_slice(&indices[1..]),
                    _ => polylines.push(indices),
                }
                chain_open = true;
            }
            "o" | "g" => chain_open = false,
            _ => {}
        }
    }
    let curves = polylines
        .iter()
        .map(|indices| {
            Curve::new(
                indices
                    .iter()
                    .map(|&index| vertices[index as usize])
                    .collect(),
            )
        })
        .collect();
    Ok(finish(Format::Obj, &units, curves, None, Vec::new()))
}

/// Writes one frame as OBJ polylines (see the module docs).
pub fn write_obj(out: &mut impl Write, curves: &CurveSet) -> Result<(), WriteError> {
    crate::write::checks::finite_points(Format::Obj, curves)?;
    let mut text = String::with_capacity(curves.point_count() * 40);
    use std::fmt::Write as _;
    let _ = writeln!(
        text,
        "# helixhair-formats: {} curves, {} points, metres, Y up",
        curves.curves.len(),
        curves.point_count()
    );
    for point in curves.curves.iter().flat_map(|c| c.points_m.iter()) {
        let _ = writeln!(text, "v {} {} {}", point.x, point.y, point.z);
    }
    let mut next = 1usize;
    for curve in &curves.curves {
        if curve.points_m.is_empty() {
            continue;
        }
        text.push('l');
        for index in next..next + curve.points_m.len() {
            let _ = write!(text, " {index}");
        }
        text.push('\n');
        next += curve.points_m.len();
    }
    out.write_all(text.as_bytes())
        .map_err(WriteError::io(Format::Obj))
}

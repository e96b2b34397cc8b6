//! Malformed OBJ files give located errors; OBJ-specific reading rules
//! (negative indices, texture indices, chaining Blender's edges).

use crate::common;

use common::expect_error;
use helixhair_formats::{Format, Location, ReadErrorKind, ReadOptions, RepairReason, read};

fn read_obj(text: &str) -> Result<helixhair_formats::Imported, helixhair_formats::ReadError> {
    read(text.as_bytes(), Format::Obj, &ReadOptions::default())
}

#[test]
fn bad_indices_name_their_line() {
    let text = "v 0 0 0\nv 0 1 0\nl 1 0\n";
    expect_error(read_obj(text), ReadErrorKind::BadValue, Location::Line(3));
    let text = "v 0 0 0\nv 0 1 0\n# forward references are refused\nl 1 3\nv 0 2 0\n";
    expect_error(read_obj(text), ReadErrorKind::BadValue, Location::Line(4));
    let text = "v 0 0 0\nl -2 -1\n";
    expect_error(read_obj(text), ReadErrorKind::BadValue, Location::Line(2));
    let text = "v 0 0 0\nl 1 99999999999999999999\n";
    expect_error(read_obj(text), ReadErrorKind::Syntax, Location::Line(2));
}

#[test]
fn bad_numbers_and_truncated_lines_name_their_line() {
    expect_error(
        read_obj("v 0 0 0\nv 1 x 2\n"),
        ReadErrorKind::Syntax,
        Location::Line(2),
    );
    // A file cut in the middle of a vertex line.
    expect_error(
        read_obj("v 0 0 0\nv 1 2"),
        ReadErrorKind::Syntax,
        Location::Line(2),
    );
    let bytes = b"v 0 0 0\nv \xff 0 0\n";
    let result = read(bytes, Format::Obj, &ReadOptions::default());
    expect_error(result, ReadErrorKind::Syntax, Location::Line(2));
}

#[test]
fn nan_points_skip_their_strand_only() {
    let text = "v 0 0 0\nv 0 1 0\nv nan 2 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\nl 4 5\n";
    let groom = read_obj(text).expect("reads");
    assert_eq!(groom.summary.strands_read, 2);
    assert_eq!(groom.summary.count(RepairReason::NonFinitePoint), 1);
    assert_eq!(groom.curves.curves.len(), 1);
}

#[test]
fn negative_and_texture_indices_resolve() {
    let text = "v 0 0 0\nv 0 1 0\nv 0 2 0\nvt 0 0\nl -3/1 -2/1 -1/1\n";
    let groom = read_obj(text).expect("reads");
    assert_eq!(groom.curves.curves[0].points_m.len(), 3);
    assert_eq!(
        groom.curves.curves[0].points_m[2],
        glam::Vec3::new(0.0, 2.0, 0.0)
    );
}

#[test]
fn blender_edges_chain_into_strands() {
    // Two strands written as one edge per line, as Blender does for curves
    // converted to meshes; a face of a head in the same file is ignored.
    let text = "o hair\nv 0 0 0\nv 0 1 0\nv 0 2 0\nv 1 0 0\nv 1 1 0\n\
                l 1 2\nl 2 3\nl 4 5\nf 1 2 4\n";
    let groom = read_obj(text).expect("reads");
    let lengths: Vec<usize> = groom
        .curves
        .curves
        .iter()
        .map(|c| c.points_m.len())
        .collect();
    assert_eq!(lengths, [3, 2]);
    // An `o` line between two edges breaks the chain.
    let text = "v 0 0 0\nv 0 1 0\nv 0 2 0\nl 1 2\no other\nl 2 3\n";
    assert_eq!(read_obj(text).expect("reads").curves.curves.len(), 2);
}

#[test]
fn units_and_up_axis_from_the_options() {
    let text = "v 0 0 0\nv 0 0 100\nl 1 2\n";
    let options = ReadOptions {
        metres_per_unit: Some(0.01),
        up_axis: Some(helixhair_formats::UpAxis::Z),
    };
    let groom = read(text.as_bytes(), Format::Obj, &options).expect("reads");
    assert_eq!(
        groom.curves.curves[0].points_m[1],
        glam::Vec3::new(0.0, 1.0, 0.0)
    );
    let bad = ReadOptions {
        metres_per_unit: Some(0.0),
        up_axis: None,
    };
    expect_error(
        read(text.as_bytes(), Format::Obj, &bad),
        ReadErrorKind::BadValue,
        Location::File,
    );
}

//! Write then read back, per format: the points come back equal to the bit
//! (the writers print shortest round-trip `f32` decimals, the binary formats
//! store `f32`), and so do the widths and colours each format carries.

use crate::common;

use common::{assert_points_equal, groom};
use helixhair_formats::{
    Animation, Format, Frame, ReadOptions, StrandValue, TriangleMesh, read, write, write_usda,
};

fn round_trip(
    format: Format,
    written: &helixhair_formats::CurveSet,
) -> helixhair_formats::Imported {
    let mut bytes = Vec::new();
    write(&mut bytes, format, written).expect("write");
    let read = read(&bytes, format, &ReadOptions::default()).expect("read back");
    assert_eq!(
        read.curves.curves.len(),
        written.curves.len(),
        "{format}: strands"
    );
    assert_eq!(
        read.summary.strands_kept,
        written.curves.len(),
        "{format}: nothing repaired"
    );
    for (index, (a, b)) in read.curves.curves.iter().zip(&written.curves).enumerate() {
        assert_points_equal(&a.points_m, &b.points_m, &format!("{format} curve {index}"));
    }
    read
}

#[test]
fn tfx_round_trip_keeps_points_and_colours() {
    let written = groom(1, 50, 16, false, true);
    let read = round_trip(Format::Tfx, &written);
    for (a, b) in read.curves.curves.iter().zip(&written.curves) {
        let expected = b.colour.as_ref().and_then(|c| c.at(0));
        for index in 0..16 {
            assert_eq!(a.colour.as_ref().and_then(|c| c.at(index)), expected);
        }
    }
}

#[test]
fn hair_round_trip_keeps_points_widths_and_colours() {
    let written = groom(2, 40, 23, true, true);
    let read = round_trip(Format::Hair, &written);
    for (a, b) in read.curves.curves.iter().zip(&written.curves) {
        assert_eq!(a.width_m, b.width_m);
        for index in 0..a.points_m.len() {
            assert_eq!(
                a.colour.as_ref().and_then(|c| c.at(index)),
                b.colour.as_ref().and_then(|c| c.at(index))
            );
        }
    }
}

#[test]
fn hair_round_trip_of_strands_of_different_lengths() {
    let mut written = groom(3, 10, 30, false, false);
    for (index, curve) in written.curves.iter_mut().enumerate() {
        curve.points_m.truncate(2 + index * 3);
    }
    round_trip(Format::Hair, &written);
}

#[test]
fn usda_round_trip_keeps_points_widths_and_colours() {
    let written = groom(4, 30, 12, true, true);
    let read = round_trip(Format::Usda, &written);
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    for (a, b) in read.curves.curves.iter().zip(&written.curves) {
        assert_eq!(a.width_m, b.width_m);
        assert_eq!(a.colour, b.colour);
    }
}

#[test]
fn usda_round_trip_of_per_strand_widths() {
    let mut written = groom(5, 8, 5, false, false);
    for (index, curve) in written.curves.iter_mut().enumerate() {
        curve.width_m = Some(StrandValue::PerStrand(1e-4 + index as f32 * 1e-6));
    }
    let read = round_trip(Format::Usda, &written);
    for (a, b) in read.curves.curves.iter().zip(&written.curves) {
        assert_eq!(a.width_m, b.width_m);
    }
}

#[test]
fn usda_round_trip_of_an_animation_with_a_head() {
    let written = groom(6, 20, 8, true, false);
    let frames: Vec<Frame> = (0..5)
        .map(|k| {
            let mut frame = Frame::from_curves(k as f64, &written);
            for point in &mut frame.points_m {
                point.x += 0.001 * k as f32;
            }
            frame
        })
        .collect();
    let animation = Animation {
        time_codes_per_second: 60.0,
        frames,
    };
    let head = TriangleMesh {
        vertices_m: vec![glam::Vec3::ZERO, glam::Vec3::X, glam::Vec3::Y],
        triangles: vec![[0, 1, 2]],
    };
    let mut bytes = Vec::new();
    write_usda(&mut bytes, &written, Some(&animation), Some(&head)).expect("write");
    let read = read(&bytes, Format::Usda, &ReadOptions::default()).expect("read back");
    let read_animation = read.animation.expect("frames");
    assert_eq!(read_animation.time_codes_per_second, 60.0);
    assert_eq!(read_animation.frames.len(), 5);
    for (a, b) in read_animation.frames.iter().zip(&animation.frames) {
        assert_eq!(a.time_code, b.time_code);
        assert_points_equal(&a.points_m, &b.points_m, "frame");
    }
    // The curves are the first frame.
    assert_points_equal(
        &read.curves.curves[0].points_m,
        &animation.frames[0].points_m[..8],
        "first frame",
    );
}

#[test]
fn obj_round_trip_keeps_points() {
    let written = groom(7, 25, 9, false, false);
    round_trip(Format::Obj, &written);
}

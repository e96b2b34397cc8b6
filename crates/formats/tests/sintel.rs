//! The real Sintel groom (TressFX 4.0, 11,400 strands × 16 points) reads
//! whole, inside the bounds its README gives. Skips with a message where
//! `../shared/data/sintel` is absent.

use crate::common;

use std::time::Instant;

use helixhair_formats::{Format, ReadOptions, read, write, write_tfx};

/// The README's bounds are given to a millimetre.
const BOUNDS_TOLERANCE_M: f32 = 0.001;

#[test]
fn sintel_tfx_reads_whole_inside_its_bounds() {
    let Some(bytes) = common::sintel_tfx() else {
        return;
    };
    let start = Instant::now();
    let groom = read(&bytes, Format::Tfx, &ReadOptions::default()).expect("the Sintel groom reads");
    let read_secs = start.elapsed().as_secs_f64();
    println!(
        "read {} bytes in {:.1} ms: {}",
        bytes.len(),
        read_secs * 1e3,
        groom.summary
    );
    assert_eq!(groom.summary.strands_read, 11_400);
    assert_eq!(groom.curves.curves.len(), 11_400, "{}", groom.summary);
    assert!(
        groom
            .curves
            .curves
            .iter()
            .all(|curve| curve.points_m.len() == 16)
    );
    let (min, max) = groom.curves.bounds_m().expect("points");
    let expected_min = glam::Vec3::new(-0.116, 1.396, -0.130);
    let expected_max = glam::Vec3::new(0.103, 1.675, 0.133);
    assert!(
        min.abs_diff_eq(expected_min, BOUNDS_TOLERANCE_M),
        "min {min}"
    );
    assert!(
        max.abs_diff_eq(expected_max, BOUNDS_TOLERANCE_M),
        "max {max}"
    );
    let mut lengths_m: Vec<f64> = groom.curves.curves.iter().map(|c| c.length_m()).collect();
    lengths_m.sort_by(f64::total_cmp);
    let median = lengths_m[lengths_m.len() / 2];
    println!(
        "lengths {:.4}..{:.4} m, median {median:.4} m",
        lengths_m[0],
        lengths_m[lengths_m.len() - 1]
    );
    assert!((lengths_m[0] - 0.025).abs() < 0.001);
    assert!((lengths_m[lengths_m.len() - 1] - 0.248).abs() < 0.001);
    assert!((median - 0.102).abs() < 0.001);
}

#[test]
fn sintel_written_back_as_tfx_has_the_same_positions_and_every_format_round_trips() {
    let Some(bytes) = common::sintel_tfx() else {
        return;
    };
    let groom = read(&bytes, Format::Tfx, &ReadOptions::default()).expect("reads");
    let mut tfx = Vec::new();
    write_tfx(&mut tfx, &groom.curves).expect("writes");
    // Same positions, w included (0 at roots, 1 elsewhere), byte for byte.
    let positions = 160..160 + 11_400 * 16 * 16;
    assert_eq!(tfx[positions.clone()], bytes[positions]);
    for format in Format::ALL {
        let start = Instant::now();
        let mut written = Vec::new();
        write(&mut written, format, &groom.curves).expect("writes");
        let write_ms = start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        let again = read(&written, format, &ReadOptions::default()).expect("reads back");
        let read_ms = start.elapsed().as_secs_f64() * 1e3;
        println!(
            "{format}: {} bytes, written in {write_ms:.1} ms, read in {read_ms:.1} ms",
            written.len()
        );
        assert_eq!(again.curves.curves.len(), 11_400);
        for (a, b) in again.curves.curves.iter().zip(&groom.curves.curves) {
            common::assert_points_equal(&a.points_m, &b.points_m, &format!("sintel via {format}"));
        }
    }
}

//! Degenerate strands are repaired or skipped one by one, with a count per
//! reason, and the groom survives.

use glam::Vec3;
use helixhair_formats::{Format, ReadOptions, RepairReason, StrandValue, read};

/// A layer whose strands are, in order: good; one point; NaN; all on one
/// spot; with repeated points; out and back within a micrometre; good with
/// a negative width.
const DEGENERATE: &str = r#"#usda 1.0
(
    metersPerUnit = 1
)
def BasisCurves "hair"
{
    uniform token type = "linear"
    int[] curveVertexCounts = [3, 1, 2, 3, 5, 3, 2]
    point3f[] points = [
        (0, 0, 0), (0, 0.1, 0), (0, 0.2, 0),
        (5, 5, 5),
        (0, nan, 0), (0, 1, 0),
        (1, 1, 1), (1, 1, 1), (1, 1, 1),
        (2, 0, 0), (2, 0, 0), (2, 0.1, 0), (2, 0.1, 0), (2, 0.2, 0),
        (3, 0, 0), (3, 0.0000009, 0), (3, 0, 0),
        (4, 0, 0), (4, 0.1, 0),
    ]
    float[] widths = [
        1e-4, 1e-4, 1e-4,
        1e-4,
        1e-4, 1e-4,
        1e-4, 1e-4, 1e-4,
        1e-4, 2e-4, 3e-4, 4e-4, 5e-4,
        1e-4, 1e-4, 1e-4,
        -1, 1e-4,
    ] (
        interpolation = "vertex"
    )
}
"#;

#[test]
fn each_degenerate_strand_is_counted_under_its_reason() {
    let groom = read(DEGENERATE.as_bytes(), Format::Usda, &ReadOptions::default()).expect("reads");
    let summary = &groom.summary;
    println!("{summary}");
    assert_eq!(summary.strands_read, 7);
    assert_eq!(summary.strands_kept, 3);
    assert_eq!(summary.count(RepairReason::TooFewPoints), 1);
    assert_eq!(summary.count(RepairReason::NonFinitePoint), 1);
    assert_eq!(summary.count(RepairReason::ZeroLength), 1);
    // A skipped strand counts under its skip reason only: the out-and-back
    // strand is too_few_distinct_points, not also repeated_points.
    assert_eq!(summary.count(RepairReason::RepeatedPoints), 1);
    assert_eq!(summary.count(RepairReason::TooFewDistinctPoints), 1);
    assert_eq!(summary.count(RepairReason::InvalidWidth), 1);
    assert_eq!(summary.count(RepairReason::InvalidColour), 0);
    assert_eq!(summary.points_dropped, 2);

    let repaired = &groom.curves.curves[1];
    assert_eq!(
        repaired.points_m,
        [
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 0.1, 0.0),
            Vec3::new(2.0, 0.2, 0.0)
        ]
    );
    // The widths of the dropped points went with them.
    assert_eq!(
        repaired.width_m,
        Some(StrandValue::PerPoint(vec![1e-4, 3e-4, 5e-4]))
    );
    assert_eq!(
        groom.curves.curves[2].width_m, None,
        "the negative width was removed"
    );
}

#[test]
fn reason_names_are_stable_json_keys() {
    let names: Vec<&str> = RepairReason::ALL
        .iter()
        .map(|reason| reason.name())
        .collect();
    assert_eq!(
        names,
        [
            "too_few_points",
            "non_finite_point",
            "zero_length",
            "repeated_points",
            "too_few_distinct_points",
            "invalid_width",
            "invalid_colour",
        ]
    );
    let skipping: Vec<bool> = RepairReason::ALL.iter().map(|r| r.skips_strand()).collect();
    assert_eq!(skipping, [true, true, true, false, true, false, false]);
}

#[test]
fn repairs_apply_to_every_frame_alike() {
    // Frame 0 has a repeated point; frame 1 moves it. Both frames lose the
    // same point, so the topology stays the same.
    let text = r#"#usda 1.0
(
    metersPerUnit = 1
)
def BasisCurves "hair"
{
    uniform token type = "linear"
    int[] curveVertexCounts = [3]
    point3f[] points.timeSamples = {
        0: [(0, 0, 0), (0, 0, 0), (0, 1, 0)],
        1: [(0, 0, 0), (0, 0.5, 0), (0, 1, 0)],
    }
}
"#;
    let groom = read(text.as_bytes(), Format::Usda, &ReadOptions::default()).expect("reads");
    let animation = groom.animation.expect("frames");
    assert_eq!(animation.frames[1].points_m, [Vec3::ZERO, Vec3::Y]);
    assert_eq!(groom.curves.curves[0].points_m, [Vec3::ZERO, Vec3::Y]);
}

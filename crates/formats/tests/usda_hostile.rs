//! Malformed `.usda` layers give located errors; no nesting, count or
//! repetition in the text can exhaust the stack or memory.

use crate::common;

use common::{expect_error, valid_file};
use helixhair_formats::{Format, Location, ReadErrorKind, ReadOptions, RepairReason, read};

fn read_usda(text: &str) -> Result<helixhair_formats::Imported, helixhair_formats::ReadError> {
    read(text.as_bytes(), Format::Usda, &ReadOptions::default())
}

fn layer(body: &str) -> String {
    format!("#usda 1.0\n(\n    metersPerUnit = 1\n)\n\ndef BasisCurves \"hair\"\n{{\n{body}\n}}\n")
}

#[test]
fn wrong_magic_is_refused() {
    expect_error(
        read_usda("#sdf 1.0\n"),
        ReadErrorKind::BadMagic,
        Location::Line(1),
    );
    expect_error(
        read_usda("PXR-USDC binary"),
        ReadErrorKind::BadMagic,
        Location::Line(1),
    );
    expect_error(
        read_usda("#usda 2.0\n"),
        ReadErrorKind::UnsupportedVersion,
        Location::Line(1),
    );
}

#[test]
fn truncated_layers_are_syntax_errors_at_their_end() {
    let bytes = valid_file(Format::Usda);
    let text = std::str::from_utf8(&bytes).expect("utf-8");
    let cut = &text[..text.len() / 2];
    let last_line = cut.lines().count();
    let error = expect_error(
        read_usda(cut),
        ReadErrorKind::Syntax,
        Location::Line(last_line),
    );
    assert!(
        error.message.contains("found the end of the file"),
        "{error}"
    );
    expect_error(
        read_usda("#usda 1.0\ndef Xform \"a\" {\n  string s = \"open\n}\n"),
        ReadErrorKind::Syntax,
        Location::Line(3),
    );
}

#[test]
fn counts_that_disagree_with_the_points_are_refused() {
    let text = layer(
        "    int[] curveVertexCounts = [2, 3]\n    point3f[] points = [(0, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0)]",
    );
    let error = expect_error(
        read_usda(&text),
        ReadErrorKind::CountMismatch,
        Location::Line(9),
    );
    assert!(
        error
            .message
            .contains("4 points but curveVertexCounts add up to 5"),
        "{error}"
    );
    let text = layer("    int[] curveVertexCounts = [-2]\n    point3f[] points = []");
    expect_error(read_usda(&text), ReadErrorKind::BadValue, Location::Line(8));
    let text = layer("    point3f[] points = [(0, 0, 0), (0, 1, 0)]");
    expect_error(
        read_usda(&text),
        ReadErrorKind::CountMismatch,
        Location::Line(6),
    );
}

#[test]
fn absurd_counts_allocate_nothing() {
    let text = layer(
        "    int[] curveVertexCounts = [4000000000, 4000000000]\n    point3f[] points = [(0, 0, 0)]",
    );
    expect_error(
        read_usda(&text),
        ReadErrorKind::CountMismatch,
        Location::Line(9),
    );
    let text = layer("    int[] curveVertexCounts = [1e30]\n    point3f[] points = [(0, 0, 0)]");
    expect_error(read_usda(&text), ReadErrorKind::BadValue, Location::Line(8));
}

#[test]
fn deep_nesting_is_refused_not_recursed() {
    let deep = format!(
        "#usda 1.0\n(\n    customData = {}\n)\n",
        "(".repeat(100_000)
    );
    expect_error(read_usda(&deep), ReadErrorKind::TooLarge, Location::Line(3));
    let mut prims = String::from("#usda 1.0\n");
    for _ in 0..10_000 {
        prims.push_str("def \"a\" {\n");
    }
    expect_error(
        read_usda(&prims),
        ReadErrorKind::TooLarge,
        Location::Line(66),
    );
}

#[test]
fn repeating_static_curves_over_many_frames_is_bounded() {
    // One animated prim with many samples of one point and a static prim of
    // many points would make frames × points far beyond the file's size.
    let mut text = String::from(
        "#usda 1.0\ndef BasisCurves \"moving\" {\n    int[] curveVertexCounts = [2]\n    point3f[] points.timeSamples = {\n",
    );
    for time in 0..5_000 {
        text.push_str(&format!("        {time}: [(0, 0, 0), (0, 1, 0)],\n"));
    }
    text.push_str("    }\n}\ndef BasisCurves \"still\" {\n    int[] curveVertexCounts = [5000]\n    point3f[] points = [");
    for index in 0..5_000 {
        text.push_str(&format!("({index}, 0, 0), "));
    }
    text.push_str("]\n}\n");
    expect_error(read_usda(&text), ReadErrorKind::TooLarge, Location::Line(2));
}

#[test]
fn nan_points_skip_their_strand_only_and_bad_metadata_is_refused() {
    let text = layer(
        "    int[] curveVertexCounts = [2, 2]\n    point3f[] points = [(0, nan, 0), (0, 1, 0), (1, 0, 0), (1, inf, 0)]",
    );
    let groom = read_usda(&text).expect("reads");
    assert_eq!(groom.summary.count(RepairReason::NonFinitePoint), 2);
    assert_eq!(groom.summary.strands_kept, 0);
    let text = "#usda 1.0\n(\n    metersPerUnit = 0\n)\n";
    expect_error(read_usda(text), ReadErrorKind::BadValue, Location::Line(3));
    let text = "#usda 1.0\n(\n    upAxis = \"X\"\n)\n";
    expect_error(read_usda(text), ReadErrorKind::BadValue, Location::Line(3));
}

/// Many prims under a very long name each deserving a warning: warnings
/// stop at 100 (and one line counting the rest) and quote names shortened,
/// instead of copying the long name once per prim.
#[test]
fn warnings_and_quoted_names_are_bounded() {
    let long_name = "n".repeat(100_000);
    // The unit authored, so every warning is about the prims.
    let mut text =
        format!("#usda 1.0\n(\n    metersPerUnit = 1\n)\ndef Xform \"{long_name}\" {{\n");
    for index in 0..5_000 {
        text.push_str(&format!(
            "  def BasisCurves \"c{index}\" {{ int[] curveVertexCounts = [2]\n    point3f[] points = [(0,0,0), (0,1,0)] }}\n"
        ));
    }
    text.push_str("}\n");
    let groom = read(text.as_bytes(), Format::Usda, &ReadOptions::default()).expect("reads");
    assert_eq!(groom.curves.curves.len(), 5_000);
    assert_eq!(
        groom.warnings.len(),
        101,
        "100 kept and one counting the rest"
    );
    assert!(
        groom.warnings[100].contains("4900 more"),
        "{}",
        groom.warnings[100]
    );
    assert!(
        groom.warnings.iter().all(|warning| warning.len() < 400),
        "{}",
        groom.warnings[0]
    );
}

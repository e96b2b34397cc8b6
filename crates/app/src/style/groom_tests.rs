//! Tests of the groom sections of a style (`scalp`, `render`): they parse
//! as bare structs with defaults, survive a save, and bad values are
//! reported at their file, line and field like every other style error.

use std::path::Path;

use glam::DVec3;

use crate::style::Style;
use crate::style::error::StyleError;
use crate::style::groom::{DEFAULT_COMB, DEFAULT_LIFT_DEG, StrandInterpolation};

const GROOMED: &str = r#"(
    version: 1,
    name: "groomed",
    groups: [
        (
            name: "scalp",
            scalp: (count: 40, comb: (0.0, 0.0, -1.0), region: (towards: (0.0, 1.0, 0.0), to_deg: 60.0)),
            render: (count: 500, method: Nearest),
        ),
        (
            name: "listed",
            roots: [(position_m: (0.0, 0.1, 0.0), direction: (0.0, 1.0, 0.0))],
            scalp: (count: 3),
        ),
    ],
)
"#;

fn load(src: &str) -> Result<Style, StyleError> {
    Style::from_ron(src, Path::new("groomed.ron"))
}

/// The 1-based line of the first line of `src` containing `needle`.
fn line_of(src: &str, needle: &str) -> usize {
    src.lines()
        .position(|l| l.contains(needle))
        .expect("needle present")
        + 1
}

#[test]
fn groom_sections_are_bare_structs_with_defaults() {
    let style = load(GROOMED).unwrap_or_else(|e| panic!("{e}"));
    let scalp = style.groups[0].scalp.as_ref().expect("scalp");
    assert_eq!(
        (scalp.count, scalp.lift_deg, scalp.seed),
        (40, DEFAULT_LIFT_DEG, 1)
    );
    let region = scalp.region.as_ref().expect("region");
    assert_eq!((region.from_deg, region.to_deg), (0.0, 60.0));
    assert!(
        region.contains(DVec3::new(0.0, 1.0, 0.5)) && !region.contains(DVec3::new(0.0, -1.0, 0.1))
    );
    let render = style.groups[0].render.as_ref().expect("render");
    assert_eq!(
        (render.count, render.method),
        (500, StrandInterpolation::Nearest)
    );
    assert!(style.groups[0].roots.is_empty());
    let second = style.groups[1].scalp.as_ref().expect("scalp");
    assert_eq!((second.comb, second.region.is_none()), (DEFAULT_COMB, true));
    assert!(style.groups[1].render.is_none());
}

#[test]
fn groomed_styles_round_trip_through_save() {
    let style = load(GROOMED).unwrap_or_else(|e| panic!("{e}"));
    let text = style.to_ron().expect("serialises");
    assert!(
        text.contains("scalp: (") && !text.contains("Some("),
        "{text}"
    );
    assert_eq!(load(&text).unwrap_or_else(|e| panic!("{e}\n{text}")), style);
}

#[test]
fn bad_groom_values_name_their_line_and_field() {
    let cases = [
        (
            "count: 40,",
            "count: 0,",
            "groups[0].scalp.count",
            "must lie in 1..=5000",
        ),
        (
            "to_deg: 60.0",
            "from_deg: 90.0, to_deg: 60.0",
            "groups[0].scalp.region.to_deg",
            "must lie in [90, 180]",
        ),
        (
            "comb: (0.0, 0.0, -1.0)",
            "comb: (0.0, 0.0, 0.0)",
            "groups[0].scalp.comb",
            "must not be zero",
        ),
        (
            "method: Nearest",
            "method: Nearest, colour_srgb: (0.5, 2.0, 0.1)",
            "groups[0].render.colour_srgb[1]",
            "must lie in [0, 1]",
        ),
        (
            "method: Nearest",
            "method: Nearest, length_variation: -0.1",
            "groups[0].render.length_variation",
            "must lie in [0, 0.9]",
        ),
    ];
    for (from, to, field, message) in cases {
        let src = GROOMED.replacen(from, to, 1);
        let error = load(&src).expect_err(to).to_string();
        let line = line_of(&src, to);
        assert!(
            error.starts_with(&format!("groomed.ron:{line}:")),
            "{error}"
        );
        assert!(
            error.contains(&format!("field `{field}`: {message}")),
            "{error}"
        );
    }
}

#[test]
fn unknown_groom_fields_and_missing_roots_are_named() {
    let src = GROOMED.replacen("count: 40,", "count: 40, lift: 3.0,", 1);
    let error = load(&src).expect_err("unknown field").to_string();
    assert!(error.contains("field `groups[0].scalp.lift`"), "{error}");
    assert!(
        error.starts_with(&format!("groomed.ron:{}:", line_of(&src, "lift:"))),
        "{error}"
    );

    let src = GROOMED
        .replacen("            scalp: (count: 3),\n", "", 1)
        .replacen(
            "roots: [(position_m: (0.0, 0.1, 0.0), direction: (0.0, 1.0, 0.0))],",
            "roots: [],",
            1,
        );
    let error = load(&src).expect_err("no roots").to_string();
    assert!(
        error.contains("field `groups[1].roots`: must list at least one root"),
        "{error}"
    );
    assert!(error.contains("or give a `scalp` placement"), "{error}");
}

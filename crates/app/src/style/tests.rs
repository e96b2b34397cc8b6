//! Tests of loading and saving styles: every class of error, with the line,
//! column and field it must report, and the save/load round trip.
//!
//! Broken styles are made by editing one line of [`VALID`]; the edited line
//! carries a `// <-` marker, so each test states where the error must be
//! reported without counting lines by hand.

use std::path::{Path, PathBuf};

use glam::DVec3;
use helixhair_physics::{ElementLayout, Method, NaturalShape};

use crate::style::error::{StyleError, StyleErrorKind};
use crate::style::field_path::FieldPath;
use crate::style::source_map::TextPosition;
use crate::style::{DEFAULT_REFERENCE, Root, Style};

const FILE: &str = "test.ron";

const VALID: &str = r#"// A small style exercising most fields.
(
    version: 1,
    name: "test",
    sim: (method: Dense, dt_secs: 0.01, gravity_m_per_s2: (0.0, -9.81, 0.0)),
    groups: [
        (
            name: "crown",
            params: (
                length_m: 0.25,
                elements: 4,
                radius_m: 35e-6,
                natural_shape: Helix(radius_m: 0.01, step_m: 0.02),
            ),
            roots: [
                (position_m: (0.0, 0.1, 0.0), direction: (0.0, 1.0, 0.0)),
                (position_m: (0.1, 0.0, 0.0), direction: (1.0, 0.0, 0.0), reference: (0.0, 1.0, 0.0)),
            ],
        ),
        (
            name: "nape",
            roots: [(position_m: (0.0, 0.0, -0.1), direction: (0.0, -1.0, -1.0))],
        ),
    ],
)
"#;

/// `VALID` with the first `from` replaced by `to`. A `// <-` marker in `to`
/// is moved to the end of its line, so it comments out nothing.
fn edit(from: &str, to: &str) -> String {
    assert!(VALID.contains(from), "VALID has no {from:?}");
    let mut out = String::new();
    for line in VALID.replacen(from, to, 1).lines() {
        match line.split_once(" // <-") {
            Some((before, after)) => out.push_str(&format!("{before}{after} // <-")),
            None => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

fn load(src: &str) -> Result<Style, StyleError> {
    Style::from_ron(src, Path::new(FILE))
}

fn load_err(src: &str) -> StyleError {
    match load(src) {
        Ok(style) => panic!("expected an error, loaded {style:?}"),
        Err(error) => error,
    }
}

/// Line (from 1) of the `// <-` marker and the column of `word` on it.
fn marker(src: &str, word: &str) -> TextPosition {
    let (index, text) = src
        .lines()
        .enumerate()
        .find(|(_, line)| line.contains("// <-"))
        .expect("the source has a `// <-` marker");
    let col = text
        .find(word)
        .unwrap_or_else(|| panic!("{word:?} not on the marked line {text:?}"));
    TextPosition {
        line: index + 1,
        col: text[..col].chars().count() + 1,
    }
}

/// Checks kind, field and position of the error loading `src`; the
/// position is that of `word` on the marked line.
#[track_caller]
fn assert_error(src: &str, kind: StyleErrorKind, field: &str, word: &str) -> StyleError {
    let error = load_err(src);
    assert_eq!(error.kind(), Some(kind), "{error}");
    assert_eq!(
        error.field().map(ToString::to_string).as_deref(),
        Some(field),
        "{error}"
    );
    assert_eq!(error.position(), Some(marker(src, word)), "{error}");
    let text = error.to_string();
    let at = marker(src, word);
    assert!(
        text.starts_with(&format!("{FILE}:{}:{}: ", at.line, at.col)),
        "{text}"
    );
    if !field.is_empty() {
        assert!(text.contains(&format!("field `{field}`: ")), "{text}");
    }
    error
}

#[test]
fn valid_style_loads_with_defaults_filled_in() {
    let style = load(VALID).expect("VALID loads");
    assert_eq!(style.name, "test");
    assert_eq!(style.sim.method, Method::Dense);
    assert_eq!(style.sim.dt_secs, 0.01);
    assert_eq!(style.sim.substeps, 1, "default");
    assert_eq!(style.groups.len(), 2);
    let crown = &style.groups[0];
    assert_eq!(crown.params.elements, 4);
    assert_eq!(
        crown.params.natural_shape,
        NaturalShape::Helix {
            radius_m: 0.01,
            step_m: 0.02
        }
    );
    assert_eq!(crown.params.ellipticity, 1.0, "default");
    assert_eq!(crown.roots[0].reference, DEFAULT_REFERENCE, "default");
    assert_eq!(crown.roots[1].reference, DVec3::Y);
    let nape = &style.groups[1];
    assert_eq!(
        nape.params,
        Default::default(),
        "params may be left out entirely"
    );
    assert_eq!(style.strand_count(), 3);
}

#[test]
fn root_pose_grows_along_the_normalised_direction() {
    let root = Root {
        position_m: DVec3::new(0.0, 0.0, -0.1),
        direction: DVec3::new(0.0, -2.0, -2.0),
        reference: DVec3::Y,
    };
    let pose = root.pose();
    assert_eq!(pose.position_m, root.position_m);
    let n0 = pose.head_from_root.col(0);
    assert!((n0 - DVec3::new(0.0, -1.0, -1.0).normalize()).length() < 1e-15);
    // n₁ is the part of the reference orthogonal to the direction.
    let n1 = pose.head_from_root.col(1);
    assert!(n1.dot(n0).abs() < 1e-15 && n1.dot(DVec3::Y) > 0.0);
}

#[test]
fn unknown_field_names_the_field_and_its_line() {
    let src = edit("radius_m: 35e-6,", "radius_mm: 35e-6, // <-");
    let error = assert_error(
        &src,
        StyleErrorKind::UnknownField,
        "groups[0].params.radius_mm",
        "radius_mm",
    );
    assert!(
        error.to_string().contains("expected one of"),
        "ron lists the known fields: {error}"
    );

    let src = edit("name: \"test\",", "name: \"test\", colour: \"red\", // <-");
    assert_error(&src, StyleErrorKind::UnknownField, "colour", "colour");

    let src = edit(
        "reference: (0.0, 1.0, 0.0))",
        "refrence: (0.0, 1.0, 0.0)), // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::UnknownField,
        "groups[0].roots[1].refrence",
        "refrence",
    );
}

#[test]
fn wrong_type_names_the_field_and_its_line() {
    let src = edit("elements: 4,", "elements: \"four\", // <-");
    assert_error(
        &src,
        StyleErrorKind::WrongType,
        "groups[0].params.elements",
        "\"four\"",
    );

    let src = edit("elements: 4,", "elements: -4, // <-");
    let error = load_err(&src);
    assert_eq!(error.kind(), Some(StyleErrorKind::WrongType), "{error}");
    assert_eq!(
        error.field(),
        Some(&FieldPath::parse("groups[0].params.elements"))
    );

    let src = edit("length_m: 0.25,", "length_m: (0.25), // <-");
    let error = load_err(&src);
    assert_eq!(
        error.field(),
        Some(&FieldPath::parse("groups[0].params.length_m")),
        "{error}"
    );

    // Two coordinates for three: ron reports it on the closing bracket.
    let src = edit(
        "(position_m: (0.0, 0.1, 0.0), direction",
        "(position_m: (0.0, 0.1), direction // <-",
    );
    let error = load_err(&src);
    assert_eq!(error.kind(), Some(StyleErrorKind::WrongType), "{error}");
    assert_eq!(
        error.field(),
        Some(&FieldPath::parse("groups[0].roots[0].position_m")),
        "{error}"
    );
    assert_eq!(
        error.position().map(|p| p.line),
        Some(marker(&src, "(").line)
    );
}

#[test]
fn unknown_variant_names_the_field() {
    let src = edit("natural_shape: Helix(", "natural_shape: Helics( // <-");
    let error = assert_error(
        &src,
        StyleErrorKind::UnknownVariant,
        "groups[0].params.natural_shape",
        "Helics",
    );
    assert!(
        error.to_string().contains("`PerElement`"),
        "ron lists the variants: {error}"
    );

    let src = edit("method: Dense,", "method: Fast, // <-");
    assert_error(&src, StyleErrorKind::UnknownVariant, "sim.method", "Fast");
}

#[test]
fn missing_field_is_reported_at_the_struct_that_lacks_it() {
    let src = edit(
        "        (\n            name: \"crown\",\n",
        "        ( // <-\n",
    );
    assert_error(&src, StyleErrorKind::MissingField, "groups[0].name", "(");

    let src = edit(
        "natural_shape: Helix(radius_m: 0.01, step_m: 0.02)",
        "natural_shape: Helix(radius_m: 0.01), // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::MissingField,
        "groups[0].params.natural_shape.step_m",
        "natural_shape",
    );

    let src = edit("    version: 1,\n", "");
    let error = load_err(&src);
    assert_eq!(error.kind(), Some(StyleErrorKind::MissingField), "{error}");
    assert_eq!(error.field(), Some(&FieldPath::parse("version")));
    assert_eq!(
        error.position(),
        Some(TextPosition { line: 2, col: 1 }),
        "the top-level struct"
    );
}

#[test]
fn a_field_given_twice_is_reported_at_the_second() {
    let src = edit("elements: 4,", "elements: 4, elements: 5, // <-");
    let error = load_err(&src);
    assert_eq!(
        error.kind(),
        Some(StyleErrorKind::DuplicateField),
        "{error}"
    );
    assert_eq!(
        error.field(),
        Some(&FieldPath::parse("groups[0].params.elements")),
        "{error}"
    );
    assert_eq!(
        error.position().map(|p| p.line),
        Some(marker(&src, "elements").line),
        "{error}"
    );
}

#[test]
fn syntax_errors_name_the_line_and_the_enclosing_field() {
    // A missing comma is noticed at the next token, on the next line.
    let src = edit("length_m: 0.25,", "length_m: 0.25 // <-");
    let error = load_err(&src);
    assert_eq!(error.kind(), Some(StyleErrorKind::Syntax), "{error}");
    assert_eq!(
        error.position().map(|p| p.line),
        Some(marker(&src, "length_m").line + 1),
        "{error}"
    );
    assert_eq!(
        error.field(),
        Some(&FieldPath::parse("groups[0].params")),
        "{error}"
    );
    assert!(
        error
            .to_string()
            .contains(": in `groups[0].params`: Expected comma"),
        "ron's words, and where: {error}"
    );

    // An unclosed bracket runs to the end of the file.
    let src = VALID.trim_end().trim_end_matches(')');
    let error = load_err(src);
    assert_eq!(error.kind(), Some(StyleErrorKind::Syntax), "{error}");
    assert_eq!(
        error.position().map(|p| p.line),
        Some(src.lines().count()),
        "{error}"
    );

    let error = load_err("");
    assert_eq!(
        error.position(),
        Some(TextPosition { line: 1, col: 1 }),
        "{error}"
    );
}

#[test]
fn nan_is_reported_after_parsing_at_its_field() {
    let src = edit("radius_m: 35e-6,", "radius_m: NaN, // <-");
    let error = assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[0].params.radius_m",
        "radius_m",
    );
    assert_eq!(
        error.to_string(),
        format!(
            "{FILE}:{}:17: field `groups[0].params.radius_m`: must be a finite number; found NaN",
            marker(&src, "radius_m").line
        )
    );
}

#[test]
fn the_engine_field_defaults_to_reference_and_reads_batch() {
    use helixhair_physics::engine::EngineKind;
    assert_eq!(load(VALID).expect("loads").engine, EngineKind::Reference);
    let src = edit(
        "    sim: (method: Dense,",
        "    engine: Batch,\n    sim: (method: Exact,",
    );
    let style = load(&src).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(style.engine, EngineKind::Batch);
    let saved = style.to_ron().expect("serialises");
    assert!(saved.contains("engine: Batch"), "{saved}");
    assert_eq!(load(&saved).expect("reloads"), style);
}

#[test]
fn the_batch_engine_with_another_solver_is_reported_at_the_engine_field() {
    // VALID's solver is Dense, which the batch engine does not run.
    let src = edit(
        "    sim: (method: Dense,",
        "    engine: Batch, // <-\n    sim: (method: Dense,",
    );
    let error = assert_error(&src, StyleErrorKind::InvalidValue, "engine", "engine");
    assert!(
        error.to_string().ends_with(
            "field `engine`: the batch engine runs `sim.method` `Exact` or `BlockDiagonal` \
             only, not `Dense`; pick one of those, or `engine: Reference` for every solver"
        ),
        "{error}"
    );
    let src = edit(
        "    sim: (method: Dense,",
        "    engine: Batch, // <-\n    accuracy_target: Some(0.02),\n    sim: (method: Exact,",
    );
    let error = assert_error(&src, StyleErrorKind::InvalidValue, "engine", "engine");
    assert!(error.to_string().contains("accuracy_target"), "{error}");
    // An unknown engine is a parse error at its value, naming the variants.
    let src = edit(
        "    sim: (method: Dense,",
        "    engine: Fast, // <-\n    sim: (method: Dense,",
    );
    let error = assert_error(&src, StyleErrorKind::UnknownVariant, "engine", "Fast");
    assert!(error.to_string().contains("`Reference`"), "{error}");
}

#[test]
fn out_of_range_values_are_reported_at_their_field() {
    let src = edit("length_m: 0.25,", "length_m: 3.0, // <-");
    let error = assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[0].params.length_m",
        "length_m",
    );
    assert!(
        error.to_string().ends_with("must lie in (0, 2]; found 3"),
        "{error}"
    );

    // A nested field of the same name as an outer one: the inner is found.
    let src = edit("Helix(radius_m: 0.01,", "Helix(radius_m: 0.0, // <-");
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[0].params.natural_shape.radius_m",
        "radius_m: 0.0",
    );

    let src = edit("dt_secs: 0.01,", "dt_secs: 0.5, // <-");
    assert_error(&src, StyleErrorKind::InvalidValue, "sim.dt_secs", "dt_secs");

    let src = edit(
        "method: Dense,",
        "method: Iterative(iterations: 5000), // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "sim.method.iterations",
        "iterations",
    );

    let src = edit(
        "gravity_m_per_s2: (0.0, -9.81, 0.0)",
        "gravity_m_per_s2: (0.0, -inf, 0.0) // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "sim.gravity_m_per_s2[1]",
        "-inf",
    );

    let src = edit("elements: 4,", "elements: 0, // <-");
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[0].params.elements",
        "elements",
    );
}

#[test]
fn a_shape_that_does_not_fit_the_default_element_count_is_reported_at_the_shape() {
    // `elements` is not written in the second group, so it has the default
    // 10, and a shape listing one triple does not fit: the error names the
    // shape. (Falling back to a written parent for unwritten fields is
    // tested in `source_map`.)
    let src = edit(
        "            name: \"nape\",\n",
        "            name: \"nape\",\n            params: (natural_shape: PerElement([(0.0, 1.0, 0.0)])), // <-\n",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[1].params.natural_shape",
        "natural_shape",
    );
}

#[test]
fn unsupported_version_is_refused_even_with_unknown_fields() {
    let src = edit("version: 1,", "version: 2, // <-");
    let error = assert_error(&src, StyleErrorKind::Version, "version", "version");
    assert!(
        error.to_string().contains("this build reads version 1"),
        "{error}"
    );
    // A newer format may add fields; the version is the error to report.
    let src = edit("version: 1,", "version: 3, hair_colour: \"red\", // <-");
    assert_error(&src, StyleErrorKind::Version, "version", "version");
}

#[test]
fn empty_lists_are_refused() {
    let src = edit("    groups: [\n", "    groups: [], // <-\n    unused: [\n");
    // (the rest of the list now sits in an unknown field, reported first)
    assert_eq!(load_err(&src).kind(), Some(StyleErrorKind::UnknownField));
    let src = "(\n    version: 1,\n    name: \"empty\",\n    groups: [], // <-\n)\n";
    assert_error(src, StyleErrorKind::InvalidValue, "groups", "groups");

    let src = edit(
        "roots: [(position_m: (0.0, 0.0, -0.1), direction: (0.0, -1.0, -1.0))],",
        "roots: [], // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[1].roots",
        "roots",
    );
}

#[test]
fn bad_roots_are_refused() {
    let src = edit(
        "direction: (0.0, -1.0, -1.0)",
        "direction: (0.0, 0.0, 0.0) // <-",
    );
    let error = assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[1].roots[0].direction",
        "direction",
    );
    assert!(error.to_string().contains("must not be zero"), "{error}");

    let src = edit(
        "(position_m: (0.1, 0.0, 0.0)",
        "(position_m: (0.1, inf, 0.0) // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[0].roots[1].position_m[1]",
        "inf",
    );

    let src = edit(
        "direction: (0.0, 1.0, 0.0)),",
        "direction: (0.0, NaN, 0.0)), // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[0].roots[0].direction[1]",
        "NaN",
    );

    let src = edit(
        "(position_m: (0.1, 0.0, 0.0)",
        "(position_m: (0.1, 20.0, 0.0) // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "groups[0].roots[1].position_m[1]",
        "20.0",
    );

    let src = edit("name: \"crown\",", "name: \"  \", // <-");
    assert_error(&src, StyleErrorKind::InvalidValue, "groups[0].name", "name");
}

#[test]
fn every_documented_enum_spelling_parses() {
    let shapes = [
        ("Straight", NaturalShape::Straight),
        (
            "Uniform(twist_per_m: 1.0, curvature1_per_m: 20.0, curvature2_per_m: -5.0)",
            NaturalShape::Uniform {
                twist_per_m: 1.0,
                curvature1_per_m: 20.0,
                curvature2_per_m: -5.0,
            },
        ),
        (
            "Helix(radius_m: 0.01, step_m: -0.02)",
            NaturalShape::Helix {
                radius_m: 0.01,
                step_m: -0.02,
            },
        ),
        (
            "PerElement([(0.0, 10.0, 0.0), (1.0, 20.0, 0.0), (0.0, 0.0, 0.0), (0.0, 5.0, 5.0)])",
            NaturalShape::PerElement(vec![
                [0.0, 10.0, 0.0],
                [1.0, 20.0, 0.0],
                [0.0, 0.0, 0.0],
                [0.0, 5.0, 5.0],
            ]),
        ),
    ];
    for (text, shape) in shapes {
        let src = edit("Helix(radius_m: 0.01, step_m: 0.02)", text);
        let style = load(&src).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(style.groups[0].params.natural_shape, shape);
    }
    let layouts = [
        ("Uniform", ElementLayout::Uniform),
        (
            "Graded(tip_to_root_ratio: 2.5)",
            ElementLayout::Graded {
                tip_to_root_ratio: 2.5,
            },
        ),
    ];
    for (text, layout) in layouts {
        let src = edit("elements: 4,", &format!("elements: 4, layout: {text},"));
        let style = load(&src).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(style.groups[0].params.layout, layout);
    }
    for (text, method) in [
        ("Dense", Method::Dense),
        ("BlockDiagonal", Method::BlockDiagonal),
        ("BlockDiagonalOwnElement", Method::BlockDiagonalOwnElement),
        ("Exact", Method::Exact),
        (
            "Iterative(iterations: 7)",
            Method::Iterative { iterations: 7 },
        ),
    ] {
        let src = edit("method: Dense", &format!("method: {text}"));
        let style = load(&src).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(style.sim.method, method);
    }
    // A named top-level struct is accepted too.
    let src = edit("(\n    version", "Style(\n    version");
    load(&src).expect("Style( … ) loads");
}

fn scratch_file(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("helixhair-style-{name}-{}.ron", std::process::id()))
}

#[test]
fn save_then_load_round_trips() {
    let mut style = load(VALID).expect("VALID loads");
    // Exercise the other variants and a value RON must print exactly.
    style.groups[1].params.layout = ElementLayout::Graded {
        tip_to_root_ratio: 3.0,
    };
    style.groups[1].params.natural_shape =
        NaturalShape::PerElement(vec![[0.1, 1.0 / 3.0, -2.0]; 10]);
    style.sim.method = Method::Iterative { iterations: 3 };
    style.sim.dt_secs = 1.0 / 60.0;

    let text = style.to_ron().expect("serialise");
    let again = Style::from_ron(&text, Path::new("saved.ron")).expect("reload from text");
    assert_eq!(again, style);

    let path = scratch_file("round-trip");
    style.save(&path).expect("save");
    let loaded = Style::load(&path).expect("load");
    assert_eq!(loaded, style);
    // Saving over an existing file replaces it whole.
    style.name = "renamed".to_owned();
    style.save(&path).expect("save again");
    assert_eq!(Style::load(&path).expect("load again").name, "renamed");
    std::fs::remove_file(&path).expect("clean up");
}

#[test]
fn saved_text_is_pretty_and_omits_default_references() {
    let style = load(VALID).expect("VALID loads");
    let text = style.to_ron().expect("serialise");
    assert!(
        text.starts_with("// HelixHair style, format version 1"),
        "{text}"
    );
    assert!(text.contains("\n    version: 1,\n"), "{text}");
    assert_eq!(
        text.matches("reference:").count(),
        1,
        "only the non-default one: {text}"
    );
}

#[test]
fn io_errors_name_the_file() {
    let path = scratch_file("missing");
    let error = Style::load(&path).expect_err("no such file");
    assert!(
        error.to_string().starts_with(&path.display().to_string()),
        "{error}"
    );
    assert_eq!(error.kind(), None);

    let style = load(VALID).expect("VALID loads");
    let error = style
        .save(&path.join("no-such-dir.ron"))
        .expect_err("cannot save below a file");
    assert!(matches!(error, StyleError::Write { .. }), "{error}");
}

#[test]
fn hostile_input_gives_errors_not_panics() {
    let deep = format!("{}{}", "(".repeat(5000), ")".repeat(5000));
    for src in [
        "\u{feff}(version: 1)",
        "(version: 4294967296)",
        "(version: 1, name: \"\\u{d800}\")",
        deep.as_str(),
        "(version: 1, name: \"x\", groups: [(name: \"g\", roots: [(position_m: (1e308, 0, 0))])])",
        "(version: 1, name: \"x\", groups: [(name: \"g\", params: (elements: 18446744073709551615), roots: [])])",
    ] {
        let error = load_err(src);
        assert!(error.to_string().starts_with(FILE), "{error}");
    }
}

#[test]
fn contact_fields_read_and_their_errors_name_file_line_and_field() {
    let src = edit(
        "dt_secs: 0.01,",
        "dt_secs: 0.01,\n        contact: (skin_m: 0.003),",
    );
    let style = load(&src).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(style.sim.contact.skin_m, 0.003);
    // Left out: the default.
    assert_eq!(style.sim.contact.implicit_stiffness_ratio, 4.0);
    let src = edit(
        "dt_secs: 0.01,",
        "dt_secs: 0.01,\n        contact: (skin_m: 0.003, implicit_stiffness_ratio: -1.0), // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "sim.contact.implicit_stiffness_ratio",
        "implicit_stiffness_ratio",
    );
}

#[test]
fn interaction_fields_read_and_their_errors_name_file_line_and_field() {
    let src = edit(
        "dt_secs: 0.01,",
        "dt_secs: 0.01,\n        interaction: (enabled: true, friction_per_s: 8.0, cell_m: 0.03),",
    );
    let style = load(&src).unwrap_or_else(|e| panic!("{e}"));
    let got = style.sim.interaction;
    assert!(got.enabled);
    assert_eq!((got.friction_per_s, got.cell_m), (8.0, 0.03));
    // Left out: the default.
    assert_eq!(got.pressure_m2_per_s2, 0.2);
    let src = edit(
        "dt_secs: 0.01,",
        "dt_secs: 0.01,\n        interaction: (enabled: true, friction_per_s: 500.0), // <-",
    );
    assert_error(
        &src,
        StyleErrorKind::InvalidValue,
        "sim.interaction.friction_per_s",
        "friction_per_s",
    );
    // The batch engine runs the model too: the style loads.
    let src = edit(
        "    sim: (method: Dense, dt_secs: 0.01,",
        "    engine: Batch,\n    sim: (method: Exact, dt_secs: 0.01,\n        interaction: (enabled: true),\n",
    );
    let style = Style::from_ron(&src, Path::new(FILE)).expect("the batch engine runs it");
    assert!(style.sim.interaction.enabled);
}

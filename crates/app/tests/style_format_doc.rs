//! `docs/style-format.md` stays true: its RON examples load, its error
//! examples are what the loader prints for the fixtures they name, and it
//! documents every field and variant the physics types have.

use std::path::{Path, PathBuf};

use helixhair_app::Style;
use helixhair_physics::{ElementLayout, Method, NaturalShape, SimSettings, StrandParams};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn doc() -> String {
    std::fs::read_to_string(root().join("docs/style-format.md"))
        .expect("docs/style-format.md is readable")
}

/// The bodies of the fenced blocks of `language`.
fn blocks(text: &str, language: &str) -> Vec<String> {
    let fence = format!("```{language}\n");
    text.split(&fence)
        .skip(1)
        .map(|rest| rest.split("```").next().unwrap_or("").to_owned())
        .collect()
}

#[test]
fn every_ron_example_loads() {
    let examples = blocks(&doc(), "ron");
    assert!(!examples.is_empty(), "the doc has RON examples");
    for (i, example) in examples.iter().enumerate() {
        let style = Style::from_ron(example, Path::new(&format!("example {i}")))
            .unwrap_or_else(|e| panic!("{e}"));
        // Saving and loading again gives the same style.
        let text = style.to_ron().expect("serialise");
        assert_eq!(
            Style::from_ron(&text, Path::new("saved")).expect("reload"),
            style
        );
    }
}

#[test]
fn every_error_example_is_what_the_loader_prints() {
    let mut checked = 0;
    for block in blocks(&doc(), "text") {
        for line in block
            .lines()
            .filter(|l| l.starts_with("error: tests/fixtures/"))
        {
            let rest = &line["error: ".len()..];
            let file = rest.split(':').next().expect("a file name");
            let src = std::fs::read_to_string(root().join(file)).expect("the fixture is readable");
            let error = Style::from_ron(&src, Path::new(file)).expect_err("the fixture is broken");
            assert_eq!(format!("error: {error}"), line);
            checked += 1;
        }
    }
    assert!(checked >= 5, "only {checked} error examples");
}

/// Field names of a serde struct, by serialising it.
fn field_names<T: serde::Serialize>(value: &T) -> Vec<String> {
    match serde_json::to_value(value).expect("serialise") {
        serde_json::Value::Object(map) => map.keys().cloned().collect(),
        other => panic!("not a struct: {other}"),
    }
}

/// How RON spells `value`.
fn ron_text<T: serde::Serialize>(value: &T) -> String {
    ron::to_string(value).expect("serialise")
}

#[test]
fn every_field_and_variant_is_documented() {
    let doc = doc();
    let mut names = field_names(&SimSettings::default());
    names.extend(field_names(&StrandParams::default()));
    names.extend(
        [
            "version",
            "name",
            "sim",
            "groups",
            "params",
            "roots",
            "position_m",
            "direction",
            "reference",
        ]
        .map(String::from),
    );
    for name in names {
        assert!(
            doc.contains(&format!("| `{name}` |")),
            "`{name}` has no row in docs/style-format.md"
        );
    }
    let shapes = [
        NaturalShape::Straight,
        NaturalShape::Uniform {
            twist_per_m: 0.0,
            curvature1_per_m: 0.0,
            curvature2_per_m: 0.0,
        },
        NaturalShape::Helix {
            radius_m: 0.01,
            step_m: 0.0,
        },
        NaturalShape::PerElement(Vec::new()),
    ];
    let layouts = [
        ElementLayout::Uniform,
        ElementLayout::Graded {
            tip_to_root_ratio: 1.0,
        },
    ];
    let mut variants: Vec<String> = Method::ALL.iter().map(ron_text).collect();
    variants.extend(shapes.iter().map(ron_text));
    variants.extend(layouts.iter().map(ron_text));
    for variant in variants {
        let name = variant.split('(').next().unwrap_or(&variant);
        assert!(
            doc.contains(&format!("| `{name}")),
            "variant {name} has no row in docs/style-format.md"
        );
    }
    for method in Method::ALL {
        assert!(
            doc.contains(&format!("| `{}", method.name())),
            "--method {} is not documented",
            method.name()
        );
    }
}

#[test]
fn every_groom_field_and_method_is_documented() {
    use helixhair_app::style::groom::{
        CurlAxis, RenderStrands, ScalpPlacement, ScalpRegion, StrandInterpolation,
    };
    let doc = doc();
    let region = ScalpRegion {
        towards: glam::DVec3::Z,
        from_deg: 0.0,
        to_deg: 180.0,
    };
    let scalp = ScalpPlacement {
        count: 1,
        comb: glam::DVec3::Z,
        lift_deg: 0.0,
        seed: 1,
        region: Some(region.clone()),
        // Not the default, so that the field is written and looked up.
        curl_axis: CurlAxis::Growth,
    };
    let mut names = field_names(&scalp);
    names.extend(field_names(&region));
    names.extend(field_names(&RenderStrands::default()));
    names.extend(["scalp", "render"].map(String::from));
    for name in names {
        assert!(
            doc.contains(&format!("| `{name}` |")),
            "`{name}` has no row in docs/style-format.md"
        );
    }
    let variants = [
        ron_text(&StrandInterpolation::Nearest),
        ron_text(&StrandInterpolation::Blend3),
        ron_text(&CurlAxis::Hug),
        ron_text(&CurlAxis::Growth),
    ];
    for name in variants {
        assert!(
            doc.contains(&format!("| `{name}` |")),
            "{name} is not documented"
        );
    }
}

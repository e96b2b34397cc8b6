//! Broken styles: `helixhair sim` must exit non-zero, and its error must
//! name the file, the line (the one marked `// <- error` in the fixture)
//! and the field.

use helixhair_e2e::{describe, marker_line, run_helixhair};

/// Each fixture in `tests/fixtures/` and the field its error must name.
const BROKEN: &[(&str, &str)] = &[
    ("unknown_field.ron", "groups[0].params.radius_mm"),
    ("unknown_variant.ron", "groups[0].params.natural_shape"),
    ("wrong_type.ron", "groups[0].params.elements"),
    ("missing_field.ron", "groups[1].name"),
    ("syntax_error.ron", "groups[0].params"),
    ("nan.ron", "groups[0].params.ellipticity"),
    ("out_of_range.ron", "groups[0].params.ellipticity"),
    (
        "nested_out_of_range.ron",
        "groups[1].params.natural_shape.step_m",
    ),
    ("bad_version.ron", "version"),
    ("empty_groups.ron", "groups"),
    ("no_roots.ron", "groups[1].roots"),
    ("zero_direction.ron", "groups[1].roots[0].direction"),
];

#[test]
fn every_broken_fixture_is_listed() {
    let dir = helixhair_e2e::workspace_root().join("tests/fixtures");
    let mut on_disk: Vec<String> = std::fs::read_dir(dir)
        .expect("tests/fixtures is readable")
        .map(|e| {
            e.expect("an entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|name| name.ends_with(".ron"))
        .collect();
    on_disk.sort();
    let mut listed: Vec<String> = BROKEN.iter().map(|(f, _)| (*f).to_owned()).collect();
    listed.sort();
    assert_eq!(on_disk, listed);
}

#[test]
fn broken_styles_fail_naming_file_line_and_field() {
    for (fixture, field) in BROKEN {
        let path = format!("tests/fixtures/{fixture}");
        let output = run_helixhair(&["sim", "--style", &path, "--steps", "1"]);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(
            output.status.code(),
            Some(1),
            "{fixture}: {}",
            describe(&output)
        );
        let line = marker_line(&path);
        let located = format!("error: {path}:{line}:");
        assert!(
            stderr.starts_with(&located),
            "{fixture}: expected `{located}`\n{}",
            describe(&output)
        );
        assert!(
            stderr.contains(&format!("`{field}`: ")),
            "{fixture}: expected field `{field}`\n{stderr}"
        );
        assert!(
            output.stdout.is_empty(),
            "{fixture}: nothing on stdout\n{}",
            describe(&output)
        );
        assert!(!stderr.contains("panicked"), "{fixture}: {stderr}");
    }
}

#[test]
fn missing_style_file_fails_naming_it() {
    let output = run_helixhair(&["sim", "--style", "tests/fixtures/no-such-style.ron"]);
    assert_eq!(output.status.code(), Some(1), "{}", describe(&output));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.starts_with("error: tests/fixtures/no-such-style.ron: cannot read the style"),
        "{stderr}"
    );
}

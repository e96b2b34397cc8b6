//! `helixhair sim --export` and `helixhair export` from the command line:
//! docs/export.md's commands into folders that do not exist yet, numbered
//! sequences, motion files, and clear errors (exit status 1, nothing left
//! under the asked name) for bad paths, formats and motion files.

use crate::support;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use helixhair_formats::{Format, ReadOptions, read};
use support::inside::{inside_share, usda_head_poses};

fn helixhair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .args(args)
        .output()
        .expect("helixhair starts")
}

/// Runs `helixhair` with `words` (split at spaces) then `more`, and
/// expects success.
fn succeeds(words: &str, more: &[&Path]) -> Output {
    let mut args: Vec<&str> = words.split_whitespace().collect();
    args.extend(more.iter().map(|p| p.to_str().expect("UTF-8")));
    let output = helixhair(&args);
    assert!(
        output.status.success(),
        "{args:?}: {}",
        text(&output.stderr)
    );
    output
}

/// Reads an exported file back with the formats crate.
fn read_back(path: &Path) -> helixhair_formats::Imported {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let format = Format::from_path(path).expect("a known extension");
    read(&bytes, format, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "helixhair-export-cli-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("lists")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn the_readme_command_writes_an_animation_into_new_folders() {
    let dir = scratch("readme");
    let out = dir.join("out/curly.usda");
    let sim = "sim --style assets/styles/curly.ron --play shake --steps 4 --export";
    let stdout = text(&succeeds(sim, &[&out]).stdout);
    assert!(stdout.contains("exported 5 frames to"), "{stdout}");
    let imported = read_back(&out);
    assert_eq!(imported.animation.expect("time samples").frames.len(), 5);
    assert_eq!(
        imported.curves.curves.len(),
        35,
        "the curly example's strands"
    );
    assert_eq!(names_in(out.parent().expect("folder")), ["curly.usda"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn one_frame_formats_write_numbered_sequences_or_the_last_frame() {
    let dir = scratch("sequence");
    let out = dir.join("c.hair");
    let sim = "sim --style assets/styles/curly.ron --steps 2 --export";
    succeeds(sim, &[&out]);
    assert_eq!(
        names_in(&dir),
        ["c.0000.hair", "c.0001.hair", "c.0002.hair"]
    );
    let last = format!(
        "{sim} {} --export-frames last --points-per-strand 7",
        out.display()
    );
    succeeds(&last, &[]);
    let imported = read_back(&out);
    assert!(imported.curves.curves.iter().all(|c| c.points_m.len() == 7));
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn export_writes_a_groomed_style_at_rest_with_its_drawn_strands() {
    let dir = scratch("export");
    let out = dir.join("rest.obj");
    let export = "export --style assets/styles/groomed/wavy.ron --strands drawn \
                  --points-per-strand 8 --out";
    succeeds(export, &[&out]);
    let curves = read_back(&out).curves.curves;
    assert!(curves.len() > 1000, "{} strands", curves.len());
    assert!(curves.iter().all(|c| c.points_m.len() == 8));
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn motion_files_play_and_their_errors_name_file_line_and_field() {
    let dir = scratch("motion");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let example = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/motions/look_left.ron"
    );
    let sim = "sim --style assets/styles/coily.ron --steps 3 --play";
    succeeds(sim, &[Path::new(example)]);

    let bad = dir.join("bad.ron");
    std::fs::write(
        &bad,
        "(version: 1, keys: [\n  (time_secs: 0.0),\n  (time_secs: 0.0),\n])",
    )
    .expect("writes");
    let mut args: Vec<&str> = sim.split_whitespace().collect();
    args.push(bad.to_str().expect("UTF-8"));
    let output = helixhair(&args);
    assert_eq!(output.status.code(), Some(1));
    let stderr = text(&output.stderr);
    let want = format!(
        "{}:3:4: field `keys[1].time_secs`: 0 s does not come after",
        bad.display()
    );
    assert!(stderr.contains(&want), "{stderr}");
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn bad_paths_and_formats_fail_before_simulating_and_leave_nothing() {
    let dir = scratch("errors");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let a_file = dir.join("a_file");
    std::fs::write(&a_file, "not a folder").expect("writes");
    let under_file = a_file.join("x.usda");
    let unknown = dir.join("x.fbx");
    let tfx = dir.join("x.tfx");
    let cases: [(&[&str], String); 4] = [
        (
            &["--export", under_file.to_str().expect("UTF-8")],
            format!("cannot create the folder {}", a_file.display()),
        ),
        (
            &["--export", unknown.to_str().expect("UTF-8")],
            "unknown export format; the extension picks one of .tfx, .hair, .usda, .usdc, .usd, .usdz, .obj, .abc".into(),
        ),
        (
            &[
                "--export",
                tfx.to_str().expect("UTF-8"),
                "--points-per-strand",
                "20",
            ],
            "TressFX (.tfx) needs a power of two from 4 to 64".into(),
        ),
        (
            &[
                "--export",
                tfx.to_str().expect("UTF-8"),
                "--points-per-strand",
                "1",
            ],
            "--points-per-strand 1: must be 2 to".into(),
        ),
    ];
    for (extra, want) in cases {
        let mut args = vec!["sim", "--style", "assets/styles/curly.ron", "--steps", "2"];
        args.extend_from_slice(extra);
        let output = helixhair(&args);
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        let stderr = text(&output.stderr);
        assert!(stderr.contains(&want), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("simulating"),
            "refused before simulating: {stderr}"
        );
    }
    assert_eq!(names_in(&dir), ["a_file"]);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

/// The share of exported hair points (roots and tips left out) issue 32
/// allows inside the head.
const ISSUE_INSIDE_SHARE: f64 = 0.01;

#[test]
fn groomed_examples_simulated_by_sim_start_and_stay_out_of_the_head_they_grow_on() {
    // Issue 32, item 3: `sim` did not collide hair grown on the scalp with
    // the head, and 27% of the exported points of `groomed/wavy.ron` lay
    // inside the exported head after a shake; 27% already at frame 0, the
    // natural shape through the skull. Checked at the start (now settled
    // on the head, `sim/settle.rs`) and every tenth frame of a shake (the
    // worst frames are mid-shake, as the head turns into the hair), on
    // every point but the root (on the skin, where a parity test is a coin
    // toss) and the tip (the contact acts at quadrature samples, which the
    // tip is not).
    //
    // Every example meets the issue's 1%. The curly and coily ones had
    // 7 to 9% inside while their helices turned about axes along the
    // scalp, and 1.0 to 2.6% with their axes along the growth direction
    // (`curl_axis: Growth`) while their first loops still started along
    // the scalp; they now leave the root along the growth direction and
    // bend into the coil over the first element (`head::coil`). With the
    // default 2 mm contact skin, every example still had 1.0 to 1.7% of
    // its points inside at its worst frame mid-shake; the groomed examples
    // set a 3 mm skin (`sim.contact`).
    let head = helixhair_render::head_generate::default_head();
    let dir = scratch("inside");
    for name in ["straight", "wavy", "curly", "coily"] {
        let style = format!("assets/styles/groomed/{name}.ron");
        let out = dir.join(format!("{name}.usda"));
        succeeds(
            &format!("sim --style {style} --play shake --steps 120 --export-frames all --export"),
            &[&out],
        );
        let imported = read_back(&out);
        let counts: Vec<usize> = imported
            .curves
            .curves
            .iter()
            .map(|c| c.points_m.len())
            .collect();
        let frames = imported.animation.expect("an animation").frames;
        assert_eq!(frames.len(), 121, "{name}: the start and 120 frames");
        let text = std::fs::read_to_string(&out).expect("the export reads");
        let poses = usda_head_poses(&text);
        for frame in frames.iter().step_by(10) {
            let (rotation, offset) = poses
                .iter()
                .find(|(time, ..)| *time == frame.time_code)
                .map_or((glam::DMat3::IDENTITY, glam::DVec3::ZERO), |(_, r, t)| {
                    (*r, *t)
                });
            let mut first = 0;
            let mut points = Vec::new();
            for count in &counts {
                let curve = &frame.points_m[first..first + count];
                points.extend(
                    curve[1..count - 1]
                        .iter()
                        .map(|p| rotation.transpose() * (p.as_dvec3() - offset)),
                );
                first += count;
            }
            let (inside, share) = inside_share(&points, &head);
            let measured = format!(
                "{name} at frame {}: {inside} of {} points ({:.2}%) inside the head",
                frame.time_code,
                points.len(),
                100.0 * share
            );
            eprintln!("{measured}");
            assert!(share < ISSUE_INSIDE_SHARE, "{measured}");
        }
    }
}

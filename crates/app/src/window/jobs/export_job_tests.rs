//! Tests of [`super::export_job`] (kept apart to keep the module short).

use std::path::Path;

use helixhair_formats::{Format, ReadOptions, read};

use super::*;
use crate::export::{capture_curves, sequence_path};
use crate::window::live::head_motion::Clip;
use crate::window::state::default_style::default_style;

const POINTS: usize = 8;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "helixhair-export-job-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn shaking_app() -> AppState {
    let mut app = AppState::new(default_style(4), None).unwrap();
    app.play(Clip::Shake);
    app.step_frame();
    app
}

fn request(path: &Path, frames: usize) -> ExportRequest {
    ExportRequest {
        path: path.to_owned(),
        strands: StrandChoice::Simulated,
        points_per_strand: POINTS,
        frames,
        clip: None,
    }
}

fn read_points(path: &Path) -> Vec<Vec<glam::Vec3>> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let format = Format::from_path(path).unwrap();
    let imported = read(&bytes, format, &ReadOptions::default()).unwrap();
    imported
        .curves
        .curves
        .into_iter()
        .map(|c| c.points_m)
        .collect()
}

#[test]
fn a_recorded_animation_is_what_the_window_shows_in_the_next_frames() {
    // Known answer: the window's own run, stepped the same frames with the
    // head shaking, exported by the same capture.
    let dir = scratch("record");
    let mut app = shaking_app();
    let path = dir.join("shot.obj");
    let frames = 5;
    let job = start_export(&app, &request(&path, frames)).unwrap();
    let JobDone::Exported(outcome) = job.wait().unwrap() else {
        panic!("an export")
    };
    assert_eq!(outcome.frames, frames + 1);
    assert_eq!(outcome.files.len(), frames + 1);
    for frame in 0..=frames {
        if frame > 0 {
            app.step_frame();
        }
        let want =
            capture_curves(app.sim().engine(), None, StrandChoice::Simulated, POINTS).unwrap();
        let got = read_points(&sequence_path(&path, frame));
        assert_eq!(got.len(), want.curves.len());
        for (g, w) in got.iter().zip(&want.curves) {
            for (a, b) in g.iter().zip(&w.points_m) {
                assert!((*a - *b).length() < 1e-6, "frame {frame}: {a} vs {b}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_cancelled_recording_leaves_no_file_under_the_final_names() {
    let dir = scratch("cancel");
    let app = shaking_app();
    for name in ["shot.usda", "shot.hair"] {
        let path = dir.join(name);
        let job = start_export(&app, &request(&path, 400)).unwrap();
        job.cancel();
        let error = job.wait().expect_err("cancelled").to_string();
        assert!(error.contains("cancelled"), "{error}");
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert!(left.is_empty(), "{name}: left {left:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn export_frame_writes_the_state_on_screen_and_bad_requests_fail_at_once() {
    let dir = scratch("frame");
    let app = shaking_app();
    let path = dir.join("now.tfx");
    let JobDone::Exported(outcome) = start_export(&app, &request(&path, 0))
        .unwrap()
        .wait()
        .unwrap()
    else {
        panic!("an export")
    };
    assert_eq!(outcome.files, vec![path.clone()]);
    let want = capture_curves(app.sim().engine(), None, StrandChoice::Simulated, POINTS).unwrap();
    let got = read_points(&path);
    assert_eq!(got.len(), want.curves.len());
    assert!((got[0][POINTS - 1] - want.curves[0].points_m[POINTS - 1]).length() < 1e-6);
    let error = start_export(&app, &request(&dir.join("x.png"), 0))
        .expect_err("unknown format")
        .to_string();
    assert!(error.contains("unknown export format"), "{error}");
    let mut bad = request(&dir.join("x.tfx"), 0);
    bad.points_per_strand = 10;
    assert!(
        start_export(&app, &bad).is_err(),
        "TressFX needs a power of two"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_exported_frame_carries_the_head_the_window_simulates_against() {
    // A head 1.5 m up (as a scanned bust stands in its file): the export
    // must carry it, not the default head at the origin.
    let dir = scratch("head");
    let mut app = shaking_app();
    let lift = glam::Vec3::new(0.0, 1.5, 0.0);
    let mut head = (**app.head_mesh()).clone();
    head.mesh.positions.iter_mut().for_each(|p| *p += lift);
    let want_low = head
        .mesh
        .positions
        .iter()
        .fold(f32::MAX, |low, p| low.min(p.y));
    app.use_head_mesh(std::sync::Arc::new(head));
    let path = dir.join("now.usda");
    start_export(&app, &request(&path, 0))
        .unwrap()
        .wait()
        .unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let (low, _) = crate::export::usda_head_extent(&text).expect("a head in the file");
    assert!(
        (low.y - f64::from(want_low)).abs() < 1e-4,
        "the exported head's lowest point is at y = {}, the window's at {want_low}",
        low.y
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_recording_plays_the_clip_picked_in_its_dialog() {
    // Issue 32, item 11: Record animation had no clip picker; it recorded
    // whatever the head was doing (nothing, on a still head).
    let dir = scratch("clip");
    let mut app = AppState::new(default_style(4), None).unwrap();
    app.step_frame();
    let still = dir.join("still.usda");
    let turned = dir.join("turned.usda");
    start_export(&app, &request(&still, 40))
        .unwrap()
        .wait()
        .unwrap();
    let turn = ExportRequest {
        clip: Some(Clip::Turn),
        ..request(&turned, 40)
    };
    start_export(&app, &turn).unwrap().wait().unwrap();
    let still_text = std::fs::read_to_string(&still).unwrap();
    let turned_text = std::fs::read_to_string(&turned).unwrap();
    assert!(!still_text.contains("xformOp:transform.timeSamples"));
    assert!(turned_text.contains("xformOp:transform.timeSamples"));
    // The last frames: the turned head carried the roots away.
    let last = |text: &str| {
        let stage = helixhair_formats::read(text.as_bytes(), Format::Usda, &ReadOptions::default())
            .unwrap();
        let frames = stage.animation.expect("an animation").frames;
        frames.last().expect("frames").points_m.clone()
    };
    let (a, b) = (last(&still_text), last(&turned_text));
    let moved = a
        .iter()
        .zip(&b)
        .map(|(p, q)| (*p - *q).length())
        .fold(0.0f32, f32::max);
    assert!(moved > 0.02, "the turn moved the hair only {moved} m");
    // The window's own head is untouched: nothing plays there.
    assert!(app.head().playing(app.now_secs()).is_none());
    std::fs::remove_dir_all(&dir).unwrap();
}

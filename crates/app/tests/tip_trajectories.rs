//! `helixhair sim --tip-trajectories`: every strand's tip per frame in the
//! JSON report, checked against a known answer. A head turned by a fixed
//! angle about the vertical and moved by a fixed offset from the start,
//! and never moving (a motion file of one key), is a rigid change of
//! frame that gravity (vertical) does not see: each tip's trajectory must
//! be the still head's, turned and moved the same, frame by frame.
//!
//! Frame 0 (the start) is left out of that comparison: it is recorded
//! before the first step, when the engine's head is still at rest (the
//! engine takes the head's pose from the trajectory only when it steps),
//! so the start is at the unmoved head for every run (docs/sim-json.md).

use std::path::PathBuf;
use std::process::Command;

use glam::{DMat3, DVec3};

const STEPS: usize = 20;

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("helixhair-tips-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn tips(extra: &[&str]) -> (Vec<f64>, Vec<Vec<DVec3>>) {
    let style = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/styles/straight.ron"
    );
    let steps = STEPS.to_string();
    let output = Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .args([
            "sim",
            "--style",
            style,
            "--steps",
            &steps,
            "--engine",
            "reference",
        ])
        .args(["--tip-trajectories", "--json", "-"])
        .args(extra)
        .output()
        .expect("runs helixhair");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let t = &report["tip_trajectories"];
    let times = t["time_secs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let tracks = t["tips_m"]
        .as_array()
        .unwrap()
        .iter()
        .map(|track| {
            track
                .as_array()
                .unwrap()
                .iter()
                .map(|p| {
                    let p: Vec<f64> = p
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|c| c.as_f64().unwrap())
                        .collect();
                    DVec3::new(p[0], p[1], p[2])
                })
                .collect()
        })
        .collect();
    // The last recorded tip is the report's final shape's tip.
    let last_points = report["strands"][0]["points_m"].as_array().unwrap();
    let tip = last_points.last().unwrap().as_array().unwrap();
    let tracks: Vec<Vec<DVec3>> = tracks;
    assert_eq!(tracks[0].last().unwrap().x, tip[0].as_f64().unwrap());
    (times, tracks)
}

#[test]
fn tips_of_a_turned_and_moved_still_head_are_the_still_heads_turned_and_moved() {
    let dir = scratch();
    let motion = dir.join("turned.ron");
    std::fs::write(
        &motion,
        "(version: 1, name: \"turned\", keys: [(time_secs: 0.0, turn_deg: 90.0, offset_m: (0.1, -0.05, 0.2))])",
    )
    .unwrap();
    let (times, still) = tips(&[]);
    let (_, turned) = tips(&["--play", motion.to_str().unwrap()]);
    assert_eq!(times.len(), STEPS + 1, "the start and every frame");
    let dt = times[1] - times[0];
    assert!(
        times
            .iter()
            .enumerate()
            .all(|(k, t)| (t - k as f64 * dt).abs() < 1e-12)
    );
    assert_eq!(still.len(), turned.len());
    let rotation = DMat3::from_rotation_y(90f64.to_radians());
    let offset = DVec3::new(0.1, -0.05, 0.2);
    let mut moved: f64 = 0.0;
    for (a, b) in still.iter().zip(&turned) {
        assert_eq!(a.len(), STEPS + 1);
        assert_eq!(a[0], b[0], "the start: the head at rest");
        for (p, q) in a.iter().zip(b).skip(1) {
            let want = rotation * *p + offset;
            assert!((*q - want).length() < 1e-9, "{q} vs {want}");
        }
        moved = moved.max((a[STEPS] - a[0]).length());
    }
    assert!(
        moved > 1e-4,
        "the tips moved ({moved} m): the check is not of a frozen run"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn tip_trajectories_need_a_json_report() {
    let style = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/styles/straight.ron"
    );
    let output = Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .args(["sim", "--style", style, "--tip-trajectories"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("--json"));
}

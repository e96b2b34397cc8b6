//! The whole Sintel groom through `helixhair import` (docs/import.md,
//! "Measured on Sintel"). Reads `../shared/data/sintel` (or
//! `HELIXHAIR_SINTEL`); skips, saying so, where it is absent.

use crate::support;

use std::process::Command;

use support::sintel::sintel;

#[test]
fn the_whole_sintel_groom_imports_within_tolerance() {
    let Some(dir) = sintel() else {
        eprintln!("skipped: the Sintel data (shared/data/sintel) is absent");
        return;
    };
    let out_dir = std::env::temp_dir().join(format!("helixhair-sintel-{}", std::process::id()));
    let style = out_dir.join("sintel.ron");
    let report = out_dir.join("report.json");
    let out = Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .arg("import")
        .arg(dir.join("sintel_hair.16points.tfx"))
        .arg("--head")
        .arg(dir.join("sintel-collider.obj"))
        .arg("--out")
        .arg(&style)
        .arg("--json")
        .arg(&report)
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).expect("report")).expect("JSON");
    // The README of the data: 11,400 strands of 16 points.
    assert_eq!(json["strands_read"], 11_400);
    let imported = json["strands_imported"].as_u64().expect("count");
    let skipped: u64 = json["skipped"]
        .as_object()
        .expect("map")
        .values()
        .filter_map(serde_json::Value::as_u64)
        .sum();
    assert_eq!(imported + skipped, 11_400, "{json}");
    // The default tolerance, 0.5% of the length, holds for most strands
    // (the rest hit the cap of 9 elements that 16 points allow).
    assert!(
        json["fit_error_over_length"]["median"]
            .as_f64()
            .expect("median")
            <= 0.005
    );
    let held = json["sag_free"]["held"].as_u64().expect("held");
    assert!(held * 10 >= imported * 9, "{json}");
    helixhair_app::style::Style::load(&style).expect("the style loads");
    gpu_engine_runs_the_groom(&style, &out_dir);
    let _ = std::fs::remove_dir_all(&out_dir);
}

/// Strands whose tip may lie farther than [`SINTEL_TIP_TOL_M`] from the
/// batch engine's after 60 frames of shake: where a sample meets the head
/// near the contact skin's edge, the GPU's f32 lookup of the collider and
/// the batch engine's f64 one can decide it apart, and the two strands
/// part. Measured on lavapipe: every tip within 1e-6 m up to frame 30,
/// then 281 of 11,348 strands (2.5%) parted by up to 5 cm at frame 60.
const SINTEL_PARTED_SHARE: f64 = 0.05;

/// A tip that did not part: the same measure as the examples' parity
/// (`tests/sim_cli.rs`, `GPU_POINT_TOL_M`).
const SINTEL_TIP_TOL_M: f64 = 1e-5;

/// The imported groom on the GPU engine (issue #31): 60 frames of shake
/// with no guard event, every tip with the batch engine's through frame 30
/// and all but [`SINTEL_PARTED_SHARE`] of them at frame 60.
fn gpu_engine_runs_the_groom(style: &std::path::Path, out_dir: &std::path::Path) {
    if helixhair_gpu::context_or_skip("Sintel on the GPU engine").is_none() {
        return;
    }
    let run = |engine: &str| -> serde_json::Value {
        let report = out_dir.join(format!("{engine}.json"));
        let out = Command::new(env!("CARGO_BIN_EXE_helixhair"))
            .arg("sim")
            .arg("--style")
            .arg(style)
            .args(["--engine", engine, "--play", "shake", "--steps", "60"])
            .args(["--tip-trajectories", "--json"])
            .arg(&report)
            .output()
            .expect("the binary runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_str(&std::fs::read_to_string(&report).expect("report")).expect("JSON")
    };
    let (gpu, batch) = (run("gpu"), run("batch"));
    let note = gpu["gpu"].as_str().expect("the GPU note");
    assert!(note.starts_with("physics on the GPU"), "{note}");
    assert_eq!(gpu["guard"]["event_count"], 0, "{}", gpu["guard"]);
    let tips = |report: &serde_json::Value| -> Vec<Vec<[f64; 3]>> {
        let strands = report["tip_trajectories"]["tips_m"]
            .as_array()
            .expect("tips");
        strands
            .iter()
            .map(|frames| {
                let frames = frames.as_array().expect("frames");
                frames
                    .iter()
                    .map(|p| [0, 1, 2].map(|k| p[k].as_f64().expect("a number")))
                    .collect()
            })
            .collect()
    };
    let (a, b) = (tips(&gpu), tips(&batch));
    assert_eq!(a.len(), b.len());
    let apart = |x: [f64; 3], y: [f64; 3]| {
        ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
    };
    let mut parted = 0;
    for (i, (x, y)) in a.iter().zip(&b).enumerate() {
        assert!(x.iter().flatten().all(|c| c.is_finite()), "strand {i}");
        // Frame 30 (the start is entry 0).
        let d = apart(x[30], y[30]);
        assert!(d <= SINTEL_TIP_TOL_M, "strand {i} at frame 30: {d:.2e} m");
        if apart(x[60], y[60]) > SINTEL_TIP_TOL_M {
            parted += 1;
        }
    }
    let share = parted as f64 / a.len() as f64;
    println!(
        "Sintel on the GPU engine: {parted} of {} tips parted at frame 60",
        a.len()
    );
    assert!(
        share <= SINTEL_PARTED_SHARE,
        "{parted} of {} parted",
        a.len()
    );
}

//! With the graphics adapter hidden (`helixhair_gpu::HIDDEN_ADAPTER_ENV`:
//! Vulkan only, pointed at a driver that does not exist), every GPU user
//! fails with a message or falls back, and none panics:
//!
//! - `helixhair render` exits with status 1 and says no adapter was found;
//! - the physics' GPU engine (`Stepper::prefer_gpu`) falls back to the CPU
//!   batch path and says why, and the fallback steps.
//!
//! The window's case needs an X server and is in
//! `crates/app/tests/window_screenshot.rs`. These tests need no GPU: they
//! hide whatever the machine has.

use std::process::Command;

use glam::DVec3;
use helixhair_e2e::{describe, helixhair_bin, scratch_dir, workspace_root};
use helixhair_gpu::HIDDEN_ADAPTER_ENV;
use helixhair_physics::gpu::Stepper;
use helixhair_physics::{RigidMotion, RootPose, SimSettings, StrandParams};

/// Set in the child process of [`the_gpu_engine_falls_back_to_the_cpu`].
const CHILD_VAR: &str = "HELIXHAIR_NO_ADAPTER_CHILD";

#[test]
fn render_says_there_is_no_adapter_and_exits_with_status_1() {
    let out = scratch_dir("no-adapter").join("never.png");
    let output = Command::new(helixhair_bin())
        .args(["render", "--style", "tests/render_fixtures/small_groom.ron"])
        .args(["--frames", "1", "--width", "64", "--height", "64", "--out"])
        .arg(&out)
        .current_dir(workspace_root())
        .envs(HIDDEN_ADAPTER_ENV)
        .output()
        .expect("helixhair starts");
    let text = describe(&output);
    assert_eq!(output.status.code(), Some(1), "{text}");
    assert!(!text.contains("panicked"), "{text}");
    assert!(text.contains("no graphics adapter found"), "{text}");
    assert!(!out.exists(), "no picture without an adapter");
}

#[test]
fn sim_on_the_gpu_engine_falls_back_to_the_cpu_batch_engine_and_says_why() {
    let report = scratch_dir("no-adapter-sim").join("report.json");
    let output = Command::new(helixhair_bin())
        .args([
            "sim",
            "--style",
            "assets/styles/curly.ron",
            "--engine",
            "gpu",
        ])
        .args(["--play", "shake", "--steps", "30", "--json"])
        .arg(&report)
        .current_dir(workspace_root())
        .envs(HIDDEN_ADAPTER_ENV)
        .output()
        .expect("helixhair starts");
    let text = describe(&output);
    assert!(output.status.success(), "{text}");
    assert!(!text.contains("panicked"), "{text}");
    assert!(text.contains("no graphics adapter found"), "{text}");
    assert!(
        text.contains("the CPU batch engine steps the hair"),
        "{text}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).expect("the report")).expect("JSON");
    assert_eq!(json["engine"], "gpu");
    assert_eq!(json["steps"], 30);
    let gpu = json["gpu"].as_str().expect("the GPU note");
    assert!(gpu.contains("no graphics adapter found"), "{gpu}");
}

/// The child's half: with the adapter hidden, the GPU engine falls back.
fn fall_back_without_an_adapter() {
    let roots: Vec<RootPose> = (0..10)
        .map(|i| {
            let a = f64::from(i) * 0.6;
            let p = DVec3::new(0.1 * a.cos(), 0.05, 0.1 * a.sin());
            RootPose::from_direction(p, p, DVec3::Y)
        })
        .collect();
    let (mut stepper, message) =
        Stepper::prefer_gpu(&SimSettings::default(), &StrandParams::default(), &roots)
            .expect("valid parameters");
    assert!(matches!(stepper, Stepper::Cpu(_)), "{message}");
    assert!(message.contains("no graphics adapter found"), "{message}");
    for _ in 0..10 {
        stepper.step_frame(&RigidMotion::default());
    }
    println!("fell back: {message}");
}

#[test]
fn the_gpu_engine_falls_back_to_the_cpu() {
    if std::env::var(CHILD_VAR).is_ok() {
        fall_back_without_an_adapter();
        return;
    }
    // The adapter is hidden through the environment, which the process
    // reads when wgpu starts: run this test again in a child process.
    // The test binary lists this test under its module path, less the
    // crate's own name (`no_adapter::the_gpu_engine_falls_back_to_the_cpu`).
    let module = module_path!().split_once("::").map_or("", |(_, rest)| rest);
    let name = format!("{module}::the_gpu_engine_falls_back_to_the_cpu");
    let output = Command::new(std::env::current_exe().expect("the test executable"))
        .args([name.as_str(), "--exact", "--nocapture"])
        .env(CHILD_VAR, "1")
        .envs(HIDDEN_ADAPTER_ENV)
        .output()
        .expect("the child starts");
    let text = describe(&output);
    assert!(output.status.success(), "{text}");
    assert!(text.contains("fell back: "), "{text}");
}

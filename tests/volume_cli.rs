//! The hair–hair model (docs/volume.md) end to end: `sim --interaction on`
//! runs it on the reference and the batch engine without guard events,
//! and the volume study's quick mode writes its tables and charts.

use helixhair_e2e::{describe, run_helixhair, scratch_dir, workspace_root};

#[test]
fn sim_runs_the_model_on_both_engines_without_guard_events() {
    let style = workspace_root().join("assets/styles/curly.ron");
    let style = style.to_string_lossy();
    let output = run_helixhair(&[
        "sim",
        "--style",
        &style,
        "--steps",
        "60",
        "--interaction",
        "on",
    ]);
    assert!(output.status.success(), "{}", describe(&output));
    // A second of settling: the model's work is in the guard's energy
    // balance, so it triggers no guard event (it did, 8 times, before).
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(!stdout.contains("stability guard stepped in"), "{stdout}");
    // The batch engine runs it too; a strand the guard reset would fail
    // the run (`--accept-resets` is not given), so success is also "no
    // resets": the batch guard counts the model's work as well.
    let output = run_helixhair(&[
        "sim",
        "--style",
        &style,
        "--steps",
        "60",
        "--interaction",
        "on",
        "--engine",
        "batch",
    ]);
    assert!(output.status.success(), "{}", describe(&output));
}

#[test]
fn bench_volume_quick_writes_its_tables_without_guard_events() {
    let out = scratch_dir("bench-volume");
    let out_arg = out.to_string_lossy().into_owned();
    let output = run_helixhair(&[
        "bench",
        "--study",
        "volume",
        "--study",
        "volume-shake",
        "--study",
        "volume-cost",
        "--quick",
        "--out",
        &out_arg,
    ]);
    assert!(output.status.success(), "{}", describe(&output));
    let volume = std::fs::read_to_string(out.join("volume.csv")).expect("volume.csv");
    let cases: Vec<&str> = volume
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').next())
        .collect();
    assert_eq!(cases, ["rest", "off", "on"], "{volume}");
    let shake = std::fs::read_to_string(out.join("volume_shake.csv")).expect("volume_shake.csv");
    let mut lines = shake.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let events = header
        .iter()
        .position(|h| *h == "guard_events")
        .expect("guard_events");
    let last = lines.last().expect("rows");
    assert_eq!(last.split(',').nth(events), Some("0"), "{shake}");
    for name in ["volume_cost.csv", "volume_shake.svg", "volume_energy.svg"] {
        assert!(out.join(name).is_file(), "{name} missing");
    }
}

//! The `helixhair` binary's own checks: the command line parses as
//! documented. (Having an integration test here also makes Cargo build the
//! binary for `cargo test`, which the end-to-end tests in `tests/` run.)

use std::process::{Command, Output};

fn helixhair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .args(args)
        .output()
        .expect("helixhair starts")
}

#[cfg(feature = "window")]
#[test]
fn without_a_display_the_window_points_to_the_headless_commands() {
    let output = Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("helixhair starts");
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("cannot open a window"), "{stderr}");
    assert!(stderr.contains("helixhair sim --style"), "{stderr}");
    // No source file of the machine that built the program (issue 14).
    assert!(!stderr.contains(".cargo"), "{stderr}");
    assert!(!stderr.contains(".rs:"), "{stderr}");
}

#[cfg(not(feature = "window"))]
#[test]
fn without_the_window_feature_no_command_says_so_and_fails() {
    let output = helixhair(&[]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("cargo feature `window`"), "{stderr}");
    assert!(stderr.contains("helixhair sim --style"), "{stderr}");
}

#[cfg(feature = "window")]
#[test]
fn window_options_are_documented() {
    let output = helixhair(&["--help"]);
    assert!(output.status.success());
    let help = String::from_utf8_lossy(&output.stdout);
    assert!(
        help.contains("Without a command, helixhair opens the styling window"),
        "{help}"
    );
    for option in [
        "--style <FILE>",
        "--play <MOTION>",
        "--screenshot <PNG>",
        "--compare",
    ] {
        assert!(
            help.contains(option),
            "{option} missing from
{help}"
        );
    }
}

#[test]
fn sim_help_lists_every_option() {
    let output = helixhair(&["sim", "--help"]);
    assert!(output.status.success());
    let help = String::from_utf8_lossy(&output.stdout);
    for option in [
        "--style <FILE>",
        "--method <METHOD>",
        "--dt <SECS>",
        "--steps <K>",
        "--json <OUT>",
    ] {
        assert!(help.contains(option), "{option} missing from\n{help}");
    }
    assert!(help.contains("[default: 60]"), "{help}");
}

#[test]
fn sim_requires_a_style() {
    let output = helixhair(&["sim"]);
    assert_eq!(output.status.code(), Some(2), "a usage error");
    assert!(String::from_utf8_lossy(&output.stderr).contains("--style <FILE>"));
}

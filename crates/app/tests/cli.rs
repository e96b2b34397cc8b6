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

#[test]
fn no_command_prints_how_to_run_headless_and_succeeds() {
    let output = helixhair(&[]);
    assert!(output.status.success());
    assert_eq!(
        String::from_utf8_lossy(&output.stdout),
        helixhair_app::cli::NO_WINDOW_MESSAGE
    );
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

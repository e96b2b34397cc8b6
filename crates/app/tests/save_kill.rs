//! Kill tests for saving: a child process saving a style (`Style::save`,
//! which writes through `atomic_write`) is killed (SIGKILL) at random
//! points, hundreds of times; the file on disk must always be the old style
//! or the new one, whole, and load as a style.
//!
//! # How it works
//!
//! The test re-runs its own executable as the child, filtered to
//! [`saver_child_process`], with the target file in an environment
//! variable. The child writes two large styles (about 1 MB of RON, so a
//! write takes milliseconds and a kill lands inside one) alternately,
//! forever, with `write_atomically` and the text `Style::save` writes
//! (serialised once, so the child's time goes to writing), and prints a
//! line when it starts. The parent waits for that line, sleeps
//! a random time of up to a few saves, kills the child, and checks the
//! file. A kill inside a write leaves a temporary file next to the target
//! (never the target itself); the parent counts those rounds, and requires
//! some of them, so that the test shows it interrupted writes rather than
//! only the gaps between them.
//!
//! Reproduce the figures of `docs/reliability.md` with
//! `cargo test --release -p helixhair-app --test suite save_kill:: -- --nocapture`.

use crate::support;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use glam::DVec3;
use helixhair_app::Style;
use helixhair_app::atomic_write::write_atomically;
use helixhair_app::style::Root;
use support::kill::{Rng, child_test_name, clear_leftovers, run_and_kill};

/// The environment variable that makes [`saver_child_process`] the saver.
const CHILD_VAR: &str = "HELIXHAIR_SAVE_KILL_TARGET";

/// What the child prints once it starts writing.
const STARTED: &str = "writing styles";

/// Kills per run.
const ROUNDS: usize = 300;

/// Roots per group of the saved styles: enough RON (about 1 MB) that one
/// save takes milliseconds.
const ROOTS: usize = 1_000;

/// Fewest rounds, out of [`ROUNDS`], whose kill must land inside a write
/// (leaving its temporary file): a tenth.
const MIN_INTERRUPTED_WRITES: usize = ROUNDS / 10;

/// The two styles the child alternates between; `which` 0 or 1.
fn style(which: u32) -> Style {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/styles/curly.ron");
    let mut style = Style::load(&path).expect("the curly example loads");
    style.name = format!("kill-test-{which}");
    for group in &mut style.groups {
        group.roots = (0..ROOTS)
            .map(|i| {
                let a = i as f64 * 0.001 + f64::from(which);
                let position_m = DVec3::new(0.1 * a.cos(), 0.05, 0.1 * a.sin());
                Root::new(position_m, position_m)
            })
            .collect();
    }
    style
}

/// The child: with [`CHILD_VAR`] set, saves the two styles alternately
/// until killed; without it (a normal test run), does nothing.
#[test]
fn saver_child_process() {
    let Ok(target) = std::env::var(CHILD_VAR) else {
        return;
    };
    // What `Style::save` writes, serialised once so that the child spends
    // its time writing (where a kill matters) rather than serialising.
    let texts = [style(0), style(1)].map(|s| s.to_ron().expect("serialises"));
    println!("{STARTED}");
    for i in 0.. {
        write_atomically(Path::new(&target), texts[i % 2].as_bytes()).expect("saves");
    }
}

fn scratch_dir() -> PathBuf {
    support::kill::scratch_dir("helixhair-save-kill")
}

#[test]
fn a_save_killed_at_any_point_leaves_the_old_or_the_new_style_whole() {
    let styles = [style(0), style(1)];
    let texts = styles.clone().map(|s| s.to_ron().expect("serialises"));
    let dir = scratch_dir();
    let target = dir.join("style.ron");
    styles[0].save(&target).expect("the first save");
    // How long one write takes here, to spread the kills over a few.
    let start = Instant::now();
    write_atomically(&target, texts[0].as_bytes()).expect("a write");
    let save_secs = start.elapsed().as_secs_f64().max(1e-4);

    let seed = 0x5eed_0f1e_u64;
    let mut rng = Rng(seed);
    let mut interrupted = 0;
    let mut seen = [0usize; 2];
    for round in 0..ROUNDS {
        // Up to three writes.
        let delay = Duration::from_secs_f64(3.0 * save_secs * rng.next_unit());
        run_and_kill(
            &child_test_name(module_path!(), "saver_child_process"),
            CHILD_VAR,
            &target,
            STARTED,
            delay,
        );

        let on_disk = std::fs::read_to_string(&target).expect("the target exists");
        let which = texts.iter().position(|t| *t == on_disk).unwrap_or_else(|| {
            panic!(
                "round {round} (seed {seed:#x}): the file is neither style, {} bytes",
                on_disk.len()
            )
        });
        seen[which] += 1;
        Style::from_ron(&on_disk, &target).expect("what is on disk loads");
        // Temporary files of interrupted writes: count, then clear.
        let left = clear_leftovers(&dir, &target);
        interrupted += usize::from(left);
    }
    eprintln!(
        "save_kill: {ROUNDS} kills (seed {seed:#x}, one write ≈ {:.1} ms, {} bytes): the file was \
         whole every time (old/new style {}/{}); {interrupted} kills landed inside a write",
        save_secs * 1e3,
        texts[0].len(),
        seen[0],
        seen[1]
    );
    assert!(
        interrupted >= MIN_INTERRUPTED_WRITES,
        "only {interrupted} of {ROUNDS} kills landed inside a write"
    );
    std::fs::remove_dir_all(&dir).expect("clean up");
}

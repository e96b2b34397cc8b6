//! Kill tests for exporting: a child process exporting the curly example's
//! simulated strands (the export path `helixhair export` and `sim --export`
//! take: `ExportRecorder::write_single`, the format's writer, then
//! `atomic_write`) is killed (SIGKILL) at random points, 75 times for each
//! of the seven formats; the file on disk must always be the old export or the new
//! one, whole, and read back with our reader.
//!
//! # How it works
//!
//! As `save_kill.rs`: the test re-runs its own executable as the child,
//! filtered to [`exporter_child_process`], with the target file in an
//! environment variable. The child grows the curly example on the default
//! head once (without the head's collision field, which no export reads),
//! then exports its simulated strands alternately at two point counts (two
//! different files of tens of kilobytes) forever, and prints a line when it
//! starts. Simulated, not drawn, strands: capturing the
//! thousand drawn strands takes most of an export's time, so few kills
//! would land inside the write, which is what the test is about. The parent writes both exports itself
//! first (the exports are deterministic), waits for the child's line,
//! sleeps a random time of up to three exports, kills the child, and checks
//! that the file is byte for byte one of the two and that the format's
//! reader reads it. It counts the kills that left a temporary file (a kill
//! inside a write) and requires some, so the test shows it interrupted
//! writes rather than only the gaps between them.
//!
//! Reproduce the figures of `docs/reliability.md` with
//! `cargo test --release -p helixhair-app --test suite export_kill:: -- --nocapture`.

use crate::support;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use helixhair_app::export::{ExportRecorder, ExportSpec, FrameChoice, StrandChoice};
use helixhair_app::{Groom, HeadlessSim, SimOverrides, Style};
use helixhair_formats::{Format, ReadOptions, read};
use helixhair_render::head_generate::default_head;
use support::kill::{Rng, child_test_name, clear_leftovers, run_and_kill};

/// The environment variable that makes [`exporter_child_process`] the
/// exporter; its value is the target file, whose extension picks the format.
const CHILD_VAR: &str = "HELIXHAIR_EXPORT_KILL_TARGET";

/// What the child prints once it starts exporting.
const STARTED: &str = "exporting";

/// Kills per format; seven formats, 525 kills in all. Each kill costs a
/// child's start (growing the curly example, a few milliseconds), most of
/// the test's time.
const ROUNDS_PER_FORMAT: usize = 75;

/// The two point counts the child alternates between: two different files
/// (TressFX needs powers of two).
const POINTS: [usize; 2] = [16, 32];

/// Fewest kills per format that must land inside a write (leaving its
/// temporary file): a tenth.
const MIN_INTERRUPTED_WRITES: usize = ROUNDS_PER_FORMAT / 10;

/// The curly example grown on the default head, at rest, as `grown_sim`
/// grows it but without the head's collision field and the settle on it:
/// an export reads neither (it writes the strands and the drawn head), and
/// building the field was most of each child's start (0.7 to 1.1 s).
fn curly() -> (Groom, HeadlessSim) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/styles/curly.ron");
    let style = Style::load(&path).expect("the curly example loads");
    let groom = Groom::new(style, default_head());
    let sim = HeadlessSim::new(&groom.grown, SimOverrides::default()).expect("it simulates");
    (groom, sim)
}

/// Exports the simulated strands of `sim` to `path` with `points` per strand.
fn export(groom: &Groom, sim: &HeadlessSim, path: &Path, points: usize) {
    let spec = ExportSpec::new(
        path,
        StrandChoice::Simulated,
        points,
        FrameChoice::Last,
        false,
    )
    .expect("a valid spec");
    ExportRecorder::new(spec, sim.engine().settings().dt_secs)
        .write_single(sim.engine(), Some(groom), None)
        .expect("exports");
}

/// The child: with [`CHILD_VAR`] set, exports alternately until killed;
/// without it (a normal test run), does nothing.
#[test]
fn exporter_child_process() {
    let Ok(target) = std::env::var(CHILD_VAR) else {
        return;
    };
    let (groom, sim) = curly();
    println!("{STARTED}");
    for i in 0.. {
        export(&groom, &sim, Path::new(&target), POINTS[i % 2]);
    }
}

fn scratch_dir() -> PathBuf {
    support::kill::scratch_dir("helixhair-export-kill")
}

/// Kills the exporting child `ROUNDS_PER_FORMAT` times for `format`;
/// returns the kills that landed inside a write.
fn kill_exports(format: Format, rng: &mut Rng, seed: u64) -> usize {
    let (groom, sim) = curly();
    let dir = scratch_dir().join(format.to_string());
    std::fs::create_dir_all(&dir).expect("a folder per format");
    let target = dir.join(format!("curly.{format}"));
    // The two files the child writes, made here by the same code.
    let mut expected = Vec::new();
    for points in POINTS {
        export(&groom, &sim, &target, points);
        expected.push(std::fs::read(&target).expect("the export exists"));
    }
    assert_ne!(expected[0], expected[1], "the two exports differ");
    let start = Instant::now();
    export(&groom, &sim, &target, POINTS[1]);
    let export_secs = start.elapsed().as_secs_f64().max(1e-4);

    let mut interrupted = 0;
    let mut seen = [0usize; 2];
    for round in 0..ROUNDS_PER_FORMAT {
        let delay = Duration::from_secs_f64(3.0 * export_secs * rng.next_unit());
        run_and_kill(
            &child_test_name(module_path!(), "exporter_child_process"),
            CHILD_VAR,
            &target,
            STARTED,
            delay,
        );

        let on_disk = std::fs::read(&target).expect("the target exists");
        let which = expected
            .iter()
            .position(|e| *e == on_disk)
            .unwrap_or_else(|| {
                panic!(
                    "{format} round {round} (seed {seed:#x}): the file is neither export, {} bytes",
                    on_disk.len()
                )
            });
        seen[which] += 1;
        let imported =
            read(&on_disk, format, &ReadOptions::default()).expect("what is on disk reads");
        assert!(!imported.curves.curves.is_empty(), "strands read back");
        let left = clear_leftovers(&dir, &target);
        interrupted += usize::from(left);
    }
    eprintln!(
        "export_kill {format}: {ROUNDS_PER_FORMAT} kills, one export ≈ {:.1} ms ({} / {} bytes): \
         the file was whole every time ({}/{} of each); {interrupted} kills landed inside a write",
        export_secs * 1e3,
        expected[0].len(),
        expected[1].len(),
        seen[0],
        seen[1]
    );
    interrupted
}

#[test]
fn an_export_killed_at_any_point_leaves_the_old_or_the_new_file_whole() {
    let seed = 0xe4b0_f1e5_u64;
    let mut rng = Rng(seed);
    for format in Format::ALL {
        let interrupted = kill_exports(format, &mut rng, seed);
        assert!(
            interrupted >= MIN_INTERRUPTED_WRITES,
            "{format}: only {interrupted} of {ROUNDS_PER_FORMAT} kills landed inside a write"
        );
    }
    let _ = std::fs::remove_dir_all(scratch_dir());
}

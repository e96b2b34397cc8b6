//! Study `soak`: a full head stepped for a long time under random head
//! motion, on both engines, watching for what only shows after hours: a
//! NaN, a guard caught in a loop of resets, memory that creeps.
//!
//! Scene: `assets/styles/groomed/full_head.ron` (3,000 curly strands of 15
//! elements grown on the default head) with the head's collider, its
//! style's settings (Exact, 1/60 s, one substep), moved by
//! [`SoakMotion`]: the window's clips (nod, shake, turn, jerk) in a seeded
//! random order with pauses of up to a second. The batch engine is the
//! style's own; the f64 reference steps the same hair (many times slower
//! per frame: the throughput study), so `--soak-steps` sets how far each
//! engine goes.
//!
//! Every [`sample_every`] frames it records the process's resident memory
//! (`VmRSS` of `/proc/self/status`; Linux), the hair's kinetic energy and
//! the guard's running counts into `soak.csv`, and draws `soak_memory.svg`
//! and `soak_guard.svg`. A frame that leaves a non-finite state ends the
//! engine's run, and the study then fails (after writing its files): a
//! soak that finds a NaN must not pass.
//!
//! What counts as a loop: the guard pins a strand that fails
//! `resets_before_pinning` times within its hold window, or
//! `long_resets_before_pinning` times each within `long_window_frames` of
//! the previous (`helixhair_physics::ResetMemory`), so resets are bounded by design; the soak checks it by the resets per sample window
//! staying flat rather than growing, and reports the most in any window.

pub mod motion;

use std::time::Instant;

use anyhow::{Context as _, bail};
use helixhair_physics::engine::{Engine, EngineKind};
use helixhair_physics::guard::GuardAction;
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, Series, draw_line_chart};
use super::table::write_csv;
use crate::bench::soak::motion::SoakMotion;
use helixhair_render::head_generate::default_head;

use crate::head::groom::Groom;
use crate::sim::build::SimOverrides;
use crate::sim::headless::HeadlessSim;
use crate::style::Style;

/// The soak's style: the full head.
const FULL_HEAD_RON: &str = include_str!("../../../../../assets/styles/groomed/full_head.ron");

/// Frames per engine unless `--soak-steps` says otherwise (full, quick).
pub const SOAK_STEPS: (usize, usize) = (1_000_000, 300);

/// Seed of the head motion's schedule.
pub const SEED: u64 = 2026;

/// Frames between two samples: about 200 samples a run, at least one a
/// second of simulated time.
pub fn sample_every(steps: usize) -> usize {
    (steps / 200).max(60)
}

/// `--soak-engine`'s parser: an engine as [`EngineKind::label`] spells it
/// (the bench does not lean on the command line's module for it).
pub fn parse_engine(name: &str) -> Result<EngineKind, String> {
    EngineKind::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = EngineKind::ALL.iter().map(|k| k.label()).collect();
        format!("unknown engine `{name}`; expected {}", names.join(" or "))
    })
}

/// One row of `soak.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct SoakRow {
    /// `reference` or `batch`.
    pub engine: String,
    /// Frames stepped so far.
    pub step: usize,
    /// Simulated time, seconds.
    pub time_secs: f64,
    /// Wall time since this engine's run started, seconds.
    pub wall_secs: f64,
    /// Resident memory of the process, MiB.
    pub rss_mib: f64,
    /// Kinetic energy of all the hair, joules.
    pub kinetic_j: f64,
    /// Guard retries (reference engine: a frame redone with Exact and
    /// substeps; the strand kept its motion) so far.
    pub retries: usize,
    /// Guard resets so far.
    pub resets: usize,
    /// Strands pinned so far.
    pub pins: usize,
    /// Resets and pins in the frames since the previous sample.
    pub losses_in_window: usize,
}

/// What one engine's run ended with.
struct Outcome {
    rows: Vec<SoakRow>,
    not_finite_at: Option<usize>,
    /// The wall-clock budget ran out before the last frame.
    out_of_time: bool,
}

/// How far each engine's run goes.
#[derive(Clone, Copy, Debug)]
pub struct SoakLength {
    /// Frames per engine (default [`SOAK_STEPS`]).
    pub steps: Option<usize>,
    /// Wall-clock budget per engine, minutes: the run stops there and
    /// reports how far it got (a million frames of the f64 reference take
    /// days on a small machine).
    pub minutes: Option<f64>,
}

/// Runs the study for `steps` frames per engine (default [`SOAK_STEPS`]).
pub fn run(
    ctx: &mut BenchContext<'_>,
    length: SoakLength,
    engines: &[EngineKind],
) -> anyhow::Result<()> {
    let steps = length.steps.unwrap_or(if ctx.quick {
        SOAK_STEPS.1
    } else {
        SOAK_STEPS.0
    });
    let budget_secs = length.minutes.map_or(f64::INFINITY, |m| 60.0 * m);
    let style = Style::from_ron(FULL_HEAD_RON, "full_head.ron".as_ref())
        .context("the built-in full-head style")?;
    let groom = Groom::new(style, default_head());
    let collider = std::sync::Arc::new(groom.collider().context("the default head's collider")?);
    let duration_secs = steps as f64 * groom.grown.sim.dt_secs;
    let motion = SoakMotion::new(SEED, duration_secs);
    let [nod, shake, turn, jerk] = motion.clip_counts();
    writeln!(
        ctx.log,
        "   {steps} frames per engine = {duration_secs:.0} s simulated; seed {SEED}: \
         {nod} nods, {shake} shakes, {turn} turns, {jerk} jerks"
    )?;
    let mut rows = Vec::new();
    let mut failures = Vec::new();
    for &kind in engines {
        let overrides = SimOverrides {
            engine: Some(kind),
            ..SimOverrides::default()
        };
        let mut sim =
            HeadlessSim::new(&groom.grown, overrides).context("building the full head")?;
        let engine = sim.engine_mut();
        engine.set_collider(Some(collider.clone()));
        let outcome = soak(engine, &motion, steps, budget_secs)?;
        summarise(ctx, kind, &outcome)?;
        if let Some(step) = outcome.not_finite_at {
            failures.push(format!("{}: not finite at frame {step}", kind.label()));
        }
        rows.extend(outcome.rows);
    }
    write_csv(&ctx.file("soak.csv"), &rows)?;
    draw(ctx, &rows, engines)?;
    if !failures.is_empty() {
        bail!("the soak failed: {}", failures.join("; "));
    }
    Ok(())
}

/// Steps `engine` under `motion` for `steps` frames, sampling as it goes.
fn soak(
    engine: &mut Engine,
    motion: &SoakMotion,
    steps: usize,
    budget_secs: f64,
) -> anyhow::Result<Outcome> {
    let every = sample_every(steps);
    let start = Instant::now();
    let (mut retries, mut resets, mut pins, mut window) = (0, 0, 0, 0);
    let mut rows = Vec::with_capacity(steps / every + 2);
    let label = engine.kind().label().to_owned();
    let sample = |engine: &Engine, step, window: usize, counts: (usize, usize, usize)| {
        Ok::<_, anyhow::Error>(SoakRow {
            engine: label.clone(),
            step,
            time_secs: engine.time_secs(),
            wall_secs: start.elapsed().as_secs_f64(),
            rss_mib: resident_mib()?,
            kinetic_j: engine.energies().kinetic_j,
            retries: counts.0,
            resets: counts.1,
            pins: counts.2,
            losses_in_window: window,
        })
    };
    rows.push(sample(engine, 0, 0, (0, 0, 0))?);
    for step in 1..=steps {
        engine.step_frame(motion);
        if let Some(reference) = engine.reference() {
            for event in reference.last_guard_events() {
                match event.action {
                    GuardAction::Retried { .. } => retries += 1,
                    GuardAction::Reset => resets += 1,
                    GuardAction::Pinned => pins += 1,
                }
                window += usize::from(!matches!(event.action, GuardAction::Retried { .. }));
            }
        }
        if let Some(batch) = engine.batch() {
            resets += batch.last_guard_resets().len();
            pins += batch.last_guard_pins().len();
            window += batch.last_guard_resets().len() + batch.last_guard_pins().len();
        }
        if !engine.is_finite() {
            rows.push(sample(engine, step, window, (retries, resets, pins))?);
            return Ok(Outcome {
                rows,
                not_finite_at: Some(step),
                out_of_time: false,
            });
        }
        let out_of_time = start.elapsed().as_secs_f64() > budget_secs;
        if step % every == 0 || step == steps || out_of_time {
            rows.push(sample(engine, step, window, (retries, resets, pins))?);
            window = 0;
        }
        if out_of_time && step < steps {
            return Ok(Outcome {
                rows,
                not_finite_at: None,
                out_of_time: true,
            });
        }
    }
    Ok(Outcome {
        rows,
        not_finite_at: None,
        out_of_time: false,
    })
}

/// The process's resident memory in MiB (`VmRSS`, Linux).
fn resident_mib() -> anyhow::Result<f64> {
    let status = std::fs::read_to_string("/proc/self/status")
        .context("reading /proc/self/status (the soak's memory figure needs Linux)")?;
    let kib = status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .context("no VmRSS line in /proc/self/status")?;
    Ok(kib / 1024.0)
}

/// Logs one engine's headline figures.
fn summarise(
    ctx: &mut BenchContext<'_>,
    kind: EngineKind,
    outcome: &Outcome,
) -> anyhow::Result<()> {
    let rows = &outcome.rows;
    let (Some(first), Some(last)) = (rows.get(1).or(rows.first()), rows.last()) else {
        return Ok(());
    };
    let worst_window = rows.iter().map(|r| r.losses_in_window).max().unwrap_or(0);
    let rss_max = rows.iter().map(|r| r.rss_mib).fold(0.0, f64::max);
    writeln!(
        ctx.log,
        "   {}: {} frames in {:.0} s ({:.2} ms a frame); {}; guard: {} retries, {} resets, \
         {} pins, at most {} losses in a window; memory {:.1} MiB after the first window, \
         {:.1} MiB at the end, {:.1} MiB at most",
        kind.label(),
        last.step,
        last.wall_secs,
        1e3 * last.wall_secs / last.step.max(1) as f64,
        match (outcome.not_finite_at, outcome.out_of_time) {
            (Some(step), _) => format!("NOT FINITE at frame {step}"),
            (None, true) => "finite throughout; stopped by the time budget".to_owned(),
            (None, false) => "finite throughout".to_owned(),
        },
        last.retries,
        last.resets,
        last.pins,
        worst_window,
        first.rss_mib,
        last.rss_mib,
        rss_max,
    )?;
    Ok(())
}

/// Memory and guard losses against frames, one series per engine.
fn draw(ctx: &BenchContext<'_>, rows: &[SoakRow], engines: &[EngineKind]) -> anyhow::Result<()> {
    let series = |value: fn(&SoakRow) -> f64| -> Vec<Series> {
        engines
            .iter()
            .enumerate()
            .map(|(i, kind)| {
                let label = kind.label().to_owned();
                Series {
                    name: label.clone(),
                    points: rows
                        .iter()
                        .filter(|r| r.engine == label)
                        .map(|r| (r.step as f64, value(r)))
                        .collect(),
                    line: true,
                    markers: false,
                    colour: i,
                }
            })
            .collect()
    };
    let frames = Axis {
        label: "frames (1/60 s each)".into(),
        log: false,
    };
    draw_line_chart(
        &ctx.file("soak_memory.svg"),
        &LineChart {
            title: "Soak: resident memory of the process".into(),
            x: frames.clone(),
            y: Axis {
                label: "resident memory, MiB".into(),
                log: false,
            },
            series: series(|r| r.rss_mib),
        },
    )?;
    draw_line_chart(
        &ctx.file("soak_guard.svg"),
        &LineChart {
            title: "Soak: strands reset or pinned by the guard, running total".into(),
            x: frames,
            y: Axis {
                label: "resets + pins so far".into(),
                log: false,
            },
            series: series(|r| (r.resets + r.pins) as f64),
        },
    )
}

//! Study `volume-cost`: what the hair–hair model (docs/volume.md) costs a
//! frame of the full head on both engines.
//!
//! For each engine (reference f64, batch f32), each size (3,000 and
//! 10,000 strands of `full_head.ron`, its guides scaled) and each
//! combination of model on/off and guard on/off: one warm-up frame (it
//! builds the rest density), then the median wall time of repeated frames
//! (9 on the reference, 45 on the batch engine, whose frames are ~10×
//! shorter) and the median of the model's own pass in them (gather,
//! splat, read-back, timed inside the engine). The guard on/off pairs
//! separate the model's pass from what the model costs the guard: its
//! work must be in the energy balance at both ends of the frame. The
//! 1-minute load average (`/proc/loadavg`) is recorded with every case:
//! the machine is shared, and a timing means little without it. The whole
//! set of cases is run [`RUNS`] times, one after another, and each figure
//! is the median over the runs, with the runs' lowest and highest share of
//! the frame beside it: a shared machine slows for seconds at a time, so
//! one case's run can land in a slow second (single studies of one build
//! within an hour read the batch engine's share at 3,000 strands with the
//! guard as 30% to 34%; the groom study saw single runs vary by half,
//! [`crate::bench::groom`]).
//!
//! Files: `volume_cost.csv` and `volume_cost.svg` (share of the frame,
//! guard on). Quick mode: 70 strands, 2 and 3 frames.

use anyhow::Context as _;
use helixhair_physics::engine::EngineKind;
use serde::Serialize;

use crate::bench::BenchContext;
use crate::bench::chart::{Axis, LineChart, Series, draw_line_chart};
use crate::bench::table::write_csv;
use crate::bench::volume::{build, scaled_groom};
use crate::stats::median;

/// Runs of the whole study (full, quick); see the module docs.
pub const RUNS: (usize, usize) = (3, 1);

/// One line of `volume_cost.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct CostRow {
    /// `reference` or `batch`.
    pub engine: String,
    /// Simulated strands.
    pub strands: usize,
    /// Whether the model was on.
    pub interaction: bool,
    /// Whether the stability guard was on.
    pub guard: bool,
    /// Frames timed per run (after one warm-up).
    pub frames: usize,
    /// Runs (module docs).
    pub runs: usize,
    /// Wall time of a frame, seconds: the median over the runs of each
    /// run's median.
    pub median_frame_secs: f64,
    /// Wall time of the model's own pass in a frame, seconds, likewise.
    pub median_volume_secs: f64,
    /// The lowest of the runs' shares of the pass in the frame (each run's
    /// median pass over its median frame), percent.
    pub share_low_percent: f64,
    /// The highest of them, percent.
    pub share_high_percent: f64,
    /// The highest 1-minute load average at the end of a run of the case
    /// (`/proc/loadavg`).
    pub load_1m: f64,
}

/// The 1-minute load average, or NaN where `/proc/loadavg` is unreadable.
fn load_1m() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(f64::NAN)
}

/// Runs the study.
pub fn cost(ctx: &mut BenchContext<'_>) -> anyhow::Result<()> {
    let counts: &[usize] = if ctx.quick { &[70] } else { &[3000, 10000] };
    let runs = if ctx.quick { RUNS.1 } else { RUNS.0 };
    let grooms = counts
        .iter()
        .map(|&count| scaled_groom(count))
        .collect::<anyhow::Result<Vec<_>>>()?;
    // Every case's run, the runs one after another.
    let mut cases: Vec<Vec<RunTiming>> = Vec::new();
    for _ in 0..runs {
        let mut k = 0;
        for groom in &grooms {
            for engine in EngineKind::CPU {
                for guard in [true, false] {
                    for on in [false, true] {
                        let timed = frames_timed(ctx.quick, engine);
                        let run = time_case(groom, engine, on, guard, timed)?;
                        if cases.len() <= k {
                            cases.push(Vec::new());
                        }
                        cases[k].push(run);
                        k += 1;
                    }
                }
            }
        }
    }
    let mut rows = Vec::new();
    for runs in &cases {
        let row = summarize(runs);
        writeln!(
            ctx.log,
            "   {} {} strands, model {}, guard {}: {:.4} s a frame, model's pass \
             {:.4} s ({:.0}%; runs {:.0}-{:.0}%), load up to {:.1}",
            row.engine,
            row.strands,
            if row.interaction { "on" } else { "off" },
            if row.guard { "on" } else { "off" },
            row.median_frame_secs,
            row.median_volume_secs,
            100.0 * row.median_volume_secs / row.median_frame_secs,
            row.share_low_percent,
            row.share_high_percent,
            row.load_1m
        )?;
        rows.push(row);
    }
    write_csv(&ctx.file("volume_cost.csv"), &rows)?;
    draw(ctx, &rows)
}

/// Frames timed per run: the reference's frames are ~10× longer.
fn frames_timed(quick: bool, engine: EngineKind) -> usize {
    match (quick, engine) {
        (true, EngineKind::Reference) => 2,
        (true, EngineKind::Batch | EngineKind::Gpu) => 3,
        (false, EngineKind::Reference) => 9,
        (false, EngineKind::Batch | EngineKind::Gpu) => 45,
    }
}

/// One run of one case: its row's identity and each frame's wall time and
/// model pass.
struct RunTiming {
    engine: EngineKind,
    strands: usize,
    on: bool,
    guard: bool,
    frame_secs: Vec<f64>,
    volume_secs: Vec<f64>,
    load_1m: f64,
}

fn time_case(
    groom: &crate::head::groom::Groom,
    engine: EngineKind,
    on: bool,
    guard: bool,
    timed: usize,
) -> anyhow::Result<RunTiming> {
    let mut sim = build(groom, engine, on)?;
    if !guard {
        sim.engine_mut().set_guard(None);
    }
    sim.run(1).context("warming up")?;
    let mut frame_secs = Vec::new();
    let mut volume_secs = Vec::new();
    for _ in 0..timed {
        frame_secs.push(sim.step());
        volume_secs.push(sim.engine().volume_secs());
    }
    Ok(RunTiming {
        engine,
        strands: sim.engine().strand_count(),
        on,
        guard,
        frame_secs,
        volume_secs,
        load_1m: load_1m(),
    })
}

/// The row of one case's runs (at least one).
fn summarize(runs: &[RunTiming]) -> CostRow {
    let first = &runs[0];
    let frames: Vec<f64> = runs.iter().map(|r| median(&r.frame_secs)).collect();
    let passes: Vec<f64> = runs.iter().map(|r| median(&r.volume_secs)).collect();
    let shares = frames.iter().zip(&passes).map(|(f, p)| 100.0 * p / f);
    let (low, high) = shares.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
        (lo.min(s), hi.max(s))
    });
    CostRow {
        engine: first.engine.label().to_owned(),
        strands: first.strands,
        interaction: first.on,
        guard: first.guard,
        frames: first.frame_secs.len(),
        runs: runs.len(),
        median_frame_secs: median(&frames),
        median_volume_secs: median(&passes),
        share_low_percent: low,
        share_high_percent: high,
        load_1m: runs.iter().map(|r| r.load_1m).fold(f64::NAN, f64::max),
    }
}

/// Per engine, with the guard on: the model's pass over the frame with
/// it, and the whole frame's extra, (on − off)/on, in percent.
fn draw(ctx: &BenchContext<'_>, rows: &[CostRow]) -> anyhow::Result<()> {
    let find = |engine: &str, strands: usize, on: bool| {
        rows.iter()
            .find(|r| r.engine == engine && r.strands == strands && r.interaction == on && r.guard)
    };
    let mut series = Vec::new();
    for (i, engine) in EngineKind::CPU.iter().map(|e| e.label()).enumerate() {
        let sizes = rows
            .iter()
            .filter(|r| r.engine == engine && r.interaction && r.guard);
        let (mut pass, mut extra) = (Vec::new(), Vec::new());
        for with in sizes {
            let x = with.strands as f64;
            pass.push((x, 100.0 * with.median_volume_secs / with.median_frame_secs));
            if let Some(without) = find(engine, with.strands, false) {
                let frame = with.median_frame_secs;
                extra.push((x, 100.0 * (frame - without.median_frame_secs) / frame));
            }
        }
        for (j, (name, points)) in [("model's pass / frame", pass), ("(on − off) / on", extra)]
            .into_iter()
            .enumerate()
        {
            series.push(Series {
                name: format!("{engine}: {name}"),
                points,
                line: true,
                markers: true,
                colour: 2 * i + j,
            });
        }
    }
    draw_line_chart(
        &ctx.file("volume_cost.svg"),
        &LineChart {
            title: "Full head: the hair–hair model's share of a frame (guard on)".to_owned(),
            x: Axis {
                label: "strands".to_owned(),
                log: false,
            },
            y: Axis {
                label: "percent of the frame with the model".to_owned(),
                log: false,
            },
            series,
        },
    )
}

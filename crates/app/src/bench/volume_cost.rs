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
//! the machine is shared, and a timing means little without it.
//!
//! Files: `volume_cost.csv` and `volume_cost.svg` (share of the frame,
//! guard on). Quick mode: 70 strands, 2 and 3 frames.

use anyhow::Context as _;
use helixhair_physics::engine::EngineKind;
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, Series, draw_line_chart};
use super::table::write_csv;
use super::volume::{build, scaled_groom};
use crate::stats::median;

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
    /// Frames timed (after one warm-up).
    pub frames: usize,
    /// Median wall time of a frame, seconds.
    pub median_frame_secs: f64,
    /// Median wall time of the model's own pass in a frame, seconds.
    pub median_volume_secs: f64,
    /// 1-minute load average at the end of the case (`/proc/loadavg`).
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
    let mut rows = Vec::new();
    for &count in counts {
        let groom = scaled_groom(count)?;
        for engine in EngineKind::ALL {
            let timed = match (ctx.quick, engine) {
                (true, EngineKind::Reference) => 2,
                (true, EngineKind::Batch) => 3,
                (false, EngineKind::Reference) => 9,
                (false, EngineKind::Batch) => 45,
            };
            for guard in [true, false] {
                for on in [false, true] {
                    let row = case(&groom, engine, on, guard, timed)?;
                    writeln!(
                        ctx.log,
                        "   {} {} strands, model {}, guard {}: {:.4} s a frame, model's pass \
                         {:.4} s ({:.0}%), load {:.1}",
                        row.engine,
                        row.strands,
                        if on { "on" } else { "off" },
                        if guard { "on" } else { "off" },
                        row.median_frame_secs,
                        row.median_volume_secs,
                        100.0 * row.median_volume_secs / row.median_frame_secs,
                        row.load_1m
                    )?;
                    rows.push(row);
                }
            }
        }
    }
    write_csv(&ctx.file("volume_cost.csv"), &rows)?;
    draw(ctx, &rows)
}

fn case(
    groom: &crate::groom::Groom,
    engine: EngineKind,
    on: bool,
    guard: bool,
    timed: usize,
) -> anyhow::Result<CostRow> {
    let mut sim = build(groom, engine, on)?;
    if !guard {
        sim.engine_mut().set_guard(None);
    }
    sim.run(1).context("warming up")?;
    let mut frames = Vec::new();
    let mut model = Vec::new();
    for _ in 0..timed {
        frames.push(sim.step());
        model.push(sim.engine().volume_secs());
    }
    Ok(CostRow {
        engine: engine.label().to_owned(),
        strands: sim.engine().strand_count(),
        interaction: on,
        guard,
        frames: timed,
        median_frame_secs: median(&frames),
        median_volume_secs: median(&model),
        load_1m: load_1m(),
    })
}

/// Per engine, with the guard on: the model's pass over the frame with
/// it, and the whole frame's extra, (on − off)/on, in percent.
fn draw(ctx: &BenchContext<'_>, rows: &[CostRow]) -> anyhow::Result<()> {
    let find = |engine: &str, strands: usize, on: bool| {
        rows.iter()
            .find(|r| r.engine == engine && r.strands == strands && r.interaction == on && r.guard)
    };
    let mut series = Vec::new();
    for (i, engine) in EngineKind::ALL.iter().map(|e| e.label()).enumerate() {
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

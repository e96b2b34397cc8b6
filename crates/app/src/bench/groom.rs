//! Study `groom`: the physics milliseconds of one 60 Hz frame of a whole
//! groom, every strand simulated (issue 11's target: under 8 ms), and
//! where a frame goes.
//!
//! `helixhair bench --study groom --style STYLE.ron [--head MESH.obj]`
//! builds the style's hair on the batch engine (the engine an import
//! writes) with the head's collider (`--head`, else the `head` an imported
//! group names, else the default head), and steps it on a still head:
//! [`WARM_UP_FRAMES`] frames, then [`FRAMES`] frames each timed alone, on
//! one thread and on all threads. That run is made [`RUNS`] times, every
//! variant in turn each time, and each figure is the median over the runs
//! of each run's median frame, with the runs' lowest and highest median
//! beside it: a shared machine slows down for seconds at a time (measured
//! on the 2-core development machine at a load average under 1: of 13
//! single runs, 4 read 23–25 ms a frame on one thread against 15–16 ms in
//! the rest), so one run's median can be a slow second's, and the median
//! of several is the figure that does not move from one try to the next.
//! The 90th percentile is over every timed frame of every run; the load
//! average is read before each run (`/proc/loadavg`) and the highest
//! kept. On one thread the
//! row also gives the thread's own CPU time per frame
//! (`/proc/thread-self/schedstat`: time on a core, not waiting for one),
//! which a busy machine inflates far less than the wall time: the work a
//! frame is, whoever else runs. The scheduler adds to it at its ticks and
//! switches, so it is exact to a few milliseconds over the whole run: good
//! for a groom's frames of tens of milliseconds, not for a small style's.
//!
//! Where a frame goes is measured by taking parts away, each variant
//! stepping the same groom from its own rest: `full` (the style's settings:
//! Exact, velocity-implicit, collider, guard), `no-guard` (the guard's two
//! sweeps per frame), `no-collider` (the contact lookups),
//! `velocity-explicit` (GMRES's iterations) and `block-diagonal`
//! (velocity-explicit Block-diagonal: the elimination's share). A
//! difference of medians is that part's cost, to within the noise of a
//! shared machine; each variant is timed on both thread counts in turn.
//!
//! Files: `groom.csv` (one row per variant and thread count) and
//! `groom.svg` (the full variant's frame times, every run's in turn,
//! against the 8 ms target).
//! The log gives the lanes used and padded.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use anyhow::Context as _;
use helixhair_physics::batch::BatchSystem;
use helixhair_physics::engine::EngineKind;
use helixhair_physics::{Method, RigidMotion, StepScheme};
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, Series, draw_line_chart};
use super::table::write_csv;
use crate::head::groom::Groom;
use crate::head::load_head;
use crate::sim::build::SimOverrides;
use crate::sim::headless::HeadlessSim;
use crate::stats::median;
use crate::style::Style;

/// The physics budget of one 60 Hz frame, milliseconds (issue 11).
pub const FRAME_BUDGET_MS: f64 = 8.0;
/// Untimed frames before each run: the first frames settle the contact.
pub const WARM_UP_FRAMES: usize = 10;
/// Timed frames per run (full, quick): one second of simulated time.
pub const FRAMES: (usize, usize) = (60, 5);
/// Runs of every variant (full, quick); see the module docs.
pub const RUNS: (usize, usize) = (5, 1);

/// What to time: the style and its head.
#[derive(Clone, Debug)]
pub struct GroomInput {
    /// The style (`--style`).
    pub style: PathBuf,
    /// The head mesh (`--head`); see the module docs for the default.
    pub head: Option<PathBuf>,
}

/// One row of `groom.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct GroomRow {
    /// `full`, `no-guard`, `no-collider`, `velocity-explicit` or
    /// `block-diagonal` (module docs).
    pub variant: String,
    /// Worker threads: 1, or every core.
    pub threads: usize,
    /// Timed frames per run.
    pub frames: usize,
    /// Runs (module docs).
    pub runs: usize,
    /// Physics time of a frame, milliseconds: the median over the runs of
    /// each run's median frame.
    pub median_ms: f64,
    /// The lowest of the runs' medians, milliseconds.
    pub run_median_low_ms: f64,
    /// The highest of the runs' medians, milliseconds.
    pub run_median_high_ms: f64,
    /// 90th percentile of every timed frame of every run, milliseconds.
    pub p90_ms: f64,
    /// Fastest frame, milliseconds.
    pub min_ms: f64,
    /// One thread only: the thread's CPU time per frame, milliseconds, the
    /// median over the runs of each run's mean over its timed frames (NaN
    /// on several threads, whose work is spread over rayon's workers, or
    /// without `/proc/thread-self`).
    pub cpu_ms: f64,
    /// One thread only: time per frame spent ready but waiting for a core,
    /// milliseconds (what the machine's other work took), as `cpu_ms`.
    pub waiting_ms: f64,
    /// The highest one-minute load average at a run's start (NaN where
    /// `/proc/loadavg` cannot be read).
    pub load_1min: f64,
    /// Strands simulated.
    pub strands: usize,
    /// Elements over all strands.
    pub elements: usize,
    /// Lane batches.
    pub batches: usize,
    /// Lanes of padding (batches × 8 − strands).
    pub padding_lanes: usize,
    /// Guard resets and pins during the timed frames.
    pub guard_losses: usize,
}

/// The one-minute load average, or NaN.
fn load_1min() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(f64::NAN)
}

/// This thread's time on a core and time waiting for one, nanoseconds
/// (`/proc/thread-self/schedstat`; Linux), or `None`.
fn thread_times_ns() -> Option<(u64, u64)> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let mut fields = text.split_whitespace().map(|f| f.parse::<u64>().ok());
    Some((fields.next()??, fields.next()??))
}

/// The head an imported group of `style` names, relative to the style.
fn imported_head(style: &Style, style_path: &Path) -> Option<PathBuf> {
    let name = style
        .groups
        .iter()
        .find_map(|g| g.imported.as_ref()?.head.clone())?;
    Some(style_path.parent().unwrap_or(Path::new(".")).join(name))
}

/// One way of stepping the groom (module docs).
#[derive(Clone, Copy, Debug)]
struct Variant {
    name: &'static str,
    /// Solver, when not the style's.
    method: Option<Method>,
    /// Step scheme, when not the style's.
    scheme: Option<StepScheme>,
    collider: bool,
    guard: bool,
}

const FULL: Variant = Variant {
    name: "full",
    method: None,
    scheme: None,
    collider: true,
    guard: true,
};

/// The full step, then each with a part taken away.
const VARIANTS: [Variant; 5] = [
    FULL,
    Variant {
        name: "no-guard",
        guard: false,
        ..FULL
    },
    Variant {
        name: "no-collider",
        collider: false,
        ..FULL
    },
    Variant {
        name: "velocity-explicit",
        scheme: Some(StepScheme::VelocityExplicit),
        ..FULL
    },
    Variant {
        name: "block-diagonal",
        method: Some(Method::BlockDiagonal),
        scheme: Some(StepScheme::VelocityExplicit),
        ..FULL
    },
];

impl GroomInput {
    /// The groom: the style's hair on the head (`--head`, else the head an
    /// imported group names, else the default head), and that head's
    /// path (`None` for the default head).
    pub fn load(&self) -> anyhow::Result<(Groom, Option<PathBuf>)> {
        let style = Style::load(&self.style)?;
        let head_path = self
            .head
            .clone()
            .or_else(|| imported_head(&style, &self.style));
        let head = load_head(head_path.as_deref())?;
        Ok((Groom::new(style, head), head_path))
    }

    /// The style and its head, as the log names them.
    pub fn describe(&self, head_path: Option<&Path>) -> String {
        format!(
            "{} on {}",
            self.style.display(),
            head_path.map_or("the default head".into(), |p| p.display().to_string())
        )
    }

    /// The input `--style` and `--head` ask for, if `--style` is given.
    pub fn from_args(style: Option<&PathBuf>, head: Option<&PathBuf>) -> Option<Self> {
        style.map(|style| Self {
            style: style.clone(),
            head: head.cloned(),
        })
    }
}

/// Runs the study on `input`: `groom.csv`, `groom.svg`.
pub fn run(ctx: &mut BenchContext<'_>, input: &GroomInput) -> anyhow::Result<()> {
    let (groom, head_path) = input.load()?;
    let collider = Arc::new(
        groom
            .collider()
            .context("cannot build the head's collision field")?,
    );
    writeln!(ctx.log, "   {}", input.describe(head_path.as_deref()))?;
    let frames = if ctx.quick { FRAMES.1 } else { FRAMES.0 };
    let runs = if ctx.quick { RUNS.1 } else { RUNS.0 };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let still = RigidMotion::default();
    let mut bases = Vec::new();
    for variant in VARIANTS {
        let overrides = SimOverrides {
            engine: Some(EngineKind::Batch),
            method: variant.method,
            scheme: variant.scheme,
            ..SimOverrides::default()
        };
        let sim = HeadlessSim::new(&groom.grown, overrides)
            .with_context(|| format!("cannot simulate {}", input.style.display()))?;
        let mut base = sim
            .engine()
            .batch()
            .context("the batch engine was asked for")?
            .clone();
        base.set_collider(variant.collider.then(|| collider.clone()));
        if !variant.guard {
            base.set_guard(None);
        }
        bases.push((variant, base));
    }
    // Per variant and thread count, every run's timing, runs interleaved.
    let mut timings: Vec<Vec<RunTiming>> = vec![Vec::new(); bases.len() * 2];
    for _ in 0..runs {
        for (v, (_, base)) in bases.iter().enumerate() {
            for (i, t) in [1, threads].into_iter().enumerate() {
                let mut system = base.clone();
                system.set_parallel(t > 1);
                timings[2 * v + i].push(time_frames(&mut system, &still, t, frames));
            }
        }
    }
    let mut rows = Vec::new();
    let mut traces = Vec::new();
    for (v, (variant, base)) in bases.iter().enumerate() {
        for (i, t) in [1, threads].into_iter().enumerate() {
            let row = summarize(&timings[2 * v + i], base, variant.name, t, frames);
            // Thread times are read on one thread only (NaN otherwise).
            let cpu = if row.cpu_ms.is_finite() {
                format!(
                    "; CPU {:.1} ms, waiting {:.1} ms per frame",
                    row.cpu_ms, row.waiting_ms
                )
            } else {
                String::new()
            };
            writeln!(
                ctx.log,
                "   {}, {t} thread(s): median {:.1} ms (runs {:.1}-{:.1}), p90 {:.1} ms per frame \
                 (load up to {:.2}){cpu}; {} guard losses",
                variant.name,
                row.median_ms,
                row.run_median_low_ms,
                row.run_median_high_ms,
                row.p90_ms,
                row.load_1min,
                row.guard_losses
            )?;
            if variant.name == FULL.name {
                let all: Vec<f64> = timings[2 * v + i]
                    .iter()
                    .flat_map(|r| r.ms.clone())
                    .collect();
                traces.push((t, all));
            }
            rows.push(row);
        }
    }
    if let Some(r) = rows.first() {
        writeln!(
            ctx.log,
            "   {} strands, {} elements in {} batches: {} lanes used, {} padded ({:.1}%)",
            r.strands,
            r.elements,
            r.batches,
            r.strands,
            r.padding_lanes,
            100.0 * r.padding_lanes as f64 / (r.strands + r.padding_lanes).max(1) as f64
        )?;
    }
    write_csv(&ctx.file("groom.csv"), &rows)?;
    draw(ctx, &traces)
}

/// One run of one variant on one thread count: each timed frame's
/// milliseconds, the thread's CPU and waiting time per frame (one thread
/// only, else NaN), the load at its start and the guard's losses.
#[derive(Clone, Debug)]
struct RunTiming {
    ms: Vec<f64>,
    cpu_ms: f64,
    waiting_ms: f64,
    load_1min: f64,
    guard_losses: usize,
}

/// Warms `system` up, then times `frames` frames one by one.
fn time_frames(
    system: &mut BatchSystem,
    head: &RigidMotion,
    threads: usize,
    frames: usize,
) -> RunTiming {
    for _ in 0..WARM_UP_FRAMES {
        system.step_frame(head);
    }
    let load_1min = load_1min();
    let losses_before = system.guard_reset_count();
    let times_before = thread_times_ns();
    let ms: Vec<f64> = (0..frames)
        .map(|_| {
            let start = Instant::now();
            system.step_frame(head);
            1e3 * start.elapsed().as_secs_f64()
        })
        .collect();
    let per_frame_ms = |ns: u64| 1e-6 * ns as f64 / frames as f64;
    let (cpu_ms, waiting_ms) = match (threads, times_before, thread_times_ns()) {
        (1, Some((cpu0, wait0)), Some((cpu1, wait1))) => {
            (per_frame_ms(cpu1 - cpu0), per_frame_ms(wait1 - wait0))
        }
        _ => (f64::NAN, f64::NAN),
    };
    RunTiming {
        ms,
        cpu_ms,
        waiting_ms,
        load_1min,
        guard_losses: system.guard_reset_count() - losses_before,
    }
}

/// The row of a variant's `runs` on `threads` threads (module docs).
fn summarize(
    runs: &[RunTiming],
    system: &BatchSystem,
    variant: &str,
    threads: usize,
    frames: usize,
) -> GroomRow {
    let medians: Vec<f64> = runs.iter().map(|r| median(&r.ms)).collect();
    let mut all: Vec<f64> = runs.iter().flat_map(|r| r.ms.iter().copied()).collect();
    all.sort_by(f64::total_cmp);
    let at = |q: f64| all[((q * all.len() as f64) as usize).min(all.len() - 1)];
    let of_runs = |f: fn(&RunTiming) -> f64| median(&runs.iter().map(f).collect::<Vec<_>>());
    let lanes = system.lanes_used();
    GroomRow {
        variant: variant.into(),
        threads,
        frames,
        runs: runs.len(),
        median_ms: median(&medians),
        run_median_low_ms: medians.iter().copied().fold(f64::INFINITY, f64::min),
        run_median_high_ms: medians.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        p90_ms: at(0.9),
        min_ms: at(0.0),
        cpu_ms: of_runs(|r| r.cpu_ms),
        waiting_ms: of_runs(|r| r.waiting_ms),
        load_1min: runs.iter().map(|r| r.load_1min).fold(f64::NAN, f64::max),
        strands: system.strand_count(),
        elements: system.element_count(),
        batches: lanes.batches,
        padding_lanes: lanes.padding,
        guard_losses: runs.iter().map(|r| r.guard_losses).sum(),
    }
}

fn draw(ctx: &BenchContext<'_>, traces: &[(usize, Vec<f64>)]) -> anyhow::Result<()> {
    let frames = traces.first().map_or(0, |(_, ms)| ms.len());
    let mut series: Vec<Series> = traces
        .iter()
        .enumerate()
        .map(|(i, (threads, ms))| Series {
            name: format!("full, {threads} thread(s)"),
            points: ms
                .iter()
                .enumerate()
                .map(|(f, &m)| ((f + 1) as f64, m))
                .collect(),
            line: true,
            markers: true,
            colour: i,
        })
        .collect();
    series.push(Series {
        name: format!("target, {FRAME_BUDGET_MS} ms"),
        points: vec![
            (1.0, FRAME_BUDGET_MS),
            (frames.max(2) as f64, FRAME_BUDGET_MS),
        ],
        line: true,
        markers: false,
        colour: traces.len(),
    });
    draw_line_chart(
        &ctx.file("groom.svg"),
        &LineChart {
            title: "Physics time per 60 Hz frame, whole groom, batch engine, still head".into(),
            x: Axis {
                label: "timed frame (the runs one after another)".into(),
                log: false,
            },
            y: Axis {
                label: "milliseconds".into(),
                log: true,
            },
            series,
        },
    )
}

//! `helixhair bench`: the studies that chart speed against accuracy.
//!
//! Each study runs the physics crate on scenes with known answers or a fine
//! reference, writes its raw numbers as CSV and its chart as SVG into the
//! output folder, and prints its headline figures. At the end [`report`]
//! rebuilds the benchmark report, one markdown page of the run's tables
//! and charts under one header line naming the machine and the date
//! (`--report`, default `OUT/benchmarks.md`). The published report is
//! `helixhair bench --out docs/results --report docs/benchmarks.md`. The
//! quick mode runs every study on small sizes (seconds, for CI) so that the
//! command cannot rot; its report says it is quick.
//!
//! | study | question | files |
//! | --- | --- | --- |
//! | `cost` | seconds per step against N, per solver | `cost.csv`, `cost.svg` |
//! | `accuracy` | error against cost on three scenes, Pareto front; iterations that win back Block-diagonal's error | `accuracy.csv`, `accuracy_*.svg`, `error_model.ron`, `iterations.csv`, `iterations.svg` |
//! | `stability` | stable, damped-out or blown-up over dt × stiffness × root speed | `stability.csv`, `stability.svg`, `curly_dt.csv` |
//! | `modes` | first-mode frequency and damping against N and the analytic value | `modes.csv`, `modes_*.svg` |
//! | `throughput` | element-steps per second and memory per strand, CPU (1 and all threads) and GPU, against strand count and N | `throughput.csv`, `throughput.svg` |
//! | `volume`, `volume-shake`, `volume-cost` (only when named) | the hair–hair model on a full head: volume kept; interpenetration and energy during a shake; cost share on both engines | `volume.csv`; `volume_shake.csv`, `volume_shake.svg`, `volume_energy.svg`; `volume_cost.csv`, `volume_cost.svg` |
//! | `groom` (only when named, with `--style`) | physics ms per 60 Hz frame of a whole groom (an imported one: every strand simulated) on the batch engine, 1 and all threads, and where a frame goes; lanes used and padded | `groom.csv`, `groom.svg` |
//! | `soak` (only when named) | a full head for a million frames of random head motion per engine: NaN, guard loops, memory | `soak.csv`, `soak_memory.svg`, `soak_guard.svg` |

pub mod accuracy;
pub mod chart;
pub mod cost;
pub mod error_model_build;
pub mod groom;
pub mod iterations;
pub mod modes;
pub mod pareto;
pub mod report;
pub mod scenes;
pub mod soak;
pub mod stability;
pub mod table;
pub mod throughput;
pub mod timing;
pub mod volume;

use std::cell::RefCell;
use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use clap::{Args, ValueEnum};
use helixhair_physics::engine::EngineKind;

/// The studies `helixhair bench` can run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Study {
    /// Cost per step against element count, all solvers.
    Cost,
    /// Error against cost on the swing, curly-bounce and head-shake scenes.
    Accuracy,
    /// Stability maps over time step, stiffness and root speed.
    Stability,
    /// First-mode frequency and damping against element count.
    Modes,
    /// Element-steps per second of the batch and GPU paths against strand
    /// count.
    Throughput,
    /// The hair–hair model on a full head settled 5 s: volume kept.
    /// Runs only when named (minutes), as do the two below.
    Volume,
    /// The hair–hair model on a full head under a shake: interpenetration
    /// per frame, energy after, guard events.
    VolumeShake,
    /// The hair–hair model's share of a frame at 3,000 and 10,000 strands.
    VolumeCost,
    /// A full head under random head motion for a million frames per
    /// engine (hours): NaN, guard loops, memory. Runs only when named.
    Soak,
    /// Physics time per frame of a whole groom (`--style`, `--head`) on
    /// the batch engine, and where it goes. Runs only when named.
    Groom,
}

impl Study {
    /// The studies `helixhair bench` runs when none is named: all but the
    /// soak, which takes hours.
    pub const ALL: [Study; 5] = [
        Study::Cost,
        Study::Accuracy,
        Study::Stability,
        Study::Modes,
        Study::Throughput,
    ];
}

/// Arguments of `helixhair bench`.
#[derive(Clone, Debug, Args)]
pub struct BenchArgs {
    /// Which study to run (repeat the flag for several); all when absent.
    #[arg(long = "study", value_enum, value_name = "STUDY")]
    pub studies: Vec<Study>,
    /// Folder for the CSV files and charts (created if needed).
    #[arg(long, value_name = "DIR", default_value = "out/bench")]
    pub out: PathBuf,
    /// The markdown report of this run's tables and charts, rebuilt from
    /// the CSV files it wrote (default: `OUT/benchmarks.md`; the published
    /// one is `--out docs/results --report docs/benchmarks.md`).
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Small sizes and short runs (seconds): checks that every study still
    /// runs and draws, as CI does; the numbers are not the published ones.
    #[arg(long)]
    pub quick: bool,
    /// Frames per engine of the `soak` study (default 1,000,000; 300 with
    /// `--quick`).
    #[arg(long, value_name = "FRAMES")]
    pub soak_steps: Option<usize>,
    /// Wall-clock budget per engine of the `soak` study, minutes; the run
    /// stops there and reports how far it got.
    #[arg(long, value_name = "MINUTES")]
    pub soak_minutes: Option<f64>,
    /// Engines the `soak` study runs (repeat the flag for both; both when
    /// absent): reference or batch.
    #[arg(long = "soak-engine", value_name = "ENGINE", value_parser = soak::parse_engine)]
    pub soak_engines: Vec<EngineKind>,
    /// The style the `groom` study times (an imported groom's, say), and
    /// the one the `volume` study settles instead of the built-in full
    /// head.
    #[arg(long, value_name = "STYLE")]
    pub style: Option<PathBuf>,
    /// The head mesh of the `groom` and `volume` studies with `--style`;
    /// default: the head its imported group names, else the default head.
    #[arg(long, value_name = "MESH")]
    pub head: Option<PathBuf>,
}

/// What every study gets: where to write, how big to go, where to report.
pub struct BenchContext<'a> {
    /// Output folder.
    pub out_dir: &'a Path,
    /// Quick mode: small sizes.
    pub quick: bool,
    /// Progress and the headline numbers.
    pub log: &'a mut dyn Write,
    /// Every output file handed out by [`Self::file`], in order: what the
    /// report shows ([`report`]).
    written: RefCell<Vec<PathBuf>>,
}

impl BenchContext<'_> {
    /// The path of output file `name`, which the study is about to write:
    /// the run keeps it for the report.
    pub fn file(&self, name: &str) -> PathBuf {
        let path = self.out_dir.join(name);
        self.written.borrow_mut().push(path.clone());
        path
    }

    /// The files handed out since the last call, in order.
    fn take_written(&self) -> Vec<PathBuf> {
        self.written.take()
    }
}

/// Runs the studies `args` asks for.
pub fn run_bench(args: &BenchArgs, log: &mut dyn Write) -> anyhow::Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create the output folder {}", args.out.display()))?;
    let studies: &[Study] = if args.studies.is_empty() {
        &Study::ALL
    } else {
        &args.studies
    };
    let mut ctx = BenchContext {
        out_dir: &args.out,
        quick: args.quick,
        log,
        written: RefCell::new(Vec::new()),
    };
    let mut written = Vec::new();
    for &study in studies {
        writeln!(ctx.log, "== study {study:?} ==")?;
        let start = std::time::Instant::now();
        match study {
            Study::Cost => cost::run(&mut ctx),
            Study::Accuracy => accuracy::run(&mut ctx),
            Study::Stability => stability::run(&mut ctx),
            Study::Modes => modes::run(&mut ctx),
            Study::Throughput => throughput::run(&mut ctx),
            Study::Volume => {
                let input = groom::GroomInput::from_args(args.style.as_ref(), args.head.as_ref());
                volume::run(&mut ctx, volume::Part::Settle, input.as_ref())
            }
            Study::VolumeShake => volume::run(&mut ctx, volume::Part::Shake, None),
            Study::VolumeCost => volume::cost::cost(&mut ctx),
            Study::Soak => {
                let engines = if args.soak_engines.is_empty() {
                    &EngineKind::CPU[..]
                } else {
                    &args.soak_engines
                };
                let length = soak::SoakLength {
                    steps: args.soak_steps,
                    minutes: args.soak_minutes,
                };
                soak::run(&mut ctx, length, engines)
            }
            Study::Groom => {
                let input = groom::GroomInput::from_args(args.style.as_ref(), args.head.as_ref())
                    .context("the groom study needs --style STYLE.ron")?;
                groom::run(&mut ctx, &input)
            }
        }
        .with_context(|| format!("study {study:?}"))?;
        written.push((study, ctx.take_written()));
        writeln!(ctx.log, "   ({:.1} s)", start.elapsed().as_secs_f64())?;
    }
    let report_path = args
        .report
        .clone()
        .unwrap_or_else(|| args.out.join("benchmarks.md"));
    let header = report::ReportHeader {
        machine: report::machine(),
        date: report::today(),
        quick: args.quick,
        command: bench_command_line(),
    };
    report::write_report(&report_path, &written, &header)?;
    writeln!(
        ctx.log,
        "wrote {} and {}",
        args.out.display(),
        report_path.display()
    )?;
    Ok(())
}

/// The command line that ran the bench, as `helixhair bench …` (the
/// program's own path replaced by its name, so the report names no local
/// folder).
fn bench_command_line() -> String {
    let args: Vec<String> = std::env::args().skip(1).collect();
    format!("helixhair {}", args.join(" "))
}

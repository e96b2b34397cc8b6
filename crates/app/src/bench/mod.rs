//! `helixhair bench`: the studies that chart speed against accuracy.
//!
//! Each study runs the physics crate on scenes with known answers or a fine
//! reference, writes its raw numbers as CSV and its chart as SVG into the
//! output folder, and prints the figures `docs/RESULTS.md` quotes. The
//! quick mode runs every study on small sizes (seconds, for CI) so that the
//! command cannot rot; the full mode makes the published charts.
//!
//! | study | question | files |
//! | --- | --- | --- |
//! | `cost` | seconds per step against N, per solver | `cost.csv`, `cost.svg` |
//! | `accuracy` | error against cost on three scenes, Pareto front; iterations that win back Block-diagonal's error | `accuracy.csv`, `accuracy_*.svg`, `error_model.ron`, `iterations.csv`, `iterations.svg` |
//! | `stability` | stable, damped-out or blown-up over dt × stiffness × root speed | `stability.csv`, `stability.svg`, `curly_dt.csv` |
//! | `modes` | first-mode frequency and damping against N and the analytic value | `modes.csv`, `modes_*.svg` |
//! | `throughput` | element-steps per second and memory per strand, CPU (1 and all threads) and GPU, against strand count and N | `throughput.csv`, `throughput.svg` |

pub mod accuracy;
pub mod chart;
pub mod cost;
pub mod error_model_build;
pub mod iterations;
pub mod modes;
pub mod pareto;
pub mod scenes;
pub mod stability;
pub mod table;
pub mod throughput;
pub mod timing;

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use clap::{Args, ValueEnum};

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
}

impl Study {
    /// Every study, in the order `--study` lists them.
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
    /// Small sizes and short runs (seconds): checks that every study still
    /// runs and draws, as CI does; the numbers are not the published ones.
    #[arg(long)]
    pub quick: bool,
}

/// What every study gets: where to write, how big to go, where to report.
pub struct BenchContext<'a> {
    /// Output folder.
    pub out_dir: &'a Path,
    /// Quick mode: small sizes.
    pub quick: bool,
    /// Progress and the headline numbers.
    pub log: &'a mut dyn Write,
}

impl BenchContext<'_> {
    /// The path of output file `name`.
    pub fn file(&self, name: &str) -> PathBuf {
        self.out_dir.join(name)
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
    };
    for &study in studies {
        writeln!(ctx.log, "== study {study:?} ==")?;
        let start = std::time::Instant::now();
        match study {
            Study::Cost => cost::run(&mut ctx),
            Study::Accuracy => accuracy::run(&mut ctx),
            Study::Stability => stability::run(&mut ctx),
            Study::Modes => modes::run(&mut ctx),
            Study::Throughput => throughput::run(&mut ctx),
        }
        .with_context(|| format!("study {study:?}"))?;
        writeln!(ctx.log, "   ({:.1} s)", start.elapsed().as_secs_f64())?;
    }
    writeln!(ctx.log, "wrote {}", args.out.display())?;
    Ok(())
}

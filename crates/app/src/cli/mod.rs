//! The `helixhair` command line: its arguments and what each command does.
//!
//! The binary only parses arguments and reports errors; [`run`] does the
//! work, writing to the streams it is given so that tests can drive it.

pub mod camera_arg;
pub mod render;

use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context as _;
use clap::{Args, Parser, Subcommand};
use helixhair_physics::engine::EngineKind;
use helixhair_physics::settings::MAX_ITERATIONS;
use helixhair_physics::{Method, StepScheme};
use helixhair_render::head_generate::default_head;

#[cfg(feature = "bench")]
use crate::bench::{BenchArgs, run_bench};
use crate::export::command::{SimExport, SimExportArgs, run_export, terminal_progress};
use crate::head::groom::{head_collider, needs_head};
use crate::head::of_style::OwnHead;
use crate::json_report::{summary_stream, write_json_report};
use crate::motion::clip::Clip;
use crate::motion::playback::{Playback, parse_play};
use crate::sim::build::SimOverrides;
use crate::sim::engine_arg::{parse_engine, parse_interaction};
use crate::sim::frame_stepper::FrameStepper;
use crate::sim::headless::HeadlessSim;
use crate::sim::report::{SimReport, refuse_lost_strands};
use crate::sim::settle::{settle_on_head, settles_on_head};
use crate::sim::tip_trajectories::Tracked;
use crate::style::Style;
#[cfg(feature = "window")]
use crate::window::{WindowArgs, run_window};

/// Frames `helixhair sim` runs unless told otherwise: one second at 60 Hz.
pub const DEFAULT_STEPS: u32 = 60;

/// Most frames one `helixhair sim` may run (the per-frame timings are kept).
pub const MAX_STEPS: u32 = 1_000_000;

/// What `helixhair` without a command says when it was built without the
/// window (cargo feature `window`).
pub const NO_WINDOW: &str = "this helixhair was built without the styling window \
    (cargo feature `window`); run a command instead, e.g. \
    `helixhair sim --style assets/styles/curly.ron`, or see `helixhair --help`";

/// HelixHair: Super-Helix hair simulation.
#[derive(Clone, Debug, Parser)]
#[command(
    name = "helixhair",
    version,
    about,
    after_help = "Without a command, helixhair opens the styling window (the options above \
                  are the window's); every command runs headless.",
    args_conflicts_with_subcommands = true
)]
pub struct Cli {
    /// The command; without one, opens the styling window.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// The window's options (used without a command).
    #[cfg(feature = "window")]
    #[command(flatten)]
    pub window: WindowArgs,
}

/// The commands of `helixhair`.
#[derive(Clone, Debug, Subcommand)]
pub enum Command {
    /// Simulate a style headless, on a still head or one moved by `--play`,
    /// and report timings, energies and final strand shapes.
    Sim(SimArgs),
    /// Measure speed against accuracy: cost per step, error against cost,
    /// stability maps, vibration modes and throughput, as CSV files, SVG
    /// charts and a markdown report of both.
    #[cfg(feature = "bench")]
    Bench(BenchArgs),
    /// Simulate a style, then draw it offscreen into a PNG (or one PNG per
    /// frame) on any graphics adapter, lavapipe included.
    Render(crate::cli::render::RenderArgs),
    /// Export a style's hair (at rest, or after some frames, or every
    /// frame) as USD (.usda, .usdc, .usd, .usdz), Alembic (.abc), .hair,
    /// .tfx or .obj,
    /// simulated on a head as
    /// `render` does.
    Export(crate::export::command::ExportArgs),
    /// Import a groom (TressFX, .hair, USD, Alembic, OBJ curves): fit Super-Helices,
    /// solve a sag-free rest shape, and write a style (docs/import.md).
    Import(crate::import::command::ImportArgs),
    /// Style by hand, headless: apply a stroke file (comb, cut, curl,
    /// freeze, …) to a style with the physics running, and write the
    /// styled style (docs/stroke-format.md).
    Groom(crate::brush::command::GroomArgs),
}

/// Arguments of `helixhair sim`.
#[derive(Clone, Debug, Args)]
pub struct SimArgs {
    /// The style file (RON; see docs/style-format.md).
    #[arg(long, value_name = "FILE")]
    pub style: PathBuf,
    /// Physics engine, instead of the style's `engine`: reference (f64,
    /// every solver, stability guard), batch (f32 SIMD on all cores,
    /// exact or block only) or gpu (the batch engine with its substeps on
    /// the GPU; the CPU steps what the GPU cannot, and the summary says
    /// why).
    #[arg(long, value_name = "ENGINE", value_parser = parse_engine)]
    pub engine: Option<EngineKind>,
    /// Solver, instead of the style's: exact, dense, block, block-own or
    /// iterative:K (K block-preconditioned CG iterations).
    #[arg(long, value_name = "METHOD", value_parser = parse_method)]
    pub method: Option<Method>,
    /// Frame time step in seconds, instead of the style's (1e-6 to 0.1).
    #[arg(long, value_name = "SECS", allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// How the step (either engine) treats the centrifugal and Coriolis
    /// terms, instead of the style's
    /// `sim.scheme`: implicit (the default: in the step matrix) or explicit
    /// (frozen at the step's start, as the GPU kernels step; for
    /// comparisons).
    #[arg(long, value_name = "TERMS", value_parser = parse_velocity_terms)]
    pub velocity_terms: Option<StepScheme>,
    /// Hair–hair interaction (the volume model, docs/volume.md) on or
    /// off, instead of the style's `sim.interaction.enabled`; either
    /// engine.
    #[arg(long, value_name = "on|off", value_parser = parse_interaction)]
    pub interaction: Option<bool>,
    /// Move the head with one of the window's clips (nod, shake, turn or
    /// jerk) or a motion file (FILE.ron, docs/motion-format.md) from time
    /// zero, then hold it still, instead of a still head.
    #[arg(long, value_name = "CLIP|FILE", value_parser = parse_play)]
    pub play: Option<Playback>,
    /// Exit 0 even when the guard had to reset or pin strands (by default
    /// such a run exits 1 after writing its report: it is not the
    /// simulation that was asked for).
    #[arg(long)]
    pub accept_resets: bool,
    /// Accuracy target, instead of the style's `accuracy_target`: the
    /// tip-position RMS error allowed as a fraction of strand length (1e-4
    /// to 1); each group's solver and element count are then chosen from
    /// the measured error model (docs/solvers.md).
    #[arg(long, value_name = "FRACTION")]
    pub accuracy: Option<f64>,
    /// Number of frames to simulate.
    #[arg(long, value_name = "K", default_value_t = DEFAULT_STEPS,
          value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_STEPS)))]
    pub steps: u32,
    /// Write a JSON report (docs/sim-json.md) to OUT, creating its folder if
    /// needed; `-` writes it to stdout, and the summary then goes to stderr.
    #[arg(long, value_name = "OUT")]
    pub json: Option<PathBuf>,
    /// Put every strand's tip, at the start and after each frame, in the
    /// JSON report (`tip_trajectories`, docs/sim-json.md).
    #[arg(long, requires = "json")]
    pub tip_trajectories: bool,
    /// Export options (`--export FILE`).
    #[command(flatten)]
    pub export: SimExportArgs,
}

/// Parses `--play`: a clip's name.
pub fn parse_clip(name: &str) -> Result<Clip, String> {
    Clip::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = Clip::ALL.iter().map(|c| c.name()).collect();
        format!(
            "unknown clip `{name}`; expected one of {}",
            names.join(", ")
        )
    })
}

/// Parses `--velocity-terms`: `implicit` or `explicit`.
pub fn parse_velocity_terms(name: &str) -> Result<StepScheme, String> {
    match name {
        "implicit" => Ok(StepScheme::default()),
        "explicit" => Ok(StepScheme::VelocityExplicit),
        _ => Err(format!(
            "unknown velocity terms `{name}`; expected implicit or explicit"
        )),
    }
}

/// Parses a solver name as [`Method::label`] spells it (`exact`,
/// `iterative:4`, …).
pub fn parse_method(name: &str) -> Result<Method, String> {
    Method::from_name(name).ok_or_else(|| {
        let names: Vec<String> = Method::ALL
            .iter()
            .map(|m| match m {
                Method::Iterative { .. } => format!("{}:K (K ≤ {MAX_ITERATIONS})", m.name()),
                _ => m.label(),
            })
            .collect();
        format!(
            "unknown method `{name}`; expected one of {}",
            names.join(", ")
        )
    })
}

/// Runs the command `cli` asks for. Normal output goes to `stdout`; the
/// summary goes to `stderr` when the JSON report takes stdout.
pub fn run(cli: &Cli, stdout: &mut dyn Write, stderr: &mut dyn Write) -> anyhow::Result<()> {
    match &cli.command {
        #[cfg(feature = "window")]
        None => run_window(&cli.window),
        #[cfg(not(feature = "window"))]
        None => anyhow::bail!("{NO_WINDOW}"),
        Some(Command::Sim(args)) => run_sim(args, stdout, stderr),
        #[cfg(feature = "bench")]
        Some(Command::Bench(args)) => run_bench(args, stdout),
        Some(Command::Render(args)) => crate::cli::render::run_render(args, stdout),
        Some(Command::Export(args)) => run_export(args, stdout),
        Some(Command::Import(args)) => crate::import::command::run_import(args, stdout, stderr),
        Some(Command::Groom(args)) => crate::brush::command::run_groom(args, stdout),
    }
}

fn run_sim(args: &SimArgs, stdout: &mut dyn Write, stderr: &mut dyn Write) -> anyhow::Result<()> {
    // A style error already names the file, line and field: no context to add.
    let style = Style::load(&args.style)?;
    let style_path = args.style.display().to_string();
    let overrides = SimOverrides {
        engine: args.engine,
        method: args.method,
        dt_secs: args.dt,
        accuracy_target: args.accuracy,
        scheme: args.velocity_terms,
        interaction: args.interaction,
    };
    let mut sim = HeadlessSim::new(&style, overrides)
        .with_context(|| format!("cannot simulate {style_path}"))?;
    // The head the hair is simulated against (and exported with): an
    // imported groom's own, which it rests on and turns with; else the
    // default head, which hair grown on its scalp and hair of listed roots
    // (the plain examples) collide with and start settled on, as `render`
    // and the window run them. An imported groom without a head of its
    // own runs with none: its rest shapes were solved with no head.
    let head_mesh = match OwnHead::of_style(&style, &args.style)? {
        Some(own) => {
            let collider = own.collision_field()?;
            sim.engine_mut().set_collider(Some(Arc::new(collider)));
            sim.set_head_pivot(own.pivot_m);
            own.drawn
        }
        None => {
            let head = default_head();
            if needs_head(&style) || settles_on_head(&style) {
                let collider = head_collider(&head)
                    .context("cannot build the default head's collision field")?;
                sim.engine_mut().set_collider(Some(Arc::new(collider)));
            }
            if settles_on_head(&style) {
                settle_on_head(sim.engine_mut());
            }
            head
        }
    };
    if let Some(play) = &args.play {
        sim.play_motion(play.load()?);
    }
    let export = match &args.export.export {
        Some(path) => Some(SimExport::prepare(
            path,
            &args.export.shape,
            &style,
            head_mesh,
        )?),
        None => None,
    };
    let steps = usize::try_from(args.steps).context("--steps does not fit this machine")?;
    let mut tracked = Tracked::new(&mut sim, args.tip_trajectories);
    let stepper = &mut tracked;
    let (per_step_secs, exported) = match export {
        Some(export) => {
            let (secs, outcome) = export
                .run(stepper, steps, &mut terminal_progress(steps))
                .with_context(|| format!("simulating and exporting {style_path}"))?;
            (secs, Some(outcome))
        }
        None => (
            run_frames(stepper, steps).with_context(|| format!("simulating {style_path}"))?,
            None,
        ),
    };
    let tips = tracked.tips;
    let mut report = SimReport::new(&style_path, &style.name, &sim, per_step_secs);
    report.tip_trajectories = tips;

    let summary_out = summary_stream(args.json.as_deref(), stdout, stderr);
    summary_out.write_all(report.summary().as_bytes())?;
    if let Some(outcome) = &exported {
        writeln!(summary_out, "  {}", outcome.summary())?;
    }
    if let Some(json_path) = &args.json {
        write_json_report(&report, json_path, stdout)?;
    }
    refuse_lost_strands(sim.strands_lost(), args.accept_resets)
}

/// Steps `steps` frames; each frame's physics wall time.
fn run_frames(sim: &mut dyn FrameStepper, steps: usize) -> anyhow::Result<Vec<f64>> {
    (1..=steps)
        .map(|frame| {
            sim.step_frame()
                .with_context(|| format!("frame {frame} of {steps}"))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run_args(args: &[&str]) -> (anyhow::Result<()>, String, String) {
        let cli = Cli::try_parse_from(std::iter::once("helixhair").chain(args.iter().copied()))
            .unwrap_or_else(|e| panic!("{e}"));
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let result = run(&cli, &mut out, &mut err);
        let text = |b: Vec<u8>| String::from_utf8(b).expect("UTF-8 output");
        (result, text(out), text(err))
    }

    #[test]
    fn method_names_parse_as_the_physics_crate_spells_them() {
        for method in Method::ALL {
            assert_eq!(parse_method(&method.label()), Ok(method));
        }
        assert_eq!(
            parse_method("iterative:9"),
            Ok(Method::Iterative { iterations: 9 })
        );
        let error = parse_method("Dense").expect_err("names are lower case");
        assert!(error.contains("expected one of dense, block"), "{error}");
    }

    #[test]
    fn sim_with_json_to_stdout_puts_the_summary_on_stderr() {
        let style = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/styles/coily.ron");
        let (result, out, err) =
            run_args(&["sim", "--style", style, "--steps", "2", "--json", "-"]);
        result.expect("runs");
        let report: serde_json::Value =
            serde_json::from_str(&out).expect("stdout is the JSON report");
        assert_eq!(report["steps"], 2);
        assert!(err.contains("style `coily`"), "{err}");
    }

    #[test]
    fn a_broken_style_is_an_error_naming_it() {
        let (result, out, _) = run_args(&["sim", "--style", "no/such/style.ron"]);
        let error = result.expect_err("no such file");
        assert!(
            format!("{error:#}").starts_with("no/such/style.ron: cannot read the style"),
            "{error:#}"
        );
        assert!(out.is_empty());
    }

    #[test]
    fn interaction_switches_on_either_engine() {
        assert_eq!(parse_interaction("on"), Ok(true));
        assert_eq!(parse_interaction("off"), Ok(false));
        assert!(
            parse_interaction("yes")
                .expect_err("on or off")
                .contains("expected on or off")
        );
        let style = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/styles/coily.ron");
        let args = [
            "sim",
            "--style",
            style,
            "--steps",
            "2",
            "--interaction",
            "on",
        ];
        let (result, _, _) = run_args(&args);
        result.expect("the reference engine runs the model");
        let (result, _, _) =
            run_args(&[&args[..], &["--engine", "batch", "--method", "exact"]].concat());
        result.expect("the batch engine runs the model");
    }
}

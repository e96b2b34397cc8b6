//! Exporting from the command line: `helixhair sim ... --export FILE` and
//! `helixhair export`.
//!
//! `sim --export` writes what `sim` simulated (same physics, same head
//! motion, so the JSON report and the file describe one run): every frame
//! by default (the start, then each of `--steps`), or `--export-frames
//! last`. `helixhair export` runs the pipeline of `helixhair render`
//! instead (the style grown on a head, `--head OBJ` or the default,
//! colliding with it) and writes the state after `--steps` frames (0: the
//! style at rest), or every frame with `--export-frames all`. What a file
//! holds is [`crate::export`]'s business.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context as _;
use clap::Args;
use helixhair_formats::TriangleMesh;
use helixhair_render::HeadMesh;

use crate::export::{
    DEFAULT_POINTS_PER_STRAND, ExportRecorder, ExportSpec, FrameChoice, StrandChoice,
    check_writable, head_triangle_mesh,
};
use crate::head::groom::Groom;
use crate::motion::playback::{Playback, parse_play};
use crate::sim::build::SimOverrides;
use crate::sim::frame_stepper::FrameStepper;
use crate::sim::grown::grown_sim;
use crate::style::Style;

/// How exported strands are made: which ones, how many points, which
/// frames, whether the head goes along.
#[derive(Clone, Debug, Args)]
pub struct ExportShapeArgs {
    /// Strands to export: simulated (the guides, sampled along their
    /// helices, width = fibre diameter) or drawn (every strand `render`
    /// draws, with its colour and tapered width).
    #[arg(long, value_enum, value_name = "WHICH", default_value_t = StrandChoice::Simulated)]
    pub strands: StrandChoice,
    /// Points per exported strand, evenly spaced by arc length (TressFX: a
    /// power of two from 4 to 64).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_POINTS_PER_STRAND)]
    pub points_per_strand: usize,
    /// Frames to export: all (the start and every frame: USD time samples,
    /// or NAME.0000.EXT, NAME.0001.EXT, … for the one-frame formats) or
    /// last. Default: all for `sim`, last for `export`.
    #[arg(long, value_enum, value_name = "WHICH")]
    pub export_frames: Option<FrameChoice>,
    /// Leave the head mesh out of a USD (.usda, .usdc, .usd, .usdz) or
    /// Alembic (.abc) file.
    #[arg(long)]
    pub no_head: bool,
}

/// `helixhair sim`'s export options.
#[derive(Clone, Debug, Args)]
pub struct SimExportArgs {
    /// Export the hair to FILE: USD BasisCurves with time samples and the
    /// head, as text (.usda), binary (.usdc, .usd) or a package (.usdz);
    /// Alembic curves with samples and the head (.abc);
    /// or .hair, .tfx or .obj (one frame each: a numbered sequence for an
    /// animation); missing folders are created.
    #[arg(long, value_name = "FILE")]
    pub export: Option<PathBuf>,
    /// What to export.
    #[command(flatten)]
    pub shape: ExportShapeArgs,
}

/// Arguments of `helixhair export`.
#[derive(Clone, Debug, Args)]
pub struct ExportArgs {
    /// The style file (RON; see docs/style-format.md).
    #[arg(long, value_name = "FILE")]
    pub style: PathBuf,
    /// Frames to simulate first (0: the style at rest).
    #[arg(long, value_name = "K", default_value_t = 0,
          value_parser = clap::value_parser!(u32).range(0..=100_000))]
    pub steps: u32,
    /// Move the head: a clip (nod, shake, turn, jerk) or a motion file
    /// (docs/motion-format.md).
    #[arg(long, value_name = "CLIP|FILE", value_parser = parse_play)]
    pub play: Option<Playback>,
    /// A head mesh (OBJ, scalp faces in a group `scalp`) instead of the
    /// default head.
    #[arg(long, value_name = "OBJ")]
    pub head: Option<PathBuf>,
    /// Physics engine, instead of the style's `engine`: reference, batch
    /// or gpu.
    #[arg(long, value_name = "ENGINE", value_parser = crate::sim::engine_arg::parse_engine)]
    pub engine: Option<helixhair_physics::engine::EngineKind>,
    /// The file to write: .usda, .usdc, .usd, .usdz, .abc, .hair, .tfx or
    /// .obj.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// What to export.
    #[command(flatten)]
    pub shape: ExportShapeArgs,
}

impl ExportShapeArgs {
    /// The spec for `path`, with `default_frames` when not given.
    pub fn spec(&self, path: &Path, default_frames: FrameChoice) -> anyhow::Result<ExportSpec> {
        ExportSpec::new(
            path,
            self.strands,
            self.points_per_strand,
            self.export_frames.unwrap_or(default_frames),
            !self.no_head,
        )
    }
}

/// What an export wrote.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportOutcome {
    /// The files, in order.
    pub files: Vec<PathBuf>,
    /// Their total size, bytes.
    pub bytes: u64,
    /// Frames in the export (1 for a single frame).
    pub frames: usize,
    /// Wall time spent capturing and writing, seconds (simulation not
    /// included).
    pub export_secs: f64,
}

impl ExportOutcome {
    /// One line for the command's summary.
    pub fn summary(&self) -> String {
        let what = match &self.files[..] {
            [one] => one.display().to_string(),
            [first, .., last] => format!(
                "{} files, {} to {}",
                self.files.len(),
                first.display(),
                last.display()
            ),
            [] => "nothing".to_owned(),
        };
        format!(
            "exported {} frame{} to {what} ({:.1} MB, {:.2} s)",
            self.frames,
            if self.frames == 1 { "" } else { "s" },
            self.bytes as f64 / 1e6,
            self.export_secs
        )
    }
}

/// Steps `sim` for `steps` frames, capturing them as `spec` asks; returns
/// each frame's physics wall time (as [`crate::sim::headless::HeadlessSim::run`]) and what was
/// written. `groom` is needed for drawn strands, `head` is the mesh a
/// `.usda` carries. `progress` is told the frames done after each frame
/// and returns false to cancel: the export then stops with an error, and
/// the files of a sequence written so far are removed (nothing is left
/// under the final names, not even whole frames of a cut-short run).
pub fn simulate_and_export(
    sim: &mut dyn FrameStepper,
    steps: usize,
    spec: ExportSpec,
    groom: Option<&Groom>,
    head: Option<&TriangleMesh>,
    progress: &mut dyn FnMut(usize) -> bool,
) -> anyhow::Result<(Vec<f64>, ExportOutcome)> {
    let animated = spec.animated(steps);
    let head = head.filter(|_| spec.writes_head());
    let mut recorder = ExportRecorder::new(spec, sim.engine().settings().dt_secs);
    let mut export_secs = 0.0;
    let mut capture = |sim: &dyn FrameStepper, recorder: &mut ExportRecorder, frame| {
        let start = Instant::now();
        let result = recorder.capture(sim.engine(), groom, frame);
        export_secs += start.elapsed().as_secs_f64();
        result
    };
    let mut wall_secs = Vec::with_capacity(steps);
    let mut run = || -> anyhow::Result<()> {
        if animated {
            capture(sim, &mut recorder, 0)?;
        }
        for frame in 1..=steps {
            wall_secs.push(sim.step_frame()?);
            if animated {
                capture(sim, &mut recorder, frame)?;
            }
            if !progress(frame) {
                anyhow::bail!("cancelled after {frame} of {steps} frames; nothing was written");
            }
        }
        Ok(())
    };
    if let Err(e) = run() {
        recorder.discard();
        return Err(e);
    }
    let start = Instant::now();
    if !animated {
        recorder.write_single(sim.engine(), groom, head)?;
    }
    let (files, bytes) = recorder.finish(head)?;
    export_secs += start.elapsed().as_secs_f64();
    let outcome = ExportOutcome {
        files,
        bytes,
        frames: if animated { steps + 1 } else { 1 },
        export_secs,
    };
    Ok((wall_secs, outcome))
}

/// A progress bar on the terminal for `steps` frames, as the closure
/// [`simulate_and_export`] reports to (never cancels).
pub fn terminal_progress(steps: usize) -> impl FnMut(usize) -> bool {
    let bar = indicatif::ProgressBar::new(steps as u64);
    move |done| {
        bar.set_position(done as u64);
        if done >= steps {
            bar.finish_and_clear();
        }
        true
    }
}

/// `sim --export`, checked before the simulation runs: the spec (format,
/// point count), the folder (created, and writable), and the groom that
/// drawn strands and the head need: the style on the head it is simulated
/// against (its own for an imported groom, the window's, or the default
/// head where `sim` grows scalp placements), so every export writes the
/// head the hair rests on.
#[derive(Debug)]
pub struct SimExport {
    spec: ExportSpec,
    groom: Option<Groom>,
    head: Option<TriangleMesh>,
}

impl SimExport {
    /// Checks `path` and `args` and prepares the export of `style`
    /// simulated against `head`.
    pub fn prepare(
        path: &Path,
        args: &ExportShapeArgs,
        style: &Style,
        head: HeadMesh,
    ) -> anyhow::Result<Self> {
        let spec = args.spec(path, FrameChoice::All)?;
        check_writable(path)?;
        let needs_groom = spec.strands == StrandChoice::Drawn || spec.writes_head();
        let groom = needs_groom.then(|| Groom::new(style.clone(), head));
        let head = groom.as_ref().map(|g| head_triangle_mesh(&g.head));
        Ok(SimExport { spec, groom, head })
    }

    /// Runs `sim`'s `steps` frames, exporting them; `progress` as in
    /// [`simulate_and_export`].
    pub fn run(
        self,
        sim: &mut dyn FrameStepper,
        steps: usize,
        progress: &mut dyn FnMut(usize) -> bool,
    ) -> anyhow::Result<(Vec<f64>, ExportOutcome)> {
        simulate_and_export(
            sim,
            steps,
            self.spec,
            self.groom.as_ref(),
            self.head.as_ref(),
            progress,
        )
    }
}

/// Runs `helixhair export`.
pub fn run_export(args: &ExportArgs, stdout: &mut dyn Write) -> anyhow::Result<()> {
    let spec = args.shape.spec(&args.out, FrameChoice::Last)?;
    let style_path = args.style.display().to_string();
    let playback = match &args.play {
        Some(play) => Some(play.load()?),
        None => None,
    };
    check_writable(&args.out)?;
    // Style and head errors already name the file, line and field.
    let overrides = SimOverrides {
        engine: args.engine,
        ..SimOverrides::default()
    };
    let (groom, mut sim) = grown_sim(&args.style, args.head.as_deref(), overrides)?;
    if let Some(playback) = playback {
        sim.play_motion(playback);
    }
    let head = head_triangle_mesh(&groom.head);
    let steps = args.steps as usize;
    let (wall_secs, outcome) = simulate_and_export(
        &mut sim,
        steps,
        spec,
        Some(&groom),
        Some(&head),
        &mut terminal_progress(steps),
    )
    .with_context(|| format!("exporting {style_path}"))?;
    writeln!(
        stdout,
        "style `{}` ({style_path}): {} simulated strands, {}\n  {}",
        groom.style.name,
        sim.engine().strand_count(),
        crate::sim::report::frames_simulated(steps, wall_secs.iter().sum()),
        outcome.summary()
    )?;
    if let Some(note) = sim.engine().gpu_note() {
        writeln!(stdout, "  {note}")?;
    }
    Ok(())
}

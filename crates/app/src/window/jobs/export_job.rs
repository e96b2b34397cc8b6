//! File → "Export frame…" and "Record animation…": the hair as curve files
//! (.usda, .usdc, .usd, .usdz, .abc, .hair, .tfx, .obj), written by the same
//! code as `helixhair sim
//! --export` ([`crate::export::command::SimExport`]).
//!
//! # How it works
//!
//! The window's run ([`LiveSim`]) and the head's driver ([`HeadDriver`],
//! the user's pose, its spring and any playback or motion file playing)
//! are cloned, and a worker thread ([`super::job`]) steps the clone as the
//! window would step it ([`WindowRun`], a
//! [`crate::sim::frame_stepper::FrameStepper`]), exporting every
//! frame through the command line's export loop. "Export frame…" is the
//! same with no frame stepped: the state on screen. The window goes on
//! with its own run meanwhile; the recording is what the next N frames
//! would have been with the user's hands off the head. A USD or Alembic file is
//! written once, atomically, at the end; a sequence's frames are each
//! written atomically as they come, and Cancel removes the ones written.

use std::path::PathBuf;
use std::time::Instant;

use helixhair_physics::engine::Engine;

use crate::export::command::{ExportShapeArgs, SimExport};
use crate::export::{FrameChoice, StrandChoice};
use crate::sim::frame_stepper::FrameStepper;

use super::job::{Job, JobDone};
use crate::motion::clip::Clip;
use crate::window::live::head_motion::HeadDriver;
use crate::window::live::live_sim::LiveSim;
use crate::window::state::app_state::AppState;

/// What the export dialog asks for.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportRequest {
    /// The file; its extension picks the format.
    pub path: PathBuf,
    /// Simulated strands or every drawn strand.
    pub strands: StrandChoice,
    /// Points per exported strand.
    pub points_per_strand: usize,
    /// Frames to record after the current one; 0 exports the frame on
    /// screen alone ("Export frame…").
    pub frames: usize,
    /// A clip the recording plays from its first frame (`None`: the head
    /// moves on as it moves now).
    pub clip: Option<Clip>,
}

/// The window's run stepped off the window, as the window steps it.
pub struct WindowRun {
    /// The run (a clone of the window's).
    pub sim: LiveSim,
    /// The head (a clone of the window's), recorder off.
    pub head: HeadDriver,
}

impl FrameStepper for WindowRun {
    fn step_frame(&mut self) -> anyhow::Result<f64> {
        let frame = self.head.frame(self.sim.now_secs());
        let started = Instant::now();
        self.sim.step(&frame);
        let secs = started.elapsed().as_secs_f64();
        self.head.advance(self.sim.engine().settings().dt_secs);
        anyhow::ensure!(
            self.sim.engine().is_finite(),
            "the simulation blew up at {:.3} s; nothing was written",
            self.sim.now_secs()
        );
        Ok(secs)
    }

    fn engine(&self) -> &Engine {
        self.sim.engine()
    }
}

/// Starts the export `request` of the window's current state on a worker
/// thread. Bad requests (unknown extension, a point count the format cannot
/// hold, an unwritable folder, an invalid style) fail here, at once.
pub fn start_export(app: &AppState, request: &ExportRequest) -> anyhow::Result<Job<JobDone>> {
    if let Err(e) = app.doc().validity() {
        anyhow::bail!("the style is invalid ({e}); fix it before exporting");
    }
    let shape = ExportShapeArgs {
        strands: request.strands,
        points_per_strand: request.points_per_strand,
        export_frames: Some(if request.frames > 0 {
            FrameChoice::All
        } else {
            FrameChoice::Last
        }),
        no_head: false,
    };
    // The head the window simulates against, as it shows it.
    let head_mesh = (**app.head_mesh()).clone();
    let export = SimExport::prepare(&request.path, &shape, app.doc().style(), head_mesh)?;
    let mut head = app.head().clone();
    head.recorder = None;
    if let Some(clip) = request.clip {
        head.play(clip, app.now_secs());
    }
    let mut run = WindowRun {
        sim: app.sim().clone(),
        head,
    };
    let steps = request.frames;
    let label = if steps == 0 {
        format!("Exporting {}", request.path.display())
    } else {
        format!("Recording {steps} frames to {}", request.path.display())
    };
    Job::spawn(label, move |progress| {
        progress.start(steps);
        let mut report = |done| {
            progress.set(done, steps);
            !progress.cancelled()
        };
        let (_, outcome) = export.run(&mut run, steps, &mut report)?;
        Ok(JobDone::Exported(outcome))
    })
}

#[cfg(test)]
#[path = "export_job_tests.rs"]
mod tests;

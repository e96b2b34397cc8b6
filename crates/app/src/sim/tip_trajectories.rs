//! Per-frame tip trajectories for `helixhair sim --tip-trajectories`: every
//! strand's tip, world coordinates, at the start and after each frame, so
//! a shot played with `--play` (a clip or a motion file) can be compared
//! frame by frame without exporting curves (docs/sim-json.md).
//!
//! [`Tracked`] wraps whatever steps the frames (a
//! [`FrameStepper`]: the headless run, with or without `--export`) and
//! records the tips after each of its frames, so the report's trajectories
//! are those of the very run it reports.

use helixhair_physics::engine::Engine;
use serde::Serialize;

use crate::sim::frame_stepper::FrameStepper;

/// The tips of every strand, frame by frame.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TipTrajectories {
    /// Simulated time of each recorded frame, seconds (the start first).
    pub time_secs: Vec<f64>,
    /// Per strand (in the report's `strands` order), its tip position at
    /// each recorded frame, metres, world frame (y up).
    pub tips_m: Vec<Vec<[f64; 3]>>,
}

impl TipTrajectories {
    /// Records the tips of `engine` now.
    pub fn record(&mut self, engine: &Engine) {
        let n = engine.strand_count();
        self.tips_m.resize(n, Vec::new());
        self.time_secs.push(engine.time_secs());
        for (i, track) in self.tips_m.iter_mut().enumerate() {
            let tip = engine.boundary_points_world(i).last().copied();
            track.push(tip.map_or([f64::NAN; 3], |p| p.to_array()));
        }
    }
}

/// A run whose tips are recorded after each frame, when asked.
pub struct Tracked<'a> {
    /// The run.
    pub sim: &'a mut dyn FrameStepper,
    /// What has been recorded (the start, then each frame); `None` when
    /// not asked.
    pub tips: Option<TipTrajectories>,
}

impl<'a> Tracked<'a> {
    /// Steps `sim`, recording its tips (now, and after each frame) if
    /// `record`.
    pub fn new(sim: &'a mut dyn FrameStepper, record: bool) -> Self {
        let tips = record.then(|| {
            let mut tips = TipTrajectories::default();
            tips.record(sim.engine());
            tips
        });
        Tracked { sim, tips }
    }
}

impl FrameStepper for Tracked<'_> {
    fn step_frame(&mut self) -> anyhow::Result<f64> {
        let secs = self.sim.step_frame()?;
        if let Some(tips) = &mut self.tips {
            tips.record(self.sim.engine());
        }
        Ok(secs)
    }

    fn engine(&self) -> &Engine {
        self.sim.engine()
    }
}

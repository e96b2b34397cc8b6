//! One frame at a time, whatever steps it: the headless run of `sim` and
//! `export` ([`HeadlessSim`]) or the window's own run (its "Record
//! animation…"), so the export loop (`export_cmd`) and the tip
//! trajectories (`tip_trajectories`) serve both.

use helixhair_physics::engine::Engine;

use crate::sim::headless::HeadlessSim;

/// Something that steps frames and shows the state: the headless
/// [`HeadlessSim`] of `sim` and `export`, or the window's own run for
/// "Record animation…", so both export through one loop.
pub trait FrameStepper {
    /// Steps one frame; returns its physics wall time, seconds, or why the
    /// run cannot go on (a blow-up).
    fn step_frame(&mut self) -> anyhow::Result<f64>;
    /// The engine whose state is exported.
    fn engine(&self) -> &Engine;
}

impl FrameStepper for HeadlessSim {
    fn step_frame(&mut self) -> anyhow::Result<f64> {
        Ok(self.run(1)?[0])
    }

    fn engine(&self) -> &Engine {
        HeadlessSim::engine(self)
    }
}

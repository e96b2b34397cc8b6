//! The window's live run as a brush's host ([`BrushHost`]): the run
//! stepped with the head held still where it is, so the brush's strokes
//! ([`crate::brush::stroke_run`]) act on the hair the artist sees, with
//! the same code `helixhair groom` replays them with.

use helixhair_physics::engine::Engine;

use crate::brush::host::BrushHost;
use crate::sim::strands::StyleStrand;
use crate::style::Style;

use super::head_motion::FrameHead;
use super::live_sim::LiveSim;

/// A live run stepped on a still head.
pub struct StillHead<'a> {
    /// The run.
    pub sim: &'a mut LiveSim,
    /// The head's (still) motion over a frame.
    pub head: FrameHead,
}

impl BrushHost for StillHead<'_> {
    fn engine(&self) -> &Engine {
        self.sim.engine()
    }

    fn engine_mut(&mut self) -> &mut Engine {
        self.sim.engine_mut()
    }

    fn grown(&self) -> &Style {
        self.sim.grown_style()
    }

    fn grown_mut(&mut self) -> &mut Style {
        self.sim.grown_style_mut()
    }

    fn strands(&self) -> &[StyleStrand] {
        self.sim.strands()
    }

    fn step_frame(&mut self) -> usize {
        self.sim.step(&self.head);
        self.sim.guard_events().len()
    }

    fn rebuild(&mut self, at_rest: &[usize]) -> anyhow::Result<()> {
        self.sim
            .rebuild_from_grown(at_rest)
            .map_err(|e| anyhow::anyhow!(e))
    }
}

//! A styling session: a style's hair simulated on its head while strokes
//! act on it, and the style it leaves behind.
//!
//! # How it works
//!
//! The session grows the style on its head and simulates it on the f64
//! reference engine (the engine whose strands take external forces: the
//! brush's drag and springs), colliding with the head, the head still. Each
//! stroke ([`crate::brush::strokes::Stroke`]) then either drives the hair
//! while the physics runs (Comb, Grab), or changes strands' parameters at
//! once (Cut, Grow, Curl, Stiffness, Part), or their shapes (Smooth,
//! Freeze), and the hair settles for the rest of the stroke's time, so the
//! next stroke meets it at rest. Settling is the physics with a drag
//! ([`crate::brush::tools::SETTLE_DRAG_PER_S`]) that brings swinging hair to rest within a
//! second; the session starts with [`START_SETTLE_SECS`] of it, from the
//! style's hair as it hangs.
//!
//! Every change is kept as a per-strand edit of the style
//! ([`crate::style::strand_edit`]): the session edits the grown style (whose
//! strand numbers the edits name) and hands the same edits to the style as
//! written, which keeps its placements and drawn strands. A change of
//! parameters rebuilds the engine from the edited style through the one
//! builder ([`crate::sim::strands`]), every strand's state carried over (by
//! arc length where a cut or growth changed its elements), so the session
//! is the style: reloading the saved style starts each edited strand where
//! the session left it (a frozen strand in its frozen shape).
//!
//! The strokes are written once ([`crate::brush::stroke_run`],
//! [`crate::brush::tools`]) against [`BrushHost`], which the session
//! implements; the window's live run implements it too.

use std::sync::Arc;

use anyhow::Context as _;
use helixhair_physics::collision::SignedDistanceField;
use helixhair_physics::engine::{Engine, EngineKind};

use crate::brush::host::BrushHost;
use crate::brush::stroke_run::{StrokeOutcome, StrokeRun};
use crate::brush::strokes::Stroke;
use crate::brush::tools::settle;
use crate::head::groom::Groom;
use crate::sim::build::SimOverrides;
use crate::sim::carry::{Carry, carry_state};
use crate::sim::headless::HeadlessSim;
use crate::sim::strands::{StyleStrand, style_strands};
use crate::style::Style;

/// Simulated time the session lets the hair settle before the first
/// stroke, seconds.
pub const START_SETTLE_SECS: f64 = 3.0;

/// A style's hair on its head, styled stroke by stroke.
pub struct GroomSession {
    /// The style as written and grown, with the edits made so far.
    groom: Groom,
    /// The simulation of the grown style.
    sim: HeadlessSim,
    /// The head's collider, kept for rebuilds.
    collider: Option<Arc<SignedDistanceField>>,
    /// The engine's strands: group and number of each.
    strands: Vec<StyleStrand>,
    /// Guard interventions in the session.
    guard_total: usize,
}

impl GroomSession {
    /// A session on `groom` (a style grown on its head) simulated by
    /// `sim` (built from it, colliding with the head). The session runs
    /// the reference engine whatever the style says: its strands take the
    /// brush's forces.
    pub fn new(groom: Groom, sim: HeadlessSim) -> anyhow::Result<Self> {
        let collider = sim.engine().collider().cloned();
        let mut session = Self {
            strands: style_strands(&groom.grown, |_, g| g.params.clone()),
            groom,
            sim,
            collider,
            guard_total: 0,
        };
        if session.sim.engine().kind() != EngineKind::Reference {
            session.rebuild(&[])?;
        }
        // The artist starts from the hair at rest, as it hangs. A strand
        // with a rest shape (imported sag-free, or frozen) starts in an
        // equilibrium already; one in its natural shape falls into its own.
        if session.strands.iter().any(|s| s.rest_strains.is_none()) {
            let frames = session.frames_of(START_SETTLE_SECS);
            settle(&mut session, frames)?;
        }
        Ok(session)
    }

    /// The style as written, with every edit the strokes made.
    pub fn style(&self) -> Style {
        let mut style = self.groom.style.clone();
        for (written, grown) in style.groups.iter_mut().zip(&self.groom.grown.groups) {
            written.edits = grown.edits.clone();
        }
        style
    }

    /// The simulation.
    pub fn sim(&self) -> &HeadlessSim {
        &self.sim
    }

    /// Applies one stroke, the physics running for its time: Comb and
    /// Grab move the brush along the path over it, the other tools act at
    /// once and the hair settles for it.
    pub fn apply(&mut self, stroke: &Stroke) -> anyhow::Result<StrokeOutcome> {
        let frames = self.frames_of(stroke.seconds);
        let mut run = StrokeRun::replay(self, stroke);
        let settle_frames = if run.drives() {
            for frame in 0..frames {
                let t = (frame as f64 + 0.5) / frames as f64;
                run.drag(self, stroke.centre_at(t), stroke.velocity_at(t))?;
            }
            0
        } else {
            frames
        };
        let (_, outcome) = run.finish(self, settle_frames)?;
        Ok(outcome)
    }

    /// Frames in `seconds` of simulated time.
    fn frames_of(&self, seconds: f64) -> usize {
        (seconds / self.sim.engine().settings().dt_secs).round() as usize
    }

    /// Lets the hair settle for `secs` of simulated time (the physics with
    /// the settling drag, [`crate::brush::tools::SETTLE_DRAG_PER_S`]).
    pub fn settle_for(&mut self, secs: f64) -> anyhow::Result<()> {
        let frames = self.frames_of(secs);
        settle(self, frames)?;
        Ok(())
    }

    /// The guard's interventions in the session so far (retries, resets
    /// and pins).
    pub fn guard_events(&self) -> usize {
        self.guard_total
    }
}

impl BrushHost for GroomSession {
    fn engine(&self) -> &Engine {
        self.sim.engine()
    }

    fn engine_mut(&mut self) -> &mut Engine {
        self.sim.engine_mut()
    }

    fn grown(&self) -> &Style {
        &self.groom.grown
    }

    fn grown_mut(&mut self) -> &mut Style {
        &mut self.groom.grown
    }

    fn strands(&self) -> &[StyleStrand] {
        &self.strands
    }

    /// Steps one frame, counting the guard's interventions in it (the
    /// engine's own list of the frame, not the run's kept report, which is
    /// capped).
    fn step_frame(&mut self) -> usize {
        self.sim.step();
        let engine = self.sim.engine();
        let events = engine
            .reference()
            .map_or(0, |r| r.last_guard_events().len())
            + engine.batch().map_or(0, |b| b.last_guard_events().len());
        self.guard_total += events;
        events
    }

    fn rebuild(&mut self, at_rest: &[usize]) -> anyhow::Result<()> {
        let overrides = SimOverrides {
            engine: Some(EngineKind::Reference),
            ..SimOverrides::default()
        };
        let mut sim = HeadlessSim::new(&self.groom.grown, overrides)
            .context("the styled hair cannot be simulated")?;
        sim.set_head_pivot(self.sim.head_pivot_m());
        sim.engine_mut().set_collider(self.collider.clone());
        carry_state(
            self.sim.engine(),
            sim.engine_mut(),
            Carry::ArcLength,
            at_rest,
        );
        self.strands = style_strands(&self.groom.grown, |_, g| g.params.clone());
        self.sim = sim;
        Ok(())
    }
}

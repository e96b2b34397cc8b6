//! The headless simulation: a style's strands on a still head, stepped
//! frame by frame and timed.
//!
//! The head sits at the origin and does not move (root positions in the
//! style are therefore also world positions). Every frame is timed with a
//! wall clock around [`Engine::step_frame`], and the state is checked
//! for NaN and infinities after each one, so a blow-up is reported at the
//! frame where it happened.
//!
//! The engine ([`helixhair_physics::engine`]) is the style's `engine` or `--engine`:
//! the f64 reference or the f32 batch path, which runs only Exact and
//! Block-diagonal. Both guards re-step a failing strand with Exact and more
//! substeps, then reset or pin it; what they did is kept
//! ([`HeadlessSim::guard_events`]) for the report.
//! The engine is built by [`crate::sim::build`], the one builder every face
//! shares: the overrides, the refusal of a combination the engine cannot
//! run, the automatic choice of an accuracy target.

use std::time::Instant;

use glam::DVec3;
use helixhair_physics::engine::Engine;
use helixhair_physics::{GuardAction, GuardEvent, HairSystem, Method, RigidMotion};
use helixhair_render::head_generate::default_head;

use crate::head::groom::{grow_scalp_roots, needs_head};
use crate::motion::clip::{Clip, ClipTrajectory};
use crate::motion::playback::{HeadPlayback, PivotedPlayback};
use crate::sim::auto_choice::Choice;
use crate::sim::build::{BuiltSim, SimError, SimOverrides, build_sim};
use crate::style::Style;

/// Guard events kept for the report; later ones are only counted.
pub const MAX_KEPT_GUARD_EVENTS: usize = 100;

/// A hair system built from a style, with a still head.
#[derive(Clone, Debug)]
pub struct HeadlessSim {
    engine: Engine,
    group_names: Vec<String>,
    group_of_strand: Vec<usize>,
    head: RigidMotion,
    clip: Option<HeadPlayback>,
    /// The point the head turns about ([`crate::head::of_style`]), metres.
    head_pivot_m: DVec3,
    strands_lost: usize,
    handed_to_exact: usize,
    choices: Vec<Choice>,
    guard_events: Vec<GuardEvent>,
}

impl HeadlessSim {
    /// How many times the guard reset or pinned a strand so far: each one
    /// means the result is not the simulation the user asked for (a retry
    /// with Exact or more substeps still is).
    pub fn strands_lost(&self) -> usize {
        self.strands_lost
    }

    /// How many strand-frames of a Block-diagonal run the guard stepped
    /// with Exact instead, because Block-diagonal could not hold them:
    /// what those frames show is Exact, and the user is told so.
    pub fn handed_to_exact(&self) -> usize {
        self.handed_to_exact
    }

    /// Plays `clip` on the head from time zero, then holds the head still
    /// (the window's clips; `helixhair sim --play`).
    pub fn play(&mut self, clip: Clip) {
        self.clip = Some(HeadPlayback::Clip(ClipTrajectory(clip)));
    }

    /// Turns the played head about `pivot_m` (world, metres) instead of
    /// the origin: an imported groom's head ([`crate::head::of_style`]).
    pub fn set_head_pivot(&mut self, pivot_m: DVec3) {
        self.head_pivot_m = pivot_m;
    }

    /// The point the played head turns about, metres.
    pub fn head_pivot_m(&self) -> DVec3 {
        self.head_pivot_m
    }

    /// Plays a clip or a motion file on the head from time zero, then
    /// holds the head still (`--play NAME|FILE`).
    pub fn play_motion(&mut self, playback: HeadPlayback) {
        self.clip = Some(playback);
    }

    /// Builds the hair system of `style`, with `overrides` applied to its
    /// settings (and checked).
    /// A style that places roots on the scalp has them grown on the
    /// default head first ([`crate::head::groom`]).
    pub fn new(style: &Style, overrides: SimOverrides) -> Result<Self, SimError> {
        let grown;
        let style = if needs_head(style) {
            grown = grow_scalp_roots(style, &default_head());
            &grown
        } else {
            style
        };
        let BuiltSim {
            engine,
            strands,
            choices,
        } = build_sim(style, overrides)?;
        Ok(Self {
            engine,
            group_names: style.groups.iter().map(|g| g.name.clone()).collect(),
            group_of_strand: strands.iter().map(|s| s.group).collect(),
            head: RigidMotion::default(),
            clip: None,
            head_pivot_m: DVec3::ZERO,
            strands_lost: 0,
            handed_to_exact: 0,
            choices,
            guard_events: Vec::new(),
        })
    }

    /// The engine and its hair system.
    pub fn engine(&self) -> &Engine {
        &self.engine
    }

    /// Mutable access to the engine (tests poison its state; `render`
    /// gives it the head collider).
    pub fn engine_mut(&mut self) -> &mut Engine {
        &mut self.engine
    }

    /// The reference hair system, when the engine is the reference one.
    pub fn reference(&self) -> Option<&HairSystem> {
        self.engine.reference()
    }

    /// The group names, in style order.
    pub fn group_names(&self) -> &[String] {
        &self.group_names
    }

    /// The name of the group strand `index` belongs to.
    pub fn group_name(&self, index: usize) -> &str {
        self.group_of_strand
            .get(index)
            .and_then(|&g| self.group_names.get(g))
            .map_or("", String::as_str)
    }

    /// The automatic choice per group, when an accuracy target was given
    /// (one entry per group, in order; empty otherwise).
    pub fn choices(&self) -> &[Choice] {
        &self.choices
    }

    /// The first [`MAX_KEPT_GUARD_EVENTS`] guard events of the run.
    pub fn guard_events(&self) -> &[GuardEvent] {
        &self.guard_events
    }

    /// Advances one frame; returns its wall time in seconds.
    pub fn step(&mut self) -> f64 {
        let start = Instant::now();
        match &self.clip {
            Some(playback) => self.engine.step_frame(&PivotedPlayback {
                playback,
                pivot_m: self.head_pivot_m,
            }),
            None => self.engine.step_frame(&self.head),
        }
        let secs = start.elapsed().as_secs_f64();
        let room = MAX_KEPT_GUARD_EVENTS.saturating_sub(self.guard_events.len());
        let events = self.engine.last_guard_events();
        self.strands_lost += events
            .iter()
            .filter(|e| matches!(e.action, GuardAction::Reset | GuardAction::Pinned))
            .count();
        if self.engine.settings().method == Method::BlockDiagonal {
            self.handed_to_exact += events
                .iter()
                .filter(|e| {
                    matches!(
                        e.action,
                        GuardAction::Retried {
                            method: Method::Exact,
                            ..
                        }
                    )
                })
                .count();
        }
        self.guard_events
            .extend_from_slice(&events[..events.len().min(room)]);
        secs
    }

    /// Advances `steps` frames, checking the state after each; returns the
    /// wall time of each frame in seconds.
    pub fn run(&mut self, steps: usize) -> Result<Vec<f64>, SimError> {
        let mut wall_secs = Vec::with_capacity(steps);
        for step in 1..=steps {
            wall_secs.push(self.step());
            if !self.engine.is_finite() {
                return Err(SimError::NotFinite {
                    step,
                    steps,
                    time_secs: self.engine.time_secs(),
                });
            }
        }
        Ok(wall_secs)
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use glam::DVec3;
    use helixhair_physics::engine::EngineKind;

    use super::*;

    const STYLE: &str = r#"(
        version: 1,
        name: "two",
        groups: [
            (name: "a", params: (elements: 3), roots: [(position_m: (0.0, 0.1, 0.0), direction: (1.0, 0.0, 0.0))]),
            (name: "b", roots: [
                (position_m: (0.1, 0.0, 0.0), direction: (1.0, 0.0, 0.0)),
                (position_m: (-0.1, 0.0, 0.0), direction: (-1.0, 0.0, 0.0)),
            ]),
        ],
    )"#;

    fn style() -> Style {
        Style::from_ron(STYLE, Path::new("two.ron")).unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn strands_follow_the_style_groups_in_order() {
        let sim = HeadlessSim::new(&style(), SimOverrides::default()).expect("builds");
        assert_eq!(sim.engine().strand_count(), 3);
        let groups: Vec<&str> = (0..3).map(|i| sim.group_name(i)).collect();
        assert_eq!(groups, ["a", "b", "b"]);
        assert_eq!(sim.group_name(3), "", "out of range");
        assert_eq!(sim.engine().element_count(), 3 + 10 + 10);
    }

    #[test]
    fn overrides_replace_the_style_settings() {
        let overrides = SimOverrides {
            method: Some(Method::Dense),
            dt_secs: Some(0.004),
            ..SimOverrides::default()
        };
        let mut sim = HeadlessSim::new(&style(), overrides).expect("builds");
        assert_eq!(sim.engine().settings().method, Method::Dense);
        assert_eq!(sim.engine().settings().dt_secs, 0.004);
        let wall = sim.run(5).expect("finite");
        assert_eq!(wall.len(), 5);
        assert!((sim.engine().time_secs() - 0.02).abs() < 1e-15);
    }

    #[test]
    fn an_out_of_range_dt_names_the_option() {
        for dt in [0.5, -1.0, f64::NAN] {
            let overrides = SimOverrides {
                dt_secs: Some(dt),
                ..SimOverrides::default()
            };
            let error = HeadlessSim::new(&style(), overrides).expect_err("refused");
            assert!(
                matches!(error, SimError::Override { option: "--dt", .. }),
                "{error}"
            );
            assert!(
                error
                    .to_string()
                    .starts_with(&format!("--dt {dt}: field `dt_secs`")),
                "{error}"
            );
        }
    }

    #[test]
    fn a_non_finite_state_stops_the_run_at_that_step() {
        let mut sim = HeadlessSim::new(&style(), SimOverrides::default()).expect("builds");
        sim.run(2).expect("finite so far");
        let engine = sim.engine_mut();
        let mut q = engine.q(1);
        q[4] = DVec3::new(f64::NAN, 0.0, 0.0);
        let v = engine.v(1);
        engine.set_state(1, &q, &v);
        let error = sim.run(10).expect_err("blows up");
        assert!(
            matches!(
                error,
                SimError::NotFinite {
                    step: 1,
                    steps: 10,
                    ..
                }
            ),
            "{error}"
        );
        assert!(error.to_string().contains("after step 1 of 10"), "{error}");
    }

    #[test]
    fn the_batch_engine_runs_the_style_and_refuses_what_it_cannot_run() {
        let batch = SimOverrides {
            engine: Some(EngineKind::Batch),
            ..SimOverrides::default()
        };
        let mut sim = HeadlessSim::new(&style(), batch).expect("Exact runs on the batch engine");
        assert_eq!(sim.engine().kind(), EngineKind::Batch);
        assert_eq!(sim.engine().element_count(), 3 + 10 + 10);
        sim.run(3).expect("finite");
        assert!(sim.reference().is_none() && sim.guard_events().is_empty());

        let cases = [
            (
                SimOverrides {
                    method: Some(Method::Dense),
                    ..batch
                },
                "--engine batch --method dense: the batch engine runs the `exact` or `block` solver only",
            ),
            (
                SimOverrides {
                    accuracy_target: Some(0.02),
                    ..batch
                },
                "--engine batch: an accuracy target chooses a solver per group",
            ),
        ];
        for (overrides, want) in cases {
            let error = HeadlessSim::new(&style(), overrides).expect_err("refused");
            assert!(matches!(error, SimError::Conflict { .. }), "{error}");
            assert!(error.to_string().starts_with(want), "{error}");
        }
        // The style's method is Dense: `--engine batch` alone names it.
        let mut dense = style();
        dense.sim.method = Method::Dense;
        let error = HeadlessSim::new(&dense, batch).expect_err("refused");
        assert!(
            error
                .to_string()
                .starts_with("--engine batch: the style's `sim.method` is `dense`"),
            "{error}"
        );
        // The style asks for the batch engine; `--method iterative:4` cannot run on it.
        let mut on_batch = style();
        on_batch.engine = EngineKind::Batch;
        let iterative = SimOverrides {
            method: Some(Method::Iterative { iterations: 4 }),
            ..SimOverrides::default()
        };
        let error = HeadlessSim::new(&on_batch, iterative).expect_err("refused");
        assert!(
            error
                .to_string()
                .starts_with("--method iterative:4: the style's `engine` is `Batch`"),
            "{error}"
        );
        // ...and `--engine reference` lifts it.
        let reference = SimOverrides {
            engine: Some(EngineKind::Reference),
            ..iterative
        };
        let sim = HeadlessSim::new(&on_batch, reference).expect("builds");
        assert_eq!(sim.engine().kind(), EngineKind::Reference);
    }
}

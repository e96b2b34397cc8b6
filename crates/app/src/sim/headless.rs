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
//! A combination the engine cannot run is refused before anything is
//! built, naming the option or field that asked for it
//! ([`SimError::Conflict`]).
//!
//! With an accuracy target (style field or `--accuracy`), each group's
//! element count and solver come from [`crate::sim::auto_choice`] (reference
//! engine only: the choice may pick any solver per group).

use std::time::Instant;

use glam::DVec3;
use helixhair_physics::engine::{Engine, EngineKind};
use helixhair_physics::{
    GuardAction, GuardEvent, HairSystem, Method, ParamError, RigidMotion, StepScheme,
};
use helixhair_render::head_generate::default_head;
use thiserror::Error;

use crate::head::groom::{grow_scalp_roots, needs_head};
use crate::motion::clip::{Clip, ClipTrajectory};
use crate::motion::playback::{HeadPlayback, PivotedPlayback};
use crate::sim::auto_choice::{Choice, choose};
use crate::sim::error_model::ErrorModel;
use crate::sim::strands::{add_strands, group_strands};
use crate::style::Style;
use crate::style::error::StyleIssue;
use crate::style::field_path::FieldPath;
use crate::style::validate::{check_accuracy_target, param_issue};

/// Command-line overrides of the style's settings.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SimOverrides {
    /// Engine to use instead of the style's `engine`.
    pub engine: Option<EngineKind>,
    /// Solver to use instead of the style's `sim.method`.
    pub method: Option<Method>,
    /// Frame time step in seconds instead of the style's `sim.dt_secs`.
    pub dt_secs: Option<f64>,
    /// Accuracy target instead of the style's `accuracy_target`: choose
    /// solver and element counts (see [`crate::sim::auto_choice`]).
    pub accuracy_target: Option<f64>,
    /// How the reference engine's step treats the velocity terms, instead
    /// of the style's `sim.scheme` (`--velocity-terms`).
    pub scheme: Option<StepScheme>,
    /// Hair–hair interaction on or off instead of the style's
    /// `sim.interaction.enabled` (`--interaction`).
    pub interaction: Option<bool>,
}

/// Guard events kept for the report; later ones are only counted.
pub const MAX_KEPT_GUARD_EVENTS: usize = 100;

/// Why a headless simulation could not be set up or finished. Each message
/// is complete on its own, so no variant reports a separate `source`.
#[derive(Debug, Error)]
pub enum SimError {
    /// A command-line override is out of range.
    #[error("{option} {value}: {error}")]
    Override {
        /// The option, e.g. `--dt`.
        option: &'static str,
        /// The value given.
        value: String,
        /// What the physics crate says about it.
        error: ParamError,
    },
    /// The engine cannot run what the options and the style ask for
    /// together (the batch engine with a solver other than Exact and
    /// Block-diagonal, or with an accuracy target).
    #[error("{options}: {message}")]
    Conflict {
        /// The command-line options involved, as written (`--engine batch
        /// --method dense`).
        options: String,
        /// What cannot be done and how to fix it.
        message: String,
    },
    /// The style does not describe a valid hair system (a loaded style has
    /// been validated, so this concerns styles built in code).
    #[error("style `{style}`: {issue}")]
    Style {
        /// The style's name.
        style: String,
        /// The offending field.
        issue: StyleIssue,
    },
    /// The built-in error model could not be read (a build problem).
    #[error("{0}")]
    ErrorModel(String),
    /// The state held NaN or infinities after a frame.
    #[error(
        "the simulation blew up: the strand state is not finite after step {step} of {steps} \
         (t = {time_secs} s); try a smaller --dt or more substeps"
    )]
    NotFinite {
        /// The frame after which it happened, counted from 1.
        step: usize,
        /// The number of frames asked for.
        steps: usize,
        /// Simulated time at that point, seconds.
        time_secs: f64,
    },
}

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
        let mut settings = style.sim.clone();
        if let Some(method) = overrides.method {
            settings.method = method;
        }
        if let Some(scheme) = overrides.scheme {
            settings.scheme = scheme;
        }
        if let Some(on) = overrides.interaction {
            settings.interaction.enabled = on;
        }
        if let Some(dt_secs) = overrides.dt_secs {
            settings.dt_secs = dt_secs;
            if let Err(error) = settings.validate()
                && error.field == "dt_secs"
            {
                return Err(SimError::Override {
                    option: "--dt",
                    value: dt_secs.to_string(),
                    error,
                });
            }
        }
        let accuracy_target = overrides.accuracy_target.or(style.accuracy_target);
        if let Some(target) = overrides.accuracy_target
            && let Err(error) = check_accuracy_target(target)
        {
            return Err(SimError::Override {
                option: "--accuracy",
                value: target.to_string(),
                error,
            });
        }
        let engine_kind = overrides.engine.unwrap_or(style.engine);
        check_engine_options(engine_kind, &settings, accuracy_target, overrides)?;
        let model = match accuracy_target {
            Some(_) => {
                Some(ErrorModel::built_in().map_err(|e| SimError::ErrorModel(format!("{e:#}")))?)
            }
            None => None,
        };
        let style_issue = |issue| SimError::Style {
            style: style.name.clone(),
            issue,
        };
        let sim_path = FieldPath::root().field("sim");
        if let (Some(model), Some(target)) = (&model, accuracy_target) {
            // One step for the whole system: the finest any group needs.
            let needed = style
                .groups
                .iter()
                .filter_map(|g| {
                    choose(
                        model,
                        &g.params,
                        settings.dt_secs,
                        settings.substeps,
                        target,
                    )
                })
                .map(|c| c.substeps)
                .max();
            settings.substeps = settings.substeps.max(needed.unwrap_or(1));
        }
        let mut system = Engine::new(engine_kind, settings)
            .map_err(|e| style_issue(param_issue(&sim_path, &e)))?;
        let mut group_of_strand = Vec::with_capacity(style.strand_count());
        let mut choices = Vec::new();
        for (i, group) in style.groups.iter().enumerate() {
            let mut params = group.params.clone();
            let choice = match (&model, accuracy_target) {
                (Some(model), Some(target)) => {
                    let settings = system.settings();
                    choose(model, &params, settings.dt_secs, settings.substeps, target)
                }
                _ => None,
            };
            if let Some(choice) = &choice {
                params.elements = choice.elements;
            }
            let range = add_strands(&mut system, &group_strands(i, group, &params))
                .map_err(|(at, e)| style_issue(param_issue(&at, &e)))?;
            if let Some(choice) = choice {
                // An accuracy target implies the reference engine (checked above).
                if let Some(reference) = system.reference_mut() {
                    for strand in &mut reference.strands_mut()[range.clone()] {
                        strand.set_method(choice.method);
                    }
                }
                choices.push(choice);
            }
            group_of_strand.extend(range.map(|_| i));
        }
        Ok(Self {
            engine: system,
            group_names: style.groups.iter().map(|g| g.name.clone()).collect(),
            group_of_strand,
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

/// Refuses what `kind` cannot run, naming the options (or the style
/// field) that asked for it. A loaded style never asks for an impossible
/// combination itself (its validation refuses one), so at least one
/// option is always involved.
fn check_engine_options(
    kind: EngineKind,
    settings: &helixhair_physics::SimSettings,
    accuracy_target: Option<f64>,
    overrides: SimOverrides,
) -> Result<(), SimError> {
    if kind == EngineKind::Reference {
        return Ok(());
    }
    let allowed = EngineKind::BATCH_METHODS.map(|m| format!("`{}`", m.label()));
    let allowed = allowed.join(" or ");
    let method = settings.method.label();
    let (options, message) = if !kind.runs(settings.method) {
        match (overrides.engine, overrides.method) {
            (Some(_), Some(_)) => (
                format!("--engine batch --method {method}"),
                format!(
                    "the batch engine runs the {allowed} solver only; \
                     use --method exact or block, or --engine reference"
                ),
            ),
            (Some(_), None) => (
                "--engine batch".to_owned(),
                format!(
                    "the style's `sim.method` is `{method}`, which the batch engine cannot run \
                     (it runs {allowed}); add --method exact or --method block"
                ),
            ),
            (None, Some(_)) => (
                format!("--method {method}"),
                format!(
                    "the style's `engine` is `Batch`, which runs the {allowed} solver only; \
                     add --engine reference to use `{method}`"
                ),
            ),
            // A style built in code (a loaded one is validated).
            (None, None) => (
                "style field `engine: Batch`".to_owned(),
                format!("the batch engine runs {allowed} only, not `sim.method` `{method}`"),
            ),
        }
    } else if accuracy_target.is_some() {
        let option = if overrides.engine.is_some() {
            "--engine batch"
        } else if overrides.accuracy_target.is_some() {
            "--accuracy"
        } else {
            "style field `engine: Batch`"
        };
        (
            option.to_owned(),
            "an accuracy target chooses a solver per group, which only the reference engine \
             runs; drop the target, or use --engine reference"
                .to_owned(),
        )
    } else {
        return Ok(());
    };
    Err(SimError::Conflict { options, message })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use glam::DVec3;

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

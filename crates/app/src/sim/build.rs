//! The one builder from a style to a running simulation: every face that
//! simulates a style (`sim`, `render`, `export`, the bench, the window and
//! its compare view, the styling tools) builds its engine here.
//!
//! # What it does, in order
//!
//! 1. The style's settings (`sim`) with the overrides applied: solver,
//!    velocity terms, hair–hair interaction, frame time step (checked, the
//!    option named: `--dt 0`).
//! 2. The engine chosen (`engine`, or `--engine`) is asked whether it can
//!    run what the settings and options ask for together; a combination it
//!    cannot run is refused before anything is built, naming the options
//!    ([`SimError::Conflict`]).
//! 3. With an accuracy target (style field or `--accuracy`), each group's
//!    element count and solver come from [`crate::sim::auto_choice`] over
//!    the measured error model, and the frame's substeps are the finest any
//!    group needs (the reference engine only: it runs a solver per strand).
//! 4. The strands are added in engine order ([`crate::sim::strands`]), each
//!    at rest in its rest shape.
//!
//! The style must be grown already (scalp placements turned into roots,
//! [`crate::head::groom::grow_scalp_roots`]): the headless run grows on the
//! default head, the window on the head it shows.
//!
//! Errors are [`SimError`]s: each names the option or style field at fault,
//! so `sim` and the window report the same sentence.

use helixhair_physics::engine::{Engine, EngineKind};
use helixhair_physics::{Method, ParamError, SimSettings, StepScheme};
use thiserror::Error;

use crate::sim::auto_choice::{Choice, choose};
use crate::sim::error_model::ErrorModel;
use crate::sim::strands::{StyleStrand, add_strands, style_strands};
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

/// A style built into an engine: the engine, its strands in engine order,
/// and the automatic choice per group when an accuracy target asked for
/// one.
#[derive(Clone, Debug)]
pub struct BuiltSim {
    /// The engine, every strand added at rest.
    pub engine: Engine,
    /// The engine's strands: group, number and parameters of each.
    pub strands: Vec<StyleStrand>,
    /// The automatic choice per group (one entry per group, in order),
    /// when an accuracy target was given; empty otherwise.
    pub choices: Vec<Choice>,
}

/// Builds the engine of the grown `style` with `overrides` applied to its
/// settings (and checked): see the module documentation for the steps.
pub fn build_sim(style: &Style, overrides: SimOverrides) -> Result<BuiltSim, SimError> {
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
    let style_issue = |issue| SimError::Style {
        style: style.name.clone(),
        issue,
    };
    let choices = match accuracy_target {
        Some(target) => {
            let model =
                ErrorModel::built_in().map_err(|e| SimError::ErrorModel(format!("{e:#}")))?;
            // One step for the whole system: the finest any group needs.
            let needed = style
                .groups
                .iter()
                .filter_map(|g| {
                    choose(
                        &model,
                        &g.params,
                        settings.dt_secs,
                        settings.substeps,
                        target,
                    )
                })
                .map(|c| c.substeps)
                .max();
            settings.substeps = settings.substeps.max(needed.unwrap_or(1));
            let (dt_secs, substeps) = (settings.dt_secs, settings.substeps);
            style
                .groups
                .iter()
                .map(|g| choose(&model, &g.params, dt_secs, substeps, target))
                .collect::<Vec<_>>()
        }
        None => Vec::new(),
    };
    let sim_path = FieldPath::root().field("sim");
    let mut engine =
        Engine::new(engine_kind, settings).map_err(|e| style_issue(param_issue(&sim_path, &e)))?;
    let choice_of = |g: usize| choices.get(g).and_then(Option::as_ref);
    let strands = style_strands(style, |g, group| {
        let mut params = group.params.clone();
        if let Some(choice) = choice_of(g) {
            params.elements = choice.elements;
        }
        params
    });
    add_strands(&mut engine, &strands).map_err(|(at, e)| style_issue(param_issue(&at, &e)))?;
    // An accuracy target implies the reference engine (checked above).
    if let Some(reference) = engine.reference_mut() {
        for (strand, built) in reference.strands_mut().iter_mut().zip(&strands) {
            if let Some(choice) = choice_of(built.group) {
                strand.set_method(choice.method);
            }
        }
    }
    Ok(BuiltSim {
        engine,
        strands,
        choices: choices.into_iter().flatten().collect(),
    })
}

/// Refuses what `kind` cannot run, naming the options (or the style
/// field) that asked for it. A loaded style never asks for an impossible
/// combination itself (its validation refuses one), so at least one
/// option is always involved.
fn check_engine_options(
    kind: EngineKind,
    settings: &SimSettings,
    accuracy_target: Option<f64>,
    overrides: SimOverrides,
) -> Result<(), SimError> {
    if kind == EngineKind::Reference {
        return Ok(());
    }
    let allowed = EngineKind::BATCH_METHODS.map(|m| format!("`{}`", m.label()));
    let allowed = allowed.join(" or ");
    let method = settings.method.label();
    let engine = kind.label();
    let style_engine = format!("{kind:?}");
    let (options, message) = if !kind.runs(settings.method) {
        match (overrides.engine, overrides.method) {
            (Some(_), Some(_)) => (
                format!("--engine {engine} --method {method}"),
                format!(
                    "the {engine} engine runs the {allowed} solver only; \
                     use --method exact or block, or --engine reference"
                ),
            ),
            (Some(_), None) => (
                format!("--engine {engine}"),
                format!(
                    "the style's `sim.method` is `{method}`, which the {engine} engine cannot run \
                     (it runs {allowed}); add --method exact or --method block"
                ),
            ),
            (None, Some(_)) => (
                format!("--method {method}"),
                format!(
                    "the style's `engine` is `{style_engine}`, which runs the {allowed} solver only; \
                     add --engine reference to use `{method}`"
                ),
            ),
            // A style built in code (a loaded one is validated).
            (None, None) => (
                format!("style field `engine: {style_engine}`"),
                format!("the {engine} engine runs {allowed} only, not `sim.method` `{method}`"),
            ),
        }
    } else if accuracy_target.is_some() {
        let option = if overrides.engine.is_some() {
            format!("--engine {engine}")
        } else if overrides.accuracy_target.is_some() {
            "--accuracy".to_owned()
        } else {
            format!("style field `engine: {style_engine}`")
        };
        (
            option,
            "an accuracy target chooses a solver per group, which only the reference engine \
             runs; drop the target, or use --engine reference"
                .to_owned(),
        )
    } else {
        return Ok(());
    };
    Err(SimError::Conflict { options, message })
}

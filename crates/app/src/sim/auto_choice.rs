//! Model no more than the scene needs: the cheapest solver and element
//! count whose measured error meets an accuracy target.
//!
//! The target is a tip-position RMS error as a fraction of the strand's
//! length (the accuracy study's measure, `docs/solvers.md`). For a group of
//! strands the choice:
//!
//! 1. takes the curl class of the [`ErrorModel`] whose curvature is the
//!    smallest at least as tight as the group's (never a looser one, so the
//!    prediction errs on the safe side);
//! 2. takes the runs measured with a step no longer than the group's
//!    (the style's step is the coarsest it accepts; the finest measured
//!    run if the style's step is finer still);
//! 3. among those whose error meets the target, picks the cheapest (CPU
//!    time per simulated second, substeps included); if none does, the most
//!    accurate, and says the target is out of reach; the substeps per frame
//!    follow from the chosen run's step;
//! 4. scales the element count by length / 20 cm, which keeps the measured
//!    element length and so the turning per element the error depends on.
//!
//! Straight hair needs few elements; tight coils and long hair get more.

use helixhair_physics::{Method, StrandParams};
use serde::Serialize;

use crate::sim::error_model::{ErrorEntry, ErrorModel, max_curvature_per_m};

/// Frame length of the measured runs, seconds (the bench's scenes).
pub const MODEL_FRAME_SECS: f64 = 1.0 / 60.0;
/// Most substeps per frame a choice may give (the settings' limit).
pub const MAX_SUBSTEPS: u32 = 64;

/// Fewest and most elements a choice may give.
pub const ELEMENT_RANGE: (usize, usize) = (2, 100);

/// The solver and element count chosen for one group.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Choice {
    /// Solver.
    pub method: Method,
    /// Elements per strand, scaled to the group's length.
    pub elements: usize,
    /// Substeps per frame, so that the step is no longer than the run's.
    pub substeps: u32,
    /// The measured error of the run the choice rests on (fraction of length).
    pub predicted_error: f64,
    /// Curl class the prediction comes from.
    pub class: String,
    /// Whether the target is met; false: the most accurate run was taken.
    pub target_met: bool,
}

/// Chooses for strands with `params` stepped at least `substeps` times
/// per frame of `dt_secs`, to meet `target` (a fraction of length, > 0).
pub fn choose(
    model: &ErrorModel,
    params: &StrandParams,
    dt_secs: f64,
    substeps: u32,
    target: f64,
) -> Option<Choice> {
    let curvature = max_curvature_per_m(params);
    let class = model
        .classes
        .iter()
        .find(|c| c.curvature_per_m >= curvature * (1.0 - 1e-9))
        .or(model.classes.last())?;
    let h_secs = dt_secs / f64::from(substeps.max(1));
    let step_of = |e: &ErrorEntry| MODEL_FRAME_SECS / f64::from(e.substeps.max(1));
    let of_class: Vec<&ErrorEntry> = model
        .entries
        .iter()
        .filter(|e| e.class == class.class && e.error.is_finite())
        .collect();
    let finest = of_class
        .iter()
        .map(|e| step_of(e))
        .fold(f64::INFINITY, f64::min);
    let allowed = h_secs.max(finest) * (1.0 + 1e-9);
    let candidates: Vec<&ErrorEntry> = of_class
        .into_iter()
        .filter(|e| step_of(e) <= allowed)
        .collect();
    let meeting = candidates
        .iter()
        .filter(|e| e.error <= target)
        .min_by(|a, b| a.cost_ms_per_sim_sec.total_cmp(&b.cost_ms_per_sim_sec));
    let (entry, target_met) = match meeting {
        Some(e) => (*e, true),
        None => (
            *candidates
                .iter()
                .min_by(|a, b| a.error.total_cmp(&b.error))?,
            false,
        ),
    };
    let needed_substeps = (dt_secs / step_of(entry) * (1.0 - 1e-9)).ceil() as u32;
    let scaled = (entry.elements as f64 * params.length_m / model.scene_length_m).ceil() as usize;
    Some(Choice {
        method: entry.method,
        elements: scaled.clamp(ELEMENT_RANGE.0, ELEMENT_RANGE.1),
        substeps: needed_substeps.max(substeps).clamp(1, MAX_SUBSTEPS),
        predicted_error: entry.error,
        class: class.class.clone(),
        target_met,
    })
}

//! The bench's side of the error model: the accuracy study's rows of the
//! `bounce-CLASS` scenes turned into a [`ErrorModel`] and written as RON.
//!
//! The data type and its reading live with the automatic choice
//! ([`crate::sim::error_model`], [`crate::sim::auto_choice`]), which the headless
//! `sim` path uses without the bench; only the writing is here.

use std::path::Path;

use anyhow::Context as _;
use helixhair_physics::StrandParams;

use super::scenes::{CurlClass, RunSetting, SCENE_LENGTH_M};
use crate::atomic_write::write_atomically;
use crate::sim::error_model::{ClassCurvature, ErrorEntry, ErrorModel, max_curvature_per_m};

/// The model from the accuracy study's measured entries (its rows of the
/// `bounce-CLASS` scenes, [`super::accuracy::error_entries`]).
pub fn error_model_from_entries(
    entries: Vec<ErrorEntry>,
    reference: RunSetting,
    duration_secs: f64,
) -> ErrorModel {
    let classes = CurlClass::ALL
        .iter()
        .map(|&c| ClassCurvature {
            class: c.name().into(),
            curvature_per_m: max_curvature_per_m(&StrandParams {
                natural_shape: c.shape(),
                ..StrandParams::default()
            }),
        })
        .collect();
    ErrorModel {
        source: format!(
            "helixhair bench --study accuracy: 20 cm strands of each curl class, root 45° below horizontal, bouncing 1.5 cm at 2 Hz for \
                 {duration_secs} s; reference {} with {} elements and {} substeps",
            reference.method.label(),
            reference.elements,
            reference.substeps
        ),
        scene_length_m: SCENE_LENGTH_M,
        classes,
        entries,
    }
}

/// Writes `model` as RON to `path`, atomically.
pub fn save_error_model(model: &ErrorModel, path: &Path) -> anyhow::Result<()> {
    let text = ron::ser::to_string_pretty(model, ron::ser::PrettyConfig::default())
        .context("cannot encode the error model")?;
    write_atomically(path, text.as_bytes())
        .with_context(|| format!("cannot write {}", path.display()))
}

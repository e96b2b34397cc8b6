//! The error model: how far each solver and element count strays from a
//! fine Dense reference, measured by `helixhair bench --study accuracy` on
//! a 20 cm strand of each curl class bouncing on its root.
//!
//! This module holds the data type and reads it; it knows nothing of the
//! bench. The bench (`bench::error_model_build`, feature `bench`) writes
//! `error_model.ron`; the copy in `assets/` (from a full bench run,
//! regenerated with the command in `docs/solvers.md`) is built into the
//! binary and read by [`crate::sim::auto_choice`]. Nothing in it is guessed:
//! every entry is one measured run.

use anyhow::Context as _;
use helixhair_physics::{Method, StrandParams};
use serde::{Deserialize, Serialize};

/// The model built into the binary (from a full bench run).
pub const BUILT_IN: &str = include_str!("../../../../assets/error_model.ron");

/// One curl class the model was measured on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClassCurvature {
    /// Class name (`straight`, `wavy`, `curly`, `coily`).
    pub class: String,
    /// Its largest natural curvature, 1/m.
    pub curvature_per_m: f64,
}

/// One measured run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ErrorEntry {
    /// Curl class of the strand.
    pub class: String,
    /// Solver.
    pub method: Method,
    /// Elements on the 20 cm strand.
    pub elements: usize,
    /// Substeps per 1/60 s frame.
    pub substeps: u32,
    /// Tip RMS error over the run, fraction of the length (infinite: blew up).
    pub error: f64,
    /// CPU milliseconds per simulated second, one strand, one thread.
    pub cost_ms_per_sim_sec: f64,
}

/// Every measured run of the curl-class scenes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ErrorModel {
    /// How the numbers were made.
    pub source: String,
    /// Length of the measured strands, metres.
    pub scene_length_m: f64,
    /// Curl classes, loosest first.
    pub classes: Vec<ClassCurvature>,
    /// The runs.
    pub entries: Vec<ErrorEntry>,
}

/// The largest natural curvature of a strand, 1/m (0 for straight hair).
pub fn max_curvature_per_m(params: &StrandParams) -> f64 {
    params
        .natural_shape
        .strains(params.elements)
        .iter()
        .map(|s| s.y.hypot(s.z))
        .fold(0.0, f64::max)
}

impl ErrorModel {
    /// Parses a model from RON text.
    pub fn from_ron(text: &str) -> anyhow::Result<Self> {
        ron::from_str(text).map_err(|e| anyhow::anyhow!("error model, {e}"))
    }

    /// The model built into the binary.
    pub fn built_in() -> anyhow::Result<Self> {
        Self::from_ron(BUILT_IN).context("the built-in error model (assets/error_model.ron)")
    }
}

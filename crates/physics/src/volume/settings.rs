//! The settings of the hair–hair model: on or off, the strength of each
//! term and the grid's cell size, with their units and why the defaults.

use serde::{Deserialize, Serialize};

use crate::error::ParamError;
use crate::error::check_range;

/// How strands of one head interact through the volume grid
/// ([`crate::volume`]). Part of [`crate::SimSettings`] (`sim.interaction`
/// in a style).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct InteractionSettings {
    /// Whether the model runs. Default off: a style asks for it, so every
    /// style and study written before it steps as it did.
    pub enabled: bool,
    /// Friction rate μ, 1/s, range 0..=200: each sample's velocity relaxes
    /// toward the grid's (the local mean of the hair around it) with time
    /// constant 1/μ. Default 5 /s (0.2 s): at 60 Hz a step moves a sample
    /// 7.7% of the way (hμ/(1+hμ)), a gentle blend toward the grid
    /// velocity of the kind Petrovic et al. (2005) apply; hair moves as a
    /// body during a shake without looking stuck.
    pub friction_per_s: f64,
    /// Pressure stiffness P, m²/s², range 0..=10: a sample in hair denser
    /// than its rest density by a fraction e feels an acceleration −P ∇e.
    /// √P is the speed at which a density excess spreads. Default
    /// 0.2 m²/s²: a layer compressed to twice its rest density over one
    /// 2 cm cell is pushed with 10 m/s², about gravity (what sagging hair
    /// needs to hold itself up), while √P h / cell = 0.37 < 1 at 60 Hz
    /// keeps the explicit push stable.
    pub pressure_m2_per_s2: f64,
    /// Edge of a grid cell, metres, range 0.002..=0.2. Default 0.02 m:
    /// about a lock of hair and twice a curl's radius, like the 1–2 cm
    /// cells of the peers' hair volumes (a full head fits in about
    /// 35 × 40 × 35 cells). The grid is capped at
    /// [`super::grid::MAX_NODES`] nodes; a finer cell is coarsened to fit.
    pub cell_m: f64,
}

impl Default for InteractionSettings {
    fn default() -> Self {
        Self {
            enabled: false,
            friction_per_s: 5.0,
            pressure_m2_per_s2: 0.2,
            cell_m: 0.02,
        }
    }
}

impl InteractionSettings {
    /// Checks every field; the error names it as a style file does
    /// (`interaction.friction_per_s`, ...).
    pub fn validate(&self) -> Result<(), ParamError> {
        check_range(
            "interaction.friction_per_s",
            self.friction_per_s,
            0.0,
            200.0,
        )?;
        check_range(
            "interaction.pressure_m2_per_s2",
            self.pressure_m2_per_s2,
            0.0,
            10.0,
        )?;
        check_range("interaction.cell_m", self.cell_m, 0.002, 0.2)
    }
}

//! The style panel's hair–hair interaction controls (`sim.interaction`,
//! docs/volume.md): on or off, friction, pressure, grid cell, and whether
//! the density grid's view ([`super::density_view`]) is open.
//!
//! The tracks are the ranges the style format accepts
//! (`InteractionSettings::validate`), so a dragged value is always valid.
//! Both engines run the model, so the switch is live on either.

use egui::Ui;

use crate::style::Style;

use super::density_view;
use super::value_slider::{Look, scaled_slider, slider};

/// Friction rate track, 1/s.
pub const FRICTION_TRACK: (f64, f64) = (0.0, 200.0);
/// Pressure stiffness track, m²/s².
pub const PRESSURE_TRACK: (f64, f64) = (0.0, 10.0);
/// Grid cell track, metres.
pub const CELL_TRACK: (f64, f64) = (0.002, 0.2);

/// Draws the controls; typed text that is not a number is reported in
/// `notes`.
pub fn interaction_settings(ui: &mut Ui, style: &mut Style, notes: &mut Vec<String>) {
    let settings = &mut style.sim.interaction;
    ui.checkbox(&mut settings.enabled, "hair–hair interaction")
        .on_hover_text("strands feel each other through a density grid (either engine)");
    if !settings.enabled {
        return;
    }
    let (f0, f1) = FRICTION_TRACK;
    slider(
        ui,
        notes,
        "friction",
        &mut settings.friction_per_s,
        f0..=f1,
        Look::log(" /s", 0.01),
    );
    let (p0, p1) = PRESSURE_TRACK;
    slider(
        ui,
        notes,
        "pressure",
        &mut settings.pressure_m2_per_s2,
        p0..=p1,
        Look::log(" m²/s²", 1e-4),
    );
    let (c0, c1) = CELL_TRACK;
    scaled_slider(
        ui,
        notes,
        "grid cell",
        &mut settings.cell_m,
        c0..=c1,
        100.0,
        Look::unit(" cm"),
    );
    density_view::toggle(ui);
}

#[cfg(test)]
mod tests {
    use helixhair_physics::InteractionSettings;

    use super::*;

    /// Each track's ends are accepted by the format and a step beyond is not.
    #[test]
    fn tracks_are_the_format_ranges() {
        let at = |f: f64, p: f64, c: f64| {
            InteractionSettings {
                enabled: true,
                friction_per_s: f,
                pressure_m2_per_s2: p,
                cell_m: c,
            }
            .validate()
            .is_ok()
        };
        let ((f0, f1), (p0, p1), (c0, c1)) = (FRICTION_TRACK, PRESSURE_TRACK, CELL_TRACK);
        assert!(at(f0, p0, c0) && at(f1, p1, c1));
        assert!(!at(f1 * 1.01, p0, c0) && !at(f0, p1 * 1.01, c0) && !at(f0, p0, c1 * 1.01));
        assert!(!at(f0, p0, c0 * 0.99));
    }
}

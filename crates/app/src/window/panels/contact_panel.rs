//! The style panel's contact control (`sim.contact.skin_m`,
//! docs/style-format.md): how far above the head's mesh the hair rests.
//!
//! The contact's spring gives under load, so hair pressed on the head
//! (draped loops, a coil turning with the head) sinks into the skin; a
//! thicker skin keeps it off the mesh itself. The track is the range the
//! style format accepts (`ContactSettings::validate`), so a dragged value
//! is always valid. The stiffness stays the format's business: stiffer
//! contact blows up as long hair lands on the head.

use egui::Ui;

use crate::style::Style;

use super::value_slider::{Look, scaled_slider};

/// Contact skin track, metres.
pub const SKIN_TRACK: (f64, f64) = (0.0, 0.02);

/// Draws the control; typed text that is not a number is reported in
/// `notes`.
pub fn contact_settings(ui: &mut Ui, style: &mut Style, notes: &mut Vec<String>) {
    let (s0, s1) = SKIN_TRACK;
    scaled_slider(
        ui,
        notes,
        "contact skin",
        &mut style.sim.contact.skin_m,
        s0..=s1,
        1000.0,
        Look::unit(" mm"),
    );
}

#[cfg(test)]
mod tests {
    use helixhair_physics::collision::ContactSettings;

    use super::*;

    /// The track's ends are accepted by the format and a step beyond is not.
    #[test]
    fn the_track_is_the_format_range() {
        let at = |skin_m: f64| {
            ContactSettings {
                skin_m,
                ..ContactSettings::default()
            }
            .validate()
            .is_ok()
        };
        let (s0, s1) = SKIN_TRACK;
        assert!(at(s0) && at(s1));
        assert!(!at(s1 * 1.01) && !at(-1e-4));
    }
}

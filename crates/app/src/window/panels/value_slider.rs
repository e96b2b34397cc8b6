//! Sliders an artist can trust: showing a value never changes it, and a
//! typed value that is not a number says so.
//!
//! egui's [`Slider`] clamps by default the value it *shows* to its track,
//! so drawing a group whose length lies beyond the track rewrote the style
//! (issue 14, item 1). Every slider of the style panel is made here with
//! [`SliderClamping::Never`]: dragging still stays on the track, but a
//! value outside it is shown as it is, untouched, and typed values are not
//! clamped either. Typed values are checked afterwards against the style
//! format itself (`Style::validate`, see `super::ui`), which rejects one
//! outside its allowed range with a message naming the field and the
//! range, so there is one list of limits, the physics crate's.
//!
//! Text that is not a number is reported by the parser installed here
//! (egui would silently keep the old value). Typed text is applied when
//! the field loses focus (Enter, Tab or a click elsewhere), not per
//! keystroke, so a half-typed `1e` is never reported or simulated.

use std::cell::RefCell;
use std::ops::RangeInclusive;

use egui::emath::Numeric;
use egui::{Slider, SliderClamping, Ui};

/// How a slider shows its number.
#[derive(Clone, Copy, Debug)]
pub struct Look {
    /// Unit after the number (with its leading space), e.g. `" m"`.
    pub unit: &'static str,
    /// Logarithmic track (wide ranges: moduli, friction, time step).
    pub logarithmic: bool,
    /// Scientific notation (`3.900e9`).
    pub scientific: bool,
    /// Smallest magnitude a logarithmic track reaches next to zero.
    pub smallest_positive: f64,
}

impl Look {
    /// A linear slider in `unit`.
    pub const fn unit(unit: &'static str) -> Self {
        Self {
            unit,
            logarithmic: false,
            scientific: false,
            smallest_positive: 1e-6,
        }
    }

    /// A logarithmic slider in `unit`, numbers in scientific notation,
    /// reaching down to `smallest_positive` next to zero.
    pub const fn log(unit: &'static str, smallest_positive: f64) -> Self {
        Self {
            unit,
            logarithmic: true,
            scientific: true,
            smallest_positive,
        }
    }
}

/// The value of typed text, or `None` when it is not a finite number.
///
/// Whitespace is ignored, the unit may be typed after the number (`5 m`),
/// and the typographic minus (U+2212) counts as `-`.
pub fn parse_typed(text: &str, unit: &str) -> Option<f64> {
    let text = text.trim();
    let text = text.strip_suffix(unit.trim()).unwrap_or(text);
    let cleaned: String = text
        .chars()
        .filter(|c| !c.is_whitespace())
        .map(|c| if c == '−' { '-' } else { c })
        .collect();
    cleaned.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// A slider over `track` that never changes `value` unless the user does;
/// returns whether the user changed it. Text typed into it that is not a
/// number leaves the value as it is and adds a message to `notes`.
pub fn slider<N: Numeric>(
    ui: &mut Ui,
    notes: &mut Vec<String>,
    label: &str,
    value: &mut N,
    track: RangeInclusive<N>,
    look: Look,
) -> bool {
    let bad_text = RefCell::new(None::<String>);
    let mut widget = Slider::new(value, track)
        .text(label)
        .suffix(look.unit)
        .clamping(SliderClamping::Never)
        .update_while_editing(false)
        .logarithmic(look.logarithmic)
        .smallest_positive(look.smallest_positive)
        .custom_parser(|text| {
            let parsed = parse_typed(text, look.unit);
            if parsed.is_none() {
                *bad_text.borrow_mut() = Some(text.trim().to_string());
            }
            parsed
        });
    if look.scientific {
        widget = widget.custom_formatter(|v, _| format!("{v:.3e}"));
    }
    let changed = ui.add(widget).changed();
    if let Some(text) = bad_text.into_inner() {
        notes.push(not_a_number(label, &text));
    }
    changed
}

/// A slider showing `value` multiplied by `scale` (a smaller unit: µm,
/// mm); `value` is written only when the user changes the shown number.
pub fn scaled_slider(
    ui: &mut Ui,
    notes: &mut Vec<String>,
    label: &str,
    value: &mut f64,
    track: RangeInclusive<f64>,
    scale: f64,
    look: Look,
) -> bool {
    let mut shown = *value * scale;
    let track = track.start() * scale..=track.end() * scale;
    let look = Look {
        smallest_positive: look.smallest_positive * scale,
        ..look
    };
    let changed = slider(ui, notes, label, &mut shown, track, look);
    if changed {
        *value = shown / scale;
    }
    changed
}

/// The message for typed text that is not a number.
pub fn not_a_number(label: &str, text: &str) -> String {
    format!("{label}: `{text}` is not a number; the value is unchanged")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typed_numbers_parse_with_or_without_their_unit() {
        assert_eq!(parse_typed(" 1.5 ", " m"), Some(1.5));
        assert_eq!(parse_typed("1.5 m", " m"), Some(1.5));
        assert_eq!(parse_typed("−2e-3", ""), Some(-2e-3));
        assert_eq!(parse_typed("3.900e9 Pa", " Pa"), Some(3.9e9));
        assert_eq!(parse_typed("abc", " m"), None);
        assert_eq!(parse_typed("", " m"), None);
        assert_eq!(parse_typed("NaN", ""), None);
        assert_eq!(parse_typed("inf", ""), None);
    }
}

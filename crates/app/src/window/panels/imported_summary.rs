//! What the group panel says about an imported groom instead of the shape
//! sliders: an imported strand keeps its own length, element count and
//! rest shape from the fit ([`crate::style::imported`]), so the group's
//! `length`, `elements` and `curl` do nothing to it, and sliders for them
//! would move without the hair answering. Only the material (radius,
//! density, moduli, friction, drag) is the group's.

use crate::style::StrandGroup;
use crate::style::imported::ImportedStrands;

/// Whether some of `group`'s strands take their shape (curl, length,
/// elements) from the group: listed or scalp roots, or no imported strands.
pub fn group_shapes_strands(group: &StrandGroup) -> bool {
    group.imported.is_none() || !group.roots.is_empty() || group.scalp.is_some()
}

/// One line on the groom: its source, how many strands and how many are
/// simulated, their element counts and lengths (ranges), and how many had
/// their moduli raised to hold their sag-free shape.
pub fn imported_summary(imported: &ImportedStrands) -> String {
    let strands = &imported.strands;
    let all = strands.len();
    let simulated = imported.guides().count();
    let elements = strands.iter().map(|s| s.strains.len());
    let (min_elements, max_elements) = (
        elements.clone().min().unwrap_or(0),
        elements.max().unwrap_or(0),
    );
    let lengths_cm = strands
        .iter()
        .map(|s| 100.0 * s.element_length_m * s.strains.len() as f64);
    let min_cm = lengths_cm.clone().fold(f64::INFINITY, f64::min);
    let max_cm = lengths_cm.fold(0.0, f64::max);
    let stiffened = strands.iter().filter(|s| s.stiffness_scale > 1.0).count();
    let simulated = if simulated == all {
        "all simulated".to_string()
    } else {
        format!("{simulated} simulated")
    };
    let mut line = format!(
        "imported from {}: {all} strands ({simulated})",
        imported.source
    );
    if all > 0 {
        let elements = if max_elements == 1 {
            "element"
        } else {
            "elements"
        };
        line += &format!(
            ", {} {elements}, {} cm long",
            range(min_elements as f64, max_elements as f64, 0),
            range(min_cm, max_cm, 1)
        );
    }
    line += ". Each keeps its own length, elements and rest shape from the groom \
             (\"set current shape as rest\" changes the rest shape); the material \
             below applies to every one";
    if stiffened > 0 {
        line += &format!(", with the moduli raised for {stiffened} to hold their shape");
    }
    line + "."
}

/// "a" or "a–b" with `decimals` decimals.
fn range(low: f64, high: f64, decimals: usize) -> String {
    if format!("{low:.decimals$}") == format!("{high:.decimals$}") {
        format!("{low:.decimals$}")
    } else {
        format!("{low:.decimals$}–{high:.decimals$}")
    }
}

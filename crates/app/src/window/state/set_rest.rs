//! "Set current shape as rest": the hair as it is now becomes the static
//! equilibrium, so an artist can pose hair with the head (drag it, shake
//! it, let it fall) and freeze it.
//!
//! Every simulated strand is frozen as a brush's Freeze freezes it
//! ([`crate::brush::freeze`]: its current strains kept as the shape it
//! starts and rests in, its natural strains solved sag-free against
//! gravity and the head's support, stiffened where the pose would be
//! unstable). What is kept is each strand's `rest` edit in its group
//! ([`crate::style::strand_edit`]), so the style keeps everything else it
//! had: its scalp placements, drawn strands, curl, length and preset
//! controls. The head stops where it is ([`HeadDriver::hold`]) and the
//! strands' rates are set to zero: the hair is then at rest in its
//! equilibrium and stays put. The edit is one undo step; the message
//! counts how each strand was held.
//!
//! [`HeadDriver::hold`]: crate::window::live::head_motion::HeadDriver::hold

use helixhair_physics::engine::Engine;

use crate::brush::freeze::{RestCounts, freeze_strands};
use crate::sim::strands::style_strands;
use crate::style::Style;

use super::app_state::AppState;

/// `written` (the style as the document holds it) with every simulated
/// strand of `grown` (the same style with its scalp roots grown, as
/// `engine` was built from it) frozen in `engine`'s current shape.
pub fn rest_style(
    written: &Style,
    grown: &Style,
    engine: &Engine,
) -> Result<(Style, RestCounts), String> {
    let strands = style_strands(grown, |_, g| g.params.clone());
    if strands.len() != engine.strand_count() {
        return Err(format!(
            "the simulation has {} strands and the style {}; edit settled?",
            engine.strand_count(),
            strands.len()
        ));
    }
    let mut frozen = grown.clone();
    let all: Vec<usize> = (0..strands.len()).collect();
    let counts = freeze_strands(engine, &strands, &all, &mut frozen)?;
    let mut style = written.clone();
    for (group, edited) in style.groups.iter_mut().zip(frozen.groups) {
        group.edits = edited.edits;
    }
    Ok((style, counts))
}

impl AppState {
    /// Sets the hair's current shape as its rest shape (see the module
    /// docs); one undo step. On failure nothing changes and the message
    /// says why.
    pub fn set_current_shape_as_rest(&mut self) {
        if self.invalid.is_some() {
            self.message = Some("fix the style first: it is not being simulated".into());
            return;
        }
        let (style, counts) =
            match rest_style(self.doc.style(), self.sim.grown_style(), self.sim.engine()) {
                Ok(done) => done,
                Err(e) => {
                    self.message = Some(format!("not set as rest: {e}"));
                    return;
                }
            };
        self.head.hold();
        self.doc.edit(|s| *s = style);
        if let Err(e) = self.sim.sync(self.doc.style()) {
            self.message = Some(format!("not set as rest: {e}"));
            self.doc.undo();
            return;
        }
        self.sim.stop();
        self.message = Some(format!(
            "current shape set as rest for {} strands ({}); Undo restores the style",
            counts.total(),
            counts.describe()
        ));
    }
}

#[cfg(test)]
#[path = "tests/set_rest_tests.rs"]
mod tests;

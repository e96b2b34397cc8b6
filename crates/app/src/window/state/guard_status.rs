//! What the stability guard did, told once in words.
//!
//! Both engines guard every strand each frame: the reference engine
//! re-steps a failing strand with a safer solver or more substeps (a
//! retry: the motion is still the style's), and when no retry passes it
//! resets the strand to its start-of-frame shape, or pins one that keeps
//! failing; the batch engine resets or pins at once. A reset or pin means
//! the picture is not the simulation the style asks for.
//!
//! A per-frame message would flicker past unread, or, in a loop of
//! resets, scroll thousands of lines. [`GuardStatus`] instead counts what
//! happened since the style last changed and makes one sentence of it
//! ([`GuardStatus::sentence`]), shown on the window's status line until
//! the next edit starts the count afresh.

use std::collections::BTreeSet;

use helixhair_physics::{GuardAction, Method};

use crate::style::Style;

use crate::window::live::live_sim::LiveSim;

/// What the guard did to one run in one frame: strand indices.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GuardFrame {
    /// Strands re-stepped with a safer setting that then passed.
    pub retried: Vec<usize>,
    /// Strands reset to an earlier shape or pinned at rest.
    pub lost: Vec<usize>,
}

impl LiveSim {
    /// What the guard did in the last frame, on either engine.
    pub fn guard_frame(&self) -> GuardFrame {
        let mut frame = GuardFrame::default();
        for e in self.engine().last_guard_events() {
            match e.action {
                GuardAction::Retried { .. } => frame.retried.push(e.strand),
                GuardAction::Reset | GuardAction::Pinned => frame.lost.push(e.strand),
            }
        }
        frame
    }
}

/// The guard's interventions since the style last changed.
#[derive(Clone, Debug, Default)]
pub struct GuardStatus {
    /// The style the counts are for.
    style: Option<Style>,
    /// Frames counted.
    frames: usize,
    retries: usize,
    losses: usize,
    retried_strands: BTreeSet<usize>,
    lost_strands: BTreeSet<usize>,
}

impl GuardStatus {
    /// Counts one frame of the run of `style`; a changed style starts the
    /// count afresh.
    pub fn record(&mut self, style: &Style, frame: &GuardFrame) {
        if self.style.as_ref() != Some(style) {
            *self = Self {
                style: Some(style.clone()),
                ..Self::default()
            };
        }
        self.frames += 1;
        self.retries += frame.retried.len();
        self.losses += frame.lost.len();
        self.retried_strands.extend(&frame.retried);
        self.lost_strands.extend(&frame.lost);
    }

    /// Resets and pins counted since the last edit.
    pub fn losses(&self) -> usize {
        self.losses
    }

    /// One sentence for the status line, or `None` while the guard has
    /// had nothing to do since the last edit.
    pub fn sentence(&self) -> Option<String> {
        if self.losses > 0 {
            // Advice for what the style does not already use.
            let on_exact = self
                .style
                .as_ref()
                .is_some_and(|s| s.sim.method == Method::Exact);
            let advice = if on_exact {
                "Try more substeps, a shorter time step or fewer elements."
            } else {
                "Try more substeps, a shorter time step, fewer elements or the Exact solver."
            };
            return Some(format!(
                "Stability guard: since the last edit it reset or pinned {} {} times (and \
                 re-stepped strands {} times): what you see is not the simulation this \
                 style asks for. {advice}",
                plural(self.lost_strands.len(), "strand"),
                self.losses,
                self.retries
            ));
        }
        let on_block = self
            .style
            .as_ref()
            .is_some_and(|s| s.sim.method == Method::BlockDiagonal);
        if self.retries > 0 && on_block {
            return Some(format!(
                "Stability guard: Block-diagonal could not hold {} at this time step, so the \
                 guard stepped them with Exact {} times: where it did, what you see is Exact. \
                 More substeps may let Block-diagonal hold them.",
                plural(self.retried_strands.len(), "strand"),
                self.retries
            ));
        }
        (self.retries > 0).then(|| {
            format!(
                "Stability guard: since the last edit it re-stepped {} {} times with a safer \
                 solver or more substeps; the motion is still this style's.",
                plural(self.retried_strands.len(), "strand"),
                self.retries
            )
        })
    }
}

/// `n strand` or `n strands`.
fn plural(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

#[cfg(test)]
mod tests {
    use super::super::default_style::default_style;
    use super::*;

    #[test]
    fn one_sentence_counts_every_frame_since_the_last_edit() {
        let style = default_style(4);
        let mut status = GuardStatus::default();
        assert_eq!(status.sentence(), None);
        let lost = GuardFrame {
            retried: vec![1],
            lost: vec![2],
        };
        for _ in 0..50 {
            status.record(&style, &lost);
        }
        let sentence = status.sentence().unwrap();
        assert!(
            sentence.contains("reset or pinned 1 strand 50 times"),
            "{sentence}"
        );
        assert!(
            sentence.contains("re-stepped strands 50 times"),
            "{sentence}"
        );
        // An edit starts afresh.
        let mut edited = style.clone();
        edited.groups[0].params.length_m = 0.3;
        status.record(&edited, &GuardFrame::default());
        assert_eq!(status.sentence(), None);
        status.record(
            &edited,
            &GuardFrame {
                retried: vec![0, 3],
                lost: vec![],
            },
        );
        let sentence = status.sentence().unwrap();
        assert!(
            sentence.contains("re-stepped 2 strands 2 times"),
            "{sentence}"
        );
    }

    /// Issue #33: where Block-diagonal could not hold strands and the guard
    /// stepped them with Exact, the sentence says so: what the user sees
    /// there is Exact, not the solver they chose.
    #[test]
    fn a_block_style_handed_to_exact_says_so() {
        let mut style = default_style(4);
        style.sim.method = Method::BlockDiagonal;
        let mut status = GuardStatus::default();
        status.record(
            &style,
            &GuardFrame {
                retried: vec![0, 3],
                lost: vec![],
            },
        );
        let sentence = status.sentence().unwrap();
        assert!(
            sentence.contains("Block-diagonal could not hold 2 strands")
                && sentence.contains("stepped them with Exact 2 times"),
            "{sentence}"
        );
    }

    /// Issue #32, item 7: the advice named the Exact solver when Exact was
    /// already the style's.
    #[test]
    fn the_advice_names_only_what_the_style_does_not_use() {
        let lost = GuardFrame {
            retried: vec![],
            lost: vec![0],
        };
        for (method, names_exact) in [(Method::Exact, false), (Method::BlockDiagonal, true)] {
            let mut style = default_style(4);
            style.sim.method = method;
            let mut status = GuardStatus::default();
            status.record(&style, &lost);
            let sentence = status.sentence().unwrap();
            assert_eq!(sentence.contains("Exact solver"), names_exact, "{sentence}");
        }
    }
}

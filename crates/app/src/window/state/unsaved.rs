//! Unsaved-changes protection: closing the window or opening another
//! style while the style has unsaved edits first asks "save, discard or
//! cancel?".
//!
//! How it works: whatever would drop the edited style (the window's close
//! button, Open…, a file dropped on the window) calls
//! [`AppState::request_leave`]. With no unsaved edits the action happens
//! at once; otherwise it waits in [`AppState::leaving`] and the window
//! shows the question ([`confirm_dialog`]). [`AppState::answer_leave`]
//! then saves (and goes on only if the save worked), discards (goes on),
//! or cancels (stays). A style never saved to a file has nowhere to be
//! saved: "Save" then opens Save as, and the pending action goes on once
//! that save succeeds ([`AppState::saved_as`]).

use std::path::{Path, PathBuf};

use super::app_state::AppState;

/// An action that drops the edited style.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Leave {
    /// Close the window.
    Close,
    /// Open this style instead.
    Open(PathBuf),
}

/// The user's answer to "save your changes?".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    /// Save, then go on (not if the save fails).
    Save,
    /// Go on and lose the edits.
    Discard,
    /// Stay, edits kept.
    Cancel,
}

/// What the window must do after an answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AfterAnswer {
    /// Nothing more (done, or staying).
    Nothing,
    /// Open the Save-as picker; the action waits for its save.
    PickSaveAs,
}

impl AppState {
    /// Asks to `leave`: done now when nothing is unsaved, else it waits
    /// for the user's answer ([`Self::answer_leave`]).
    pub fn request_leave(&mut self, leave: Leave) {
        if self.doc.is_dirty() {
            self.leaving = Some(leave);
        } else {
            self.leave_now(leave);
        }
    }

    /// Applies the user's answer to the pending question.
    pub fn answer_leave(&mut self, answer: Answer) -> AfterAnswer {
        let Some(leave) = self.leaving.take() else {
            return AfterAnswer::Nothing;
        };
        match answer {
            Answer::Cancel => {}
            Answer::Discard => self.leave_now(leave),
            Answer::Save if self.doc.path().is_none() => {
                self.leaving = Some(leave);
                return AfterAnswer::PickSaveAs;
            }
            Answer::Save => {
                self.save(None);
                if self.doc.is_dirty() {
                    // The save failed (its message is shown): stay.
                } else {
                    self.leave_now(leave);
                }
            }
        }
        AfterAnswer::Nothing
    }

    /// Saves to `path` (the Save-as picker's choice); an action waiting
    /// for that save goes on if it worked.
    pub fn saved_as(&mut self, path: &Path) {
        self.save(Some(path));
        if !self.doc.is_dirty()
            && let Some(leave) = self.leaving.take()
        {
            self.leave_now(leave);
        }
    }

    fn leave_now(&mut self, leave: Leave) {
        match leave {
            Leave::Close => self.quit = true,
            Leave::Open(path) => self.load(&path),
        }
    }
}

/// The question, while an action waits for it; returns the answer given
/// this frame.
pub fn confirm_dialog(ctx: &egui::Context, app: &AppState) -> Option<Answer> {
    let leave = app.leaving.as_ref()?;
    let what = match leave {
        Leave::Close => "Close the window".to_string(),
        Leave::Open(path) => format!(
            "Open {}",
            path.file_name().map_or_else(
                || path.display().to_string(),
                |n| n.to_string_lossy().into()
            )
        ),
    };
    let mut answer = None;
    egui::Window::new("Unsaved changes")
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
            ui.label(format!(
                "{} has unsaved changes. {what} without saving them?",
                app.doc.title().trim_end_matches(" — HelixHair")
            ));
            ui.horizontal(|ui| {
                if ui.button("Save").clicked() {
                    answer = Some(Answer::Save);
                }
                if ui.button("Discard changes").clicked() {
                    answer = Some(Answer::Discard);
                }
                if ui.button("Cancel").clicked() {
                    answer = Some(Answer::Cancel);
                }
            });
        });
    answer
}

#[cfg(test)]
mod tests {
    use super::super::default_style::default_style;
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("helixhair-unsaved-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// An app on file `mine.ron` and another style file, `other.ron`.
    fn app_with_files(name: &str) -> (AppState, PathBuf, PathBuf) {
        let dir = scratch(name);
        let (mine, other) = (dir.join("mine.ron"), dir.join("other.ron"));
        default_style(3).save(&mine).unwrap();
        let mut style = default_style(5);
        style.name = "other".into();
        style.save(&other).unwrap();
        let app = AppState::new(default_style(3), Some(&mine)).unwrap();
        (app, mine, other)
    }

    fn edit(app: &mut AppState) {
        app.doc.edit(|s| s.groups[0].params.ellipticity = 2.5);
    }

    #[test]
    fn opening_another_file_over_unsaved_edits_asks_first() {
        let (mut app, mine, other) = app_with_files("open");
        edit(&mut app);
        app.request_leave(Leave::Open(other.clone()));
        assert_eq!(
            app.doc.path(),
            Some(mine.as_path()),
            "loaded without asking"
        );
        assert_eq!(app.leaving, Some(Leave::Open(other.clone())));
        // Cancel: the edit stays, nothing is loaded.
        assert_eq!(app.answer_leave(Answer::Cancel), AfterAnswer::Nothing);
        assert_eq!(app.doc.style().groups[0].params.ellipticity, 2.5);
        assert_eq!(app.doc.path(), Some(mine.as_path()));
        // Discard: the other file is open, and mine is as it was.
        app.request_leave(Leave::Open(other.clone()));
        app.answer_leave(Answer::Discard);
        assert_eq!(app.doc.style().name, "other");
        assert_eq!(Style::load(&mine).unwrap(), default_style(3));
        std::fs::remove_dir_all(mine.parent().unwrap()).unwrap();
    }

    use crate::style::Style;

    #[test]
    fn closing_over_unsaved_edits_asks_and_save_keeps_them() {
        let (mut app, mine, _) = app_with_files("close");
        edit(&mut app);
        app.request_leave(Leave::Close);
        assert!(!app.quit, "closed without asking");
        app.answer_leave(Answer::Save);
        assert!(app.quit);
        assert_eq!(
            Style::load(&mine).unwrap().groups[0].params.ellipticity,
            2.5
        );
        std::fs::remove_dir_all(mine.parent().unwrap()).unwrap();
    }

    #[test]
    fn with_nothing_unsaved_close_and_open_happen_at_once() {
        let (mut app, _, other) = app_with_files("clean");
        app.request_leave(Leave::Open(other.clone()));
        assert_eq!(app.doc.style().name, "other");
        app.request_leave(Leave::Close);
        assert!(app.quit);
        std::fs::remove_dir_all(other.parent().unwrap()).unwrap();
    }

    #[test]
    fn a_style_never_saved_goes_through_save_as_before_closing() {
        let dir = scratch("never");
        let mut app = AppState::new(default_style(3), None).unwrap();
        edit(&mut app);
        app.request_leave(Leave::Close);
        assert_eq!(app.answer_leave(Answer::Save), AfterAnswer::PickSaveAs);
        assert!(!app.quit);
        app.saved_as(&dir.join("new.ron"));
        assert!(app.quit);
        assert!(dir.join("new.ron").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! The style being edited: its file, its unsaved changes and its history.
//!
//! Every change goes through [`StyleDoc`]. Discrete edits (a preset, a
//! combo box, a load) call [`StyleDoc::edit`], which records an undo step at
//! once. A slider changes the style every frame while it is dragged; the
//! panels write straight into [`StyleDoc::style_mut`], and
//! [`StyleDoc::settle`], called once per frame with whether a drag is still
//! going on, turns the whole drag into one undo step when it ends. Edits
//! that would make the style invalid are kept out of the simulation by the
//! caller ([`StyleDoc::validity`]), never written over the last good one.
//!
//! The unsaved marker compares the style with the one last loaded or saved,
//! so undoing back to the saved state clears it.

use std::path::{Path, PathBuf};

use crate::style::Style;
use crate::style::error::StyleError;

use super::undo::UndoStack;

/// A style with its file and history.
#[derive(Clone, Debug)]
pub struct StyleDoc {
    style: Style,
    path: Option<PathBuf>,
    saved: Style,
    baseline: Style,
    history: UndoStack<Style>,
}

impl StyleDoc {
    /// A document holding `style`, not yet saved to any file.
    pub fn new(style: Style) -> Self {
        Self {
            saved: style.clone(),
            baseline: style.clone(),
            style,
            path: None,
            history: UndoStack::default(),
        }
    }

    /// The style as edited.
    pub fn style(&self) -> &Style {
        &self.style
    }

    /// The style for in-place edits (sliders); call [`Self::settle`] each
    /// frame so they become undo steps.
    pub fn style_mut(&mut self) -> &mut Style {
        &mut self.style
    }

    /// The file the style was loaded from or saved to.
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// Applies a discrete edit as one undo step.
    pub fn edit(&mut self, change: impl FnOnce(&mut Style)) {
        self.settle(false);
        let before = self.style.clone();
        change(&mut self.style);
        if self.style != before {
            self.history.record(before);
            self.baseline = self.style.clone();
        }
    }

    /// Ends an in-place edit once no drag is going on: if the style changed
    /// since the last undo step, that change becomes one.
    pub fn settle(&mut self, dragging: bool) {
        if !dragging && self.style != self.baseline {
            let before = std::mem::replace(&mut self.baseline, self.style.clone());
            self.history.record(before);
        }
    }

    /// Undoes the last edit; false when there is none.
    pub fn undo(&mut self) -> bool {
        self.travel(UndoStack::undo)
    }

    /// Redoes the last undone edit; false when there is none.
    pub fn redo(&mut self) -> bool {
        self.travel(UndoStack::redo)
    }

    /// Moves through the history with `step` (undo or redo).
    fn travel(&mut self, step: fn(&mut UndoStack<Style>, Style) -> Option<Style>) -> bool {
        self.settle(false);
        match step(&mut self.history, self.style.clone()) {
            Some(style) => {
                self.style = style;
                self.baseline = self.style.clone();
                true
            }
            None => false,
        }
    }

    /// Whether undo and redo have something to do.
    pub fn can_undo_redo(&self) -> (bool, bool) {
        (
            self.history.can_undo() || self.style != self.baseline,
            self.history.can_redo(),
        )
    }

    /// Whether the style differs from the file's.
    pub fn is_dirty(&self) -> bool {
        self.style != self.saved
    }

    /// The window title: file name (or the style's name), an asterisk when
    /// unsaved, and the program.
    pub fn title(&self) -> String {
        let name = match &self.path {
            Some(path) => path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| path.display().to_string()),
            None => format!("{} (not saved)", self.style.name),
        };
        let marker = if self.is_dirty() { "*" } else { "" };
        format!("{name}{marker} — HelixHair")
    }

    /// Whether the style is valid: `Err` names the first bad field.
    pub fn validity(&self) -> Result<(), String> {
        self.style
            .validate()
            .map_err(|issue| format!("{}: {}", issue.field, issue.message))
    }

    /// Loads `path`. On any error (unreadable, malformed, invalid) nothing
    /// changes and the error names the file, line and field. A load is one
    /// undo step.
    pub fn load(&mut self, path: &Path) -> Result<(), StyleError> {
        let style = Style::load(path)?;
        self.edit(|s| *s = style.clone());
        self.saved = style;
        self.path = Some(path.to_owned());
        Ok(())
    }

    /// Saves atomically to `path` (the current file when `None`), and
    /// makes it the document's file. An invalid style is not saved.
    pub fn save(&mut self, path: Option<&Path>) -> Result<PathBuf, String> {
        let path = path
            .map(Path::to_owned)
            .or_else(|| self.path.clone())
            .ok_or_else(|| "no file name yet: use Save as".to_string())?;
        self.validity()
            .map_err(|e| format!("not saved, the style is invalid: {e}"))?;
        self.style.save(&path).map_err(|e| e.to_string())?;
        self.saved = self.style.clone();
        self.path = Some(path.clone());
        Ok(path)
    }
}

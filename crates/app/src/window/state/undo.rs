//! Undo and redo of whole-document snapshots.
//!
//! A style is small (a few kilobytes even with hundreds of roots), so the
//! history keeps whole copies instead of inverse operations: an undo can
//! then never disagree with what an edit did, whatever the edit was
//! (slider, preset, file load, root regrowth). The depth is capped so a
//! long session cannot grow without bound.

use std::collections::VecDeque;

/// Snapshots kept for undo before the oldest are dropped.
pub const MAX_UNDO_DEPTH: usize = 200;

/// Past and future versions of a document of type `T`.
#[derive(Clone, Debug)]
pub struct UndoStack<T> {
    past: VecDeque<T>,
    future: Vec<T>,
}

impl<T> Default for UndoStack<T> {
    fn default() -> Self {
        Self {
            past: VecDeque::new(),
            future: Vec::new(),
        }
    }
}

impl<T: Clone> UndoStack<T> {
    /// Records `before`, the state an edit is about to change. A new edit
    /// forgets what could have been redone.
    pub fn record(&mut self, before: T) {
        if self.past.len() == MAX_UNDO_DEPTH {
            self.past.pop_front();
        }
        self.past.push_back(before);
        self.future.clear();
    }

    /// Steps back: returns the previous state and keeps `current` for redo.
    pub fn undo(&mut self, current: T) -> Option<T> {
        let previous = self.past.pop_back()?;
        self.future.push(current);
        Some(previous)
    }

    /// Steps forward again: returns the undone state and keeps `current`
    /// for undo.
    pub fn redo(&mut self, current: T) -> Option<T> {
        let next = self.future.pop()?;
        self.past.push_back(current);
        Some(next)
    }

    /// Whether there is something to undo.
    pub fn can_undo(&self) -> bool {
        !self.past.is_empty()
    }

    /// Whether there is something to redo.
    pub fn can_redo(&self) -> bool {
        !self.future.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undo_and_redo_walk_the_history_both_ways() {
        let mut stack = UndoStack::default();
        let mut doc = 0;
        for next in 1..=3 {
            stack.record(doc);
            doc = next;
        }
        doc = stack.undo(doc).unwrap();
        doc = stack.undo(doc).unwrap();
        assert_eq!(doc, 1);
        doc = stack.redo(doc).unwrap();
        assert_eq!(doc, 2);
        // A new edit drops the redo branch.
        stack.record(doc);
        doc = 10;
        assert!(!stack.can_redo());
        assert_eq!(stack.undo(doc), Some(2));
    }

    #[test]
    fn depth_is_capped_by_dropping_the_oldest() {
        let mut stack = UndoStack::default();
        for i in 0..MAX_UNDO_DEPTH + 5 {
            stack.record(i);
        }
        let mut doc = usize::MAX;
        let mut undone = 0;
        while let Some(previous) = stack.undo(doc) {
            doc = previous;
            undone += 1;
        }
        assert_eq!(undone, MAX_UNDO_DEPTH);
        assert_eq!(doc, 5);
    }
}

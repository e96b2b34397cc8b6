//! Warnings a reader collects, bounded whatever the file holds.
//!
//! A layer can hold any number of prims that each deserve a warning, and
//! names of any length: the list keeps the first [`MAX_WARNINGS`] (then
//! counts the rest), each message is built only when kept, and names from
//! the file are shortened with [`short`] so a warning stays a line long.

/// The most warnings kept; the rest are counted in one last line.
pub const MAX_WARNINGS: usize = 100;
/// The most characters of a name from the file quoted in a message.
pub const MAX_QUOTED_CHARS: usize = 64;

/// Warnings, at most [`MAX_WARNINGS`] of them.
#[derive(Debug, Default)]
pub(crate) struct Warnings {
    list: Vec<String>,
    more: usize,
}

impl Warnings {
    /// Keeps a warning, building it only if there is room.
    pub fn push(&mut self, message: impl FnOnce() -> String) {
        if self.list.len() < MAX_WARNINGS {
            self.list.push(message());
        } else {
            self.more += 1;
        }
    }

    /// The kept warnings, and a line counting the others.
    pub fn into_vec(mut self) -> Vec<String> {
        if self.more > 0 {
            self.list.push(format!("… and {} more warnings", self.more));
        }
        self.list
    }
}

/// A name from the file, cut to [`MAX_QUOTED_CHARS`] characters.
pub(crate) fn short(text: &str) -> String {
    match text.char_indices().nth(MAX_QUOTED_CHARS) {
        Some((end, _)) => format!("{}…", &text[..end]),
        None => text.to_string(),
    }
}

//! RON files other than styles (motion files, stroke files) read with the
//! style's error locating: every error names the file, the line and the
//! field (``shot.ron:7:20: field `keys[2].time_secs`: …``), and a save is
//! atomic.
//!
//! A file kind gives its noun ([`RonFile::WHAT`], "motion file") and its
//! checks ([`RonFile::check`], the first problem as a field and a
//! message); parsing, locating and writing are the same for every kind.

use std::path::{Path, PathBuf};

use serde::Serialize;
use serde::de::DeserializeOwned;
use thiserror::Error;

use crate::atomic_write::write_atomically;
use crate::style::error::StyleError;
use crate::style::field_path::FieldPath;
use crate::style::source_map::{SourceMap, TextPosition};

/// A kind of RON file: its noun in messages and its checks.
pub trait RonFile: DeserializeOwned + Serialize {
    /// What the file is called in messages ("motion file").
    const WHAT: &'static str;

    /// The first problem of a parsed file: the field and what is wrong.
    fn check(&self) -> Result<(), (FieldPath, String)>;

    /// Reads and checks the file at `path`.
    fn load(path: &Path) -> Result<Self, RonFileError> {
        let src = std::fs::read_to_string(path).map_err(|error| RonFileError::Read {
            path: path.to_owned(),
            what: Self::WHAT,
            error,
        })?;
        Self::from_ron(&src, path)
    }

    /// Parses and checks RON text; `path` only names the file in errors.
    fn from_ron(src: &str, path: &Path) -> Result<Self, RonFileError> {
        let parsed: Self = ron::from_str(src).map_err(|error| {
            match crate::style::locate_ron_error(src, path, &error) {
                StyleError::Located {
                    position,
                    field,
                    message,
                    ..
                } => RonFileError::Located {
                    path: path.to_owned(),
                    position,
                    field,
                    message,
                },
                // locate_ron_error only builds located errors.
                other => RonFileError::Located {
                    path: path.to_owned(),
                    position: TextPosition { line: 1, col: 1 },
                    field: FieldPath::root(),
                    message: other.to_string(),
                },
            }
        })?;
        if let Err((field, message)) = parsed.check() {
            let (position, _) = SourceMap::new(src).locate(&field);
            return Err(RonFileError::Located {
                path: path.to_owned(),
                position,
                field,
                message,
            });
        }
        Ok(parsed)
    }

    /// The file as pretty RON text under a header comment.
    fn to_ron(&self, header: &str) -> Result<String, RonFileError> {
        let body = ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::default()).map_err(
            |error| RonFileError::Serialize {
                what: Self::WHAT,
                error,
            },
        )?;
        Ok(format!("// {header}\n{body}\n"))
    }

    /// Writes the file atomically (the old file stays whole on a crash).
    fn save(&self, path: &Path, header: &str) -> Result<(), RonFileError> {
        let text = self.to_ron(header)?;
        write_atomically(path, text.as_bytes()).map_err(|error| RonFileError::Write {
            path: path.to_owned(),
            what: Self::WHAT,
            error,
        })
    }
}

/// Why a RON file could not be read or written.
#[derive(Debug, Error)]
pub enum RonFileError {
    /// The file could not be read.
    #[error("{}: cannot read the {what}: {error}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What the file is ("motion file").
        what: &'static str,
        /// The cause.
        error: std::io::Error,
    },
    /// The file could not be written.
    #[error("{}: cannot write the {what}: {error}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What the file is.
        what: &'static str,
        /// The cause.
        error: std::io::Error,
    },
    /// The content could not be turned into RON text.
    #[error("cannot write the {what} as RON: {error}")]
    Serialize {
        /// What the file is.
        what: &'static str,
        /// The cause.
        error: ron::Error,
    },
    /// The file's content is wrong at a known place.
    #[error("{}:{position}: {}", path.display(), located_message(field, message))]
    Located {
        /// The file.
        path: PathBuf,
        /// Line and column of the problem.
        position: TextPosition,
        /// The field concerned (the root for syntax errors).
        field: FieldPath,
        /// What is wrong.
        message: String,
    },
}

fn located_message(field: &FieldPath, message: &str) -> String {
    if field.is_root() {
        message.to_owned()
    } else {
        format!("field `{field}`: {message}")
    }
}

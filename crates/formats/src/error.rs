//! What the readers and writers report when they cannot do their work.
//!
//! A [`ReadError`] says where in the file the problem is (a byte offset for
//! the binary formats, a 1-based line for the text formats), what kind of
//! problem it is ([`ReadErrorKind`], for code that reacts to it) and, in
//! words, what is wrong. It does not name the file: the caller knows it and
//! prefixes it, e.g. `sintel.tfx: tfx byte 4: 4294967295 strands of 16
//! points need 1099511627520 bytes of positions, the file has 2918560`.

use std::fmt;

use crate::format::Format;

/// Where in a file a problem was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// A byte offset from the start of the file (binary formats).
    Byte(u64),
    /// A 1-based line (text formats).
    Line(usize),
    /// The file as a whole (nothing in it to point at, e.g. no curves).
    File,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Byte(offset) => write!(f, "byte {offset}"),
            Location::Line(line) => write!(f, "line {line}"),
            Location::File => f.write_str("file"),
        }
    }
}

/// The kind of problem a reader found, for code that reacts to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReadErrorKind {
    /// The file does not start like a file of this format (magic, header
    /// line).
    BadMagic,
    /// A version of the format this reader does not know.
    UnsupportedVersion,
    /// The file ends before the data its header or its syntax promises.
    Truncated,
    /// Counts that disagree with each other or with the data present.
    CountMismatch,
    /// A count or size larger than the file could hold: reading it would
    /// allocate memory the file does not justify, so nothing is allocated.
    TooLarge,
    /// Text that does not parse.
    Syntax,
    /// A value out of its range (an index, an offset, an option).
    BadValue,
    /// Well formed, but a feature this reader does not handle.
    Unsupported,
}

/// Why a file could not be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{format} {location}: {message}")]
pub struct ReadError {
    /// The format being read.
    pub format: Format,
    /// Where the problem is.
    pub location: Location,
    /// What kind of problem it is.
    pub kind: ReadErrorKind,
    /// What is wrong, in words.
    pub message: String,
}

impl ReadError {
    /// A new error.
    pub fn new(
        format: Format,
        location: Location,
        kind: ReadErrorKind,
        message: impl Into<String>,
    ) -> ReadError {
        ReadError {
            format,
            location,
            kind,
            message: message.into(),
        }
    }
}

/// Why curves could not be written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The writer (a file, a socket) failed.
    #[error("cannot write {format}: {source}")]
    Io {
        /// The format being written.
        format: Format,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The curves cannot be expressed in this format (e.g. TressFX needs the
    /// same power-of-two point count on every strand), or are not valid
    /// (a non-finite point).
    #[error("cannot write {format}: {message}")]
    Invalid {
        /// The format being written.
        format: Format,
        /// What is wrong, in words.
        message: String,
    },
}

impl WriteError {
    /// An [`WriteError::Invalid`] error.
    pub fn invalid(format: Format, message: impl Into<String>) -> WriteError {
        WriteError::Invalid {
            format,
            message: message.into(),
        }
    }

    /// A closure that wraps an I/O error, for `map_err`.
    pub(crate) fn io(format: Format) -> impl Fn(std::io::Error) -> WriteError {
        move |source| WriteError::Io { format, source }
    }
}

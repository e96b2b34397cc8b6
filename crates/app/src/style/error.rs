//! Errors of loading and saving styles, each naming the file, the line and
//! the field: `curly.ron:12:13: field `groups\[0\].params.radius_m`: …`.

use std::fmt;
use std::io;
use std::path::PathBuf;

use thiserror::Error;

use crate::style::field_path::FieldPath;
use crate::style::source_map::TextPosition;

/// What kind of mistake a style file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StyleErrorKind {
    /// Not well-formed RON: a missing comma, an unclosed bracket, a stray
    /// character.
    Syntax,
    /// A field name the format does not have (often a typo).
    UnknownField,
    /// An enum variant the format does not have (`Helics` for `Helix`).
    UnknownVariant,
    /// A required field left out.
    MissingField,
    /// The same field written twice.
    DuplicateField,
    /// A value of the wrong type: a string for a number, two coordinates
    /// for three, a negative count.
    WrongType,
    /// A `version` this build cannot read.
    Version,
    /// A well-typed value that is not allowed: NaN, out of range, an empty
    /// list, a zero direction.
    InvalidValue,
}

impl StyleErrorKind {
    /// The kind of a `ron` parse error.
    pub fn of_ron(code: &ron::Error) -> Self {
        use ron::Error as E;
        match code {
            E::NoSuchStructField { .. } => Self::UnknownField,
            E::NoSuchEnumVariant { .. } => Self::UnknownVariant,
            E::MissingStructField { .. } => Self::MissingField,
            E::DuplicateStructField { .. } => Self::DuplicateField,
            E::Message(_)
            | E::InvalidValueForType { .. }
            | E::ExpectedDifferentLength { .. }
            | E::ExpectedDifferentStructName { .. }
            | E::ExpectedStructName(_)
            | E::IntegerOutOfBounds
            | E::ExpectedArray
            | E::ExpectedBoolean
            | E::ExpectedChar
            | E::ExpectedFloat
            | E::ExpectedInteger
            | E::ExpectedMap
            | E::ExpectedOption
            | E::ExpectedString
            | E::ExpectedByteString
            | E::ExpectedStructLike
            | E::ExpectedNamedStructLike(_)
            | E::ExpectedUnit => Self::WrongType,
            _ => Self::Syntax,
        }
    }
}

/// A problem with one field of a style, before it is tied to a file: what
/// [`crate::Style::validate`] finds.
#[derive(Clone, Debug, PartialEq, Error)]
#[error("field `{field}`: {message}")]
pub struct StyleIssue {
    /// The offending field, e.g. `groups[0].params.radius_m`.
    pub field: FieldPath,
    /// What kind of problem it is.
    pub kind: StyleErrorKind,
    /// What is wrong and what the value must be.
    pub message: String,
}

/// Why a style could not be loaded or saved.
///
/// Each message is complete on its own (it includes its cause), so no
/// variant reports a separate `source`: printing the chain would repeat it.
#[derive(Debug, Error)]
pub enum StyleError {
    /// The file could not be read.
    #[error("{}: cannot read the style: {error}", path.display())]
    Read {
        /// The style file.
        path: PathBuf,
        /// The cause.
        error: io::Error,
    },
    /// The file could not be written.
    #[error("{}: cannot write the style: {error}", path.display())]
    Write {
        /// The style file.
        path: PathBuf,
        /// The cause.
        error: io::Error,
    },
    /// The style could not be turned into RON text.
    #[error("cannot write the style as RON: {0}")]
    Serialize(ron::Error),
    /// The file's content is wrong at a known place.
    #[error("{}:{position}: {}", path.display(), FieldMessage { field, kind: *kind, message })]
    Located {
        /// The style file.
        path: PathBuf,
        /// Line and column of the problem.
        position: TextPosition,
        /// The field concerned; the root path for file-level syntax errors.
        field: FieldPath,
        /// What kind of problem it is.
        kind: StyleErrorKind,
        /// What is wrong (for parse errors, `ron`'s own words).
        message: String,
    },
}

impl StyleError {
    /// The kind of a [`StyleError::Located`] error; `None` for I/O errors.
    pub fn kind(&self) -> Option<StyleErrorKind> {
        match self {
            StyleError::Located { kind, .. } => Some(*kind),
            _ => None,
        }
    }

    /// Line and column of a [`StyleError::Located`] error.
    pub fn position(&self) -> Option<TextPosition> {
        match self {
            StyleError::Located { position, .. } => Some(*position),
            _ => None,
        }
    }

    /// The field of a [`StyleError::Located`] error.
    pub fn field(&self) -> Option<&FieldPath> {
        match self {
            StyleError::Located { field, .. } => Some(field),
            _ => None,
        }
    }
}

/// "field `x`: message"; "in `x`: message" for a syntax error, which is
/// about the text inside a value rather than the value; just the message
/// when no field is known.
struct FieldMessage<'a> {
    field: &'a FieldPath,
    kind: StyleErrorKind,
    message: &'a str,
}

impl fmt::Display for FieldMessage<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (field, message) = (self.field, self.message);
        match self.kind {
            _ if field.is_root() => f.write_str(message),
            StyleErrorKind::Syntax => write!(f, "in `{field}`: {message}"),
            _ => write!(f, "field `{field}`: {message}"),
        }
    }
}

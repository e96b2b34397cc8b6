//! Paths to a field of a style file, as error messages print them:
//! `groups[0].params.natural_shape.radius_m`.
//!
//! A path is a list of segments, each a struct field name or a list index.
//! The same path type names a field in the parsed [`crate::Style`] and, via
//! [`crate::style::source_map::SourceMap`], a place in the file's text.

use std::fmt;

/// One step of a [`FieldPath`].
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Segment {
    /// A struct field (or map key), by name.
    Field(String),
    /// An element of a list or tuple, by index from 0.
    Index(usize),
}

/// A path from the top of a style file to one of its values.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct FieldPath {
    segments: Vec<Segment>,
}

impl FieldPath {
    /// The empty path: the whole file.
    pub fn root() -> Self {
        Self::default()
    }

    /// This path extended by the field `name`.
    pub fn field(&self, name: &str) -> Self {
        let mut out = self.clone();
        out.segments.push(Segment::Field(name.to_owned()));
        out
    }

    /// This path extended by the list index `index`.
    pub fn index(&self, index: usize) -> Self {
        let mut out = self.clone();
        out.segments.push(Segment::Index(index));
        out
    }

    /// This path followed by every segment of `tail`.
    pub fn join(&self, tail: &FieldPath) -> Self {
        let mut out = self.clone();
        out.segments.extend(tail.segments.iter().cloned());
        out
    }

    /// Parses a dotted path as the physics crate writes field names in a
    /// [`helixhair_physics::ParamError`] (`natural_shape.radius_m`,
    /// `gravity_m_per_s2[1]`). Text that is not a well-formed path becomes
    /// a single field segment, so nothing is lost from the message.
    pub fn parse(text: &str) -> Self {
        Self::try_parse(text).unwrap_or_else(|| Self {
            segments: vec![Segment::Field(text.to_owned())],
        })
    }

    fn try_parse(text: &str) -> Option<Self> {
        let mut segments = Vec::new();
        for part in text.split('.') {
            let (name, mut rest) = match part.find('[') {
                Some(open) => part.split_at(open),
                None => (part, ""),
            };
            if name.is_empty() {
                return None;
            }
            segments.push(Segment::Field(name.to_owned()));
            while !rest.is_empty() {
                let close = rest.find(']')?;
                let index = rest.get(1..close)?.parse().ok()?;
                segments.push(Segment::Index(index));
                rest = &rest[close + 1..];
                if !rest.is_empty() && !rest.starts_with('[') {
                    return None;
                }
            }
        }
        Some(Self { segments })
    }

    /// The segments, from the top of the file down.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Whether this is the empty path.
    pub fn is_root(&self) -> bool {
        self.segments.is_empty()
    }

    /// The path without its last segment (the root stays the root).
    pub fn parent(&self) -> Self {
        let mut out = self.clone();
        out.segments.pop();
        out
    }

    /// Whether the last segment is the field `name`.
    pub fn ends_with_field(&self, name: &str) -> bool {
        matches!(self.segments.last(), Some(Segment::Field(f)) if f == name)
    }
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, segment) in self.segments.iter().enumerate() {
            match segment {
                Segment::Field(name) if i == 0 => write!(f, "{name}")?,
                Segment::Field(name) => write!(f, ".{name}")?,
                Segment::Index(index) => write!(f, "[{index}]")?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_joins_fields_with_dots_and_indices_with_brackets() {
        let path = FieldPath::root()
            .field("groups")
            .index(2)
            .field("params")
            .field("radius_m");
        assert_eq!(path.to_string(), "groups[2].params.radius_m");
        assert_eq!(FieldPath::root().to_string(), "");
    }

    #[test]
    fn parse_reads_physics_field_names() {
        let nested = FieldPath::parse("natural_shape.radius_m");
        assert_eq!(
            nested,
            FieldPath::root().field("natural_shape").field("radius_m")
        );
        let indexed = FieldPath::parse("gravity_m_per_s2[1]");
        assert_eq!(
            indexed,
            FieldPath::root().field("gravity_m_per_s2").index(1)
        );
        let double = FieldPath::parse("a[1][2].b");
        assert_eq!(double.to_string(), "a[1][2].b");
    }

    #[test]
    fn parse_keeps_malformed_text_as_one_field() {
        for text in ["", "a..b", "a[x]", "a[1", "a[1]b"] {
            let path = FieldPath::parse(text);
            assert_eq!(
                path.segments(),
                [Segment::Field(text.to_owned())],
                "{text:?}"
            );
        }
    }
}

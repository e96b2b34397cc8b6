//! Where each field of a RON file sits in its text, so that errors found
//! after parsing can name a line.
//!
//! # How it works
//!
//! `ron` reports the line and column of syntax and type errors, but a value
//! that parses and is then rejected (a NaN radius, an empty group) carries no
//! position any more. [`SourceMap::new`] scans the text once more with a
//! small, forgiving outline parser: it knows RON's brackets, commas, field
//! names, strings and comments, nothing of types, and records for every
//! value its [`FieldPath`] and its span (from its field name, if it has one,
//! to the end of the value). Then:
//!
//! - [`SourceMap::locate`] goes from a path to a position (or to the nearest
//!   written ancestor, when the field was left at its default);
//! - [`SourceMap::path_at`] goes from a position `ron` reported to the
//!   innermost value there.
//!
//! The scan never fails: on malformed text it keeps what it saw up to the
//! first surprise, and values left open there extend to the end of the file.

use std::fmt;

use crate::style::field_path::FieldPath;

/// Deepest bracket nesting the outline parser follows (`ron` itself stops
/// at 128), so hostile input cannot overflow the stack.
const MAX_DEPTH: usize = 256;

/// A 1-based line and column (in characters), as `ron` counts them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct TextPosition {
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub col: usize,
}

impl fmt::Display for TextPosition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.col)
    }
}

/// One value of the file: its path and its byte span.
#[derive(Clone, Debug)]
struct Entry {
    path: FieldPath,
    /// Start of the field name (or of the value, for list items).
    start: usize,
    /// One past the value's last byte; `None` while (or if) it never closed.
    end: Option<usize>,
    /// Whether the value is a struct: `(name: value, …)`, named or not, or
    /// empty parentheses.
    is_struct: bool,
}

/// The outline of one RON text: every value's path and span.
#[derive(Clone, Debug)]
pub struct SourceMap<'a> {
    src: &'a str,
    line_starts: Vec<usize>,
    entries: Vec<Entry>,
}

impl<'a> SourceMap<'a> {
    /// Scans `src`; never fails (see the module docs).
    pub fn new(src: &'a str) -> Self {
        let line_starts = std::iter::once(0)
            .chain(src.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        let mut outline = Outline {
            tokens: lex(src),
            next: 0,
            src,
            entries: Vec::new(),
        };
        // A parse error only ends the scan; what was seen stays useful.
        let _ = outline.file();
        Self {
            src,
            line_starts,
            entries: outline.entries,
        }
    }

    /// Where the value at `path` is written: the start of its field name.
    pub fn position_of(&self, path: &FieldPath) -> Option<TextPosition> {
        self.entries
            .iter()
            .find(|e| e.path == *path)
            .map(|e| self.position_at(e.start))
    }

    /// The position of `path` or, when it is not written in the file (left
    /// at its default), of its nearest written ancestor; returns that
    /// position and the path found there. The whole file sits at 1:1.
    pub fn locate(&self, path: &FieldPath) -> (TextPosition, FieldPath) {
        let mut probe = path.clone();
        loop {
            if let Some(position) = self.position_of(&probe) {
                return (position, probe);
            }
            if probe.is_root() {
                return (TextPosition { line: 1, col: 1 }, probe);
            }
            probe = probe.parent();
        }
    }

    /// The innermost value whose span holds `position`. (`ron` reports
    /// errors about a whole value, such as a missing field or a tuple too
    /// short, on its closing bracket, which is inside the span.)
    pub fn path_at(&self, position: TextPosition) -> FieldPath {
        let offset = self.offset_of(position);
        self.entries
            .iter()
            .filter(|e| e.start <= offset && offset < e.end.unwrap_or(usize::MAX))
            .max_by_key(|e| (e.path.segments().len(), e.start))
            .map(|e| e.path.clone())
            .unwrap_or_default()
    }

    /// The innermost struct at or above `path` (see [`SourceMap::path_at`]),
    /// with the position where it starts; `None` if there is none.
    pub fn enclosing_struct(&self, path: &FieldPath) -> Option<(FieldPath, TextPosition)> {
        let mut probe = path.clone();
        loop {
            if let Some(entry) = self.entries.iter().find(|e| e.path == probe && e.is_struct) {
                return Some((probe, self.position_at(entry.start)));
            }
            if probe.is_root() {
                return None;
            }
            probe = probe.parent();
        }
    }

    /// `position`, moved forward past any whitespace to the next character
    /// that is not (`ron` reports some errors where the blank before a
    /// value starts).
    pub fn skip_whitespace(&self, position: TextPosition) -> TextPosition {
        let offset = self.offset_of(position);
        let rest = &self.src[offset..];
        let skipped = rest.len() - rest.trim_start().len();
        if skipped == 0 || offset + skipped >= self.src.len() {
            return position;
        }
        self.position_at(offset + skipped)
    }

    /// The line and column of byte `offset`.
    fn position_at(&self, offset: usize) -> TextPosition {
        let line = self.line_starts.partition_point(|&start| start <= offset);
        let line_start = self
            .line_starts
            .get(line.wrapping_sub(1))
            .copied()
            .unwrap_or(0);
        let col = 1 + self
            .src
            .get(line_start..offset)
            .map_or(0, |s| s.chars().count());
        TextPosition {
            line: line.max(1),
            col,
        }
    }

    /// The byte offset of a line and column, clamped to the text.
    fn offset_of(&self, position: TextPosition) -> usize {
        let Some(&line_start) = self.line_starts.get(position.line.saturating_sub(1)) else {
            return self.src.len();
        };
        let rest = &self.src[line_start..];
        let skip = position.col.saturating_sub(1);
        line_start + rest.char_indices().nth(skip).map_or(rest.len(), |(i, _)| i)
    }
}

/// What a token is, as far as the outline cares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// `(`, `[` or `{`.
    Open(u8),
    /// `)`, `]` or `}`.
    Close(u8),
    Colon,
    Comma,
    /// An identifier, number or other bare word.
    Word,
    /// A string, raw string, byte string or character literal.
    Quoted,
    /// Any other character (`#`, `!` of an attribute).
    Other(u8),
}

#[derive(Clone, Copy, Debug)]
struct Token {
    kind: Kind,
    start: usize,
    end: usize,
}

/// Splits `src` into tokens, dropping whitespace and comments. Unterminated
/// strings and comments run to the end of the text.
fn lex(src: &str) -> Vec<Token> {
    let bytes = src.as_bytes();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        let start = i;
        let kind = match c {
            _ if c.is_ascii_whitespace() => {
                i += 1;
                continue;
            }
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                i = src[i..].find('\n').map_or(bytes.len(), |n| i + n);
                continue;
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                i = skip_block_comment(bytes, i);
                continue;
            }
            b'(' | b'[' | b'{' => {
                i += 1;
                Kind::Open(c)
            }
            b')' | b']' | b'}' => {
                i += 1;
                Kind::Close(c)
            }
            b':' => {
                i += 1;
                Kind::Colon
            }
            b',' => {
                i += 1;
                Kind::Comma
            }
            b'"' => {
                i = skip_quoted(bytes, i + 1, b'"');
                Kind::Quoted
            }
            b'\'' => {
                i = skip_quoted(bytes, i + 1, b'\'');
                Kind::Quoted
            }
            _ if is_word_byte(c) || c == b'+' || c == b'-' || c >= 0x80 => {
                match raw_or_byte_string(bytes, i) {
                    Some(end) => i = end,
                    None => i = skip_word(bytes, i),
                }
                if bytes
                    .get(start..i)
                    .is_some_and(|w| w.ends_with(b"\"") || w.ends_with(b"'"))
                {
                    Kind::Quoted
                } else {
                    Kind::Word
                }
            }
            _ => {
                i += src[i..].chars().next().map_or(1, char::len_utf8);
                Kind::Other(c)
            }
        };
        tokens.push(Token {
            kind,
            start,
            end: i,
        });
    }
    tokens
}

fn is_word_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_' || c == b'.'
}

/// End of a bare word starting at `i`: letters, digits, `_`, `.`, non-ASCII
/// letters, a leading sign, and a sign after the `e` of a number's exponent.
fn skip_word(bytes: &[u8], start: usize) -> usize {
    let numeric = matches!(bytes[start], b'0'..=b'9' | b'+' | b'-' | b'.');
    let mut i = start + 1;
    while let Some(&c) = bytes.get(i) {
        let exponent_sign =
            numeric && (c == b'+' || c == b'-') && matches!(bytes[i - 1], b'e' | b'E');
        let raw_ident = c == b'#' && i == start + 1 && bytes[start] == b'r';
        if is_word_byte(c) || c >= 0x80 || exponent_sign || raw_ident {
            i += 1;
        } else {
            break;
        }
    }
    i
}

/// If a raw string (`r"…"`, `r#"…"#`), byte string (`b"…"`, `b'…'`) or raw
/// byte string starts at `i`, the index just past it.
fn raw_or_byte_string(bytes: &[u8], i: usize) -> Option<usize> {
    let mut j = i;
    if bytes.get(j) == Some(&b'b') {
        j += 1;
        match bytes.get(j) {
            Some(b'"') => return Some(skip_quoted(bytes, j + 1, b'"')),
            Some(b'\'') => return Some(skip_quoted(bytes, j + 1, b'\'')),
            _ => {}
        }
    }
    if bytes.get(j) != Some(&b'r') {
        return None;
    }
    j += 1;
    let hashes = bytes[j..].iter().take_while(|&&c| c == b'#').count();
    j += hashes;
    if bytes.get(j) != Some(&b'"') {
        return None;
    }
    j += 1;
    while j < bytes.len() {
        if bytes[j] == b'"'
            && bytes[j + 1..]
                .iter()
                .take(hashes)
                .filter(|&&c| c == b'#')
                .count()
                == hashes
        {
            return Some(j + 1 + hashes);
        }
        j += 1;
    }
    Some(bytes.len())
}

/// Index just past the closing `quote`, honouring backslash escapes.
fn skip_quoted(bytes: &[u8], mut i: usize, quote: u8) -> usize {
    while let Some(&c) = bytes.get(i) {
        match c {
            b'\\' => i += 2,
            _ if c == quote => return i + 1,
            _ => i += 1,
        }
    }
    bytes.len()
}

/// Index just past a (nested) block comment starting at `i`.
fn skip_block_comment(bytes: &[u8], mut i: usize) -> usize {
    let mut depth = 0usize;
    while i < bytes.len() {
        if bytes[i..].starts_with(b"/*") {
            depth += 1;
            i += 2;
        } else if bytes[i..].starts_with(b"*/") {
            depth -= 1;
            i += 2;
            if depth == 0 {
                return i;
            }
        } else {
            i += 1;
        }
    }
    bytes.len()
}

/// The scan ended early: the text is not well-formed RON at this point.
struct Malformed;

/// The outline parser's state.
struct Outline<'a> {
    tokens: Vec<Token>,
    next: usize,
    src: &'a str,
    entries: Vec<Entry>,
}

impl Outline<'_> {
    fn peek(&self) -> Option<Token> {
        self.tokens.get(self.next).copied()
    }

    fn peek_kind(&self, ahead: usize) -> Option<Kind> {
        self.tokens.get(self.next + ahead).map(|t| t.kind)
    }

    fn bump(&mut self) -> Result<Token, Malformed> {
        let token = self.peek().ok_or(Malformed)?;
        self.next += 1;
        Ok(token)
    }

    fn expect(&mut self, kind: Kind) -> Result<Token, Malformed> {
        match self.bump()? {
            token if token.kind == kind => Ok(token),
            _ => Err(Malformed),
        }
    }

    fn text(&self, token: Token) -> &str {
        &self.src[token.start..token.end]
    }

    /// Inner attributes (`#![enable(…)]`), then the one top-level value.
    fn file(&mut self) -> Result<(), Malformed> {
        while self.peek_kind(0) == Some(Kind::Other(b'#')) {
            self.bump()?;
            if self.peek_kind(0) == Some(Kind::Other(b'!')) {
                self.bump()?;
            }
            self.skip_value(0)?;
        }
        self.value(FieldPath::root(), None, 0)
    }

    /// Skips one value without recording it.
    fn skip_value(&mut self, depth: usize) -> Result<(), Malformed> {
        if depth > MAX_DEPTH {
            return Err(Malformed);
        }
        let token = self.bump()?;
        let close = match token.kind {
            Kind::Open(b'(') => b')',
            Kind::Open(b'[') => b']',
            Kind::Open(_) => b'}',
            Kind::Word if self.peek_kind(0) == Some(Kind::Open(b'(')) => {
                return self.skip_value(depth + 1);
            }
            Kind::Word | Kind::Quoted => return Ok(()),
            _ => return Err(Malformed),
        };
        loop {
            match self.peek_kind(0).ok_or(Malformed)? {
                Kind::Close(c) if c == close => {
                    self.bump()?;
                    return Ok(());
                }
                Kind::Colon | Kind::Comma => {
                    self.bump()?;
                }
                _ => self.skip_value(depth + 1)?,
            }
        }
    }

    /// One value at `path`; `key_start` is where its field name starts.
    fn value(
        &mut self,
        path: FieldPath,
        key_start: Option<usize>,
        depth: usize,
    ) -> Result<(), Malformed> {
        if depth > MAX_DEPTH {
            return Err(Malformed);
        }
        let first = self.peek().ok_or(Malformed)?;
        let index = self.entries.len();
        self.entries.push(Entry {
            path: path.clone(),
            start: key_start.unwrap_or(first.start),
            end: None,
            is_struct: false,
        });
        let mut is_struct = false;
        match first.kind {
            Kind::Word => {
                self.bump()?;
                // A named struct, tuple struct or enum variant.
                if self.peek_kind(0) == Some(Kind::Open(b'(')) {
                    is_struct = self.parenthesised(&path, depth)?;
                }
            }
            Kind::Quoted => {
                self.bump()?;
            }
            Kind::Open(b'(') => is_struct = self.parenthesised(&path, depth)?,
            Kind::Open(b'[') => self.list(&path, depth)?,
            Kind::Open(_) => self.map(&path, depth)?,
            _ => return Err(Malformed),
        }
        let end = self.tokens.get(self.next.wrapping_sub(1)).map(|t| t.end);
        self.entries[index].end = end;
        self.entries[index].is_struct = is_struct;
        Ok(())
    }

    /// `( name: value, … )` or `( value, … )`; returns whether it is a
    /// struct (the first form, or empty).
    fn parenthesised(&mut self, path: &FieldPath, depth: usize) -> Result<bool, Malformed> {
        self.expect(Kind::Open(b'('))?;
        let is_struct = matches!(
            (self.peek_kind(0), self.peek_kind(1)),
            (Some(Kind::Word), Some(Kind::Colon)) | (Some(Kind::Close(b')')), _)
        );
        let mut item = 0;
        loop {
            if self.peek_kind(0) == Some(Kind::Close(b')')) {
                self.bump()?;
                return Ok(is_struct);
            }
            if is_struct {
                let key = self.expect(Kind::Word)?;
                self.expect(Kind::Colon)?;
                let name = self.text(key);
                let name = name.strip_prefix("r#").unwrap_or(name).to_owned();
                self.value(path.field(&name), Some(key.start), depth + 1)?;
            } else {
                self.value(path.index(item), None, depth + 1)?;
                item += 1;
            }
            self.separator(b')')?;
        }
    }

    /// `[ value, … ]`.
    fn list(&mut self, path: &FieldPath, depth: usize) -> Result<(), Malformed> {
        self.expect(Kind::Open(b'['))?;
        let mut item = 0;
        loop {
            if self.peek_kind(0) == Some(Kind::Close(b']')) {
                self.bump()?;
                return Ok(());
            }
            self.value(path.index(item), None, depth + 1)?;
            item += 1;
            self.separator(b']')?;
        }
    }

    /// `{ key: value, … }`; keys that are strings or words name the field.
    fn map(&mut self, path: &FieldPath, depth: usize) -> Result<(), Malformed> {
        self.expect(Kind::Open(b'{'))?;
        loop {
            if self.peek_kind(0) == Some(Kind::Close(b'}')) {
                self.bump()?;
                return Ok(());
            }
            let key = self.peek().ok_or(Malformed)?;
            let name = match key.kind {
                Kind::Word | Kind::Quoted => self.text(key).trim_matches('"').to_owned(),
                _ => "?".to_owned(),
            };
            self.skip_value(depth + 1)?;
            self.expect(Kind::Colon)?;
            self.value(path.field(&name), Some(key.start), depth + 1)?;
            self.separator(b'}')?;
        }
    }

    /// A comma, or the closing bracket (left for the caller to consume).
    fn separator(&mut self, close: u8) -> Result<(), Malformed> {
        match self.peek_kind(0) {
            Some(Kind::Comma) => {
                self.bump()?;
                Ok(())
            }
            Some(Kind::Close(c)) if c == close => Ok(()),
            _ => Err(Malformed),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pos(line: usize, col: usize) -> TextPosition {
        TextPosition { line, col }
    }

    fn path(text: &str) -> FieldPath {
        FieldPath::parse(text)
    }

    const STYLE: &str = r##"// a comment with ( brackets [ and "quotes"
#![enable(implicit_some)]
(
    version: 1,
    name: "a (tricky) \" name",
    /* nested /* block */ comment ) */
    groups: [
        (
            name: r#"raw "string""#,
            params: (radius_m: 3.5e-5, natural_shape: Helix(radius_m: 0.01, step_m: -0.02)),
            roots: [(position_m: (0.0, 0.1, 0.0), direction: (0.0, 1.0, 0.0))],
        ),
    ],
)
"##;

    #[test]
    fn position_of_finds_each_field_name() {
        let map = SourceMap::new(STYLE);
        assert_eq!(map.position_of(&path("version")), Some(pos(4, 5)));
        assert_eq!(map.position_of(&path("groups[0]")), Some(pos(8, 9)));
        assert_eq!(map.position_of(&path("groups[0].name")), Some(pos(9, 13)));
        assert_eq!(
            map.position_of(&path("groups[0].params.radius_m")),
            Some(pos(10, 22))
        );
        assert_eq!(
            map.position_of(&path("groups[0].params.natural_shape.step_m")),
            Some(pos(10, 77))
        );
        assert_eq!(
            map.position_of(&path("groups[0].roots[0].direction[1]")),
            Some(pos(11, 68))
        );
        assert_eq!(map.position_of(&path("groups[1]")), None);
    }

    #[test]
    fn locate_falls_back_to_the_nearest_written_ancestor() {
        let map = SourceMap::new(STYLE);
        let (at, found) = map.locate(&path("groups[0].params.ellipticity"));
        assert_eq!((at, found), (pos(10, 13), path("groups[0].params")));
        // The whole file starts at its top-level value, after comments.
        let (at, found) = map.locate(&path("sim.dt_secs"));
        assert_eq!((at, found), (pos(3, 1), FieldPath::root()));
        let (at, found) = SourceMap::new("").locate(&path("sim"));
        assert_eq!((at, found), (pos(1, 1), FieldPath::root()));
    }

    #[test]
    fn path_at_finds_the_innermost_value() {
        let map = SourceMap::new(STYLE);
        assert_eq!(map.path_at(pos(10, 32)), path("groups[0].params.radius_m"));
        assert_eq!(map.path_at(pos(10, 13)), path("groups[0].params"));
        // The closing bracket belongs to the value, what follows does not.
        assert_eq!(map.path_at(pos(12, 9)), path("groups[0]"));
        assert_eq!(map.path_at(pos(12, 10)), path("groups"));
        assert_eq!(map.path_at(pos(3, 1)), FieldPath::root());
        assert_eq!(map.path_at(pos(99, 1)), FieldPath::root());
    }

    #[test]
    fn enclosing_struct_skips_scalars_and_tuples() {
        let map = SourceMap::new(STYLE);
        let (found, at) = map
            .enclosing_struct(&path("groups[0].params.natural_shape.radius_m"))
            .expect("a struct");
        assert_eq!(
            (found, at),
            (path("groups[0].params.natural_shape"), pos(10, 40))
        );
        let (found, _) = map
            .enclosing_struct(&path("groups[0].roots[0].position_m[1]"))
            .expect("a struct");
        assert_eq!(found, path("groups[0].roots[0]"));
        assert_eq!(
            SourceMap::new("[1, 2]").enclosing_struct(&path("[0]")),
            None
        );
    }

    #[test]
    fn skip_whitespace_moves_to_the_next_character() {
        let map = SourceMap::new("(a:   1,\n   b: 2)");
        assert_eq!(map.skip_whitespace(pos(1, 4)), pos(1, 7));
        assert_eq!(map.skip_whitespace(pos(1, 9)), pos(2, 4));
        assert_eq!(map.skip_whitespace(pos(1, 7)), pos(1, 7));
        assert_eq!(map.skip_whitespace(pos(9, 9)), pos(9, 9));
    }

    #[test]
    fn malformed_text_keeps_the_outline_up_to_the_error() {
        let src = "(\n  groups: [\n    (name: \"a\" params: ()),\n  ],\n)\n";
        let map = SourceMap::new(src);
        assert_eq!(map.position_of(&path("groups[0].name")), Some(pos(3, 6)));
        // The group never closed, so everything after it lies inside it.
        assert_eq!(map.path_at(pos(3, 16)), path("groups[0]"));
        assert_eq!(map.path_at(pos(5, 1)), path("groups[0]"));
    }

    #[test]
    fn hostile_text_does_not_panic() {
        let deep = "(".repeat(10_000);
        for src in [
            "",
            "\"unterminated",
            "r#\"unterminated",
            "/* unterminated",
            "(a: b'x', c: 'é', d: -1e-5, e: +.5, é: 1)",
            deep.as_str(),
            ")))",
            "(a:",
            "#",
            "#![",
        ] {
            let map = SourceMap::new(src);
            let _ = map.path_at(pos(1, 3));
            let _ = map.locate(&path("a.b[3]"));
        }
    }
}

//! Tokens of a `.usda` layer, each with its line.
//!
//! The lexer is pulled one token at a time, so it never holds more than the
//! token it returns; strings and identifiers are slices of the input.
//! Comments (`#` to the end of the line, after the `#usda` header line) are
//! skipped.

use crate::error::{Location, ReadError, ReadErrorKind};
use crate::format::Format;

/// One token.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Token<'a> {
    /// A name: keyword, type, property (`primvars:displayColor`,
    /// `points.timeSamples`), `inf`, `nan`, `None`.
    Ident(&'a str),
    /// A number.
    Number(f64),
    /// A quoted string's contents (escapes left as written).
    Str(&'a str),
    /// A path `</a/b>`'s contents.
    Path(&'a str),
    /// An asset path `@a.usd@`'s contents.
    Asset(&'a str),
    /// Punctuation: `( ) [ ] { } = , : ; &` and others.
    Punct(u8),
    /// The end of the input.
    End,
}

/// Pulls tokens from a layer's text.
pub(crate) struct Lexer<'a> {
    text: &'a str,
    at: usize,
    line: usize,
}

impl<'a> Lexer<'a> {
    /// A lexer over `text`, starting at line 1.
    pub fn new(text: &'a str) -> Lexer<'a> {
        Lexer {
            text,
            at: 0,
            line: 1,
        }
    }

    /// The line the next token starts on (after skipping blanks).
    pub fn line(&self) -> usize {
        self.line
    }

    fn error(&self, message: String) -> ReadError {
        ReadError::new(
            Format::Usda,
            Location::Line(self.line),
            ReadErrorKind::Syntax,
            message,
        )
    }

    fn skip_blanks(&mut self) {
        let bytes = self.text.as_bytes();
        while let Some(&byte) = bytes.get(self.at) {
            match byte {
                b'\n' => {
                    self.line += 1;
                    self.at += 1;
                }
                b' ' | b'\t' | b'\r' => self.at += 1,
                b'#' => {
                    while bytes.get(self.at).is_some_and(|&b| b != b'\n') {
                        self.at += 1;
                    }
                }
                _ => break,
            }
        }
    }

    /// The next token and the line it starts on.
    pub fn next_token(&mut self) -> Result<(Token<'a>, usize), ReadError> {
        self.skip_blanks();
        let line = self.line;
        let bytes = self.text.as_bytes();
        let Some(&first) = bytes.get(self.at) else {
            return Ok((Token::End, line));
        };
        let start = self.at;
        let token = match first {
            b'"' | b'\'' => self.string(first)?,
            b'<' => {
                let end = self.find_byte(b'>', "a path </...> is not closed")?;
                self.count_lines(start, end);
                self.at = end + 1;
                Token::Path(&self.text[start + 1..end])
            }
            b'@' => self.asset()?,
            b'-' | b'+' | b'.' | b'0'..=b'9' => {
                let next = bytes.get(self.at + 1).copied().unwrap_or(b' ');
                if first == b'-' && next.is_ascii_alphabetic() {
                    self.at += 1;
                    self.ident_end();
                    Token::Ident(&self.text[start..self.at])
                } else if first.is_ascii_digit() || next.is_ascii_digit() || next == b'.' {
                    self.number()?
                } else {
                    self.at += 1;
                    Token::Punct(first)
                }
            }
            b'a'..=b'z' | b'A'..=b'Z' | b'_' => {
                self.ident_end();
                Token::Ident(&self.text[start..self.at])
            }
            _ => {
                // One byte of punctuation; a multi-byte character is taken
                // whole so the next token starts on a character boundary.
                let width = self.text[start..].chars().next().map_or(1, char::len_utf8);
                self.at += width;
                Token::Punct(first)
            }
        };
        Ok((token, line))
    }

    fn ident_end(&mut self) {
        let bytes = self.text.as_bytes();
        while bytes
            .get(self.at)
            .is_some_and(|&b| b.is_ascii_alphanumeric() || matches!(b, b'_' | b':' | b'.'))
        {
            self.at += 1;
        }
    }

    fn number(&mut self) -> Result<Token<'a>, ReadError> {
        let bytes = self.text.as_bytes();
        let start = self.at;
        self.at += 1;
        while let Some(&b) = bytes.get(self.at) {
            let exponent_sign =
                matches!(b, b'-' | b'+') && matches!(bytes[self.at - 1], b'e' | b'E');
            if b.is_ascii_digit() || matches!(b, b'.' | b'e' | b'E') || exponent_sign {
                self.at += 1;
            } else {
                break;
            }
        }
        let text = &self.text[start..self.at];
        text.parse()
            .map(Token::Number)
            .map_err(|_| self.error(format!("{text:?} is not a number")))
    }

    fn find_byte(&self, byte: u8, message: &str) -> Result<usize, ReadError> {
        self.text.as_bytes()[self.at + 1..]
            .iter()
            .position(|&b| b == byte)
            .map(|offset| self.at + 1 + offset)
            .ok_or_else(|| self.error(message.to_string()))
    }

    fn count_lines(&mut self, from: usize, to: usize) {
        self.line += self.text.as_bytes()[from..to]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
    }

    fn string(&mut self, quote: u8) -> Result<Token<'a>, ReadError> {
        let bytes = self.text.as_bytes();
        let start = self.at;
        let triple = bytes.get(start + 1) == Some(&quote) && bytes.get(start + 2) == Some(&quote);
        let open = if triple { 3 } else { 1 };
        let mut at = start + open;
        loop {
            match bytes.get(at) {
                None => return Err(self.error("a string is not closed".to_string())),
                Some(b'\\') => at += 2,
                Some(b'\n') if !triple => {
                    return Err(self.error("a string runs past the end of its line".to_string()));
                }
                Some(&b) if b == quote => {
                    let closes = !triple
                        || (bytes.get(at + 1) == Some(&quote) && bytes.get(at + 2) == Some(&quote));
                    if closes {
                        let contents = &self.text[start + open..at];
                        self.count_lines(start, at);
                        self.at = at + open;
                        return Ok(Token::Str(contents));
                    }
                    at += 1;
                }
                Some(_) => at += 1,
            }
        }
    }

    fn asset(&mut self) -> Result<Token<'a>, ReadError> {
        let bytes = self.text.as_bytes();
        let start = self.at;
        let (open, close): (usize, &[u8]) = if bytes[start..].starts_with(b"@@@") {
            (3, b"@@@")
        } else {
            (1, b"@")
        };
        let body = &bytes[start + open..];
        let end = body
            .windows(close.len())
            .position(|window| window == close)
            .ok_or_else(|| self.error("an asset path @...@ is not closed".to_string()))?;
        let contents = &self.text[start + open..start + open + end];
        self.count_lines(start, start + open + end);
        self.at = start + open + end + close.len();
        Ok(Token::Asset(contents))
    }
}

//! A position in a crate file's bytes, read little-endian with bounds
//! checks, and the allocation budget every decoded array is charged to.
//!
//! Crate files are full of offsets and counts, and most of their lists are
//! compressed, so a few hostile bytes could claim gigabytes. Every read
//! here is bounds-checked (a short file is [`ReadErrorKind::Truncated`]
//! at the byte that is missing), and everything decoded is first charged
//! to a [`Budget`] of [`BUDGET_PER_FILE_BYTE`] bytes per byte of the file,
//! so a file of `n` bytes can make the reader hold at most that many times
//! `n` however its counts and compressed sizes lie.

use std::cell::Cell;

use crate::error::{Location, ReadError, ReadErrorKind};
use crate::format::Format;

/// Decoded bytes allowed per byte of the file, over the whole read.
pub const BUDGET_PER_FILE_BYTE: usize = 32;

/// An error of a crate file at a byte offset.
pub(crate) fn error(offset: u64, kind: ReadErrorKind, message: impl Into<String>) -> ReadError {
    ReadError::new(Format::Usdc, Location::Byte(offset), kind, message)
}

/// What the reader may still allocate (also the Alembic reader's).
#[derive(Debug)]
pub(crate) struct Budget {
    left: Cell<usize>,
    total: usize,
    format: Format,
}

impl Budget {
    pub fn for_file(file_bytes: usize, format: Format) -> Budget {
        let total = file_bytes.saturating_mul(BUDGET_PER_FILE_BYTE).max(4096);
        Budget {
            left: Cell::new(total),
            total,
            format,
        }
    }

    /// Takes `bytes` from the budget, or refuses at `offset` (where the
    /// count or size that asked for them is).
    pub fn charge(&self, bytes: usize, offset: u64, what: &str) -> Result<(), ReadError> {
        match self.left.get().checked_sub(bytes) {
            Some(left) => {
                self.left.set(left);
                Ok(())
            }
            None => Err(ReadError::new(
                self.format,
                Location::Byte(offset),
                ReadErrorKind::TooLarge,
                format!(
                    "{what} would take {bytes} bytes, past the {} bytes of decoded data this file's size allows",
                    self.total
                ),
            )),
        }
    }
}

/// A read position in a crate file.
#[derive(Clone, Copy)]
pub(crate) struct Cursor<'a> {
    pub bytes: &'a [u8],
    pub at: u64,
}

impl<'a> Cursor<'a> {
    pub fn new(bytes: &'a [u8], at: u64) -> Cursor<'a> {
        Cursor { bytes, at }
    }

    /// The next `size` bytes, naming `what` if the file ends first.
    pub fn take(&mut self, size: u64, what: &str) -> Result<&'a [u8], ReadError> {
        let len = self.bytes.len() as u64;
        let end = self.at.checked_add(size).filter(|&end| end <= len);
        let Some(end) = end else {
            return Err(error(
                len.min(self.at),
                ReadErrorKind::Truncated,
                format!(
                    "{what} (bytes {}..{}) runs past the end of the file at byte {len}",
                    self.at,
                    self.at.saturating_add(size)
                ),
            ));
        };
        let slice = &self.bytes[self.at as usize..end as usize];
        self.at = end;
        Ok(slice)
    }

    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N], ReadError> {
        let mut array = [0; N];
        array.copy_from_slice(self.take(N as u64, what)?);
        Ok(array)
    }

    pub fn u8(&mut self, what: &str) -> Result<u8, ReadError> {
        self.array::<1>(what).map(|b| b[0])
    }

    pub fn u32(&mut self, what: &str) -> Result<u32, ReadError> {
        self.array(what).map(u32::from_le_bytes)
    }

    pub fn u64(&mut self, what: &str) -> Result<u64, ReadError> {
        self.array(what).map(u64::from_le_bytes)
    }

    pub fn i64(&mut self, what: &str) -> Result<i64, ReadError> {
        self.array(what).map(i64::from_le_bytes)
    }

    pub fn f64(&mut self, what: &str) -> Result<f64, ReadError> {
        self.array(what).map(f64::from_le_bytes)
    }

    /// A count of items of `item_bytes` each that must fit in the rest of
    /// the file (so counts of stored, uncompressed items cannot lie).
    pub fn count(&mut self, item_bytes: u64, what: &str) -> Result<usize, ReadError> {
        let at = self.at;
        let count = self.u64(what)?;
        let left = (self.bytes.len() as u64).saturating_sub(self.at);
        match count.checked_mul(item_bytes) {
            Some(size) if size <= left => Ok(count as usize),
            _ => Err(error(
                at,
                ReadErrorKind::TooLarge,
                format!("{count} {what} of {item_bytes} bytes do not fit in the {left} bytes left"),
            )),
        }
    }

    /// Moves to an offset read from the file (checked when next read).
    pub fn seek(&mut self, at: u64) {
        self.at = at;
    }
}

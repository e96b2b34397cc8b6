//! Bounds-checked little-endian reads for the binary readers.
//!
//! Every read names what it reads, so a short file gives an error that says
//! which field is missing and where. Offsets and sizes are `u64` and all
//! arithmetic on counts taken from a file is checked, so a hostile count
//! can neither overflow nor allocate: [`LeBytes::require`] is called before
//! anything sized by the file is allocated.

use crate::error::{Location, ReadError, ReadErrorKind};
use crate::format::Format;

/// A file's bytes, read little-endian with bounds checks.
pub(crate) struct LeBytes<'a> {
    data: &'a [u8],
    format: Format,
}

impl<'a> LeBytes<'a> {
    pub fn new(data: &'a [u8], format: Format) -> LeBytes<'a> {
        LeBytes { data, format }
    }

    pub fn len(&self) -> u64 {
        self.data.len() as u64
    }

    /// An error of this file's format at a byte offset.
    pub fn error(&self, offset: u64, kind: ReadErrorKind, message: String) -> ReadError {
        ReadError::new(self.format, Location::Byte(offset), kind, message)
    }

    /// Checks that `size` bytes starting at `start` lie inside the file.
    /// `field_offset` is where the count or offset that asked for them is
    /// stored, for the error's location. A size beyond the whole file is
    /// [`ReadErrorKind::TooLarge`] (at `field_offset`); a range that runs off
    /// the file's end is [`ReadErrorKind::Truncated`] (at the end of the
    /// file, or at `field_offset` when the range starts past it).
    pub fn require(
        &self,
        start: u64,
        size: Option<u64>,
        field_offset: u64,
        what: &str,
    ) -> Result<(), ReadError> {
        let len = self.len();
        let Some(size) = size.filter(|&size| size <= len) else {
            let size = size.map_or("more than 2^64".to_string(), |s| s.to_string());
            return Err(self.error(
                field_offset,
                ReadErrorKind::TooLarge,
                format!("{what} need {size} bytes, the whole file has {len}"),
            ));
        };
        match start.checked_add(size) {
            Some(end) if end <= len => Ok(()),
            // The array would start past the end: the offset is wrong.
            _ if start >= len && size > 0 => Err(self.error(
                field_offset,
                ReadErrorKind::Truncated,
                format!("{what} start at byte {start}, past the end of the file at byte {len}"),
            )),
            _ => Err(self.error(
                len,
                ReadErrorKind::Truncated,
                format!(
                    "{what} take bytes {start}..{} but the file ends at byte {len}",
                    start.saturating_add(size)
                ),
            )),
        }
    }

    /// Checks that a fixed-size part (a header, a field) lies inside the
    /// file: a short file is [`ReadErrorKind::Truncated`].
    pub fn require_fixed(&self, start: u64, size: u64, what: &str) -> Result<(), ReadError> {
        let len = self.len();
        if start + size <= len {
            return Ok(());
        }
        Err(self.error(
            len.min(start),
            ReadErrorKind::Truncated,
            format!(
                "the file ends at byte {len}, inside {what} (bytes {start}..{})",
                start + size
            ),
        ))
    }

    fn array<const N: usize>(&self, offset: u64, what: &str) -> Result<[u8; N], ReadError> {
        self.require_fixed(offset, N as u64, what)?;
        let start = offset as usize;
        let mut bytes = [0; N];
        bytes.copy_from_slice(&self.data[start..start + N]);
        Ok(bytes)
    }

    pub fn u32_at(&self, offset: u64, what: &str) -> Result<u32, ReadError> {
        self.array(offset, what).map(u32::from_le_bytes)
    }

    pub fn f32_at(&self, offset: u64, what: &str) -> Result<f32, ReadError> {
        self.array(offset, what).map(f32::from_le_bytes)
    }

    /// `size` bytes from `offset`, which [`Self::require`] has already
    /// checked lie in the file.
    pub fn slice(&self, offset: u64, size: usize) -> &'a [u8] {
        let start = offset as usize;
        &self.data[start..start + size]
    }
}

/// The `index`th little-endian `f32` of a slice the caller sized.
pub(crate) fn f32_in(bytes: &[u8], index: usize) -> f32 {
    let at = 4 * index;
    f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

/// Little-endian writes into a byte vector, for the binary writers.
pub(crate) fn put_u32(out: &mut Vec<u8>, value: u32) {
    out.extend_from_slice(&value.to_le_bytes());
}

/// See [`put_u32`].
pub(crate) fn put_f32(out: &mut Vec<u8>, value: f32) {
    out.extend_from_slice(&value.to_le_bytes());
}

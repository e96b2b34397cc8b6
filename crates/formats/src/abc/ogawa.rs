//! Ogawa, the container under Alembic files: a tree of groups and data
//! blocks, read and written.
//!
//! # How it works
//!
//! A file starts with 16 bytes: `Ogawa`, a "frozen" byte (0xff once the
//! writer closed the file cleanly), the version (0, 1) and the offset of
//! the root group. A group at an offset is a `u64` child count and one
//! `u64` per child: with the top bit set, the offset of a data block (a
//! `u64` size, then the bytes), else the offset of a group; offset 0 is
//! the empty group or the empty data. Nothing else: names, types and
//! samples are Alembic's layer above ([`crate::abc::archive`]).
//!
//! Reading checks every offset and count against the file and charges
//! every group's children to the read's [`Budget`], so a hostile file
//! cannot make the reader allocate more than its size justifies, however
//! often its groups name each other. Writing appends data and groups
//! bottom up (children before their parent), so every offset is known
//! when it is written.

use crate::error::{Location, ReadError, ReadErrorKind};
use crate::format::Format;
use crate::usdc::cursor::Budget;

/// What an Ogawa file starts with.
pub const MAGIC: &[u8; 5] = b"Ogawa";
/// The top bit of a child entry: the child is data, not a group.
const DATA_BIT: u64 = 1 << 63;

/// An error of an Alembic file at a byte offset.
pub(crate) fn error(offset: u64, kind: ReadErrorKind, message: impl Into<String>) -> ReadError {
    ReadError::new(Format::Abc, Location::Byte(offset), kind, message)
}

/// A child of a group: a group or a data block, by offset (0: empty).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Child {
    Group(u64),
    Data(u64),
}

impl Child {
    fn from_entry(entry: u64) -> Child {
        if entry & DATA_BIT != 0 {
            Child::Data(entry & !DATA_BIT)
        } else {
            Child::Group(entry)
        }
    }
}

/// An Ogawa file being read.
pub(crate) struct Ogawa<'a> {
    pub bytes: &'a [u8],
    pub budget: &'a Budget,
}

fn u64_at(bytes: &[u8], at: u64) -> Option<u64> {
    let at = usize::try_from(at).ok()?;
    let word = bytes.get(at..at.checked_add(8)?)?;
    let mut array = [0; 8];
    array.copy_from_slice(word);
    Some(u64::from_le_bytes(array))
}

impl<'a> Ogawa<'a> {
    /// Checks the header; returns the file and its root group.
    pub fn open(bytes: &'a [u8], budget: &'a Budget) -> Result<(Ogawa<'a>, Child), ReadError> {
        if !bytes.starts_with(MAGIC) {
            let message = if bytes.starts_with(b"\x89HDF") {
                "this is an HDF5 Alembic file (before Alembic 1.5); re-export it as Ogawa"
            } else {
                "an Alembic file starts with \"Ogawa\""
            };
            return Err(error(0, ReadErrorKind::BadMagic, message));
        }
        let Some(root) = u64_at(bytes, 8) else {
            return Err(error(
                bytes.len() as u64,
                ReadErrorKind::Truncated,
                "the file ends inside its 16-byte header",
            ));
        };
        if bytes[5] != 0xff {
            return Err(error(
                5,
                ReadErrorKind::Truncated,
                "the file was not closed cleanly by its writer (not frozen)",
            ));
        }
        if bytes[6..8] != [0, 1] {
            return Err(error(
                6,
                ReadErrorKind::UnsupportedVersion,
                format!(
                    "Ogawa version {}.{} is not read (0.1 is)",
                    bytes[6], bytes[7]
                ),
            ));
        }
        Ok((Ogawa { bytes, budget }, Child::Group(root)))
    }

    /// A group's children (none for the empty group).
    pub fn group(&self, child: Child) -> Result<Vec<Child>, ReadError> {
        let offset = match child {
            Child::Group(0) => return Ok(Vec::new()),
            Child::Group(offset) => offset,
            Child::Data(offset) => {
                return Err(error(
                    offset,
                    ReadErrorKind::BadValue,
                    "a group was expected here, the file has data",
                ));
            }
        };
        let count = u64_at(self.bytes, offset).ok_or_else(|| {
            error(
                offset,
                ReadErrorKind::Truncated,
                format!("a group at byte {offset} is past the end of the file"),
            )
        })?;
        let left = (self.bytes.len() as u64).saturating_sub(offset + 8);
        if count > left / 8 {
            return Err(error(
                offset,
                ReadErrorKind::TooLarge,
                format!("a group of {count} children does not fit in the {left} bytes left"),
            ));
        }
        let count = count as usize;
        self.budget.charge(count * 16, offset, "groups")?;
        Ok((0..count)
            .filter_map(|index| u64_at(self.bytes, offset + 8 + 8 * index as u64))
            .map(Child::from_entry)
            .collect())
    }

    /// A data block's bytes (none for the empty data).
    pub fn data(&self, child: Child) -> Result<&'a [u8], ReadError> {
        let offset = match child {
            Child::Data(0) => return Ok(&[]),
            Child::Data(offset) => offset,
            Child::Group(offset) => {
                return Err(error(
                    offset,
                    ReadErrorKind::BadValue,
                    "data was expected here, the file has a group",
                ));
            }
        };
        let size = u64_at(self.bytes, offset).ok_or_else(|| {
            error(
                offset,
                ReadErrorKind::Truncated,
                format!("data at byte {offset} is past the end of the file"),
            )
        })?;
        let start = offset + 8;
        let end = start
            .checked_add(size)
            .filter(|&end| end <= self.bytes.len() as u64);
        match end {
            Some(end) => Ok(&self.bytes[start as usize..end as usize]),
            None => Err(error(
                offset,
                ReadErrorKind::Truncated,
                format!(
                    "{size} bytes of data from byte {start} run past the end of the file at byte {}",
                    self.bytes.len()
                ),
            )),
        }
    }
}

/// An Ogawa file being written, bottom up.
pub(crate) struct OgawaWriter {
    bytes: Vec<u8>,
}

impl OgawaWriter {
    pub fn new() -> OgawaWriter {
        let mut bytes = Vec::with_capacity(1 << 16);
        bytes.extend_from_slice(MAGIC);
        // Frozen (written in one go), version 0.1, the root's offset later.
        bytes.extend_from_slice(&[0xff, 0, 1]);
        bytes.extend_from_slice(&[0; 8]);
        OgawaWriter { bytes }
    }

    /// Appends a data block made of `parts`; returns its child entry.
    pub fn data(&mut self, parts: &[&[u8]]) -> u64 {
        let size: usize = parts.iter().map(|p| p.len()).sum();
        if size == 0 {
            return DATA_BIT;
        }
        let at = self.bytes.len() as u64;
        self.bytes.extend_from_slice(&(size as u64).to_le_bytes());
        for part in parts {
            self.bytes.extend_from_slice(part);
        }
        at | DATA_BIT
    }

    /// Appends a group of child entries; returns its child entry.
    pub fn group(&mut self, children: &[u64]) -> u64 {
        if children.is_empty() {
            return 0;
        }
        let at = self.bytes.len() as u64;
        self.bytes
            .extend_from_slice(&(children.len() as u64).to_le_bytes());
        for child in children {
            self.bytes.extend_from_slice(&child.to_le_bytes());
        }
        at
    }

    /// The file, with `root` (a group entry) as its root group.
    pub fn finish(mut self, root: u64) -> Vec<u8> {
        self.bytes[8..16].copy_from_slice(&root.to_le_bytes());
        self.bytes
    }
}

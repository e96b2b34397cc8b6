//! Alembic's layer over Ogawa (`AbcCoreOgawa`), read: the archive, its
//! objects and their properties, time samplings and samples.
//!
//! # How an Alembic file is laid out
//!
//! The root group holds, in order: the file version (`i32`, 0), the
//! library version (`i32`), the top object's group, the archive's
//! metadata, the time samplings and the indexed metadata. An **object**
//! group holds its property compound's group, one group per child
//! object, and last a data block of the children's headers (name and
//! metadata each, then 32 bytes of hashes). A **compound property** group
//! holds one group per property and last a data block of their headers,
//! packed: an info word (kind, value type, extent, flags, a size hint
//! that says whether the counts that follow take 1, 2 or 4 bytes), the
//! sample count, the first and last changed sample (repeated samples are
//! stored once), the time sampling's index, the name and the metadata
//! (inline, or an index into the indexed metadata). A **scalar** property
//! group holds one data block per stored sample, an **array** property two
//! (the values, then their dimensions, empty for plain lists); each
//! sample's data starts with a 16-byte key (a hash), then the values.
//! Metadata is `key=value;key=value` text.
//!
//! Every count and offset is checked, every decoded array is charged to
//! the read's [`Budget`], and the caller walks objects at most
//! [`MAX_DEPTH`] deep.

use crate::abc::ogawa::{Child, Ogawa, error};
use crate::error::{ReadError, ReadErrorKind};
use crate::usdc::cursor::Budget;

/// The deepest object nesting read.
pub const MAX_DEPTH: usize = 64;

/// Alembic's `chrono_t` maximum / 32: the time per cycle of an acyclic
/// time sampling.
pub const ACYCLIC_TIME_PER_CYCLE: f64 = f64::MAX / 32.0;

/// Value types (`PlainOldDataType`).
pub(crate) mod pod {
    pub const BOOL: u8 = 0;
    pub const U8: u8 = 1;
    pub const I8: u8 = 2;
    pub const U16: u8 = 3;
    pub const I16: u8 = 4;
    pub const U32: u8 = 5;
    pub const I32: u8 = 6;
    pub const U64: u8 = 7;
    pub const I64: u8 = 8;
    pub const F16: u8 = 9;
    pub const F32: u8 = 10;
    pub const F64: u8 = 11;
    pub const WSTRING: u8 = 13;
}

/// A property's kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Compound,
    Scalar,
    Array,
}

/// A property: its header and where its samples are.
#[derive(Clone, Debug)]
pub(crate) struct Property {
    pub name: String,
    pub kind: Kind,
    pub pod: u8,
    pub extent: u8,
    pub metadata: String,
    pub samples: u32,
    pub first_changed: u32,
    pub last_changed: u32,
    pub time_sampling: u32,
    pub group: Child,
}

/// An object: its name, metadata and group.
#[derive(Clone, Debug)]
pub(crate) struct Object {
    pub name: String,
    pub metadata: String,
    pub group: Child,
}

/// When a property's samples are: `times` per cycle of `time_per_cycle`
/// seconds (one time and a period: uniform sampling), or all the times
/// (acyclic).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct TimeSampling {
    pub time_per_cycle: f64,
    pub times: Vec<f64>,
}

impl TimeSampling {
    /// Whether every sample's time is listed.
    pub fn acyclic(&self) -> bool {
        self.time_per_cycle == ACYCLIC_TIME_PER_CYCLE
    }

    /// The time of sample `index`, seconds.
    pub fn time(&self, index: u32) -> f64 {
        let n = self.times.len().max(1);
        let index = index as usize;
        if self.acyclic() {
            return self
                .times
                .get(index)
                .or(self.times.last())
                .copied()
                .unwrap_or(0.0);
        }
        let cycle = (index / n) as f64;
        self.times.get(index % n).copied().unwrap_or(0.0) + cycle * self.time_per_cycle
    }
}

/// The value of `key` in `key=value;…` metadata.
pub(crate) fn metadata_value<'m>(metadata: &'m str, key: &str) -> Option<&'m str> {
    metadata
        .split(';')
        .filter_map(|pair| pair.split_once('='))
        .find(|(k, _)| *k == key)
        .map(|(_, v)| v)
}

/// An Alembic archive being read.
pub(crate) struct Archive<'a> {
    pub ogawa: Ogawa<'a>,
    pub time_samplings: Vec<TimeSampling>,
    indexed_metadata: Vec<String>,
    /// The top object's group.
    pub top: Child,
}

/// A little-endian reader over one data block, whose errors name the
/// block's offset.
struct Block<'a> {
    bytes: &'a [u8],
    at: usize,
    offset: u64,
    what: &'static str,
}

impl Block<'_> {
    fn take(&mut self, size: usize) -> Result<&[u8], ReadError> {
        let slice = self
            .at
            .checked_add(size)
            .and_then(|end| self.bytes.get(self.at..end))
            .ok_or_else(|| {
                error(
                    self.offset,
                    ReadErrorKind::Truncated,
                    format!(
                        "{} are cut off at byte {} of {}",
                        self.what,
                        self.at,
                        self.bytes.len()
                    ),
                )
            })?;
        self.at += size;
        Ok(slice)
    }

    fn u32(&mut self) -> Result<u32, ReadError> {
        let b = self.take(4)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn f64(&mut self) -> Result<f64, ReadError> {
        let b = self.take(8)?;
        let mut word = [0; 8];
        word.copy_from_slice(b);
        Ok(f64::from_le_bytes(word))
    }

    /// A count of 1, 2 or 4 bytes, as the size hint says.
    fn hinted(&mut self, hint: u32) -> Result<u32, ReadError> {
        match hint {
            0 => Ok(u32::from(self.take(1)?[0])),
            1 => {
                let b = self.take(2)?;
                Ok(u32::from(u16::from_le_bytes([b[0], b[1]])))
            }
            2 => self.u32(),
            _ => Err(error(
                self.offset,
                ReadErrorKind::BadValue,
                format!("{}: size hint {hint} is not 0, 1 or 2", self.what),
            )),
        }
    }

    fn text(&mut self, size: u32) -> Result<String, ReadError> {
        Ok(String::from_utf8_lossy(self.take(size as usize)?).into_owned())
    }

    fn done(&self) -> bool {
        self.at >= self.bytes.len()
    }
}

impl<'a> Archive<'a> {
    /// Opens the archive: the root group's six entries.
    pub fn open(bytes: &'a [u8], budget: &'a Budget) -> Result<Archive<'a>, ReadError> {
        let (ogawa, root) = Ogawa::open(bytes, budget)?;
        let children = ogawa.group(root)?;
        let shape_ok = children.len() >= 6
            && matches!(children[0], Child::Data(_))
            && matches!(children[1], Child::Data(_))
            && matches!(children[2], Child::Group(_))
            && children[3..6].iter().all(|c| matches!(c, Child::Data(_)));
        if !shape_ok {
            return Err(error(
                8,
                ReadErrorKind::BadMagic,
                "an Ogawa file, but not an Alembic archive (its root does not hold versions, the top object, metadata and time samplings)",
            ));
        }
        let version = ogawa.data(children[0])?;
        if version != [0, 0, 0, 0] {
            return Err(error(
                16,
                ReadErrorKind::UnsupportedVersion,
                format!("Alembic file version {version:?} is not read (0 is)"),
            ));
        }
        let mut archive = Archive {
            ogawa,
            time_samplings: Vec::new(),
            indexed_metadata: vec![String::new()],
            top: children[2],
        };
        archive.read_time_samplings(children[4])?;
        archive.read_indexed_metadata(children[5])?;
        Ok(archive)
    }

    fn block(&self, child: Child, what: &'static str) -> Result<Block<'a>, ReadError> {
        let bytes = self.ogawa.data(child)?;
        let offset = match child {
            Child::Data(offset) | Child::Group(offset) => offset,
        };
        Ok(Block {
            bytes,
            at: 0,
            offset,
            what,
        })
    }

    fn read_time_samplings(&mut self, child: Child) -> Result<(), ReadError> {
        let mut block = self.block(child, "the time samplings")?;
        while !block.done() {
            let _max_sample = block.u32()?;
            let time_per_cycle = block.f64()?;
            let count = block.u32()? as usize;
            let left = block.bytes.len() - block.at;
            if count == 0 || count > left / 8 {
                return Err(error(
                    block.offset,
                    ReadErrorKind::CountMismatch,
                    format!("a time sampling of {count} times in {left} bytes"),
                ));
            }
            self.ogawa
                .budget
                .charge(count * 8, block.offset, "time samplings")?;
            let times = (0..count)
                .map(|_| block.f64())
                .collect::<Result<Vec<_>, _>>()?;
            self.time_samplings.push(TimeSampling {
                time_per_cycle,
                times,
            });
        }
        Ok(())
    }

    fn read_indexed_metadata(&mut self, child: Child) -> Result<(), ReadError> {
        let mut block = self.block(child, "the indexed metadata")?;
        while !block.done() {
            let size = u32::from(block.take(1)?[0]);
            self.ogawa
                .budget
                .charge(size as usize + 32, block.offset, "metadata")?;
            let text = block.text(size)?;
            self.indexed_metadata.push(text);
        }
        Ok(())
    }

    fn metadata(&self, index: u32, offset: u64) -> Result<String, ReadError> {
        self.indexed_metadata
            .get(index as usize)
            .cloned()
            .ok_or_else(|| {
                error(
                    offset,
                    ReadErrorKind::BadValue,
                    format!(
                        "metadata index {index} is past the {} indexed",
                        self.indexed_metadata.len()
                    ),
                )
            })
    }

    /// An object's children, from the headers in its group's last block.
    pub fn children(&self, object: Child) -> Result<Vec<Object>, ReadError> {
        let groups = self.ogawa.group(object)?;
        let Some(&last) = groups.last() else {
            return Ok(Vec::new());
        };
        if !matches!(last, Child::Data(_)) {
            return Ok(Vec::new());
        }
        let mut block = self.block(last, "the object headers")?;
        let hashes = 32.min(block.bytes.len());
        block.bytes = &block.bytes[..block.bytes.len() - hashes];
        let mut objects = Vec::new();
        while !block.done() {
            let name_size = block.u32()?;
            self.ogawa
                .budget
                .charge(name_size as usize + 64, block.offset, "object names")?;
            let name = block.text(name_size)?;
            let index = u32::from(block.take(1)?[0]);
            let metadata = if index == 0xff {
                let size = block.u32()?;
                self.ogawa
                    .budget
                    .charge(size as usize, block.offset, "metadata")?;
                block.text(size)?
            } else {
                self.metadata(index, block.offset)?
            };
            let group = groups
                .get(objects.len() + 1)
                .copied()
                .filter(|c| matches!(c, Child::Group(_)));
            let Some(group) = group else {
                return Err(error(
                    block.offset,
                    ReadErrorKind::CountMismatch,
                    format!("object {name:?} has a header but no group"),
                ));
            };
            objects.push(Object {
                name,
                metadata,
                group,
            });
        }
        Ok(objects)
    }

    /// An object's properties (its compound, the group's first child).
    pub fn object_properties(&self, object: Child) -> Result<Vec<Property>, ReadError> {
        match self.ogawa.group(object)?.first() {
            Some(&compound @ Child::Group(_)) => self.properties(compound),
            _ => Ok(Vec::new()),
        }
    }

    /// A compound property's properties, from the headers in its last
    /// block.
    pub fn properties(&self, compound: Child) -> Result<Vec<Property>, ReadError> {
        let groups = self.ogawa.group(compound)?;
        let Some(&last @ Child::Data(_)) = groups.last() else {
            return Ok(Vec::new());
        };
        let mut block = self.block(last, "the property headers")?;
        let mut properties = Vec::new();
        while !block.done() {
            let info = block.u32()?;
            let kind = match info & 3 {
                0 => Kind::Compound,
                1 => Kind::Scalar,
                _ => Kind::Array,
            };
            let hint = (info >> 2) & 3;
            let mut property = Property {
                name: String::new(),
                kind,
                pod: 0,
                extent: 0,
                metadata: String::new(),
                samples: 0,
                first_changed: 0,
                last_changed: 0,
                time_sampling: 0,
                group: Child::Group(0),
            };
            if kind != Kind::Compound {
                property.pod = ((info >> 4) & 0xf) as u8;
                if property.pod > pod::WSTRING {
                    return Err(error(
                        block.offset,
                        ReadErrorKind::BadValue,
                        format!("value type {} is not one of Alembic's", property.pod),
                    ));
                }
                property.extent = ((info >> 12) & 0xff) as u8;
                property.samples = block.hinted(hint)?;
                if info & 0x200 != 0 {
                    property.first_changed = block.hinted(hint)?;
                    property.last_changed = block.hinted(hint)?;
                } else if info & 0x800 == 0 {
                    property.first_changed = 1;
                    property.last_changed = property.samples.saturating_sub(1);
                }
                if info & 0x100 != 0 {
                    property.time_sampling = block.hinted(hint)?;
                }
            }
            let name_size = block.hinted(hint)?;
            self.ogawa
                .budget
                .charge(name_size as usize + 128, block.offset, "property names")?;
            property.name = block.text(name_size)?;
            let index = (info >> 20) & 0xff;
            property.metadata = if index == 0xff {
                let size = block.hinted(hint)?;
                self.ogawa
                    .budget
                    .charge(size as usize, block.offset, "metadata")?;
                block.text(size)?
            } else {
                self.metadata(index, block.offset)?
            };
            property.group = match groups.get(properties.len()) {
                Some(&child) if properties.len() + 1 < groups.len() => child,
                _ => {
                    return Err(error(
                        block.offset,
                        ReadErrorKind::CountMismatch,
                        format!("property {:?} has a header but no group", property.name),
                    ));
                }
            };
            properties.push(property);
        }
        Ok(properties)
    }

    /// The time sampling a property names.
    pub fn time_sampling(&self, property: &Property) -> Result<&TimeSampling, ReadError> {
        self.time_samplings
            .get(property.time_sampling as usize)
            .ok_or_else(|| {
                error(
                    0,
                    ReadErrorKind::BadValue,
                    format!(
                        "{} names time sampling {}, the archive has {}",
                        property.name,
                        property.time_sampling,
                        self.time_samplings.len()
                    ),
                )
            })
    }

    /// A property's stored samples (its group's children): read once per
    /// property, so reading every sample costs the file's size, not its
    /// square.
    pub fn stored(&self, property: &Property) -> Result<Vec<Child>, ReadError> {
        self.ogawa.group(property.group)
    }

    /// Sample `index`'s values (after the 16-byte key), and the offset of
    /// its data block; `stored` is [`Archive::stored`] of the property.
    pub fn sample(
        &self,
        property: &Property,
        stored: &[Child],
        index: u32,
    ) -> Result<(&'a [u8], u64), ReadError> {
        if index >= property.samples {
            return Err(error(
                0,
                ReadErrorKind::BadValue,
                format!(
                    "{} has {} samples, not {}",
                    property.name,
                    property.samples,
                    index + 1
                ),
            ));
        }
        let slot = if index < property.first_changed
            || (property.first_changed == 0 && property.last_changed == 0)
        {
            0
        } else if index >= property.last_changed {
            property.last_changed.saturating_sub(property.first_changed) + 1
        } else {
            index - property.first_changed + 1
        } as usize;
        let per_sample = if property.kind == Kind::Array { 2 } else { 1 };
        let child = stored.get(slot * per_sample).copied().ok_or_else(|| {
            error(
                0,
                ReadErrorKind::CountMismatch,
                format!("{}: stored sample {slot} is missing", property.name),
            )
        })?;
        let offset = match child {
            Child::Data(offset) | Child::Group(offset) => offset,
        };
        let data = self.ogawa.data(child)?;
        Ok((data.get(16..).unwrap_or(&[]), offset))
    }

    /// Sample `index` of a numeric property, every value as `f64`.
    pub fn numbers(&self, property: &Property, index: u32) -> Result<Vec<f64>, ReadError> {
        let stored = self.stored(property)?;
        self.numbers_in(property, &stored, index)
    }

    /// [`Archive::numbers`] with the property's stored samples at hand.
    pub fn numbers_in(
        &self,
        property: &Property,
        stored: &[Child],
        index: u32,
    ) -> Result<Vec<f64>, ReadError> {
        let (data, offset) = self.sample(property, stored, index)?;
        let size = match property.pod {
            pod::BOOL | pod::U8 | pod::I8 => 1,
            pod::U16 | pod::I16 | pod::F16 => 2,
            pod::U32 | pod::I32 | pod::F32 => 4,
            pod::U64 | pod::I64 | pod::F64 => 8,
            _ => {
                return Err(error(
                    offset,
                    ReadErrorKind::Unsupported,
                    format!("{} holds strings, not numbers", property.name),
                ));
            }
        };
        self.ogawa
            .budget
            .charge(data.len() / size * 8, offset, "a property's values")?;
        Ok(data
            .chunks_exact(size)
            .map(|c| match property.pod {
                pod::BOOL | pod::U8 => f64::from(c[0]),
                pod::I8 => f64::from(c[0] as i8),
                pod::U16 => f64::from(u16::from_le_bytes([c[0], c[1]])),
                pod::I16 => f64::from(i16::from_le_bytes([c[0], c[1]])),
                pod::F16 => f64::from(crate::usdc::values::half(u16::from_le_bytes([c[0], c[1]]))),
                pod::U32 => f64::from(u32::from_le_bytes([c[0], c[1], c[2], c[3]])),
                pod::I32 => f64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]])),
                pod::F32 => f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])),
                _ => {
                    let mut word = [0; 8];
                    word.copy_from_slice(c);
                    match property.pod {
                        pod::U64 => u64::from_le_bytes(word) as f64,
                        pod::I64 => i64::from_le_bytes(word) as f64,
                        _ => f64::from_le_bytes(word),
                    }
                }
            })
            .collect())
    }
}

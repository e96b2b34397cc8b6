//! USD packages (`.usdz`): a zip archive, stored without compression,
//! whose first file is the layer (a `.usdc` or `.usda`), the rest its
//! assets (textures), each file's data starting on a 64-byte boundary so
//! it can be mapped in place.
//!
//! # How it works
//!
//! Reading takes the first local file header (`PK\x03\x04` at byte 0):
//! method 0 (stored) is required, as USD requires; the name says which
//! reader gets the data, and errors from it are moved to the package's
//! byte offsets. Writing makes a one-file archive: local header (its extra
//! field padded so the data starts at byte 64), the layer, the central
//! directory and its end record, with the CRC-32 zip readers check.

use std::io::Write;

use crate::animation::Animation;
use crate::curve_set::CurveSet;
use crate::error::{Location, ReadError, ReadErrorKind, WriteError};
use crate::format::Format;
use crate::imported::Imported;
use crate::mesh::{MeshPose, TriangleMesh};
use crate::options::ReadOptions;
use crate::{usda, usdc};

const LOCAL_HEADER: u32 = 0x0403_4b50;
const CENTRAL_HEADER: u32 = 0x0201_4b50;
const END_RECORD: u32 = 0x0605_4b50;
/// Where the layer's data starts in a written package.
const DATA_OFFSET: usize = 64;
/// The layer's name inside a written package.
const LAYER_NAME: &[u8] = b"hair.usdc";

fn error(offset: u64, kind: ReadErrorKind, message: impl Into<String>) -> ReadError {
    ReadError::new(Format::Usdz, Location::Byte(offset), kind, message)
}

fn u16_at(bytes: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(bytes.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?))
}

/// Reads a package's first layer.
pub fn read_usdz(bytes: &[u8], options: &ReadOptions) -> Result<Imported, ReadError> {
    if u32_at(bytes, 0) != Some(LOCAL_HEADER) {
        return Err(error(
            0,
            ReadErrorKind::BadMagic,
            "a usdz package is a zip archive, starting with \"PK\\x03\\x04\"",
        ));
    }
    let truncated = || {
        error(
            bytes.len() as u64,
            ReadErrorKind::Truncated,
            "the first file's header is cut off",
        )
    };
    let flags = u16_at(bytes, 6).ok_or_else(truncated)?;
    let method = u16_at(bytes, 8).ok_or_else(truncated)?;
    let size = u32_at(bytes, 18).ok_or_else(truncated)? as usize;
    let name_len = usize::from(u16_at(bytes, 26).ok_or_else(truncated)?);
    let extra_len = usize::from(u16_at(bytes, 28).ok_or_else(truncated)?);
    if method != 0 {
        return Err(error(
            8,
            ReadErrorKind::Unsupported,
            format!(
                "the layer is compressed (zip method {method}); USD packages store files uncompressed"
            ),
        ));
    }
    if flags & 1 != 0 {
        return Err(error(
            6,
            ReadErrorKind::Unsupported,
            "the layer is encrypted",
        ));
    }
    let name_start = 30usize;
    let name = bytes
        .get(name_start..name_start + name_len)
        .ok_or_else(truncated)?;
    let start = name_start + name_len + extra_len;
    let data = start
        .checked_add(size)
        .and_then(|end| bytes.get(start..end))
        .ok_or_else(|| {
            error(
                18,
                ReadErrorKind::Truncated,
                format!(
                    "the first file's {size} bytes from byte {start} run past the end at byte {}",
                    bytes.len()
                ),
            )
        })?;
    let name = String::from_utf8_lossy(name).to_ascii_lowercase();
    let result = if name.ends_with(".usda") {
        usda::read_usda(data, options)
    } else if name.ends_with(".usdc") || name.ends_with(".usd") {
        usdc::read_usdc(data, options)
    } else {
        return Err(error(
            30,
            ReadErrorKind::Unsupported,
            format!(
                "the package's first file, {:?}, is not a USD layer",
                crate::warnings::short(&name)
            ),
        ));
    };
    result.map_err(|mut inner| {
        if let Location::Byte(offset) = inner.location {
            inner.location = Location::Byte(offset + start as u64);
        }
        inner.message = format!("in {}: {}", inner.format, inner.message);
        inner.format = Format::Usdz;
        inner
    })
}

/// Writes a package holding one crate layer: what [`usdc::write::write_usdc`]
/// writes for the same arguments.
pub fn write_usdz(
    out: &mut impl Write,
    curves: &CurveSet,
    animation: Option<&Animation>,
    head: Option<&TriangleMesh>,
    head_poses: &[MeshPose],
) -> Result<(), WriteError> {
    let mut layer = Vec::new();
    usdc::write::write_usdc(&mut layer, curves, animation, head, head_poses).map_err(
        |e| match e {
            WriteError::Invalid { message, .. } => WriteError::invalid(Format::Usdz, message),
            WriteError::Io { source, .. } => WriteError::Io {
                format: Format::Usdz,
                source,
            },
        },
    )?;
    let size = u32::try_from(layer.len()).map_err(|_| {
        WriteError::invalid(Format::Usdz, "the layer is over 4 GB, past zip's limit")
    })?;
    let crc = crc32(&layer);
    let extra_len = DATA_OFFSET - 30 - LAYER_NAME.len();
    let mut bytes = Vec::with_capacity(layer.len() + 256);
    let header = |bytes: &mut Vec<u8>, central: bool, extra: usize| {
        let signature = if central {
            CENTRAL_HEADER
        } else {
            LOCAL_HEADER
        };
        bytes.extend_from_slice(&signature.to_le_bytes());
        if central {
            bytes.extend_from_slice(&20u16.to_le_bytes()); // made by
        }
        for half in [20u16, 0, 0, 0, 0x21] {
            // version needed, flags, method (stored), time, date (1980-01-01)
            bytes.extend_from_slice(&half.to_le_bytes());
        }
        for word in [crc, size, size] {
            bytes.extend_from_slice(&word.to_le_bytes());
        }
        bytes.extend_from_slice(&(LAYER_NAME.len() as u16).to_le_bytes());
        bytes.extend_from_slice(&(extra as u16).to_le_bytes());
        if central {
            // comment length, disk, internal and external attributes, offset
            for half in [0u16, 0, 0] {
                bytes.extend_from_slice(&half.to_le_bytes());
            }
            bytes.extend_from_slice(&0u32.to_le_bytes());
            bytes.extend_from_slice(&0u32.to_le_bytes());
        }
        bytes.extend_from_slice(LAYER_NAME);
    };
    header(&mut bytes, false, extra_len);
    // Padding in an extra field of unknown id, as USD's own writer does.
    bytes.extend_from_slice(&0x1986u16.to_le_bytes());
    bytes.extend_from_slice(&((extra_len - 4) as u16).to_le_bytes());
    bytes.resize(DATA_OFFSET, 0);
    bytes.extend_from_slice(&layer);
    let central_start = bytes.len();
    header(&mut bytes, true, 0);
    let central_size = bytes.len() - central_start;
    bytes.extend_from_slice(&END_RECORD.to_le_bytes());
    for half in [0u16, 0, 1, 1] {
        bytes.extend_from_slice(&half.to_le_bytes());
    }
    let too_big =
        || WriteError::invalid(Format::Usdz, "the package is over 4 GB, past zip's limit");
    bytes.extend_from_slice(
        &u32::try_from(central_size)
            .map_err(|_| too_big())?
            .to_le_bytes(),
    );
    bytes.extend_from_slice(
        &u32::try_from(central_start)
            .map_err(|_| too_big())?
            .to_le_bytes(),
    );
    bytes.extend_from_slice(&0u16.to_le_bytes());
    out.write_all(&bytes).map_err(WriteError::io(Format::Usdz))
}

/// The CRC-32 (IEEE) zip stores for each file.
fn crc32(data: &[u8]) -> u32 {
    let mut table = [0u32; 256];
    for (n, entry) in table.iter_mut().enumerate() {
        let mut c = n as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
        *entry = c;
    }
    !data.iter().fold(!0u32, |c, &b| {
        table[((c ^ u32::from(b)) & 0xFF) as usize] ^ (c >> 8)
    })
}

#[cfg(test)]
mod tests {
    use super::crc32;

    #[test]
    fn crc32_matches_the_standard_check_value() {
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }
}

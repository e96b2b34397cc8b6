//! Malformed TressFX files: each gives its own error, located, and nothing
//! is allocated for counts the file cannot hold.

use crate::common;

use common::{expect_error, put_u32, valid_file};
use helixhair_formats::{Format, Location, ReadErrorKind, ReadOptions, RepairReason, read};

fn read_tfx(bytes: &[u8]) -> Result<helixhair_formats::Imported, helixhair_formats::ReadError> {
    read(bytes, Format::Tfx, &ReadOptions::default())
}

#[test]
fn truncated_header_and_truncated_positions() {
    let bytes = valid_file(Format::Tfx);
    expect_error(
        read_tfx(&bytes[..2]),
        ReadErrorKind::Truncated,
        Location::Byte(0),
    );
    expect_error(
        read_tfx(&bytes[..100]),
        ReadErrorKind::Truncated,
        Location::Byte(0),
    );
    // 20 strands × 8 points × 16 bytes of positions from byte 160 to 2720;
    // cut in them.
    let error = expect_error(
        read_tfx(&bytes[..2600]),
        ReadErrorKind::Truncated,
        Location::Byte(2600),
    );
    assert!(
        error.message.contains("positions of 20 strands × 8 points"),
        "{error}"
    );
}

#[test]
fn wrong_version_is_refused() {
    let mut bytes = valid_file(Format::Tfx);
    bytes[..4].copy_from_slice(&7.0f32.to_le_bytes());
    expect_error(
        read_tfx(&bytes),
        ReadErrorKind::UnsupportedVersion,
        Location::Byte(0),
    );
    bytes[..4].copy_from_slice(b"HAIR");
    expect_error(
        read_tfx(&bytes),
        ReadErrorKind::UnsupportedVersion,
        Location::Byte(0),
    );
    bytes[..4].copy_from_slice(&f32::NAN.to_le_bytes());
    expect_error(
        read_tfx(&bytes),
        ReadErrorKind::UnsupportedVersion,
        Location::Byte(0),
    );
}

#[test]
fn wrong_counts_are_refused() {
    let valid = valid_file(Format::Tfx);
    // One strand more than the positions hold: the colours follow the
    // positions, so the positions still fit and the colours run off the end.
    let mut bytes = valid.clone();
    put_u32(&mut bytes, 4, 21);
    expect_error(
        read_tfx(&bytes),
        ReadErrorKind::Truncated,
        Location::Byte(valid.len() as u64),
    );
    // Points per strand doubled: the colours need more than the whole file.
    let mut bytes = valid.clone();
    put_u32(&mut bytes, 8, 16);
    expect_error(
        read_tfx(&bytes),
        ReadErrorKind::Truncated,
        Location::Byte(valid.len() as u64),
    );
    // A positions offset inside the header.
    let mut bytes = valid;
    put_u32(&mut bytes, 12, 20);
    expect_error(
        read_tfx(&bytes),
        ReadErrorKind::BadValue,
        Location::Byte(12),
    );
}

#[test]
fn absurd_sizes_allocate_nothing() {
    let mut bytes = valid_file(Format::Tfx);
    put_u32(&mut bytes, 4, u32::MAX);
    put_u32(&mut bytes, 8, u32::MAX);
    let error = expect_error(
        read_tfx(&bytes),
        ReadErrorKind::TooLarge,
        Location::Byte(12),
    );
    assert!(
        error
            .message
            .contains("4294967295 strands × 4294967295 points"),
        "{error}"
    );
}

#[test]
fn nan_points_skip_their_strand_only() {
    let mut bytes = valid_file(Format::Tfx);
    // Strand 3, point 5, y.
    let offset = 160 + (3 * 8 + 5) * 16 + 4;
    bytes[offset..offset + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let groom = read_tfx(&bytes).expect("reads");
    assert_eq!(groom.summary.strands_read, 20);
    assert_eq!(groom.summary.strands_kept, 19);
    assert_eq!(groom.summary.count(RepairReason::NonFinitePoint), 1);
}

#[test]
fn tressfx_3_layout_reads() {
    // A 3.x file by hand: 2 strands × 4 points of f32 × 3 after the
    // 296-byte header, no other arrays.
    let mut bytes = vec![0u8; 296];
    bytes[..4].copy_from_slice(&3.0f32.to_le_bytes());
    put_u32(&mut bytes, 4, 2);
    put_u32(&mut bytes, 8, 4);
    put_u32(&mut bytes, 144, 296);
    for strand in 0..2 {
        for point in 0..4 {
            for value in [strand as f32, 1.0 - 0.1 * point as f32, 0.5] {
                bytes.extend_from_slice(&value.to_le_bytes());
            }
        }
    }
    let groom = read_tfx(&bytes).expect("reads");
    assert_eq!(groom.curves.curves.len(), 2);
    assert_eq!(
        groom.curves.curves[1].points_m[3],
        glam::Vec3::new(1.0, 1.0 - 0.1 * 3.0, 0.5)
    );
    // Cut: the positions run off the end.
    expect_error(
        read_tfx(&bytes[..300]),
        ReadErrorKind::Truncated,
        Location::Byte(300),
    );
}

/// Regression (found by fuzzing): a 3.x header asking for 2 million strands
/// of 0 points passed every size check (they take no bytes) and made the
/// reader allocate 160 MB of empty strands from a 400-byte file.
#[test]
fn zero_points_per_strand_allocates_nothing() {
    let mut bytes = vec![0u8; 400];
    bytes[..4].copy_from_slice(&3.0f32.to_le_bytes());
    put_u32(&mut bytes, 4, 0x0020_0002);
    put_u32(&mut bytes, 144, 296);
    expect_error(read_tfx(&bytes), ReadErrorKind::BadValue, Location::Byte(8));
}

//! Malformed `.hair` files: each gives its own error, located, and nothing
//! is allocated for counts the file cannot hold.

use crate::common;

use common::{expect_error, put_u32, valid_file};
use helixhair_formats::{Format, Location, ReadErrorKind, ReadOptions, RepairReason, read};

fn read_hair(bytes: &[u8]) -> Result<helixhair_formats::Imported, helixhair_formats::ReadError> {
    read(bytes, Format::Hair, &ReadOptions::default())
}

#[test]
fn wrong_magic_is_refused() {
    let mut bytes = valid_file(Format::Hair);
    bytes[3] = b'X';
    expect_error(
        read_hair(&bytes),
        ReadErrorKind::BadMagic,
        Location::Byte(0),
    );
    expect_error(read_hair(b""), ReadErrorKind::BadMagic, Location::Byte(0));
}

#[test]
fn truncated_files_say_where_they_end() {
    let bytes = valid_file(Format::Hair);
    expect_error(
        read_hair(&bytes[..64]),
        ReadErrorKind::Truncated,
        Location::Byte(0),
    );
    // Segments (40 bytes) then points from byte 168 to 2088: cut inside the
    // points.
    expect_error(
        read_hair(&bytes[..2000]),
        ReadErrorKind::Truncated,
        Location::Byte(2000),
    );
    // Cut so short that the points alone are longer than the file: the
    // counts cannot be right for this file.
    expect_error(
        read_hair(&bytes[..500]),
        ReadErrorKind::TooLarge,
        Location::Byte(8),
    );
}

#[test]
fn wrong_counts_are_refused() {
    let valid = valid_file(Format::Hair);
    // One point fewer in the header: the arrays (points, thickness,
    // colours: 28 bytes a point) end before the file does.
    let mut bytes = valid.clone();
    put_u32(&mut bytes, 8, 159);
    expect_error(
        read_hair(&bytes),
        ReadErrorKind::CountMismatch,
        Location::Byte(valid.len() as u64 - 28),
    );
    // A strand's segment count off by one: the segments no longer add up.
    let mut bytes = valid.clone();
    bytes[128] += 1;
    expect_error(
        read_hair(&bytes),
        ReadErrorKind::CountMismatch,
        Location::Byte(128),
    );
    // No segments array and default segments that do not fit the points.
    let mut bytes = valid;
    put_u32(&mut bytes, 12, 2); // points only
    bytes.drain(128..168);
    bytes.truncate(128 + 160 * 12);
    put_u32(&mut bytes, 16, 8);
    expect_error(
        read_hair(&bytes),
        ReadErrorKind::CountMismatch,
        Location::Byte(16),
    );
    put_u32(&mut bytes, 16, 7); // 20 × (7 + 1) = 160: right
    assert_eq!(read_hair(&bytes).expect("reads").curves.curves.len(), 20);
}

#[test]
fn a_file_without_points_is_refused() {
    let mut bytes = valid_file(Format::Hair);
    put_u32(&mut bytes, 12, 1);
    expect_error(
        read_hair(&bytes),
        ReadErrorKind::Unsupported,
        Location::Byte(12),
    );
}

#[test]
fn absurd_sizes_allocate_nothing() {
    let mut bytes = valid_file(Format::Hair);
    put_u32(&mut bytes, 4, u32::MAX);
    put_u32(&mut bytes, 8, u32::MAX);
    put_u32(&mut bytes, 12, 31);
    let error = expect_error(
        read_hair(&bytes),
        ReadErrorKind::TooLarge,
        Location::Byte(4),
    );
    println!("{error}");
    put_u32(&mut bytes, 4, 1);
    expect_error(
        read_hair(&bytes),
        ReadErrorKind::TooLarge,
        Location::Byte(8),
    );
}

#[test]
fn nan_points_skip_their_strand_only() {
    let mut bytes = valid_file(Format::Hair);
    // Strand 7, point 2, z: points start after 40 bytes of segments.
    let offset = 168 + (7 * 8 + 2) * 12 + 8;
    bytes[offset..offset + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    let groom = read_hair(&bytes).expect("reads");
    assert_eq!(groom.summary.strands_kept, 19);
    assert_eq!(groom.summary.count(RepairReason::NonFinitePoint), 1);
}

//! Malformed binary USD (crate files and packages) gives located errors:
//! no count, offset or compressed size in a file can make the reader
//! panic, loop, or allocate beyond its budget. The seeded mutations run
//! over a crate file Pixar's library wrote (compressed int and float
//! arrays, lookup tables, time samples), beside `mutation.rs`'s runs over
//! the files this crate writes.

use crate::common;

use std::panic::{AssertUnwindSafe, catch_unwind};

use common::{Rng, expect_error, fixture, valid_file};
use helixhair_formats::{Format, Location, ReadErrorKind, ReadOptions, read};

fn read_usdc(bytes: &[u8]) -> Result<helixhair_formats::Imported, helixhair_formats::ReadError> {
    read(bytes, Format::Usdc, &ReadOptions::default())
}

#[test]
fn wrong_magic_old_versions_and_a_lost_table_of_contents_are_refused() {
    expect_error(
        read_usdc(b"PXR-USDA and more"),
        ReadErrorKind::BadMagic,
        Location::Byte(0),
    );
    expect_error(read_usdc(b""), ReadErrorKind::BadMagic, Location::Byte(0));
    let mut old = fixture("pxr_groom.usdc");
    old[9] = 3;
    expect_error(
        read_usdc(&old),
        ReadErrorKind::UnsupportedVersion,
        Location::Byte(8),
    );
    let mut lost = fixture("pxr_groom.usdc");
    lost[16..24].copy_from_slice(&u64::MAX.to_le_bytes());
    let error = read_usdc(&lost).expect_err("the table of contents is past the end");
    assert_eq!(error.kind, ReadErrorKind::Truncated, "{error}");
    // The text reader names the binary it cannot read.
    let error = read(
        &fixture("pxr_groom.usdc"),
        Format::Usda,
        &ReadOptions::default(),
    )
    .expect_err("binary is not text");
    assert!(error.message.contains(".usdc"), "{error}");
}

#[test]
fn every_truncation_is_an_error() {
    for valid in [fixture("pxr_groom.usdc"), valid_file(Format::Usdc)] {
        for cut in 0..valid.len() {
            let result = catch_unwind(|| read_usdc(&valid[..cut]));
            match result {
                Ok(Err(_)) => {}
                Ok(Ok(_)) => panic!("a file cut at byte {cut} of {} read", valid.len()),
                Err(_) => panic!("a file cut at byte {cut} panicked"),
            }
        }
    }
}

#[test]
fn absurd_counts_allocate_nothing() {
    let valid = valid_file(Format::Usdc);
    // The table of contents' section count, then each section's first
    // count, set to 2^64 − 1 and 2^40.
    let toc = u64::from_le_bytes(valid[16..24].try_into().expect("8 bytes")) as usize;
    let mut at = vec![toc];
    let sections = u64::from_le_bytes(valid[toc..toc + 8].try_into().expect("8 bytes")) as usize;
    for index in 0..sections {
        let entry = toc + 8 + 32 * index;
        at.push(
            u64::from_le_bytes(valid[entry + 16..entry + 24].try_into().expect("8 bytes")) as usize,
        );
    }
    for offset in at {
        for value in [u64::MAX, 1 << 40] {
            let mut bytes = valid.clone();
            bytes[offset..offset + 8].copy_from_slice(&value.to_le_bytes());
            let error = read_usdc(&bytes).expect_err("an absurd count is refused");
            println!("{error}");
            assert!(
                matches!(
                    error.kind,
                    ReadErrorKind::TooLarge
                        | ReadErrorKind::Truncated
                        | ReadErrorKind::CountMismatch
                ),
                "{error}"
            );
        }
    }
}

#[test]
fn packages_must_store_a_usd_layer_first() {
    let valid = valid_file(Format::Usdz);
    let mut deflated = valid.clone();
    deflated[8] = 8;
    expect_error(
        read(&deflated, Format::Usdz, &ReadOptions::default()),
        ReadErrorKind::Unsupported,
        Location::Byte(8),
    );
    let mut renamed = valid.clone();
    renamed[30..39].copy_from_slice(b"hair.png\0");
    expect_error(
        read(&renamed, Format::Usdz, &ReadOptions::default()),
        ReadErrorKind::Unsupported,
        Location::Byte(30),
    );
    // An error inside the layer is placed in the package.
    let mut broken = valid.clone();
    broken[64..72].copy_from_slice(b"PXR-USDX");
    expect_error(
        read(&broken, Format::Usdz, &ReadOptions::default()),
        ReadErrorKind::BadMagic,
        Location::Byte(64),
    );
}

#[test]
fn pixars_crate_file_survives_mutation() {
    let valid = fixture("pxr_groom.usdc");
    let mut rng = Rng::new(0x0C5);
    let (mut ok, mut errors) = (0, 0);
    for case in 0..4000 {
        let mut bytes = valid.clone();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(bytes.len());
            match rng.below(4) {
                0 => bytes[at] ^= 1 << rng.below(8),
                1 => bytes[at] = rng.next_u64() as u8,
                2 => {
                    // A word set to an edge value (counts, offsets, reps).
                    let edges = [0u64, 1, u64::MAX, 1 << 32, 1 << 48, 0x7FFF_FFFF];
                    let at = at.min(bytes.len().saturating_sub(8));
                    let value = edges[rng.below(edges.len())];
                    if let Some(word) = bytes.get_mut(at..at + 8) {
                        word.copy_from_slice(&value.to_le_bytes());
                    }
                }
                _ => bytes.truncate(at.max(1)),
            }
        }
        match catch_unwind(AssertUnwindSafe(|| read_usdc(&bytes))) {
            Ok(Ok(imported)) => {
                ok += 1;
                assert!(imported.points_held() <= bytes.len(), "case {case}");
            }
            Ok(Err(_)) => errors += 1,
            Err(_) => {
                let path = format!(
                    "{}/../../target/mutation-failure.pxr.usdc",
                    env!("CARGO_MANIFEST_DIR")
                );
                let _ = std::fs::write(&path, &bytes);
                panic!("case {case} panicked; input written to {path}");
            }
        }
    }
    println!("pxr's usdc: 4000 mutated files, {ok} read, {errors} refused, no panic");
    assert!(ok > 0 && errors > 0);
}

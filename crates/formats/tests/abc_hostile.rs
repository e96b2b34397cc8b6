//! Malformed Alembic archives give located errors: no count, offset or
//! group cycle in a file can make the reader panic, recurse without end
//! or allocate beyond its budget. The seeded mutations run over an
//! archive the Alembic library wrote (transforms, indexed widths), beside
//! `mutation.rs`'s run over the archives this crate writes.

use crate::common;

use std::panic::{AssertUnwindSafe, catch_unwind};

use common::{Rng, expect_error, fixture, valid_file};
use helixhair_formats::{Format, Location, ReadErrorKind, ReadOptions, read};

fn read_abc(bytes: &[u8]) -> Result<helixhair_formats::Imported, helixhair_formats::ReadError> {
    read(bytes, Format::Abc, &ReadOptions::default())
}

#[test]
fn wrong_magic_hdf5_unfinished_files_and_other_versions_are_refused() {
    expect_error(
        read_abc(b"Ogaw"),
        ReadErrorKind::BadMagic,
        Location::Byte(0),
    );
    let error = expect_error(
        read_abc(b"\x89HDF\r\n\x1a\n and the rest"),
        ReadErrorKind::BadMagic,
        Location::Byte(0),
    );
    assert!(error.message.contains("HDF5"), "{error}");
    let mut open = fixture("alembic3d_groom.abc");
    open[5] = 0;
    expect_error(read_abc(&open), ReadErrorKind::Truncated, Location::Byte(5));
    let mut version = fixture("alembic3d_groom.abc");
    version[7] = 2;
    expect_error(
        read_abc(&version),
        ReadErrorKind::UnsupportedVersion,
        Location::Byte(6),
    );
}

#[test]
fn every_truncation_is_an_error() {
    for valid in [fixture("alembic3d_groom.abc"), valid_file(Format::Abc)] {
        for cut in 0..valid.len() {
            match catch_unwind(|| read_abc(&valid[..cut])) {
                Ok(Err(_)) => {}
                Ok(Ok(_)) => panic!("a file cut at byte {cut} of {} read", valid.len()),
                Err(_) => panic!("a file cut at byte {cut} panicked"),
            }
        }
    }
}

#[test]
fn absurd_counts_and_group_cycles_are_refused() {
    let valid = valid_file(Format::Abc);
    let root = u64::from_le_bytes(valid[8..16].try_into().expect("8 bytes")) as usize;
    // The root group's child count.
    for value in [u64::MAX, 1 << 40] {
        let mut bytes = valid.clone();
        bytes[root..root + 8].copy_from_slice(&value.to_le_bytes());
        let error = read_abc(&bytes).expect_err("refused");
        println!("{error}");
        assert_eq!(error.kind, ReadErrorKind::TooLarge, "{error}");
    }
    // The top object's group made its own first child object: a cycle.
    let top = u64::from_le_bytes(valid[root + 24..root + 32].try_into().expect("8 bytes"));
    let mut cycle = valid.clone();
    let at = top as usize + 16;
    cycle[at..at + 8].copy_from_slice(&top.to_le_bytes());
    let error = read_abc(&cycle).expect_err("refused");
    println!("{error}");
}

#[test]
fn alembics_own_archive_survives_mutation() {
    let valid = fixture("alembic3d_groom.abc");
    let mut rng = Rng::new(0xABC);
    let (mut ok, mut errors) = (0, 0);
    for case in 0..4000 {
        let mut bytes = valid.clone();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(bytes.len());
            match rng.below(4) {
                0 => bytes[at] ^= 1 << rng.below(8),
                1 => bytes[at] = rng.next_u64() as u8,
                2 => {
                    // A word set to an edge value (offsets, counts, sizes).
                    let edges = [0u64, 1, u64::MAX, 1 << 63, 1 << 32, 0x7FFF_FFFF];
                    let at = at.min(bytes.len().saturating_sub(8));
                    let value = edges[rng.below(edges.len())];
                    if let Some(word) = bytes.get_mut(at..at + 8) {
                        word.copy_from_slice(&value.to_le_bytes());
                    }
                }
                _ => bytes.truncate(at.max(1)),
            }
        }
        match catch_unwind(AssertUnwindSafe(|| read_abc(&bytes))) {
            Ok(Ok(imported)) => {
                ok += 1;
                assert!(imported.points_held() <= bytes.len(), "case {case}");
            }
            Ok(Err(_)) => errors += 1,
            Err(_) => {
                let path = format!(
                    "{}/../../target/mutation-failure.alembic3d.abc",
                    env!("CARGO_MANIFEST_DIR")
                );
                let _ = std::fs::write(&path, &bytes);
                panic!("case {case} panicked; input written to {path}");
            }
        }
    }
    println!("alembic3d's abc: 4000 mutated files, {ok} read, {errors} refused, no panic");
    assert!(ok > 0 && errors > 0);
}

/// Found by the fuzzer: curve counts whose sum passes `usize::MAX / 3`
/// (their sum saturates) made the point count check overflow.
#[test]
fn counts_past_any_point_count_are_an_error() {
    let bytes = fixture("abc_counts_overflow.abc");
    let error = read_abc(&bytes).expect_err("refused");
    println!("{error}");
}

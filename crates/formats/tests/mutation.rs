//! Seeded mutation of valid files, per reader: thousands of files with
//! bytes flipped, overwritten, inserted, deleted, duplicated or cut, and
//! header words set to edge values. No reader may panic, and what a reader
//! returns must stay within the file's size (no count in a file may make
//! it allocate beyond the bound of `read`'s docs).
//!
//! Deterministic (fixed seeds); a failure prints the seed and case and
//! writes the input to `target/mutation-failure.<format>` to replay.

use crate::common;

use std::panic::{AssertUnwindSafe, catch_unwind};

use common::{Rng, valid_file};
use helixhair_formats::{Format, ReadOptions, read};

/// Mutated files per format.
const CASES: usize = 6_000;

/// Edge values for 32-bit header words.
const EDGE_WORDS: [u32; 8] = [
    0,
    1,
    2,
    0x7FFF_FFFF,
    0x8000_0000,
    u32::MAX,
    160,
    0x4080_0000,
];

fn mutate(rng: &mut Rng, valid: &[u8], binary: bool) -> Vec<u8> {
    let mut bytes = valid.to_vec();
    for _ in 0..1 + rng.below(4) {
        let len = bytes.len().max(1);
        match rng.below(if binary { 8 } else { 7 }) {
            0 => {
                let at = rng.below(len);
                if let Some(byte) = bytes.get_mut(at) {
                    *byte ^= 1 << rng.below(8);
                }
            }
            1 => {
                let at = rng.below(len);
                if let Some(byte) = bytes.get_mut(at) {
                    *byte = rng.next_u64() as u8;
                }
            }
            2 => {
                let at = rng.below(len + 1).min(bytes.len());
                let text_bytes = b"()[]{}\",:=-.e0123456789#\n <>@";
                let byte = if binary {
                    rng.next_u64() as u8
                } else {
                    text_bytes[rng.below(text_bytes.len())]
                };
                bytes.insert(at, byte);
            }
            3 => {
                let at = rng.below(len).min(bytes.len());
                let end = (at + 1 + rng.below(16)).min(bytes.len());
                bytes.drain(at..end);
            }
            4 => {
                let at = rng.below(len).min(bytes.len());
                let end = (at + 1 + rng.below(64)).min(bytes.len());
                let chunk = bytes[at..end].to_vec();
                let to = rng.below(bytes.len() + 1);
                bytes.splice(to..to, chunk);
            }
            5 => bytes.truncate(rng.below(len)),
            6 => {
                // Repeat a chunk many times (long arrays, deep nesting).
                let at = rng.below(len).min(bytes.len());
                let end = (at + 1 + rng.below(4)).min(bytes.len());
                let chunk = bytes[at..end].repeat(1 + rng.below(200));
                bytes.splice(at..at, chunk);
            }
            _ => {
                // A header word (first 300 bytes) set to an edge value.
                let word = rng.below(75) * 4;
                if word + 4 <= bytes.len() {
                    let value = EDGE_WORDS[rng.below(EDGE_WORDS.len())];
                    bytes[word..word + 4].copy_from_slice(&value.to_le_bytes());
                }
            }
        }
    }
    bytes
}

fn mutation_run(format: Format, seed: u64) {
    let valid = valid_file(format);
    let binary = matches!(
        format,
        Format::Tfx | Format::Hair | Format::Usdc | Format::Usdz | Format::Abc
    );
    let mut rng = Rng::new(seed);
    let (mut ok, mut errors) = (0, 0);
    for case in 0..CASES {
        let bytes = mutate(&mut rng, &valid, binary);
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            read(&bytes, format, &ReadOptions::default())
        }));
        match outcome {
            Ok(Ok(imported)) => {
                ok += 1;
                let points = imported.points_held();
                assert!(
                    points <= bytes.len(),
                    "{format} seed {seed} case {case}: {points} points out of {} bytes",
                    bytes.len()
                );
            }
            Ok(Err(_)) => errors += 1,
            Err(_) => {
                let path = format!(
                    "{}/../../target/mutation-failure.{format}",
                    env!("CARGO_MANIFEST_DIR")
                );
                let _ = std::fs::write(&path, &bytes);
                panic!(
                    "{format} reader panicked: seed {seed} case {case}; input written to {path}"
                );
            }
        }
    }
    println!(
        "{format}: {CASES} mutated files, {ok} read, {errors} refused with an error, no panic"
    );
    assert!(
        ok > 0 && errors > 0,
        "the mutations should reach both outcomes"
    );
}

#[test]
fn tfx_reader_survives_mutation() {
    mutation_run(Format::Tfx, 0x7F0);
}

#[test]
fn hair_reader_survives_mutation() {
    mutation_run(Format::Hair, 0x4A1);
}

#[test]
fn usda_reader_survives_mutation() {
    mutation_run(Format::Usda, 0x05D);
}

#[test]
fn obj_reader_survives_mutation() {
    mutation_run(Format::Obj, 0x0B1);
}

#[test]
fn usdc_reader_survives_mutation() {
    mutation_run(Format::Usdc, 0x05C);
}

#[test]
fn usdz_reader_survives_mutation() {
    mutation_run(Format::Usdz, 0x05E);
}

#[test]
fn abc_reader_survives_mutation() {
    mutation_run(Format::Abc, 0x0AB);
}

//! Shared helpers of the format tests: a seeded generator, small grooms,
//! and the Sintel data's place.

#![allow(dead_code)] // each test file uses a different part

use std::path::PathBuf;

use glam::Vec3;
use helixhair_formats::{Curve, CurveSet, StrandValue};

/// SplitMix64: a small seeded generator, the same on every machine.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        let unit = (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        lo + (hi - lo) * unit
    }
}

/// A small groom: `strands` wavy strands of `points` points hanging from a
/// head-sized sphere, with per-point widths and per-strand colours when
/// asked.
pub fn groom(seed: u64, strands: usize, points: usize, widths: bool, colours: bool) -> CurveSet {
    let mut rng = Rng::new(seed);
    let curves = (0..strands)
        .map(|_| {
            let root = Vec3::new(
                rng.range(-0.1, 0.1),
                rng.range(1.5, 1.7),
                rng.range(-0.1, 0.1),
            );
            let step_m = rng.range(0.005, 0.02);
            let phase = rng.range(0.0, 6.0);
            let points_m = (0..points)
                .map(|i| {
                    let t = i as f32;
                    root + Vec3::new(
                        0.01 * (t + phase).sin(),
                        -step_m * t,
                        0.01 * (t + phase).cos(),
                    )
                })
                .collect::<Vec<_>>();
            let width_m = widths.then(|| {
                StrandValue::PerPoint(
                    (0..points)
                        .map(|i| 8e-5 * (1.0 - i as f32 / (2 * points) as f32))
                        .collect(),
                )
            });
            let colour = colours.then(|| {
                StrandValue::PerStrand([
                    rng.range(0.0, 1.0),
                    rng.range(0.0, 1.0),
                    rng.range(0.0, 1.0),
                ])
            });
            Curve {
                points_m,
                width_m,
                colour,
            }
        })
        .collect();
    CurveSet::new(curves)
}

/// The Sintel data folder, `../shared/data/sintel` from the repository.
pub fn sintel_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/sintel")
}

/// The Sintel groom's bytes, or `None` after printing why the test skips.
pub fn sintel_tfx() -> Option<Vec<u8>> {
    let path = sintel_dir().join("sintel_hair.16points.tfx");
    let bytes = std::fs::read(&path).ok();
    if bytes.is_none() {
        println!(
            "SKIPPED: {} is absent (the Sintel data lives in ../shared)",
            path.display()
        );
    }
    bytes
}

/// Asserts two point lists are equal to the bit.
pub fn assert_points_equal(read: &[Vec3], written: &[Vec3], what: &str) {
    assert_eq!(read.len(), written.len(), "{what}: point counts");
    for (index, (a, b)) in read.iter().zip(written).enumerate() {
        assert_eq!(a, b, "{what}: point {index}");
    }
}

/// A valid file of each format, from [`groom`] (20 strands × 8 points,
/// with widths and colours where the format holds them; the USD and
/// Alembic ones with three time samples).
pub fn valid_file(format: helixhair_formats::Format) -> Vec<u8> {
    use helixhair_formats::{Animation, Format, Frame};
    let mut bytes = Vec::new();
    match format {
        Format::Tfx => helixhair_formats::write_tfx(&mut bytes, &groom(11, 20, 8, false, true)),
        Format::Hair => helixhair_formats::write_hair(&mut bytes, &groom(12, 20, 8, true, true)),
        Format::Obj => helixhair_formats::write_obj(&mut bytes, &groom(13, 20, 8, false, false)),
        Format::Usda | Format::Usdc | Format::Usdz | Format::Abc => {
            let curves = groom(14, 20, 8, true, true);
            let frames = (0..3)
                .map(|k| Frame::from_curves(k as f64, &curves))
                .collect();
            let animation = Animation {
                time_codes_per_second: 24.0,
                frames,
            };
            match format {
                Format::Usda => {
                    helixhair_formats::write_usda(&mut bytes, &curves, Some(&animation), None)
                }
                Format::Usdc => {
                    helixhair_formats::write_usdc(&mut bytes, &curves, Some(&animation), None, &[])
                }
                Format::Abc => {
                    helixhair_formats::write_abc(&mut bytes, &curves, Some(&animation), None, &[])
                }
                _ => {
                    helixhair_formats::write_usdz(&mut bytes, &curves, Some(&animation), None, &[])
                }
            }
        }
    }
    .expect("the sample groom writes");
    bytes
}

/// Asserts a read failed with this kind of error at this place, and prints
/// the message (the tests' record of what users see).
pub fn expect_error(
    result: Result<helixhair_formats::Imported, helixhair_formats::ReadError>,
    kind: helixhair_formats::ReadErrorKind,
    location: helixhair_formats::Location,
) -> helixhair_formats::ReadError {
    match result {
        Ok(imported) => panic!(
            "expected a {kind:?} error at {location}, read {}",
            imported.summary
        ),
        Err(error) => {
            println!("{error}");
            assert_eq!((error.kind, error.location), (kind, location), "{error}");
            error
        }
    }
}

/// Overwrites a little-endian `u32` (a header field) in a file.
pub fn put_u32(bytes: &mut [u8], offset: usize, value: u32) {
    bytes[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
}

/// A file of `crates/formats/tests/data` (fixtures written by other tools).
pub fn fixture(name: &str) -> Vec<u8> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

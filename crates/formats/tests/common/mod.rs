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

/// Asserts two point lists are equal to the bit.
pub fn assert_points_equal(read: &[Vec3], written: &[Vec3], what: &str) {
    assert_eq!(read.len(), written.len(), "{what}: point counts");
    for (index, (a, b)) in read.iter().zip(written).enumerate() {
        assert_eq!(a, b, "{what}: point {index}");
    }
}

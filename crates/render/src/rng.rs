//! A small seeded random number generator (SplitMix64), so that root
//! placement and strand variation are the same on every machine and every
//! run for the same seed, without a dependency.

/// SplitMix64: 64 bits of state, passes BigCrush, enough for geometry.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// An index in `0..n` (`n` > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_seed_gives_the_same_numbers_in_the_unit_interval() {
        let a: Vec<f32> = {
            let mut r = SplitMix64::new(7);
            (0..100).map(|_| r.next_f32()).collect()
        };
        let mut r = SplitMix64::new(7);
        assert!(
            a.iter()
                .all(|&x| x == r.next_f32() && (0.0..1.0).contains(&x))
        );
        assert_ne!(SplitMix64::new(8).next_u64(), SplitMix64::new(7).next_u64());
    }
}

//! Curled drawn strands that do not all curl in step: each strand of a
//! clump gets its own curl phase and a little more or less radius around
//! the ringlet's axis, drawn at random per strand and the same every
//! frame. The clumping that applies them is the renderer's
//! ([`helixhair_render::strand_shape::clump_curl_onto`], which says why:
//! strands of one clump grown from nearby roots curl in phase and read as
//! a regular net, issue 32, item 10).

use helixhair_render::rng::SplitMix64;

/// How much a drawn strand's curl radius may differ from its guide's, as a
/// fraction: ±20%, as Yeti's default curl radius noise.
pub const CURL_RADIUS_VARIATION: f32 = 0.2;

/// How far a drawn strand's curl phase may differ from its clump's,
/// radians: ±0.6 (about a tenth of a turn each way). Strands of a ringlet
/// curl nearly together (that is what makes it a ringlet); a phase drawn
/// from the whole circle turned the fringe into frizz.
pub const CURL_PHASE_VARIATION_RAD: f32 = 0.6;

/// Seed of the per-strand variation (mixed with the strand's index).
const VARIATION_SEED: u64 = 0xC04C_5EED;

/// Drawn strand `index`'s curl phase (radians, within
/// ±[`CURL_PHASE_VARIATION_RAD`]) and radius factor
/// (1 ± [`CURL_RADIUS_VARIATION`]); the same for the same index every
/// frame.
pub fn curl_variation(index: usize) -> (f32, f32) {
    let mut rng = SplitMix64::new(VARIATION_SEED ^ (index as u64).wrapping_mul(0x9E37_79B9));
    let phase = CURL_PHASE_VARIATION_RAD * (2.0 * rng.next_f32() - 1.0);
    let scale = 1.0 + CURL_RADIUS_VARIATION * (2.0 * rng.next_f32() - 1.0);
    (phase, scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phases_and_radii_vary_from_strand_to_strand_the_same_each_frame() {
        let all: Vec<(f32, f32)> = (0..50).map(curl_variation).collect();
        assert_eq!(all, (0..50).map(curl_variation).collect::<Vec<_>>());
        let spread = all.iter().map(|v| v.0).fold(f32::MIN, f32::max)
            - all.iter().map(|v| v.0).fold(f32::MAX, f32::min);
        // Spread over the allowed range (±0.6 rad), within it.
        assert!(
            spread > CURL_PHASE_VARIATION_RAD,
            "phases span {spread} rad"
        );
        assert!(all.iter().all(|v| v.0.abs() <= CURL_PHASE_VARIATION_RAD));
        assert!(
            all.iter()
                .all(|v| (v.1 - 1.0).abs() <= CURL_RADIUS_VARIATION)
        );
    }
}

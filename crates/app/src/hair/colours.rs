//! The colours of drawn strands: each its own shade of its group's colour,
//! as real hair varies from fibre to fibre.

use glam::Vec3;
use helixhair_render::rng::SplitMix64;

use crate::style::groom::RenderStrands;

/// An sRGB component in [0, 1] as linear light.
fn srgb_to_linear(c: f64) -> f32 {
    let c = c.clamp(0.0, 1.0) as f32;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// `count` shades of `render`'s colour: brightness varies by up to
/// ±`colour_variation`, darker strands a little redder (more pheomelanin
/// shows), as in real hair.
pub fn strand_colours(render: &RenderStrands, count: usize, seed: u64) -> Vec<Vec3> {
    let base = Vec3::from_array(render.colour_srgb.to_array().map(srgb_to_linear));
    let amount = render.colour_variation as f32;
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|_| {
            let v = amount * (2.0 * rng.next_f32() - 1.0);
            let tint = Vec3::new(1.0 - 0.3 * v, 1.0, 1.0 + 0.3 * v);
            (base * (1.0 + v) * tint).clamp(Vec3::ZERO, Vec3::ONE)
        })
        .collect()
}

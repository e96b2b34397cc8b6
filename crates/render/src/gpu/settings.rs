//! Picture size and quality settings of the offscreen renderer.

/// Colour format of the picture by default (shaders write linear light;
/// the format encodes sRGB).
pub const COLOUR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// The picture formats the renderer draws: [`COLOUR_FORMAT`], or the same
/// bytes in a window surface's usual order.
pub const PICTURE_FORMATS: [wgpu::TextureFormat; 2] =
    [COLOUR_FORMAT, wgpu::TextureFormat::Bgra8UnormSrgb];
/// Samples per pixel of the main pass by default (antialiasing, and partial
/// coverage of strands thinner than a pixel through the sample mask);
/// [`RenderSettings::msaa_samples`]
/// may ask for 1.
pub const MSAA_SAMPLES: u32 = 4;

/// Picture size and quality settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Picture width, pixels.
    pub width_px: u32,
    /// Picture height, pixels.
    pub height_px: u32,
    /// Side of the deep opacity map, texels. 1024 resolves single strands
    /// over a head at a few tenths of a millimetre per texel.
    pub shadow_map_px: u32,
    /// Narrowest ribbon drawn, pixels; thinner strands are drawn this wide
    /// with partial coverage (a random subset of the MSAA samples), so they neither vanish
    /// nor alias.
    pub min_ribbon_px: f32,
    /// Thickness of the first opacity layer, metres (the others end 2, 4
    /// and 8 times deeper): about the depth over which hair goes from lit
    /// to shaded.
    pub shadow_layer_m: f32,
    /// Opacity one strand fragment adds in the opacity map (light through
    /// n strands: exp(−n × this)).
    pub strand_opacity: f32,
    /// Samples per pixel of the main pass: 4 (antialiased strands, thin
    /// strands as partial coverage of the samples) or 1 (no MSAA: a thin
    /// strand covers a pixel or not, at random in proportion to its
    /// coverage, and the pass rasterises a quarter of the samples). 4 by
    /// default; 1 is for quick previews on a CPU rasteriser.
    pub msaa_samples: u32,
    /// Whether the hair casts its self-shadow (the two passes from the
    /// light, [`super::shadow`]). Without, the opacity map is only
    /// cleared, so everything is lit as if unshadowed; for quick previews.
    pub shadows: bool,
    /// The picture's format: `Rgba8UnormSrgb` (the default; what
    /// [`super::readback`] and PNGs hold) or `Bgra8UnormSrgb` (the byte
    /// order of most window surfaces, so a window can copy the picture
    /// onto its image instead of drawing it as a texture).
    pub picture_format: wgpu::TextureFormat,
}

impl RenderSettings {
    /// Default settings for a `width_px` × `height_px` picture.
    pub fn new(width_px: u32, height_px: u32) -> Self {
        Self {
            width_px,
            height_px,
            shadow_map_px: 1024,
            min_ribbon_px: 1.0,
            shadow_layer_m: 0.004,
            strand_opacity: 0.6,
            msaa_samples: MSAA_SAMPLES,
            shadows: true,
            picture_format: COLOUR_FORMAT,
        }
    }

    /// Width over height.
    pub fn aspect(&self) -> f32 {
        self.width_px as f32 / self.height_px as f32
    }
}

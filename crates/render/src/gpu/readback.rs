//! Copying a rendered texture back into CPU memory.
//!
//! wgpu copies textures into buffers in rows padded to
//! [`wgpu::COPY_BYTES_PER_ROW_ALIGNMENT`] (256) bytes; the padding is
//! dropped here, so the image rows are tight.

use crate::gpu::context::GpuError;

/// An 8-bit RGBA image, rows top to bottom, sRGB-encoded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbaImage {
    /// Width in pixels.
    pub width_px: u32,
    /// Height in pixels.
    pub height_px: u32,
    /// `width_px * height_px * 4` bytes.
    pub rgba: Vec<u8>,
}

impl RgbaImage {
    /// The mean absolute difference per channel from `other` (same size),
    /// in 8-bit levels, and how many pixels differ by more than
    /// `levels` in some channel: how two renderings of the same scene are
    /// compared.
    pub fn difference(&self, other: &Self, levels: u8) -> (f64, usize) {
        let mean = self
            .rgba
            .iter()
            .zip(&other.rgba)
            .map(|(a, b)| f64::from(a.abs_diff(*b)))
            .sum::<f64>()
            / self.rgba.len().max(1) as f64;
        let differing = self
            .rgba
            .chunks_exact(4)
            .zip(other.rgba.chunks_exact(4))
            .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > levels))
            .count();
        (mean, differing)
    }

    /// The pixel at column `x`, row `y` (0 at the top).
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 4] {
        let i = 4 * (y as usize * self.width_px as usize + x as usize);
        [
            self.rgba[i],
            self.rgba[i + 1],
            self.rgba[i + 2],
            self.rgba[i + 3],
        ]
    }
}

/// Bytes per row of a copy of `width_px` RGBA8 pixels, padded.
pub fn padded_bytes_per_row(width_px: u32) -> u32 {
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    (4 * width_px).div_ceil(align) * align
}

/// Records a copy of the RGBA8 `texture` into `buffer` (sized for
/// [`padded_bytes_per_row`] rows).
pub fn copy_to_buffer(
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    buffer: &wgpu::Buffer,
) {
    let size = texture.size();
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_bytes_per_row(size.width)),
                rows_per_image: Some(size.height),
            },
        },
        size,
    );
}

/// Waits for the GPU, maps `buffer` and returns its image without padding.
pub fn read_buffer(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    width_px: u32,
    height_px: u32,
) -> Result<RgbaImage, GpuError> {
    let slice = buffer.slice(..);
    helixhair_gpu::map_and_wait(device, slice).map_err(GpuError::Readback)?;
    let padded = padded_bytes_per_row(width_px) as usize;
    let tight = 4 * width_px as usize;
    let mut rgba = Vec::with_capacity(tight * height_px as usize);
    {
        let view = slice
            .get_mapped_range()
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        for row in view.chunks_exact(padded).take(height_px as usize) {
            rgba.extend_from_slice(&row[..tight]);
        }
    }
    buffer.unmap();
    Ok(RgbaImage {
        width_px,
        height_px,
        rgba,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_padded_to_256_bytes() {
        assert_eq!(padded_bytes_per_row(1), 256);
        assert_eq!(padded_bytes_per_row(64), 256);
        assert_eq!(padded_bytes_per_row(65), 512);
        assert_eq!(padded_bytes_per_row(1280), 5120);
    }
}

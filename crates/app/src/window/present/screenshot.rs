//! Screenshots of the window (`--screenshot`): egui's frame painted a
//! second time into an offscreen texture like the window's image, read
//! back and written as a PNG.

use std::path::Path;

use anyhow::Context as _;
use helixhair_render::RgbaImage;
use helixhair_render::gpu::readback::padded_bytes_per_row;

/// An offscreen texture like the window's image (`config`), and a buffer
/// to read it back.
pub fn screenshot_target(
    device: &wgpu::Device,
    config: &wgpu::SurfaceConfiguration,
) -> (wgpu::Texture, wgpu::Buffer) {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("screenshot"),
        size: wgpu::Extent3d {
            width: config.width,
            height: config.height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: config.format,
        usage: config.usage | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("screenshot readback"),
        size: u64::from(padded_bytes_per_row(config.width)) * u64::from(config.height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    (texture, buffer)
}

/// `image` read from a texture of `format`, in RGBA byte order.
pub fn in_rgba_order(mut image: RgbaImage, format: wgpu::TextureFormat) -> RgbaImage {
    if matches!(
        format,
        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
    ) {
        for px in image.rgba.chunks_exact_mut(4) {
            px.swap(0, 2);
        }
    }
    image
}

/// Writes `image` as a PNG file.
pub fn save_png(image: &RgbaImage, path: &Path) -> anyhow::Result<()> {
    let buffer = image::RgbaImage::from_raw(image.width_px, image.height_px, image.rgba.clone())
        .context("screenshot buffer has the wrong size")?;
    buffer
        .save(path)
        .with_context(|| format!("writing the screenshot {}", path.display()))
}

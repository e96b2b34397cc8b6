//! The textures a frame draws into, made once per picture size.

use super::passes::{
    COLOUR_FORMAT, DEPTH_FORMAT, FIRST_DEPTH_FORMAT, MSAA_SAMPLES, OPACITY_FORMAT,
};
use super::readback::padded_bytes_per_row;
use super::settings::RenderSettings;

/// The render targets and the readback buffer.
#[derive(Debug)]
pub struct Targets {
    /// Multisampled colour of the main pass.
    pub msaa_colour: wgpu::TextureView,
    /// Multisampled depth of the main pass.
    pub msaa_depth: wgpu::TextureView,
    /// The resolved picture (also sampled by windows, as `Rgba8Unorm`).
    pub picture: wgpu::Texture,
    /// The light's first-hair depth per texel (a colour texture).
    pub light_depth: wgpu::TextureView,
    /// The depth buffer of the light's depth pass.
    pub light_depth_buffer: wgpu::TextureView,
    /// The four opacity layers.
    pub opacity: wgpu::TextureView,
    /// Where the picture is copied for reading.
    pub readback: wgpu::Buffer,
}

fn texture(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    sample_count: u32,
    usage: wgpu::TextureUsages,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats,
    })
}

impl Targets {
    /// Makes the targets for `s`'s sizes.
    pub fn new(device: &wgpu::Device, s: &RenderSettings) -> Self {
        use wgpu::TextureUsages as U;
        let size = (s.width_px, s.height_px);
        let shadow = (s.shadow_map_px, s.shadow_map_px);
        let view = |t: wgpu::Texture| t.create_view(&Default::default());
        let sampled = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING;
        Self {
            msaa_colour: view(texture(
                device,
                "msaa colour",
                size,
                COLOUR_FORMAT,
                MSAA_SAMPLES,
                U::RENDER_ATTACHMENT,
                &[],
            )),
            msaa_depth: view(texture(
                device,
                "msaa depth",
                size,
                DEPTH_FORMAT,
                MSAA_SAMPLES,
                U::RENDER_ATTACHMENT,
                &[],
            )),
            picture: texture(
                device,
                "picture",
                size,
                COLOUR_FORMAT,
                1,
                U::RENDER_ATTACHMENT | U::COPY_SRC | U::TEXTURE_BINDING,
                &[wgpu::TextureFormat::Rgba8Unorm],
            ),
            light_depth: view(texture(
                device,
                "light depth",
                shadow,
                FIRST_DEPTH_FORMAT,
                1,
                sampled,
                &[],
            )),
            light_depth_buffer: view(texture(
                device,
                "light depth buffer",
                shadow,
                DEPTH_FORMAT,
                1,
                U::RENDER_ATTACHMENT,
                &[],
            )),
            opacity: view(texture(
                device,
                "opacity layers",
                shadow,
                OPACITY_FORMAT,
                1,
                sampled,
                &[],
            )),
            readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("readback"),
                size: u64::from(padded_bytes_per_row(s.width_px)) * u64::from(s.height_px),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            }),
        }
    }
}

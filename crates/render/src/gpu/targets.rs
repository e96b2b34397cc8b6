//! The textures a frame draws into, made once per picture size, and
//! [`begin`], which starts a pass that clears them.

use super::passes::{DEPTH_FORMAT, FIRST_DEPTH_FORMAT, OPACITY_FORMAT};
use super::readback::padded_bytes_per_row;
use super::settings::RenderSettings;

/// The render targets and the readback buffer.
#[derive(Debug)]
pub struct Targets {
    /// Multisampled colour of the main pass, resolved into the picture;
    /// `None` at one sample per pixel (the pass draws into the picture).
    pub msaa_colour: Option<wgpu::TextureView>,
    /// Depth of the main pass, at its samples per pixel.
    pub main_depth: wgpu::TextureView,
    /// The resolved picture (also sampled by windows, as `Rgba8Unorm` or
    /// `Bgra8Unorm`).
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
        let samples = s.msaa_samples;
        Self {
            msaa_colour: (samples > 1).then(|| {
                view(texture(
                    device,
                    "msaa colour",
                    size,
                    s.picture_format,
                    samples,
                    U::RENDER_ATTACHMENT,
                    &[],
                ))
            }),
            main_depth: view(texture(
                device,
                "main depth",
                size,
                DEPTH_FORMAT,
                samples,
                U::RENDER_ATTACHMENT,
                &[],
            )),
            picture: texture(
                device,
                "picture",
                size,
                s.picture_format,
                1,
                U::RENDER_ATTACHMENT | U::COPY_SRC | U::TEXTURE_BINDING,
                &[s.picture_format.remove_srgb_suffix()],
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

/// A colour target: the view, an optional resolve target (the
/// multisampled colour is then discarded), and the clear colour.
pub type ColourTarget<'a> = (
    &'a wgpu::TextureView,
    Option<&'a wgpu::TextureView>,
    wgpu::Color,
);

/// Starts a pass that clears its targets: colour and depth (to 1).
pub fn begin<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    colour: Option<ColourTarget<'_>>,
    depth: Option<&wgpu::TextureView>,
) -> wgpu::RenderPass<'e> {
    let colour = colour.map(
        |(view, resolve_target, clear)| wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(clear),
                store: if resolve_target.is_some() {
                    wgpu::StoreOp::Discard
                } else {
                    wgpu::StoreOp::Store
                },
            },
        },
    );
    let colours = [colour];
    let colour_count = usize::from(colours[0].is_some());
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &colours[..colour_count],
        depth_stencil_attachment: depth.map(|view| wgpu::RenderPassDepthStencilAttachment {
            view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        ..Default::default()
    })
}

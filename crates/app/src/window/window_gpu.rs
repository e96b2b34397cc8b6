//! The window's GPU side: the surface, the 3D renderers and egui's
//! renderer on one device.
//!
//! # Why the 3D view is a texture
//!
//! The renderer (`helixhair-render`) draws a scene into its own picture
//! texture (4× MSAA resolved, with its shadow passes); the window hands that
//! picture to egui as a native texture and egui paints it in the central
//! panel like any image. So the panels dock around the view with egui's
//! ordinary layout, the view's size is the panel's size, the compare view
//! is simply two pictures side by side, and the renderer stays unaware of
//! windows. The cost is one extra full-screen texture read per frame,
//! negligible next to the hair itself.
//!
//! The surface uses a non-sRGB format (egui works in gamma space); the
//! picture is sRGB-encoded and is sampled through an `Rgba8Unorm` view, so
//! its bytes reach the screen unchanged.
//!
//! A screenshot ([`WindowGpu::present`] with a path) paints the same egui
//! frame a second time into an offscreen texture and reads that back: a
//! surface texture may not be copyable, and this works on every backend.

use std::path::Path;
use std::sync::Arc;

use anyhow::Context as _;
use helixhair_render::gpu::readback::{copy_to_buffer, padded_bytes_per_row, read_buffer};
use helixhair_render::{GpuContext, OffscreenRenderer, RenderSettings, RgbaImage, Scene};
use winit::window::Window;

/// Side of the hair's shadow map in the window, texels: half the offline
/// renderer's, which quarters the shadow passes' cost on a software
/// rasteriser and is still finer than a strand's width at the view's size.
pub const WINDOW_SHADOW_MAP_PX: u32 = 512;

/// The window's device, surface and renderers.
pub struct WindowGpu {
    /// The window.
    pub window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    egui: egui_wgpu::Renderer,
    scenes: [Option<(OffscreenRenderer, egui::TextureId)>; 2],
    /// The adapter and device, shared with the pictures' renderers.
    gpu: GpuContext,
}

impl WindowGpu {
    /// Opens the surface on `window` and makes a device that can draw to it.
    pub fn new(instance: &wgpu::Instance, window: Arc<Window>) -> anyhow::Result<Self> {
        let surface = instance
            .create_surface(window.clone())
            .context("creating the window's drawing surface")?;
        let gpu = GpuContext::for_surface(instance, &surface)
            .context("no graphics adapter can draw to this window")?;
        let (device, queue) = (gpu.device.clone(), gpu.queue.clone());
        let caps = surface.get_capabilities(&gpu.adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .or_else(|| caps.formats.first().map(|f| f.remove_srgb_suffix()))
            .context("the surface offers no texture format")?;
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&device, &config);
        let egui = egui_wgpu::Renderer::new(&device, format, Default::default());
        Ok(Self {
            window,
            surface,
            device,
            queue,
            config,
            egui,
            scenes: [None, None],
            gpu,
        })
    }

    /// Adapter name and backend, for the readouts.
    pub fn adapter_label(&self) -> String {
        self.gpu.adapter_label()
    }

    /// Whether the adapter is a CPU rasteriser (lavapipe, SwiftShader):
    /// the window then previews while the user drags
    /// ([`super::preview`]).
    pub fn is_software(&self) -> bool {
        self.gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu
    }

    /// Waits until the GPU has done all submitted work (profiling only:
    /// it serialises CPU and GPU).
    pub fn wait_idle(&self) {
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }

    /// Follows a window resize.
    pub fn resize(&mut self, width_px: u32, height_px: u32) {
        if width_px > 0 && height_px > 0 {
            self.config.width = width_px;
            self.config.height = height_px;
            self.surface.configure(&self.device, &self.config);
        }
    }

    /// Draws `scene` into picture `slot` (0 main, 1 compare) at `size_px`
    /// and returns the egui texture showing it.
    pub fn draw_scene(
        &mut self,
        slot: usize,
        scene: &Scene<'_>,
        size_px: [u32; 2],
    ) -> anyhow::Result<egui::TextureId> {
        let [w, h] = size_px;
        if self.scenes[slot].is_none() {
            let gpu = self.gpu.clone();
            let settings = RenderSettings {
                shadow_map_px: WINDOW_SHADOW_MAP_PX,
                ..RenderSettings::new(w, h)
            };
            let renderer = OffscreenRenderer::new(gpu, settings)?;
            let view = renderer.picture_view_unorm();
            let id =
                self.egui
                    .register_native_texture(&self.device, &view, wgpu::FilterMode::Linear);
            self.scenes[slot] = Some((renderer, id));
        }
        let Some((renderer, id)) = &mut self.scenes[slot] else {
            anyhow::bail!("no renderer for view {slot}");
        };
        renderer.resize(w, h)?;
        renderer.draw(scene);
        let view = renderer.picture_view_unorm();
        self.egui.update_egui_texture_from_wgpu_texture(
            &self.device,
            &view,
            wgpu::FilterMode::Linear,
            *id,
        );
        Ok(*id)
    }

    /// Paints egui's output to the window, and, given `screenshot`, also
    /// returns the frame as a picture.
    pub fn present(
        &mut self,
        output: egui::FullOutput,
        ctx: &egui::Context,
        screenshot: bool,
    ) -> anyhow::Result<Option<RgbaImage>> {
        let ppp = output.pixels_per_point;
        let jobs = ctx.tessellate(output.shapes, ppp);
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                self.egui
                    .update_texture(&self.device, &self.queue, *id, delta);
            }
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [self.config.width, self.config.height],
            pixels_per_point: ppp,
        };
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let extra =
            self.egui
                .update_buffers(&self.device, &self.queue, &mut encoder, &jobs, &screen);
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => Some(t),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.device, &self.config);
                None
            }
            _ => None,
        };
        if let Some(frame) = &frame {
            let view = frame.texture.create_view(&Default::default());
            self.paint(&mut encoder, &view, &jobs, &screen);
        }
        let shot = if screenshot {
            let texture = self.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("screenshot"),
                size: wgpu::Extent3d {
                    width: self.config.width,
                    height: self.config.height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: self.config.format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            });
            let view = texture.create_view(&Default::default());
            self.paint(&mut encoder, &view, &jobs, &screen);
            let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("screenshot readback"),
                size: u64::from(padded_bytes_per_row(self.config.width))
                    * u64::from(self.config.height),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            copy_to_buffer(&mut encoder, &texture, &buffer);
            Some(buffer)
        } else {
            None
        };
        self.queue
            .submit(extra.into_iter().chain([encoder.finish()]));
        if let Some(frame) = frame {
            self.window.pre_present_notify();
            self.queue.present(frame);
        }
        for id in &output.textures_delta.free {
            self.egui.free_texture(id);
        }
        // A lost device (or any failed GPU operation) ends the window with
        // wgpu's reason instead of drawing garbage; see helixhair_gpu.
        self.gpu
            .check()
            .context("the window cannot draw any more")?;
        let Some(buffer) = shot else {
            return Ok(None);
        };
        let mut image = read_buffer(&self.device, &buffer, self.config.width, self.config.height)?;
        if matches!(
            self.config.format,
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        ) {
            for px in image.rgba.chunks_exact_mut(4) {
                px.swap(0, 2);
            }
        }
        Ok(Some(image))
    }

    fn paint(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        jobs: &[egui::ClippedPrimitive],
        screen: &egui_wgpu::ScreenDescriptor,
    ) {
        let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("egui"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        self.egui.render(&mut pass.forget_lifetime(), jobs, screen);
    }
}

/// Writes `image` as a PNG file.
pub fn save_png(image: &RgbaImage, path: &Path) -> anyhow::Result<()> {
    let buffer = image::RgbaImage::from_raw(image.width_px, image.height_px, image.rgba.clone())
        .context("screenshot buffer has the wrong size")?;
    buffer
        .save(path)
        .with_context(|| format!("writing the screenshot {}", path.display()))
}

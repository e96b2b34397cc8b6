//! The window's GPU side: the surface, the 3D renderers and egui's
//! renderer on one device.
//!
//! # Why the 3D view is a texture
//!
//! The renderer (`helixhair-render`) draws a scene into its own picture
//! texture (4× MSAA resolved, with its shadow passes; the interactive
//! preview's renderer without either, [`super::preview`]); the window hands that
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
//!
//! egui is painted by [`EguiPainter`], which on a software adapter keeps
//! the panels as a layer repainted only where they change.

use std::sync::Arc;

use anyhow::Context as _;
use helixhair_render::gpu::device_hair::DeviceStrands;
use helixhair_render::gpu::readback::{copy_to_buffer, read_buffer};
use helixhair_render::{GpuContext, OffscreenRenderer, RenderSettings, RgbaImage, Scene};
use winit::window::Window;

use super::egui_paint::{EguiPainter, Picture};
use super::frame_profile::FrameProfile;
use super::preview::{Quality, caches_panels, present_mode};
use super::screenshot::{in_rgba_order, screenshot_target};

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
    egui: EguiPainter,
    /// The pictures' renderers: view slot (0 main, 1 compare), samples
    /// per pixel and shadows, and the egui texture showing the picture.
    scenes: Vec<(usize, u32, bool, OffscreenRenderer, egui::TextureId)>,
    /// The pictures' format: the surface's byte order when the panels are
    /// cached (the pictures are then copied onto the window), else the
    /// renderer's default.
    picture_format: wgpu::TextureFormat,
    /// The adapter and device, shared with the pictures' renderers.
    gpu: GpuContext,
}

impl WindowGpu {
    /// Opens the surface on `window` and makes a device that can draw to it;
    /// `forced_preview` (`--preview`) caches the panels as a software
    /// adapter does ([`caches_panels`]).
    pub fn new(
        instance: &wgpu::Instance,
        window: Arc<Window>,
        forced_preview: bool,
    ) -> anyhow::Result<Self> {
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
        let software = gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu;
        // The panels' layer is copied onto the surface: only where the
        // surface takes copies.
        let cache = caches_panels(forced_preview, software)
            && caps.usages.contains(wgpu::TextureUsages::COPY_DST);
        let usage = if cache {
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_DST
        } else {
            wgpu::TextureUsages::RENDER_ATTACHMENT
        };
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: present_mode(cache, &caps.present_modes),
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
        let egui = EguiPainter::new(&device, &queue, format, cache);
        let picture_format = match format {
            wgpu::TextureFormat::Bgra8Unorm if cache => wgpu::TextureFormat::Bgra8UnormSrgb,
            _ => RenderSettings::new(1, 1).picture_format,
        };
        Ok(Self {
            window,
            surface,
            device,
            queue,
            config,
            egui,
            scenes: Vec::new(),
            picture_format,
            gpu,
        })
    }

    /// The window's device, which the GPU engine steps on so that its
    /// strands are drawn from its own buffers
    /// ([`crate::window::live::device_plan`]).
    pub fn context(&self) -> &GpuContext {
        &self.gpu
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

    /// Draws `scene` into picture `slot` (0 main, 1 compare) at
    /// `quality`'s size, samples and shadows, and returns the egui texture
    /// showing it. Each slot keeps a renderer per quality (full and
    /// preview), made when first needed.
    /// With `device`, the hair is drawn from strand points on this device
    /// instead of `scene.hair`'s ([`OffscreenRenderer::draw_device`]).
    pub fn draw_scene(
        &mut self,
        slot: usize,
        scene: &Scene<'_>,
        device: Option<&DeviceStrands<'_>>,
        quality: &Quality,
    ) -> anyhow::Result<egui::TextureId> {
        let [w, h] = quality.picture_px;
        let key = (slot, quality.msaa_samples, quality.shadows);
        let found = self.scenes.iter().position(|s| (s.0, s.1, s.2) == key);
        let index = match found {
            Some(index) => index,
            None => {
                let settings = RenderSettings {
                    shadow_map_px: WINDOW_SHADOW_MAP_PX,
                    msaa_samples: quality.msaa_samples,
                    shadows: quality.shadows,
                    picture_format: self.picture_format,
                    ..RenderSettings::new(w, h)
                };
                let renderer = OffscreenRenderer::new(self.gpu.clone(), settings)?;
                let view = renderer.picture_view_unorm();
                let id = self.egui.renderer.register_native_texture(
                    &self.device,
                    &view,
                    wgpu::FilterMode::Linear,
                );
                self.scenes.push((slot, key.1, key.2, renderer, id));
                self.scenes.len() - 1
            }
        };
        let (_, _, _, renderer, id) = &mut self.scenes[index];
        renderer.resize(w, h)?;
        match device {
            Some(strands) => renderer.draw_device(scene, strands),
            None => renderer.draw(scene),
        }
        let view = renderer.picture_view_unorm();
        self.egui.renderer.update_egui_texture_from_wgpu_texture(
            &self.device,
            &view,
            wgpu::FilterMode::Linear,
            *id,
        );
        Ok(*id)
    }

    /// Paints egui's output to the window, and, given `screenshot`, also
    /// returns the frame as a picture. Laps `profile`'s stages 5
    /// (tessellation), 6 (painting) and 7 (presenting); with `wait` each
    /// is waited for, so lavapipe's work is counted where it is done.
    pub fn present(
        &mut self,
        output: egui::FullOutput,
        ctx: &egui::Context,
        screenshot: bool,
        (profile, wait): (&mut FrameProfile, bool),
    ) -> anyhow::Result<Option<RgbaImage>> {
        let ppp = output.pixels_per_point;
        let jobs = ctx.tessellate(output.shapes, ppp);
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                self.egui
                    .renderer
                    .update_texture(&self.device, &self.queue, *id, delta);
            }
        }
        profile.lap(5);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [self.config.width, self.config.height],
            pixels_per_point: ppp,
        };
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => Some(t),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.device, &self.config);
                None
            }
            _ => None,
        };
        let shot = screenshot.then(|| screenshot_target(&self.device, &self.config));
        let targets: Vec<&wgpu::Texture> = frame
            .iter()
            .map(|f| &f.texture)
            .chain(shot.as_ref().map(|(t, _)| t))
            .collect();
        let copyable =
            self.egui.caches() && self.picture_format.remove_srgb_suffix() == self.config.format;
        let pictures: Vec<Picture> = self
            .scenes
            .iter()
            .map(|s| Picture {
                id: s.4,
                texture: copyable.then(|| s.3.picture().clone()),
            })
            .collect();
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let changed = !output.textures_delta.set.is_empty();
        let extra = self
            .egui
            .paint(&mut encoder, &targets, jobs, &screen, &pictures, changed);
        if let Some((texture, buffer)) = &shot {
            copy_to_buffer(&mut encoder, texture, buffer);
        }
        self.queue
            .submit(extra.into_iter().chain([encoder.finish()]));
        if wait {
            self.wait_idle();
        }
        profile.lap(6);
        if let Some(frame) = frame {
            self.window.pre_present_notify();
            self.queue.present(frame);
        }
        for id in &output.textures_delta.free {
            self.egui.renderer.free_texture(id);
        }
        // A lost device (or any failed GPU operation) ends the window with
        // wgpu's reason instead of drawing garbage; see helixhair_gpu.
        self.gpu
            .check()
            .context("the window cannot draw any more")?;
        if wait {
            self.wait_idle();
        }
        profile.lap(7);
        let Some((_, buffer)) = shot else {
            return Ok(None);
        };
        let image = read_buffer(&self.device, &buffer, self.config.width, self.config.height)?;
        Ok(Some(in_rgba_order(image, self.config.format)))
    }

    /// Pixels of the panels repainted last frame (`--profile`).
    pub fn panels_repainted_px(&self) -> u64 {
        self.egui.repainted_px
    }
}

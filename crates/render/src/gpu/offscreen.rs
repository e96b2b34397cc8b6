//! Draws a [`Scene`] into a texture and reads it back: pictures without a
//! window, on any adapter (lavapipe included).
//!
//! # One frame
//!
//! 1. Upload ([`super::frame_data`]): strands become ribbon vertices
//!    ([`crate::ribbons`]), the head becomes mesh vertices; uniforms for
//!    the camera, the light and the materials.
//! 2. Shadow depth and shadow opacity passes from the light
//!    ([`super::shadow`]); without [`RenderSettings::shadows`] they only
//!    clear their targets and the main pass reads no shadow.
//! 3. The main pass at 4× MSAA (or [`RenderSettings::msaa_samples`]):
//!    backdrop, head, hair; resolved into the picture.
//! 4. The picture is copied into a buffer and read back
//!    ([`super::readback`]).
//!
//! [`OffscreenRenderer::draw_device`] replaces step 1's strands with a
//! compute pass over strand points already on the device
//! ([`super::device_hair`]): the ribbons are built there, and nothing of
//! the hair is uploaded.

use helixhair_gpu::upload_buffer;

use glam::Vec3;

use super::context::{GpuContext, GpuError};
use super::device_hair::{DeviceRibbons, DeviceStrands};
use super::frame_data::{FrameUniforms, IndexedGeometry, head_vertices};
use super::passes::Pipelines;
use super::readback::{RgbaImage, copy_to_buffer, read_buffer};
use super::settings::PICTURE_FORMATS;
use super::settings::RenderSettings;
use super::targets::{Targets, begin};
use crate::ribbons::ribbon_mesh;
use crate::scene::Scene;

/// Renders scenes into pictures, headless.
#[derive(Debug)]
pub struct OffscreenRenderer {
    gpu: GpuContext,
    settings: RenderSettings,
    pipelines: Pipelines,
    targets: Targets,
    sampler: wgpu::Sampler,
    /// The pass that builds ribbons from points on the device, made on
    /// the first [`Self::draw_device`].
    device_ribbons: Option<DeviceRibbons>,
}

/// The bind groups of one frame.
struct FrameBindings {
    camera: wgpu::BindGroup,
    light: wgpu::BindGroup,
    lighting: wgpu::BindGroup,
    opacity: wgpu::BindGroup,
}

impl OffscreenRenderer {
    /// Builds the pipelines and the targets for `settings`' size.
    pub fn new(gpu: GpuContext, settings: RenderSettings) -> Result<Self, GpuError> {
        let max_px = gpu.device.limits().max_texture_dimension_2d;
        let sides = [
            settings.width_px,
            settings.height_px,
            settings.shadow_map_px,
        ];
        if sides.iter().any(|&s| s == 0 || s > max_px) {
            return Err(GpuError::BadSize {
                width_px: settings.width_px,
                height_px: settings.height_px,
                max_px,
            });
        }
        // An adapter that cannot run a shader (a backend without a feature
        // it uses) is an error to report, not a panic.
        let internal = gpu.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let validation = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        if !PICTURE_FORMATS.contains(&settings.picture_format) {
            return Err(GpuError::Unsupported {
                adapter: gpu.adapter_label(),
                error: format!(
                    "picture format {:?} (the renderer draws {PICTURE_FORMATS:?})",
                    settings.picture_format
                ),
            });
        }
        let pipelines = Pipelines::new(&gpu.device, gpu.backend != wgpu::Backend::Gl, &settings);
        let errors = [validation, internal].map(|scope| pollster::block_on(scope.pop()));
        if let Some(error) = errors.into_iter().flatten().next() {
            return Err(GpuError::Unsupported {
                adapter: gpu.adapter_label(),
                error: error.to_string(),
            });
        }
        let targets = Targets::new(&gpu.device, &settings);
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("opacity"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Ok(Self {
            gpu,
            settings,
            pipelines,
            targets,
            sampler,
            device_ribbons: None,
        })
    }

    /// The adapter's name, for reports.
    pub fn adapter_label(&self) -> String {
        self.gpu.adapter_label()
    }

    /// The settings the renderer was made with.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    fn bindings(&self, uniforms: &FrameUniforms) -> FrameBindings {
        let device = &self.gpu.device;
        let layouts = &self.pipelines.layouts;
        let bind = |layout, entries: &[wgpu::BindingResource<'_>]| {
            let entries: Vec<wgpu::BindGroupEntry<'_>> = entries
                .iter()
                .enumerate()
                .map(|(i, resource)| wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource: resource.clone(),
                })
                .collect();
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: None,
                layout,
                entries: &entries,
            })
        };
        let queue = &self.gpu.queue;
        let uniform = |bytes: &[u8]| {
            upload_buffer(device, queue, "uniform", bytes, wgpu::BufferUsages::UNIFORM)
        };
        let camera = uniform(bytemuck::bytes_of(&uniforms.camera));
        let light = uniform(bytemuck::bytes_of(&uniforms.light));
        let lighting = uniform(bytemuck::bytes_of(&uniforms.lighting));
        let t = &self.targets;
        FrameBindings {
            camera: bind(&layouts.view, &[camera.as_entire_binding()]),
            light: bind(&layouts.view, &[light.as_entire_binding()]),
            lighting: bind(
                &layouts.lighting,
                &[
                    lighting.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&t.light_depth),
                ],
            ),
            opacity: bind(
                &layouts.opacity,
                &[
                    wgpu::BindingResource::TextureView(&t.opacity),
                    wgpu::BindingResource::Sampler(&self.sampler),
                ],
            ),
        }
    }

    /// Draws `scene` and returns the picture.
    pub fn render(&mut self, scene: &Scene<'_>) -> Result<RgbaImage, GpuError> {
        self.draw(scene);
        self.read_picture()
    }

    /// [`Self::draw_device`] and returns the picture.
    pub fn render_device(
        &mut self,
        scene: &Scene<'_>,
        strands: &DeviceStrands<'_>,
    ) -> Result<RgbaImage, GpuError> {
        self.draw_device(scene, strands);
        self.read_picture()
    }

    /// Reads back the picture the last draw submitted.
    fn read_picture(&mut self) -> Result<RgbaImage, GpuError> {
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        copy_to_buffer(&mut encoder, &self.targets.picture, &self.targets.readback);
        self.gpu.queue.submit([encoder.finish()]);
        let picture = read_buffer(
            &self.gpu.device,
            &self.targets.readback,
            self.settings.width_px,
            self.settings.height_px,
        )
        .map(|mut image| {
            if self.settings.picture_format == wgpu::TextureFormat::Bgra8UnormSrgb {
                for px in image.rgba.chunks_exact_mut(4) {
                    px.swap(0, 2);
                }
            }
            image
        });
        // A lost device or a failed operation first: a readback error is
        // then only its consequence, and a picture read back is not trusted.
        self.gpu.check()?;
        picture
    }

    /// Draws `scene`'s head with the hair of `strands`, whose points are
    /// already on this renderer's device ([`super::device_hair`]: built into
    /// ribbons there, never read back), into the picture texture, and
    /// submits it. `scene.hair` gives the ribbon widths and the scalp's
    /// tint (its points are not drawn); the light's view fits the head
    /// grown by [`DeviceStrands::reach_m`].
    pub fn draw_device(&mut self, scene: &Scene<'_>, strands: &DeviceStrands<'_>) {
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        let mut ribbons = self
            .device_ribbons
            .take()
            .unwrap_or_else(|| DeviceRibbons::new(&self.gpu.device));
        let hair = ribbons.encode(&self.gpu.device, &self.gpu.queue, strands, &mut encoder);
        let (lo, hi) = scene.head.mesh.bounds_m();
        let reach = Vec3::splat(strands.reach_m.max(0.0));
        let uniforms = FrameUniforms::within(scene, &self.settings, (lo - reach, hi + reach));
        self.encode_with(scene, &uniforms, hair, &mut encoder);
        self.gpu.queue.submit([encoder.finish()]);
        self.device_ribbons = Some(ribbons);
    }

    /// The device ribbon pass, once [`Self::draw_device`] has run (tests
    /// read its vertices).
    pub fn device_ribbons(&self) -> Option<&DeviceRibbons> {
        self.device_ribbons.as_ref()
    }

    /// Draws `scene` into the picture texture and submits it, without
    /// reading it back: what a window does every frame before showing the
    /// picture through [`Self::picture_view_unorm`].
    pub fn draw(&mut self, scene: &Scene<'_>) {
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        self.encode(scene, &mut encoder);
        self.gpu.queue.submit([encoder.finish()]);
    }

    /// A view of the picture that samples its sRGB-encoded bytes as they
    /// are (`Rgba8Unorm` or `Bgra8Unorm`), which is what UI toolkits that
    /// work in gamma space (egui) expect of a texture.
    pub fn picture_view_unorm(&self) -> wgpu::TextureView {
        self.targets
            .picture
            .create_view(&wgpu::TextureViewDescriptor {
                format: Some(self.settings.picture_format.remove_srgb_suffix()),
                ..Default::default()
            })
    }

    /// The picture texture itself (`picture_format`, sRGB-encoded bytes),
    /// to copy into a window's image of the same byte order.
    pub fn picture(&self) -> &wgpu::Texture {
        &self.targets.picture
    }

    /// Changes the picture size (a window was resized); the shadow map
    /// keeps its size. Zero or too large sides are refused.
    pub fn resize(&mut self, width_px: u32, height_px: u32) -> Result<(), GpuError> {
        let max_px = self.gpu.device.limits().max_texture_dimension_2d;
        if [width_px, height_px].iter().any(|&s| s == 0 || s > max_px) {
            return Err(GpuError::BadSize {
                width_px,
                height_px,
                max_px,
            });
        }
        if (width_px, height_px) != (self.settings.width_px, self.settings.height_px) {
            self.settings.width_px = width_px;
            self.settings.height_px = height_px;
            self.targets = Targets::new(&self.gpu.device, &self.settings);
        }
        Ok(())
    }

    /// Records the shadow and main passes of `scene` into `encoder`.
    fn encode(&mut self, scene: &Scene<'_>, encoder: &mut wgpu::CommandEncoder) {
        let (device, queue) = (&self.gpu.device, &self.gpu.queue);
        let (strand_vertices, strand_indices) = ribbon_mesh(scene.hair);
        let hair =
            IndexedGeometry::upload(device, queue, "strands", &strand_vertices, &strand_indices);
        let uniforms = FrameUniforms::new(scene, &self.settings);
        self.encode_with(scene, &uniforms, hair.as_ref(), encoder);
    }

    /// Records the shadow and main passes of `scene`'s head with `hair`'s
    /// ribbons into `encoder`.
    fn encode_with(
        &self,
        scene: &Scene<'_>,
        uniforms: &FrameUniforms,
        hair: Option<&IndexedGeometry>,
        encoder: &mut wgpu::CommandEncoder,
    ) {
        let (device, queue) = (&self.gpu.device, &self.gpu.queue);
        let bindings = self.bindings(uniforms);
        let head = IndexedGeometry::upload(
            device,
            queue,
            "head",
            &head_vertices(scene.head),
            &scene.head.mesh.indices,
        );

        let t = &self.targets;
        let p = &self.pipelines;
        // Without shadows the light's passes only clear their targets.
        let shadow_hair = hair.filter(|_| self.settings.shadows);
        // Cleared to the far plane: no hair.
        let far = wgpu::Color {
            r: 1.0,
            g: 0.0,
            b: 0.0,
            a: 0.0,
        };
        let mut pass = begin(
            encoder,
            "shadow depth",
            Some((&t.light_depth, None, far)),
            Some(&t.light_depth_buffer),
        );
        if let Some(hair) = shadow_hair {
            pass.set_pipeline(&p.shadow_depth);
            pass.set_bind_group(0, &bindings.light, &[]);
            hair.draw(&mut pass);
        }
        drop(pass);
        let mut pass = begin(
            encoder,
            "shadow opacity",
            Some((&t.opacity, None, wgpu::Color::TRANSPARENT)),
            None,
        );
        if let Some(hair) = shadow_hair {
            pass.set_pipeline(&p.shadow_opacity);
            pass.set_bind_group(0, &bindings.light, &[]);
            pass.set_bind_group(1, &bindings.lighting, &[]);
            hair.draw(&mut pass);
        }
        drop(pass);
        let picture = t.picture.create_view(&Default::default());
        let colour = match &t.msaa_colour {
            Some(msaa) => (msaa, Some(&picture), wgpu::Color::BLACK),
            None => (&picture, None, wgpu::Color::BLACK),
        };
        let mut pass = begin(encoder, "main", Some(colour), Some(&t.main_depth));
        pass.set_bind_group(0, &bindings.camera, &[]);
        pass.set_bind_group(1, &bindings.lighting, &[]);
        pass.set_bind_group(2, &bindings.opacity, &[]);
        pass.set_pipeline(&p.backdrop);
        pass.draw(0..3, 0..1);
        for (pipeline, geometry) in [(&p.head, head.as_ref()), (&p.hair, hair)] {
            if let Some(geometry) = geometry {
                pass.set_pipeline(pipeline);
                geometry.draw(&mut pass);
            }
        }
        drop(pass);
    }
}

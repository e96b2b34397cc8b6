//! Painting egui's frame onto the window (and a screenshot), optionally
//! through the panels' cached layer ([`super::panel_layer`]).
//!
//! Without the cache every job is painted onto a cleared target, as egui
//! does. With it:
//!
//! 1. the jobs before the first 3D picture (the panels) are compared with
//!    last frame's, and only the rectangles where they differ are painted
//!    again into the layer texture (all of it after a resize, a change of
//!    egui's own textures, or anything not comparable);
//! 2. the layer is copied onto the target (a plain copy, no shading);
//! 3. the 3D pictures are copied on top where they can be (drawn at the
//!    view's size in the targets' byte order), else painted by egui;
//! 4. the rest of the overlay (what egui paints after the pictures: labels
//!    over the view, menus, tooltips) is painted on top.
//!
//! egui's renderer uploads one job list per frame and paints a prefix of
//! it, so all the frame's jobs go in one list: the layer's repaint jobs,
//! then the overlay's; the overlay's pass gets the repaint jobs with empty
//! clip rectangles, which the renderer steps over.

use egui::TextureId;
use egui::epaint::ClippedPrimitive;

use super::panel_layer::{damage, layer_len, picture_copy, repaint_jobs, skipped, to_whole_pixels};

/// A 3D picture as the painter sees it: its egui texture, and the
/// texture itself when it can be copied onto the targets (same byte order).
pub struct Picture {
    /// The egui texture showing it.
    pub id: TextureId,
    /// The picture, when copyable.
    pub texture: Option<wgpu::Texture>,
}

/// The panels' layer: a texture the size of the window and the jobs
/// painted into it.
struct Layer {
    texture: wgpu::Texture,
    size_px: [u32; 2],
    pixels_per_point: f32,
    jobs: Vec<ClippedPrimitive>,
}

/// egui's renderer and, when caching, the panels' layer.
pub struct EguiPainter {
    /// egui's wgpu renderer (textures are registered here).
    pub renderer: egui_wgpu::Renderer,
    device: wgpu::Device,
    queue: wgpu::Queue,
    format: wgpu::TextureFormat,
    cache: bool,
    layer: Option<Layer>,
    /// Pixels of the layer repainted in the last frame (for `--profile`).
    pub repainted_px: u64,
}

impl EguiPainter {
    /// A painter for targets of `format`; `cache` keeps the panels in a
    /// layer (the targets must then allow copies into them).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        format: wgpu::TextureFormat,
        cache: bool,
    ) -> Self {
        Self {
            renderer: egui_wgpu::Renderer::new(device, format, Default::default()),
            device: device.clone(),
            queue: queue.clone(),
            format,
            cache,
            layer: None,
            repainted_px: 0,
        }
    }

    /// Whether the panels are kept as a layer.
    pub fn caches(&self) -> bool {
        self.cache
    }

    /// Records the painting of `jobs` onto every one of `targets` into
    /// `encoder`; `pictures` are the 3D views' textures (where the overlay
    /// starts), `textures_changed` whether egui changed its own textures
    /// this frame (glyphs may have moved: everything is repainted). Returns
    /// the renderer's extra command buffers, to submit first.
    pub fn paint(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &[&wgpu::Texture],
        jobs: Vec<ClippedPrimitive>,
        screen: &egui_wgpu::ScreenDescriptor,
        pictures: &[Picture],
        textures_changed: bool,
    ) -> Vec<wgpu::CommandBuffer> {
        let (device, queue) = (&self.device, &self.queue);
        if !self.cache {
            let extra = self
                .renderer
                .update_buffers(device, queue, encoder, &jobs, screen);
            for target in targets {
                let view = target.create_view(&Default::default());
                self.pass(encoder, &view, &jobs, screen, true);
            }
            self.repainted_px = 0;
            return extra;
        }
        let ids: Vec<TextureId> = pictures.iter().map(|p| p.id).collect();
        let split = layer_len(&jobs, &ids);
        let (panels, overlay) = jobs.split_at(split);
        let ppp = screen.pixels_per_point;
        let copyable: Vec<(TextureId, [u32; 2])> = pictures
            .iter()
            .filter_map(|p| {
                let size = p.texture.as_ref()?.size();
                Some((p.id, [size.width, size.height]))
            })
            .collect();
        let mut copies = Vec::new();
        let overlay: Vec<ClippedPrimitive> = overlay
            .iter()
            .filter(|job| {
                let copy = picture_copy(job, &copyable, ppp, screen.size_in_pixels);
                copies.extend(copy);
                copy.is_none()
            })
            .cloned()
            .collect();
        let screen_pt = egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(
                screen.size_in_pixels[0] as f32,
                screen.size_in_pixels[1] as f32,
            ) / ppp,
        );
        let reusable = self.layer.as_ref().filter(|l| {
            l.size_px == screen.size_in_pixels && l.pixels_per_point == ppp && !textures_changed
        });
        let rects: Vec<egui::Rect> = match reusable {
            Some(layer) => damage(&layer.jobs, panels, screen_pt)
                .into_iter()
                .map(|r| to_whole_pixels(r, ppp).intersect(screen_pt))
                .filter(|r| r.is_positive())
                .collect(),
            None => vec![screen_pt],
        };
        self.repainted_px = rects
            .iter()
            .map(|r| (r.area() * ppp * ppp).round() as u64)
            .sum();
        let mut all = repaint_jobs(panels, &rects);
        let repaint = all.len();
        all.extend_from_slice(&overlay);
        let extra = self
            .renderer
            .update_buffers(device, queue, encoder, &all, screen);
        let layer = self.layer_for(screen, panels);
        let layer_view = layer.create_view(&Default::default());
        self.pass(encoder, &layer_view, &all[..repaint], screen, false);
        let on_top: Vec<ClippedPrimitive> = skipped(&all[..repaint])
            .chain(overlay.iter().cloned())
            .collect();
        for target in targets {
            encoder.copy_texture_to_texture(
                layer.as_image_copy(),
                target.as_image_copy(),
                layer.size(),
            );
            for &(index, [x, y], [width, height]) in &copies {
                let Some(picture) = pictures
                    .iter()
                    .find(|p| p.id == copyable[index].0)
                    .and_then(|p| p.texture.as_ref())
                else {
                    continue;
                };
                encoder.copy_texture_to_texture(
                    picture.as_image_copy(),
                    wgpu::TexelCopyTextureInfo {
                        origin: wgpu::Origin3d { x, y, z: 0 },
                        ..target.as_image_copy()
                    },
                    wgpu::Extent3d {
                        width,
                        height,
                        depth_or_array_layers: 1,
                    },
                );
            }
            let view = target.create_view(&Default::default());
            self.pass(encoder, &view, &on_top, screen, false);
        }
        extra
    }

    /// The layer's texture for this frame's size, made anew when the size
    /// changed; the layer remembers `panels` as what it will hold.
    fn layer_for(
        &mut self,
        screen: &egui_wgpu::ScreenDescriptor,
        panels: &[ClippedPrimitive],
    ) -> wgpu::Texture {
        let [width, height] = screen.size_in_pixels;
        let texture = match &self.layer {
            Some(layer) if layer.size_px == [width, height] => layer.texture.clone(),
            _ => self.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("egui panels"),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: self.format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            }),
        };
        self.layer = Some(Layer {
            texture: texture.clone(),
            size_px: [width, height],
            pixels_per_point: screen.pixels_per_point,
            jobs: panels.to_vec(),
        });
        texture
    }

    /// One pass painting `jobs` onto `view`, cleared to black first or
    /// painted over what it holds.
    fn pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        jobs: &[ClippedPrimitive],
        screen: &egui_wgpu::ScreenDescriptor,
        clear: bool,
    ) {
        let load = if clear {
            wgpu::LoadOp::Clear(wgpu::Color::BLACK)
        } else {
            wgpu::LoadOp::Load
        };
        let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("egui"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        self.renderer
            .render(&mut pass.forget_lifetime(), jobs, screen);
    }
}

#[cfg(test)]
#[path = "egui_paint_tests.rs"]
mod tests;

//! What one frame uploads: the uniforms computed from a scene, and indexed
//! geometry buffers.

use bytemuck::Pod;
use glam::Vec3;
use helixhair_gpu::upload_buffer;

use super::gpu_data::{Lighting, MeshVertex, View, mat, vec4};
use super::settings::RenderSettings;
use super::shadow::LightView;
use crate::mesh::HeadMesh;
use crate::scene::Scene;

/// Highlight shifts along the strand normal (R towards the root, TRT
/// towards the tip, as Marschner measured: a few degrees) and exponents
/// (R sharp, TRT broader).
const SPECULAR: [f32; 4] = [-0.08, 0.12, 90.0, 28.0];

/// The uniforms of one frame.
#[derive(Clone, Copy, Debug)]
pub struct FrameUniforms {
    /// The camera's view.
    pub camera: View,
    /// The light's view (for the shadow passes).
    pub light: View,
    /// Lights and materials.
    pub lighting: Lighting,
}

impl FrameUniforms {
    /// The uniforms that draw `scene` with `settings`.
    pub fn new(scene: &Scene<'_>, settings: &RenderSettings) -> Self {
        Self::within(scene, settings, scene.bounds_m())
    }

    /// [`Self::new`] with the light's view fitted to the box `(lo, hi)`
    /// (world, metres) instead of the scene's own bounds: for hair whose
    /// points are on the device and not read back.
    pub fn within(scene: &Scene<'_>, settings: &RenderSettings, (lo, hi): (Vec3, Vec3)) -> Self {
        let s = settings;
        let towards_light = scene.light.direction.normalize_or(Vec3::Y);
        let light_view = LightView::fit(towards_light, lo, hi);
        let ribbon = [scene.hair.root_width_m, scene.hair.tip_width_m, 0.0, 0.0];
        let aspect = s.aspect();
        // Focal length in pixels: clip y per metre at unit w, times half
        // the height.
        let camera_focal_px =
            scene.camera.clip_from_view(aspect).y_axis.y * s.height_px as f32 * 0.5;
        let shadow_px = s.shadow_map_px as f32;
        let light_clip = light_view.clip_from_world;
        let light_focal_px = light_clip.row(1).truncate().length() * shadow_px * 0.5;
        let l = &scene.light;
        Self {
            camera: View {
                clip_from_world: mat(scene.camera.clip_from_world(aspect)),
                eye: vec4(scene.camera.eye_m(), 1.0),
                viewport: [
                    s.width_px as f32,
                    s.height_px as f32,
                    camera_focal_px,
                    s.min_ribbon_px,
                ],
                ribbon,
            },
            light: View {
                clip_from_world: mat(light_clip),
                eye: vec4(towards_light, 0.0),
                viewport: [shadow_px, shadow_px, light_focal_px, 1.0],
                ribbon,
            },
            lighting: Lighting {
                light_clip_from_world: mat(light_clip),
                light_direction: vec4(towards_light, l.intensity),
                light_colour: vec4(l.colour, 0.0),
                ambient: vec4(l.ambient_colour, l.ambient_strength),
                shadow: [
                    s.shadow_layer_m,
                    s.strand_opacity,
                    light_view.depth_range_m,
                    0.0,
                ],
                scalp: vec4(scene.mean_hair_colour(), 0.0),
                specular: SPECULAR,
            },
        }
    }
}

/// A vertex buffer, an index buffer and the index count.
#[derive(Debug)]
pub struct IndexedGeometry {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    count: u32,
}

impl IndexedGeometry {
    /// Uploads `vertices` and `indices`; `None` when there is nothing to
    /// draw.
    pub fn upload<V: Pod>(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        label: &str,
        vertices: &[V],
        indices: &[u32],
    ) -> Option<Self> {
        if indices.is_empty() {
            return None;
        }
        let buffer = |contents: &[u8], usage| upload_buffer(device, queue, label, contents, usage);
        Some(Self {
            vertices: buffer(bytemuck::cast_slice(vertices), wgpu::BufferUsages::VERTEX),
            indices: buffer(bytemuck::cast_slice(indices), wgpu::BufferUsages::INDEX),
            count: indices.len() as u32,
        })
    }

    /// Geometry in buffers already on the device: `indices` holds `count`
    /// `u32` indices into `vertices`.
    pub fn from_buffers(vertices: wgpu::Buffer, indices: wgpu::Buffer, count: usize) -> Self {
        Self {
            vertices,
            indices,
            count: count as u32,
        }
    }

    /// Binds the buffers and draws every triangle.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.count, 0, 0..1);
    }
}

/// The head's vertices with their scalp weights.
pub fn head_vertices(head: &HeadMesh) -> Vec<MeshVertex> {
    let scalp = head.scalp_vertex_weights();
    let mesh = &head.mesh;
    (0..mesh.positions.len())
        .map(|i| MeshVertex {
            position_m: mesh.positions[i].to_array(),
            normal: mesh.normals.get(i).copied().unwrap_or(Vec3::Y).to_array(),
            scalp: scalp[i],
        })
        .collect()
}

//! The render pipelines and their bind group layouts.
//!
//! | pass | target | pipeline | bind groups |
//! | --- | --- | --- | --- |
//! | shadow depth | first-hair depth (`Rgba16Float`) + depth buffer | `shadow_depth`: ribbons writing their depth | view (light) |
//! | shadow opacity | four layers (`Rgba16Float`, additive) | `shadow_opacity` | view (light), lighting + light depth |
//! | main (4× MSAA, or 1 sample) | colour (`Rgba8UnormSrgb`) + depth | `backdrop`, `head`, `hair` (stochastic sample mask) | view (camera), lighting + light depth, opacity layers |
//!
//! Group 0 is always a [`View`](super::gpu_data::View), group 1 the
//! [`Lighting`](super::gpu_data::Lighting) with the light's depth texture,
//! group 2 the opacity layers and their sampler, as `shaders/common.wgsl`
//! declares them.

use super::gpu_data::{MeshVertex, StrandVertex, vertex_layout};
use super::settings::RenderSettings;
use super::shaders::{self, ShaderFile};

/// Depth format of the light's depth map and of the main pass.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Format of the light's first-hair depth, read back by later passes. Half
/// floats resolve depth to about 5e-4 of the light's depth range (a few
/// tenths of a millimetre over a head), well under the first opacity
/// layer; R32Float would be finer but GL cannot render to it.
pub const FIRST_DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Format of the four opacity layers.
pub const OPACITY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The bind group layouts of groups 0, 1 and 2.
#[derive(Debug)]
pub struct Layouts {
    /// Group 0: a `View` uniform.
    pub view: wgpu::BindGroupLayout,
    /// Group 1: the `Lighting` uniform and the light's depth texture.
    pub lighting: wgpu::BindGroupLayout,
    /// Group 2: the opacity layers and their sampler.
    pub opacity: wgpu::BindGroupLayout,
}

/// Every pipeline of a frame.
#[derive(Debug)]
pub struct Pipelines {
    /// The bind group layouts the pipelines use.
    pub layouts: Layouts,
    /// Hair depth from the light.
    pub shadow_depth: wgpu::RenderPipeline,
    /// Hair opacity layers from the light.
    pub shadow_opacity: wgpu::RenderPipeline,
    /// The backdrop.
    pub backdrop: wgpu::RenderPipeline,
    /// The head.
    pub head: wgpu::RenderPipeline,
    /// The hair.
    pub hair: wgpu::RenderPipeline,
}

fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn texture_entry(binding: u32, sample_type: wgpu::TextureSampleType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        // The hair is shaded per point, in the vertex shader.
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

impl Layouts {
    fn new(device: &wgpu::Device) -> Self {
        let layout = |label, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        Self {
            view: layout("view", &[uniform_entry(0)]),
            lighting: layout(
                "lighting",
                &[
                    uniform_entry(0),
                    texture_entry(1, wgpu::TextureSampleType::Float { filterable: false }),
                ],
            ),
            opacity: layout(
                "opacity",
                &[
                    texture_entry(0, wgpu::TextureSampleType::Float { filterable: true }),
                    wgpu::BindGroupLayoutEntry {
                        binding: 1,
                        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                        count: None,
                    },
                ],
            ),
        }
    }
}

/// What differs between the pipelines.
struct PipelineSpec<'a> {
    file: ShaderFile,
    vertex_entry: &'a str,
    fragment_entry: Option<&'a str>,
    groups: &'a [Option<&'a wgpu::BindGroupLayout>],
    buffer: Option<wgpu::VertexBufferLayout<'static>>,
    colour: Option<(wgpu::TextureFormat, Option<wgpu::BlendState>)>,
    depth: Option<(bool, wgpu::CompareFunction)>,
    samples: u32,
    alpha_to_coverage: bool,
    /// Pipeline-overridable constants of the shader (`SHADOWS`).
    constants: &'a [(&'a str, f64)],
}

fn pipeline(device: &wgpu::Device, spec: PipelineSpec<'_>) -> wgpu::RenderPipeline {
    let module = shaders::module(device, &spec.file);
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(spec.vertex_entry),
        bind_group_layouts: spec.groups,
        immediate_size: 0,
    });
    let buffers = [spec.buffer];
    let targets = [spec.colour.map(|(format, blend)| wgpu::ColorTargetState {
        format,
        blend,
        write_mask: wgpu::ColorWrites::ALL,
    })];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.vertex_entry),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(spec.vertex_entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: spec.constants,
                ..Default::default()
            },
            buffers: if buffers[0].is_some() { &buffers } else { &[] },
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: spec.depth.map(|(write, compare)| wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(write),
            depth_compare: Some(compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: wgpu::MultisampleState {
            count: spec.samples,
            mask: !0,
            alpha_to_coverage_enabled: spec.alpha_to_coverage,
        },
        fragment: spec.fragment_entry.map(|entry| wgpu::FragmentState {
            module: &module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: spec.constants,
                ..Default::default()
            },
            targets: if spec.colour.is_some() { &targets } else { &[] },
        }),
        multiview_mask: None,
        cache: None,
    })
}

impl Pipelines {
    /// Compiles every shader and builds every pipeline, the main pass's at
    /// `settings`' samples per pixel and picture format, reading the
    /// hair's shadow or not. Without `sample_mask` (GL cannot write it)
    /// hair coverage falls back to alpha to coverage.
    pub fn new(device: &wgpu::Device, sample_mask: bool, settings: &RenderSettings) -> Self {
        let shadows = [("SHADOWS", f64::from(u8::from(settings.shadows)))];
        let layouts = Layouts::new(device);
        let view = Some(&layouts.view);
        let lighting = Some(&layouts.lighting);
        let opacity = Some(&layouts.opacity);
        let additive = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let main = |file, vertex_entry, fragment_entry, buffer, depth, alpha_to_coverage| {
            pipeline(
                device,
                PipelineSpec {
                    file,
                    vertex_entry,
                    fragment_entry: Some(fragment_entry),
                    groups: &[view, lighting, opacity],
                    buffer,
                    colour: Some((settings.picture_format, None)),
                    depth: Some(depth),
                    samples: settings.msaa_samples,
                    alpha_to_coverage,
                    constants: &shadows,
                },
            )
        };
        let less = (true, wgpu::CompareFunction::Less);
        Self {
            shadow_depth: pipeline(
                device,
                PipelineSpec {
                    file: shaders::HAIR_SHADOW,
                    vertex_entry: "vs_shadow",
                    fragment_entry: Some("fs_first_depth"),
                    groups: &[view],
                    buffer: Some(vertex_layout::<StrandVertex>(&StrandVertex::ATTRIBUTES)),
                    colour: Some((FIRST_DEPTH_FORMAT, None)),
                    depth: Some(less),
                    samples: 1,
                    alpha_to_coverage: false,
                    constants: &[],
                },
            ),
            shadow_opacity: pipeline(
                device,
                PipelineSpec {
                    file: shaders::HAIR_SHADOW,
                    vertex_entry: "vs_shadow",
                    fragment_entry: Some("fs_opacity"),
                    groups: &[view, lighting],
                    buffer: Some(vertex_layout::<StrandVertex>(&StrandVertex::ATTRIBUTES)),
                    colour: Some((
                        OPACITY_FORMAT,
                        Some(wgpu::BlendState {
                            color: additive,
                            alpha: additive,
                        }),
                    )),
                    depth: None,
                    samples: 1,
                    alpha_to_coverage: false,
                    constants: &[],
                },
            ),
            backdrop: main(
                shaders::BACKDROP,
                "vs_backdrop",
                "fs_backdrop",
                None,
                (false, wgpu::CompareFunction::Always),
                false,
            ),
            head: main(
                shaders::HEAD,
                "vs_head",
                "fs_head",
                Some(vertex_layout::<MeshVertex>(&MeshVertex::ATTRIBUTES)),
                less,
                false,
            ),
            hair: main(
                shaders::HAIR,
                "vs_hair",
                if sample_mask {
                    "fs_hair"
                } else {
                    "fs_hair_alpha"
                },
                Some(vertex_layout::<StrandVertex>(&StrandVertex::ATTRIBUTES)),
                less,
                !sample_mask,
            ),
            layouts,
        }
    }
}

//! Drawn strands shaped by their guides on the device, before their
//! ribbons are built there ([`super::device_hair`]): the compute passes
//! `stage_guide_shapes` and `stage_shape` (`shaders/strand_shape.wgsl`),
//! whose CPU reference is [`crate::strand_shape`] (clumping, curls with a
//! phase and radius of their own, following the guides' blended shape;
//! the module docs say why).
//!
//! # The contract
//!
//! Besides the points ([`super::device_hair::DeviceStrands::points`], one
//! `vec4<f32>` per point, head coordinates), the pass reads
//! [`DeviceShaping::strains`]: one `f32` per curve, the mean magnitude of
//! its strains in m⁻¹ (what sets a curl's period,
//! [`crate::strand_shape::curl_period_m`]). [`DeviceShaping::curves`] gives
//! every curve's points, guides and drawn strands alike; a drawn strand
//! and a guide are never the same curve. It writes the shaped points ([`DeviceShaper::encode`] returns their buffer),
//! indexed as the points: the drawn strands' shaped points at their own
//! curves' ranges, which the ribbon pass then reads.

use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use helixhair_gpu::{bind_buffers, dispatch_dims, upload_buffer};

use super::shaders::STRAND_SHAPE;
use crate::strand_shape::{FOLLOW_POINTS, MAX_FOLLOW, Shaping};

/// What shapes the drawn strands (module docs).
#[derive(Clone, Copy, Debug)]
pub struct DeviceShaping<'a> {
    /// Each curve's mean strain magnitude, m⁻¹, one `f32` per curve.
    pub strains: &'a wgpu::Buffer,
    /// Every curve's points in the points buffer, in points.
    pub curves: &'a [Range<usize>],
    /// The curves of the guides [`Self::shapings`] name, by their index.
    pub guides: &'a [usize],
    /// Each drawn strand's curve (the ribbons' strands, in order).
    pub strands: &'a [usize],
    /// How each drawn strand is shaped, guides named by their place in
    /// [`Self::guides`].
    pub shapings: &'a [Shaping],
}

/// WGSL `ShapeParams`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct ShapeParamsGpu {
    strand_count: u32,
    guide_count: u32,
    pad: [u32; 2],
}

/// WGSL `ShapeStrand`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ShapeStrandGpu {
    /// The strand's curve.
    pub curve: u32,
    /// The guide it clumps onto, or `u32::MAX`.
    pub clump_guide: u32,
    /// How many guides it follows.
    pub follow_count: u32,
    /// Padding.
    pub pad0: u32,
    /// How far it clumps at the tip.
    pub clump_amount: f32,
    /// Its curl's phase, radians.
    pub phase_rad: f32,
    /// Its curl's radius factor.
    pub curl_scale: f32,
    /// Padding.
    pub pad1: f32,
    /// The guides it follows.
    pub follow_guide: [u32; 4],
    /// Their weights.
    pub follow_weight: [f32; 4],
}

const _: () = assert!(size_of::<ShapeStrandGpu>() == 64);
const _: () = assert!(MAX_FOLLOW == 4);

/// Why a layout cannot be shaped on the device.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum ShapeError {
    /// A strand follows more guides than the pass holds.
    #[error("a drawn strand follows {0} guides; the device pass holds {MAX_FOLLOW}")]
    TooManyFollowed(usize),
    /// A curve, guide or strand named that does not exist.
    #[error("drawn strand {0} names a curve or guide that does not exist")]
    Dangling(usize),
}

/// The shape table of drawn strands on `strands` (curves, of
/// `curve_count`) shaped as `shapings` say by `guide_curves`, checked:
/// what [`DeviceShaper::encode`] uploads, and refuses where this does.
pub fn shape_table(
    curve_count: usize,
    guide_curves: &[usize],
    strands: &[usize],
    shapings: &[Shaping],
) -> Result<Vec<ShapeStrandGpu>, ShapeError> {
    strands
        .iter()
        .zip(shapings)
        .enumerate()
        .map(|(i, (&curve, s))| {
            if s.follow.len() > MAX_FOLLOW {
                return Err(ShapeError::TooManyFollowed(s.follow.len()));
            }
            let named = s.clump.iter().map(|c| c.guide);
            let named = named.chain(s.follow.iter().map(|f| f.0));
            if curve >= curve_count
                || named.clone().any(|g| g >= guide_curves.len())
                || guide_curves.iter().any(|&c| c >= curve_count)
            {
                return Err(ShapeError::Dangling(i));
            }
            let mut follow_guide = [0u32; 4];
            let mut follow_weight = [0f32; 4];
            for (k, &(g, w)) in s.follow.iter().enumerate() {
                follow_guide[k] = g as u32;
                follow_weight[k] = w;
            }
            Ok(ShapeStrandGpu {
                curve: curve as u32,
                clump_guide: s.clump.map_or(u32::MAX, |c| c.guide as u32),
                follow_count: s.follow.len() as u32,
                pad0: 0,
                clump_amount: s.clump.map_or(0.0, |c| c.amount),
                phase_rad: s.clump.map_or(0.0, |c| c.phase_rad),
                curl_scale: s.clump.map_or(1.0, |c| c.curl_scale),
                pad1: 0.0,
                follow_guide,
                follow_weight,
            })
        })
        .collect()
}

/// What one built layout was made for.
#[derive(Debug)]
struct ShapeKey {
    curves: Vec<Range<usize>>,
    guides: Vec<usize>,
    strands: Vec<usize>,
    shapings: Vec<Shaping>,
    points: wgpu::Buffer,
    strains: wgpu::Buffer,
}

#[derive(Debug)]
struct ShapeBuilt {
    bind_group: wgpu::BindGroup,
    shaped: wgpu::Buffer,
    strand_count: u32,
    guide_count: u32,
}

/// The two passes and the buffers of one layout.
#[derive(Debug)]
pub struct DeviceShaper {
    group_layout: wgpu::BindGroupLayout,
    guide_pipeline: wgpu::ComputePipeline,
    shape_pipeline: wgpu::ComputePipeline,
    layout: Option<(ShapeKey, ShapeBuilt)>,
}

impl DeviceShaper {
    /// The passes' pipelines on `device` (one bind group layout for both).
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(STRAND_SHAPE.name),
            source: wgpu::ShaderSource::Wgsl(STRAND_SHAPE.source.into()),
        });
        let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..9)
            .map(|binding| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: match binding {
                        0 => wgpu::BufferBindingType::Uniform,
                        1..=5 => wgpu::BufferBindingType::Storage { read_only: true },
                        _ => wgpu::BufferBindingType::Storage { read_only: false },
                    },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            })
            .collect();
        let group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("strand shape"),
            entries: &entries,
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("strand shape"),
            bind_group_layouts: &[Some(&group_layout)],
            immediate_size: 0,
        });
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let (guide_pipeline, shape_pipeline) =
            (pipeline("stage_guide_shapes"), pipeline("stage_shape"));
        Self {
            group_layout,
            guide_pipeline,
            shape_pipeline,
            layout: None,
        }
    }

    /// Records both passes over `points` into `encoder` and returns the
    /// shaped points' buffer (module docs), or why the layout cannot be
    /// shaped here.
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        points: &wgpu::Buffer,
        shaping: &DeviceShaping<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<&wgpu::Buffer, ShapeError> {
        // Compared in place every frame; the table is made and checked
        // only when the layout changes.
        let same = self.layout.as_ref().is_some_and(|(k, _)| {
            k.curves == shaping.curves
                && k.guides == shaping.guides
                && k.strands == shaping.strands
                && k.shapings == shaping.shapings
                && k.points == *points
                && k.strains == *shaping.strains
        });
        if !same {
            let table = shape_table(
                shaping.curves.len(),
                shaping.guides,
                shaping.strands,
                shaping.shapings,
            )?;
            let built = self.build(device, queue, points, shaping, &table);
            let key = ShapeKey {
                curves: shaping.curves.to_vec(),
                guides: shaping.guides.to_vec(),
                strands: shaping.strands.to_vec(),
                shapings: shaping.shapings.to_vec(),
                points: points.clone(),
                strains: shaping.strains.clone(),
            };
            self.layout = Some((key, built));
        }
        let (_, built) = self.layout.as_ref().expect("built above");
        let limits = device.limits();
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("strand shape"),
            timestamp_writes: None,
        });
        pass.set_bind_group(0, &built.bind_group, &[]);
        for (pipeline, count) in [
            (&self.guide_pipeline, built.guide_count),
            (&self.shape_pipeline, built.strand_count),
        ] {
            if count == 0 {
                continue;
            }
            let (x, y) = dispatch_dims(&limits, count.div_ceil(64));
            pass.set_pipeline(pipeline);
            pass.dispatch_workgroups(x, y, 1);
        }
        drop(pass);
        Ok(&built.shaped)
    }

    fn build(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        points: &wgpu::Buffer,
        shaping: &DeviceShaping<'_>,
        table: &[ShapeStrandGpu],
    ) -> ShapeBuilt {
        let storage = wgpu::BufferUsages::STORAGE;
        let upload = |label: &str, bytes: &[u8], usage| {
            let bytes = if bytes.is_empty() {
                &[0u8; 16][..]
            } else {
                bytes
            };
            upload_buffer(device, queue, label, bytes, usage)
        };
        let params = ShapeParamsGpu {
            strand_count: table.len() as u32,
            guide_count: shaping.guides.len() as u32,
            pad: [0; 2],
        };
        let params_buffer = upload(
            "shape params",
            bytemuck::bytes_of(&params),
            wgpu::BufferUsages::UNIFORM,
        );
        let curves: Vec<[u32; 2]> = shaping
            .curves
            .iter()
            .map(|r| [r.start as u32, r.len() as u32])
            .collect();
        let guides: Vec<u32> = shaping.guides.iter().map(|&c| c as u32).collect();
        let curves_buffer = upload("shape curves", bytemuck::cast_slice(&curves), storage);
        let guides_buffer = upload("shape guides", bytemuck::cast_slice(&guides), storage);
        let table_buffer = upload("shape strands", bytemuck::cast_slice(table), storage);
        let point_bytes = points.size();
        let scratch = |label: &str, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(16),
                usage: storage | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        // Every value read from these is written first by the same frame's
        // passes: axes and shapes by `stage_guide_shapes` (guides) and
        // `stage_shape` (its own strand's), the shaped points by
        // `stage_shape`.
        let axes = scratch("shape axes", point_bytes);
        let shapes = scratch(
            "guide shapes",
            (shaping.guides.len() * FOLLOW_POINTS * 16) as u64,
        );
        let shaped = scratch("shaped points", point_bytes);
        let buffers = [
            &params_buffer,
            &curves_buffer,
            &guides_buffer,
            &table_buffer,
            points,
            shaping.strains,
            &axes,
            &shapes,
            &shaped,
        ];
        let bind_group = bind_buffers(device, "strand shape", &self.group_layout, &buffers);
        ShapeBuilt {
            bind_group,
            shaped,
            strand_count: params.strand_count,
            guide_count: params.guide_count,
        }
    }
}

//! The strands' centrelines written on the device that steps them, for a
//! renderer to draw from without a readback: [`CurveStage`], the GPU
//! engine's `stage_curves` (`shaders/physics/curves.wgsl`), and its CPU
//! twin [`stage_curves`].
//!
//! # How it works
//!
//! After a frame, one invocation per strand sweeps root to tip over the
//! state the step left in the engine's own `q` buffer: each element is cut
//! into the strand's [`CurveSampling`] count of equal pieces, and every
//! piece of one element is the same piece of helix turned by the frames
//! before it, so the sweep carries the frame across each piece
//! (R ← R exp([σ k]×), p ← p + R h(σ, k), the batch engine's
//! [`crate::batch::forward::advance`]) and writes the point at each
//! piece's start, then the tip.
//!
//! Layout of [`CurveStage::points`], the contract with a renderer: one
//! `vec4<f32>` per point (x, y, z in metres, head coordinates, w = 1),
//! strand after strand in the engine's strand order, strand s's points at
//! [`CurveStage::ranges`]`[s]`, root first. Head coordinates, because
//! drawing keeps hair out of the head in the head's frame and then poses
//! it, as the CPU's drawn hair does.
//!
//! Why a fixed count per strand: a GPU buffer cannot change size from
//! frame to frame, and the CPU's drawn curves
//! (`helixhair_app::hair::strain_blend::helix_polyline`) cut each element
//! by its current curl. The caller picks the counts, so both can cut by the
//! same rule (the natural curl is the one a drawn strand keeps).

use std::ops::Range;

use bytemuck::{Pod, Zeroable};

use super::kernels::{dispatch_dims, read_vec4, scratch_buffer, storage_buffer, submit_pass};
use super::{GpuContext, GpuError};
use crate::batch::forward::{FrameState, advance};
use crate::batch::layout::{BatchModel, RootMotion};
use crate::batch::vec::V3;
use crate::motion::{RigidMotion, RootPose};

/// Pieces per element each strand's curve is cut into (WGSL
/// `CurveStrand::samples`); zero reads as one.
pub type CurveSampling = Vec<u32>;

/// One strand's place in the points buffer (WGSL `CurveStrand`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct CurveStrandGpu {
    /// Index of the strand's root point in the points buffer.
    pub first_point: u32,
    /// Pieces each of its elements is cut into.
    pub samples: u32,
    /// Padding.
    pub pad: [u32; 2],
}

const _: () = assert!(size_of::<CurveStrandGpu>() == 16);

/// Points of a strand of `elements` elements cut `samples` times each.
pub fn curve_point_count(elements: usize, samples: u32) -> usize {
    elements * samples.max(1) as usize + 1
}

/// The curves' pipeline, table and points on the engine's device.
#[derive(Debug)]
pub struct CurveStage {
    sampling: CurveSampling,
    ranges: Vec<Range<usize>>,
    points: wgpu::Buffer,
    pipeline: wgpu::ComputePipeline,
    state_group: wgpu::BindGroup,
    curve_group: wgpu::BindGroup,
}

/// What [`CurveStage::new`] binds from the engine: its uniforms, strand
/// table, element constants and q, group 0 of `stage_curves`.
pub struct EngineBuffers<'a> {
    /// The step's uniforms (only `strand_count` is read).
    pub params: &'a wgpu::Buffer,
    /// The strands' table.
    pub strands: &'a wgpu::Buffer,
    /// The element constants (ℓ).
    pub elements: &'a wgpu::Buffer,
    /// The strains q.
    pub q: &'a wgpu::Buffer,
}

impl CurveStage {
    /// The stage for strands of `elements[s]` elements, each cut
    /// `sampling[s]` times, built from `module` (the engine's).
    pub fn new(
        ctx: &GpuContext,
        module: &wgpu::ShaderModule,
        buffers: &EngineBuffers<'_>,
        elements: &[usize],
        sampling: &[u32],
    ) -> Result<Self, GpuError> {
        assert_eq!(elements.len(), sampling.len(), "one count per strand");
        let mut table = Vec::with_capacity(elements.len());
        let mut ranges = Vec::with_capacity(elements.len());
        let mut next = 0usize;
        for (&n, &samples) in elements.iter().zip(sampling) {
            let count = curve_point_count(n, samples);
            table.push(CurveStrandGpu {
                first_point: next as u32,
                samples: samples.max(1),
                pad: [0; 2],
            });
            ranges.push(next..next + count);
            next += count;
        }
        let table_bytes: &[u8] = if table.is_empty() {
            &[0; size_of::<CurveStrandGpu>()]
        } else {
            bytemuck::cast_slice(&table)
        };
        let table_buffer = storage_buffer(ctx, "curve strands", table_bytes)?;
        // Every point is written by each dispatch before anything reads it.
        let points = scratch_buffer(ctx, "curve points", next.max(1) * 16)?;
        let device = &ctx.device;
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("stage_curves"),
            layout: None,
            module,
            entry_point: Some("stage_curves"),
            compilation_options: Default::default(),
            cache: None,
        });
        let group = |index: u32, buffers: &[&wgpu::Buffer]| {
            helixhair_gpu::bind_buffers(
                device,
                "stage_curves",
                &pipeline.get_bind_group_layout(index),
                buffers,
            )
        };
        let state_group = group(
            0,
            &[buffers.params, buffers.strands, buffers.elements, buffers.q],
        );
        let curve_group = group(1, &[&table_buffer, &points]);
        ctx.check()?;
        Ok(Self {
            sampling: sampling.to_vec(),
            ranges,
            points,
            pipeline,
            state_group,
            curve_group,
        })
    }

    /// The counts it was built for.
    pub fn sampling(&self) -> &[u32] {
        &self.sampling
    }

    /// Each strand's points in [`Self::points`], in points.
    pub fn ranges(&self) -> &[Range<usize>] {
        &self.ranges
    }

    /// The points (module docs for the layout).
    pub fn points(&self) -> &wgpu::Buffer {
        &self.points
    }

    /// Submits the stage over the engine's current state. Nothing waits.
    pub fn submit(&self, ctx: &GpuContext) {
        let dims = dispatch_dims(ctx, (self.ranges.len() as u32).div_ceil(64));
        let groups = [&self.state_group, &self.curve_group];
        submit_pass(ctx, "stage_curves", &groups, &[(&self.pipeline, dims)]);
    }

    /// Reads the points back (tests and tools; a renderer binds them).
    pub fn read_points(&self, ctx: &GpuContext) -> Result<Vec<[f32; 4]>, GpuError> {
        read_vec4(ctx, &self.points)
    }
}

/// WGSL `stage_curves` for one strand (`model` rooted at `root`, strains
/// `q`), cut `samples` times per element: the batch engine's sweep at f32,
/// one strand wide. Appends the points (head coordinates, w = 1).
pub fn stage_curves(
    model: &BatchModel,
    root: &RootPose,
    q: &[V3<f32>],
    samples: u32,
    out: &mut Vec<[f32; 4]>,
) {
    let at_rest = RigidMotion::at_rest(root.position_m, root.head_from_root);
    let motion: RootMotion<f32> = RootMotion::gather(std::slice::from_ref(&at_rest));
    let root_m = V3::<f32>::splat_f64(root.position_m.to_array());
    let pieces = samples.max(1);
    let mut s = FrameState::at_root(&motion);
    let point = |s: &FrameState<f32>| {
        let p = root_m + s.point_m;
        [p.x, p.y, p.z, 1.0]
    };
    for (e, &k) in q.iter().enumerate().take(model.elements()) {
        let piece_m = model.lengths_m[e] / pieces as f32;
        for _ in 0..pieces {
            out.push(point(&s));
            s = advance(&s, piece_m, k, V3::zero()).0;
        }
    }
    out.push(point(&s));
}

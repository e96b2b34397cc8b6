//! Centrelines written on the device that steps the strands, for a
//! renderer to draw from without a readback: [`CurveBlend`] (which curves),
//! [`CurveStage`] (the GPU engine's `stage_curves`,
//! `shaders/physics/curves.wgsl`) and its CPU twin [`stage_curves`].
//!
//! # What a curve is
//!
//! A strand grown from its own root frame (head coordinates) with its own
//! element lengths, whose element e bends by
//! k_e = base_e + Σ w · q\[element\] over the element's sources: the
//! engine's strains blended with weights. A simulated strand drawn as it
//! is has one source per element (its own, weight 1) and no base
//! ([`CurveBlend::engine_strands`]); a drawn strand between guides takes
//! each element from its guides' elements at the same fraction of length,
//! and an imported strand adds its own shape as the base. So the renderer's
//! drawn strands, not only the simulated ones, are swept where the strains
//! are.
//!
//! # How it works
//!
//! After a frame, one invocation per curve blends each element's strain
//! from the engine's own `q` buffer and sweeps root to tip: each element
//! is cut into the curve's count of equal pieces, and every piece of one
//! element is the same piece of helix turned by the frames before it, so
//! the sweep carries the frame across each piece
//! (R ← R exp([σ k]×), p ← p + R h(σ, k), the batch engine's
//! [`crate::batch::forward::advance`]) and writes the point at each
//! piece's start, then the tip.
//!
//! Layout of [`CurveStage::points`], the contract with a renderer: one
//! `vec4<f32>` per point (x, y, z in metres, head coordinates, w = 1),
//! curve after curve in the blend's order, curve c's points at
//! [`CurveStage::ranges`]`[c]`, root first; [`CurveStage::strains`] holds
//! one `f32` per curve, the mean of |k_e| over its elements in m⁻¹ (how
//! curled it is now: a helix of strains k turns once every 2π/|k| of arc).
//! Head coordinates, because drawing keeps hair out of the head in the
//! head's frame and then poses it, as the CPU's drawn hair does.
//!
//! Why a fixed count per curve: a GPU buffer cannot change size from
//! frame to frame. The caller picks the counts (a drawn strand's natural
//! curl is the one it keeps).

use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};

use bytemuck::{Pod, Zeroable};

use super::kernels::{
    at_least_one, dispatch_dims, read_pod, read_vec4, scratch_buffer, storage_buffer, submit_pass,
};
use super::layout::Mat3Gpu;
use super::{GpuContext, GpuError};
use crate::batch::forward::{FrameState, advance};
use crate::batch::layout::RootMotion;
use crate::batch::vec::V3;
use crate::motion::{RigidMotion, RootPose};

/// One curve (WGSL `CurveStrand`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct CurveStrandGpu {
    /// Index of the curve's root point in the points buffer.
    pub first_point: u32,
    /// Pieces each of its elements is cut into.
    pub samples: u32,
    /// Its first element in the element table.
    pub first_element: u32,
    /// Its element count.
    pub elements: u32,
    /// Root point, head coordinates, m (w unused).
    pub root_m: [f32; 4],
    /// Root frame, head coordinates.
    pub head_from_root: Mat3Gpu,
}

/// One element of a curve (WGSL `CurveElement`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct CurveElementGpu {
    /// xyz: the strain added to the blend, m⁻¹; w: the element's length,
    /// m.
    pub base_length: [f32; 4],
    /// Its first source in the source table.
    pub first_source: u32,
    /// Its source count.
    pub source_count: u32,
    /// Padding.
    pub pad: [u32; 2],
}

/// One source of an element's strain (WGSL `CurveSource`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct CurveSourceGpu {
    /// The engine's element (index into its state, over all strands).
    pub element: u32,
    /// Its weight.
    pub weight: f32,
}

const _: () = assert!(size_of::<CurveStrandGpu>() == 80);
const _: () = assert!(size_of::<CurveElementGpu>() == 32);
const _: () = assert!(size_of::<CurveSourceGpu>() == 8);

/// Points of a curve of `elements` elements cut `samples` times each.
pub fn curve_point_count(elements: usize, samples: u32) -> usize {
    elements * samples.max(1) as usize + 1
}

/// The curves [`CurveStage`] writes (module docs): built once per layout
/// and handed in every frame.
#[derive(Clone, Debug)]
pub struct CurveBlend {
    strands: Vec<CurveStrandGpu>,
    elements: Vec<CurveElementGpu>,
    sources: Vec<CurveSourceGpu>,
    ranges: Vec<Range<usize>>,
    /// Which build this is: new at every change, kept by a clone, so the
    /// stage knows the blend it holds without comparing its tables (a
    /// groom's are megabytes) every frame.
    id: u64,
}

/// A new [`CurveBlend::id`].
fn next_blend_id() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

impl Default for CurveBlend {
    fn default() -> Self {
        Self {
            strands: Vec::new(),
            elements: Vec::new(),
            sources: Vec::new(),
            ranges: Vec::new(),
            id: next_blend_id(),
        }
    }
}

impl PartialEq for CurveBlend {
    /// The same curves: the same build, or equal tables.
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
            || (self.strands == other.strands
                && self.elements == other.elements
                && self.sources == other.sources)
    }
}

/// One element of a curve being pushed: its length (m), the strain added
/// to the blend (m⁻¹) and its sources (engine element, weight).
pub struct BlendElement<S> {
    /// Element length, m.
    pub length_m: f64,
    /// Strain added to the blend, m⁻¹.
    pub base: glam::DVec3,
    /// (engine element over all strands, weight).
    pub sources: S,
}

impl CurveBlend {
    /// Every strand of an engine drawn as it is, strand s cut
    /// `sampling[s]` times per element: `roots[s]` and `lengths_m[s]` are
    /// the engine's own, and its elements follow one another in the
    /// engine's state.
    pub fn engine_strands(roots: &[RootPose], lengths_m: &[&[f64]], sampling: &[u32]) -> Self {
        let mut blend = Self::default();
        let mut first = 0u32;
        for ((root, lengths), &samples) in roots.iter().zip(lengths_m).zip(sampling) {
            blend.push_strand(root, lengths, samples, first);
            first += lengths.len() as u32;
        }
        blend
    }

    /// Adds an engine strand drawn as it is: grown from `root` with
    /// `lengths_m`, its elements the engine's from `first_element` on,
    /// each cut `samples` times; returns its index.
    pub fn push_strand(
        &mut self,
        root: &RootPose,
        lengths_m: &[f64],
        samples: u32,
        first_element: u32,
    ) -> usize {
        let own = lengths_m
            .iter()
            .enumerate()
            .map(|(e, &length_m)| BlendElement {
                length_m,
                base: glam::DVec3::ZERO,
                sources: [(first_element + e as u32, 1.0)],
            });
        self.push(root, samples, own)
    }

    /// Adds a curve grown from `root`, each element cut `samples` times;
    /// returns its index.
    pub fn push<S: IntoIterator<Item = (u32, f32)>>(
        &mut self,
        root: &RootPose,
        samples: u32,
        elements: impl IntoIterator<Item = BlendElement<S>>,
    ) -> usize {
        let first_element = self.elements.len();
        for element in elements {
            let first_source = self.sources.len();
            self.sources.extend(
                element
                    .sources
                    .into_iter()
                    .map(|(element, weight)| CurveSourceGpu { element, weight }),
            );
            let b = element.base.as_vec3();
            self.elements.push(CurveElementGpu {
                base_length: [b.x, b.y, b.z, element.length_m as f32],
                first_source: first_source as u32,
                source_count: (self.sources.len() - first_source) as u32,
                pad: [0; 2],
            });
        }
        self.id = next_blend_id();
        let elements = self.elements.len() - first_element;
        let first_point = self.ranges.last().map_or(0, |r| r.end);
        let samples = samples.max(1);
        self.ranges
            .push(first_point..first_point + curve_point_count(elements, samples));
        let f4 = |v: glam::DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
        let m = root.head_from_root;
        self.strands.push(CurveStrandGpu {
            first_point: first_point as u32,
            samples,
            first_element: first_element as u32,
            elements: elements as u32,
            root_m: f4(root.position_m),
            head_from_root: [f4(m.x_axis), f4(m.y_axis), f4(m.z_axis)],
        });
        self.strands.len() - 1
    }

    /// Number of curves.
    pub fn len(&self) -> usize {
        self.strands.len()
    }

    /// Whether it has no curve.
    pub fn is_empty(&self) -> bool {
        self.strands.is_empty()
    }

    /// Each curve's points in the points buffer, in points.
    pub fn ranges(&self) -> &[Range<usize>] {
        &self.ranges
    }

    /// The highest engine element any source reads, plus one.
    pub fn elements_read(&self) -> usize {
        self.sources
            .iter()
            .map(|s| s.element as usize + 1)
            .max()
            .unwrap_or(0)
    }
}

/// The curves' pipeline, tables and outputs on the engine's device.
#[derive(Debug)]
pub struct CurveStage {
    blend: CurveBlend,
    points: wgpu::Buffer,
    strains: wgpu::Buffer,
    pipeline: wgpu::ComputePipeline,
    state_group: wgpu::BindGroup,
    curve_group: wgpu::BindGroup,
}

impl CurveStage {
    /// The stage writing `blend`'s curves from `q` (the engine's strains,
    /// `engine_elements` of them), built from `module` (the engine's).
    pub fn new(
        ctx: &GpuContext,
        module: &wgpu::ShaderModule,
        q: &wgpu::Buffer,
        engine_elements: usize,
        blend: &CurveBlend,
    ) -> Result<Self, GpuError> {
        if blend.elements_read() > engine_elements {
            return Err(GpuError::CurveSource {
                element: blend.elements_read() - 1,
                engine_elements,
            });
        }
        let strands = storage_buffer(ctx, "curve strands", &at_least_one(&blend.strands))?;
        let elements = storage_buffer(ctx, "curve elements", &at_least_one(&blend.elements))?;
        let sources = storage_buffer(ctx, "curve sources", &at_least_one(&blend.sources))?;
        let point_count = blend.ranges.last().map_or(0, |r| r.end);
        // Every point and strain is written by each dispatch before
        // anything reads it; the strains' length is the curve count.
        let points = scratch_buffer(ctx, "curve points", point_count.max(1) * 16)?;
        let strains = scratch_buffer(ctx, "curve strains", blend.len().max(1) * 4)?;
        let device = &ctx.device;
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("stage_curves"),
            layout: None,
            module,
            entry_point: Some("stage_curves"),
            compilation_options: Default::default(),
            cache: None,
        });
        // Of the engine's group 0 the stage reads only q (binding 3).
        let state_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("stage_curves q"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 3,
                resource: q.as_entire_binding(),
            }],
        });
        let curve_group = helixhair_gpu::bind_buffers(
            device,
            "stage_curves",
            &pipeline.get_bind_group_layout(1),
            &[&strands, &elements, &sources, &points, &strains],
        );
        ctx.check()?;
        Ok(Self {
            blend: blend.clone(),
            points,
            strains,
            pipeline,
            state_group,
            curve_group,
        })
    }

    /// The curves it was built for.
    pub fn blend(&self) -> &CurveBlend {
        &self.blend
    }

    /// Whether it writes `blend`'s curves: the same build at once, or
    /// equal tables, after which it takes `blend`'s build as its own (a
    /// layout made again the same is compared once, not every frame).
    pub fn holds(&mut self, blend: &CurveBlend) -> bool {
        if self.blend.id == blend.id {
            return true;
        }
        let same = self.blend == *blend;
        if same {
            self.blend.id = blend.id;
        }
        same
    }

    /// Each curve's points in [`Self::points`], in points.
    pub fn ranges(&self) -> &[Range<usize>] {
        self.blend.ranges()
    }

    /// The points (module docs for the layout).
    pub fn points(&self) -> &wgpu::Buffer {
        &self.points
    }

    /// Each curve's mean strain magnitude, m⁻¹, one `f32` per curve.
    pub fn strains(&self) -> &wgpu::Buffer {
        &self.strains
    }

    /// Submits the stage over the engine's current state. Nothing waits.
    pub fn submit(&self, ctx: &GpuContext) {
        if self.blend.is_empty() {
            return;
        }
        let dims = dispatch_dims(ctx, (self.blend.len() as u32).div_ceil(64));
        let groups = [&self.state_group, &self.curve_group];
        submit_pass(ctx, "stage_curves", &groups, &[(&self.pipeline, dims)]);
    }

    /// Reads the points back (tests and tools; a renderer binds them).
    pub fn read_points(&self, ctx: &GpuContext) -> Result<Vec<[f32; 4]>, GpuError> {
        read_vec4(ctx, &self.points)
    }

    /// Reads the mean strains back (tests and tools).
    pub fn read_strains(&self, ctx: &GpuContext) -> Result<Vec<f32>, GpuError> {
        read_pod(ctx, &self.strains)
    }
}

/// WGSL `stage_curves` for curve `c` of `blend` over the engine's strains
/// `q` (one `[k, 0]` per element, all strands): the blend in the same
/// order, then the batch engine's sweep at f32, one curve wide. Appends
/// the points (head coordinates, w = 1) and returns the mean strain
/// magnitude, m⁻¹.
pub fn stage_curves(blend: &CurveBlend, c: usize, q: &[[f32; 4]], out: &mut Vec<[f32; 4]>) -> f32 {
    let cs = &blend.strands[c];
    let col = |i: usize| {
        let a = cs.head_from_root[i];
        glam::DVec3::new(a[0].into(), a[1].into(), a[2].into())
    };
    let frame = glam::DMat3::from_cols(col(0), col(1), col(2));
    let at_rest = RigidMotion::at_rest(glam::DVec3::ZERO, frame);
    let motion: RootMotion<f32> = RootMotion::gather(std::slice::from_ref(&at_rest));
    let root_m = V3::new(cs.root_m[0], cs.root_m[1], cs.root_m[2]);
    let pieces = cs.samples.max(1);
    let mut s = FrameState::at_root(&motion);
    let point = |s: &FrameState<f32>| {
        let p = root_m + s.point_m;
        [p.x, p.y, p.z, 1.0]
    };
    let mut strain_sum = 0.0f32;
    let first = cs.first_element as usize;
    for element in &blend.elements[first..first + cs.elements as usize] {
        let [bx, by, bz, length_m] = element.base_length;
        let mut k = V3::new(bx, by, bz);
        let first_source = element.first_source as usize;
        for source in &blend.sources[first_source..first_source + element.source_count as usize] {
            let [x, y, z, _] = q[source.element as usize];
            k += V3::new(x, y, z).scale(source.weight);
        }
        strain_sum += (k.x * k.x + k.y * k.y + k.z * k.z).sqrt();
        let piece_m = length_m / pieces as f32;
        for _ in 0..pieces {
            out.push(point(&s));
            s = advance(&s, piece_m, k, V3::zero()).0;
        }
    }
    out.push(point(&s));
    strain_sum / cs.elements.max(1) as f32
}

//! [`GpuSystem`]: one group of strands stepped by the velocity-explicit
//! Dense kernel in `shaders/physics/` (`common.wgsl` + `group.wgsl` +
//! `chain.wgsl` + `dense.wgsl`), and the buffer, dispatch and readback
//! helpers both GPU paths use. Exact and Block-diagonal run on the GPU
//! engine's step ([`super::engine`]).
//!
//! How it works. The state (q, q̇ as vec4 per element) and the per-element
//! scratch live in storage buffers; each substep writes the uniforms (step,
//! gravity, the head's motion at that instant) and submits the stage
//! dispatches: `stage_frames` (per strand), `stage_elements` (per
//! element) and `stage_dense` (a workgroup per strand, see
//! [`super::dense_kernels`]).
//! Nothing is read back in the frame loop: [`GpuSystem::read_state`] exists
//! for tests and tools, and a renderer binds [`GpuSystem::frames_buffer`]
//! directly:
//! its `point_m` members are the element boundary points relative to each
//! root, so a vertex or compute pass can build the strand polylines on the
//! GPU (see `docs/gpu.md`).

use std::borrow::Cow;

use helixhair_gpu::upload_buffer;

use super::dense_kernels::{self, DENSE_WGSL};
use super::layout::Span;
use super::layout::{ElementConstGpu, ParamsGpu, RootPoseGpu};
use super::{GpuContext, GpuError};
use crate::model::StrandModel;
use crate::motion::{HeadTrajectory, RigidMotion, RootPose};
use crate::params::StrandParams;
use crate::settings::{Method, SimSettings};

/// `shaders/physics/common.wgsl`: structs and the arithmetic shared by the kernels.
pub const COMMON_WGSL: &str = include_str!("../../../../shaders/physics/common.wgsl");
/// `shaders/physics/group.wgsl`: the uniform group's parameters, roots and
/// own sums, which the kernels of [`GpuSystem`] share (the engine's step,
/// [`super::engine`], reads each strand's own constants instead).
pub const GROUP_WGSL: &str = include_str!("../../../../shaders/physics/group.wgsl");
/// `shaders/physics/chain.wgsl`: the bindings and the `stage_frames`
/// stage of the Dense kernel (which sets `LOCAL_MOMENTS`).
pub const CHAIN_WGSL: &str = include_str!("../../../../shaders/physics/chain.wgsl");

/// The full source of `method`'s kernel module on [`GpuSystem`]: the
/// common part, the uniform group's, the frame chain, then the kernel.
/// Only Dense has one (Exact and Block-diagonal are the GPU engine's,
/// [`super::engine::engine_source`]).
pub fn kernel_source(method: Method) -> Option<String> {
    (method == Method::Dense)
        .then(|| format!("{COMMON_WGSL}\n{GROUP_WGSL}\n{CHAIN_WGSL}\n{DENSE_WGSL}"))
}

const WORKGROUP: u32 = 64;

/// A state read back: (q, q̇), one vec4 per element, strand-major.
pub type GpuState = crate::batch::FlatState;

fn f4(v: glam::DVec3) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, 0.0]
}

fn mat(m: glam::DMat3) -> [[f32; 4]; 3] {
    [f4(m.x_axis), f4(m.y_axis), f4(m.z_axis)]
}

/// Strands of one group stepped on the GPU.
#[derive(Debug)]
pub struct GpuSystem {
    ctx: GpuContext,
    settings: SimSettings,
    params: ParamsGpu,
    elements: Vec<ElementConstGpu>,
    roots: Vec<RootPoseGpu>,
    params_buffer: wgpu::Buffer,
    q_buffer: wgpu::Buffer,
    v_buffer: wgpu::Buffer,
    scratch: Vec<wgpu::Buffer>,
    bind_group: wgpu::BindGroup,
    stages: Vec<(wgpu::ComputePipeline, Span)>,
    time_secs: f64,
}

impl GpuSystem {
    /// Uploads strands sharing `params`, one per root, at rest in their
    /// natural shape, and builds the Dense kernel (`settings.method` must
    /// be Dense).
    pub fn new(
        ctx: GpuContext,
        settings: &SimSettings,
        params: &StrandParams,
        roots: &[RootPose],
    ) -> Result<Self, GpuError> {
        settings.validate()?;
        let source = kernel_source(settings.method).ok_or_else(|| GpuError::UnsupportedMethod {
            method: settings.method.label(),
            runs: "`dense` (Exact and Block-diagonal run on the GPU engine, `GpuEngine`)",
        })?;
        let model = StrandModel::new(params, settings.quadrature_points)?;
        let n = model.elements();
        dense_kernels::check(n, &ctx.limits)?;
        let elements: Vec<ElementConstGpu> = (0..n)
            .map(|e| {
                let mut stiffness_length = f4(model.stiffness[e]);
                stiffness_length[3] = model.lengths_m[e] as f32;
                let mut natural_friction = f4(model.natural[e]);
                natural_friction[3] = model.friction[e] as f32;
                ElementConstGpu {
                    stiffness_length,
                    natural_friction,
                }
            })
            .collect();
        let roots_gpu: Vec<RootPoseGpu> = roots
            .iter()
            .map(|r| RootPoseGpu {
                position_m: f4(r.position_m),
                head_from_root: mat(r.head_from_root),
            })
            .collect();
        let mut nodes = [[0.0; 4]; 2];
        let mut weights = [[0.0; 4]; 2];
        for (i, (x, w)) in model
            .quadrature
            .nodes
            .iter()
            .zip(&model.quadrature.weights)
            .enumerate()
        {
            nodes[i / 4][i % 4] = *x as f32;
            weights[i / 4][i % 4] = *w as f32;
        }
        let h = settings.substep_secs();
        let gpu_params = ParamsGpu {
            strand_count: roots.len() as u32,
            elements: n as u32,
            points: model.quadrature.len() as u32,
            pad0: 0,
            h_secs: h as f32,
            mass_per_length: model.mass_per_length as f32,
            air_drag: model.air_drag as f32,
            mass_scale: (1.0 + h * model.air_drag / model.mass_per_length) as f32,
            gravity_m_per_s2: f4(settings.gravity_m_per_s2),
            air_velocity_m_per_s: f4(settings.air_velocity_m_per_s),
            nodes,
            weights,
            head_rotation: mat(glam::DMat3::IDENTITY),
            head_angular_velocity: [0.0; 4],
            head_angular_acceleration: [0.0; 4],
            head_velocity: [0.0; 4],
            head_acceleration: [0.0; 4],
        };
        let count = roots.len() * n;
        let natural: Vec<[f32; 4]> = (0..count).map(|i| f4(model.natural[i % n])).collect();
        let zero = vec![[0.0f32; 4]; count];
        let device = &ctx.device;
        let params_buffer = uniform_buffer(&ctx, "params", bytemuck::bytes_of(&gpu_params))?;
        let elements_buffer = storage_buffer(&ctx, "elements", bytemuck::cast_slice(&elements))?;
        let roots_buffer = storage_buffer(&ctx, "roots", bytemuck::cast_slice(&roots_gpu))?;
        let q_buffer = storage_buffer(&ctx, "q", bytemuck::cast_slice(&natural))?;
        let v_buffer = storage_buffer(&ctx, "v", bytemuck::cast_slice(&zero))?;
        let scratch = dense_kernels::scratch_sizes(n)
            .iter()
            .map(|(label, size)| scratch_buffer(&ctx, label, size * count.max(1)))
            .collect::<Result<Vec<_>, _>>()?;
        let buffers: Vec<&wgpu::Buffer> = [
            &params_buffer,
            &elements_buffer,
            &roots_buffer,
            &q_buffer,
            &v_buffer,
        ]
        .into_iter()
        .chain(scratch.iter())
        .collect();
        let (bind_group, pipeline_layout) = bind_all(device, "physics", &buffers, |b| b <= 2);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(settings.method.name()),
            source: wgpu::ShaderSource::Wgsl(Cow::Owned(source)),
        });
        let stages = dense_kernels::STAGES
            .iter()
            .map(|(name, span)| {
                let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(name),
                    layout: Some(&pipeline_layout),
                    module: &module,
                    entry_point: Some(name),
                    compilation_options: Default::default(),
                    cache: None,
                });
                (pipeline, *span)
            })
            .collect();
        Ok(Self {
            settings: settings.clone(),
            params: gpu_params,
            elements,
            roots: roots_gpu,
            params_buffer,
            q_buffer,
            v_buffer,
            scratch,
            bind_group,
            stages,
            time_secs: 0.0,
            ctx,
        })
    }

    /// The uniforms of a step taken while the head moves as `head`.
    pub fn params_at(&self, head: &RigidMotion) -> ParamsGpu {
        ParamsGpu {
            head_rotation: mat(head.world_from_body),
            head_angular_velocity: f4(head.angular_velocity_rad_per_s),
            head_angular_acceleration: f4(head.angular_acceleration_rad_per_s2),
            head_velocity: f4(head.velocity_m_per_s),
            head_acceleration: f4(head.acceleration_m_per_s2),
            ..self.params
        }
    }

    /// Per-element constants as uploaded (binding 1).
    pub fn element_constants(&self) -> &[ElementConstGpu] {
        &self.elements
    }

    /// Roots as uploaded (binding 2).
    pub fn roots(&self) -> &[RootPoseGpu] {
        &self.roots
    }

    /// The adapter's name.
    pub fn adapter_name(&self) -> &str {
        &self.ctx.adapter_name
    }

    /// Simulated time in seconds.
    pub fn time_secs(&self) -> f64 {
        self.time_secs
    }

    /// Number of strands.
    pub fn strand_count(&self) -> usize {
        self.roots.len()
    }

    /// Elements per strand.
    pub fn elements(&self) -> usize {
        self.elements.len()
    }

    /// Bytes of GPU memory per strand (state and scratch).
    pub fn bytes_per_strand(&self) -> usize {
        let per_element = 2 * 16
            + self
                .scratch
                .iter()
                .map(|b| b.size() as usize)
                .sum::<usize>()
                / (self.roots.len() * self.elements.len()).max(1);
        per_element * self.elements.len() + size_of::<RootPoseGpu>()
    }

    /// The frame state buffer (binding 5: one [`super::layout::FrameGpu`] per element,
    /// strand-major), for a renderer to read points from on the GPU.
    pub fn frames_buffer(&self) -> &wgpu::Buffer {
        &self.scratch[0]
    }

    /// The state buffers (q, q̇), one vec4 per element, strand-major.
    pub fn state_buffers(&self) -> (&wgpu::Buffer, &wgpu::Buffer) {
        (&self.q_buffer, &self.v_buffer)
    }

    /// Uploads a state (one vec4 per element, strand-major).
    pub fn set_state(&self, q: &[[f32; 4]], v: &[[f32; 4]]) {
        self.ctx
            .queue
            .write_buffer(&self.q_buffer, 0, bytemuck::cast_slice(q));
        self.ctx
            .queue
            .write_buffer(&self.v_buffer, 0, bytemuck::cast_slice(v));
    }

    fn dispatch_size(&self, span: Span) -> (u32, u32) {
        let strands = self.roots.len() as u32;
        let groups = match span {
            Span::PerStrand => strands.div_ceil(WORKGROUP),
            Span::PerElement => (strands * self.elements.len() as u32).div_ceil(WORKGROUP),
            Span::WorkgroupPerStrand => strands,
        };
        dispatch_dims(&self.ctx, groups)
    }

    /// Advances one frame: `substeps` submissions of the stage dispatches,
    /// the head's motion sampled at the start of each. No readback.
    pub fn step_frame(&mut self, head: &dyn HeadTrajectory) {
        let h = self.settings.substep_secs();
        for _ in 0..self.settings.substeps {
            let params = self.params_at(&head.motion_at(self.time_secs));
            let stages: Vec<_> = self
                .stages
                .iter()
                .map(|(pipeline, span)| (pipeline, self.dispatch_size(*span)))
                .collect();
            submit_step(
                &self.ctx,
                (&self.params_buffer, bytemuck::bytes_of(&params)),
                &self.bind_group,
                &stages,
            );
            self.time_secs += h;
        }
    }

    /// Waits for every submitted step to finish (for timing).
    pub fn wait(&self) -> Result<(), GpuError> {
        wait(&self.ctx)
    }

    /// Reads (q, q̇) back: one vec4 per element, strand-major. For tests and
    /// tools, not the frame loop.
    pub fn read_state(&self) -> Result<GpuState, GpuError> {
        Ok((
            read_vec4(&self.ctx, &self.q_buffer)?,
            read_vec4(&self.ctx, &self.v_buffer)?,
        ))
    }
}

/// Waits for every submission on `ctx` to finish; a lost device or a failed
/// operation (recorded by the context, not panicked on) fails the wait, so
/// no state read after it is trusted.
pub(crate) fn wait(ctx: &GpuContext) -> Result<(), GpuError> {
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    ctx.check()?;
    Ok(())
}

/// Copies `buffer` (vec4s of f32) back to the CPU through a staging buffer.
pub(crate) fn read_vec4(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
) -> Result<Vec<[f32; 4]>, GpuError> {
    read_pod(ctx, buffer)
}

/// Copies `buffer` (items of `T`) back to the CPU through a staging
/// buffer.
pub(crate) fn read_pod<T: bytemuck::Pod>(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
) -> Result<Vec<T>, GpuError> {
    let bytes = helixhair_gpu::read_bytes(&ctx.device, &ctx.queue, buffer);
    // A lost device or a failed operation first: a readback error is then
    // only its consequence.
    ctx.check()?;
    let bytes = bytes.map_err(GpuError::Readback)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

/// The bytes of `items`, or of one zeroed item where there are none: a
/// storage binding holds at least one element.
pub(crate) fn at_least_one<T: bytemuck::Pod>(items: &[T]) -> std::borrow::Cow<'_, [u8]> {
    if items.is_empty() {
        std::borrow::Cow::Owned(vec![0; size_of::<T>()])
    } else {
        std::borrow::Cow::Borrowed(bytemuck::cast_slice(items))
    }
}

/// The bind group of a kernel whose binding 0 is a uniform buffer and
/// bindings 1.. storage buffers (read-only where `read_only(binding)`),
/// `buffers` in binding order, with the pipeline layout of that one group.
pub(crate) fn bind_all(
    device: &wgpu::Device,
    label: &str,
    buffers: &[&wgpu::Buffer],
    read_only: impl Fn(u32) -> bool,
) -> (wgpu::BindGroup, wgpu::PipelineLayout) {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..buffers.len() as u32)
        .map(|binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: if binding == 0 {
                    wgpu::BufferBindingType::Uniform
                } else {
                    wgpu::BufferBindingType::Storage {
                        read_only: read_only(binding),
                    }
                },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        })
        .collect();
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &entries,
    });
    let bind_group = helixhair_gpu::bind_buffers(device, label, &layout, buffers);
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    (bind_group, pipeline_layout)
}

/// Writes a step's uniforms (`buffer`, `bytes`) and submits one compute
/// pass of `stages` (each pipeline with its workgroup counts along x and
/// y) over `bind_group`. Nothing waits.
pub(crate) fn submit_step(
    ctx: &GpuContext,
    (buffer, bytes): (&wgpu::Buffer, &[u8]),
    bind_group: &wgpu::BindGroup,
    stages: &[(&wgpu::ComputePipeline, (u32, u32))],
) {
    ctx.queue.write_buffer(buffer, 0, bytes);
    submit_pass(ctx, "step", &[bind_group], stages);
}

/// Submits one compute pass of `stages` (each pipeline with its
/// workgroup counts along x and y) with `bind_groups` bound as groups 0,
/// 1, …. Nothing waits.
pub(crate) fn submit_pass(
    ctx: &GpuContext,
    label: &str,
    bind_groups: &[&wgpu::BindGroup],
    stages: &[(&wgpu::ComputePipeline, (u32, u32))],
) {
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes: None,
        });
        for (index, group) in bind_groups.iter().enumerate() {
            pass.set_bind_group(index as u32, *group, &[]);
        }
        for (pipeline, (x, y)) in stages {
            pass.set_pipeline(pipeline);
            pass.dispatch_workgroups(*x, *y, 1);
        }
    }
    ctx.queue.submit([encoder.finish()]);
}

/// Workgroup counts (x, y) for `groups` workgroups (at least one), split
/// over y past the device's per-dimension limit (the kernels' `flat_index`
/// reads them back as one index).
pub(crate) fn dispatch_dims(ctx: &GpuContext, groups: u32) -> (u32, u32) {
    helixhair_gpu::dispatch_dims(&ctx.limits, groups)
}

/// Refuses a buffer of `bytes` larger than one storage binding may be.
fn check_size(ctx: &GpuContext, what: &'static str, bytes: u64) -> Result<(), GpuError> {
    let limit_bytes = ctx.limits.max_storage_buffer_binding_size;
    if bytes > limit_bytes {
        return Err(GpuError::TooLarge {
            what,
            bytes,
            limit_bytes,
        });
    }
    Ok(())
}

/// Read-write storage (also copied to and from) for the kernels.
const STORAGE: wgpu::BufferUsages = wgpu::BufferUsages::STORAGE
    .union(wgpu::BufferUsages::COPY_DST)
    .union(wgpu::BufferUsages::COPY_SRC);

/// A uniform buffer holding `bytes`, rewritten each step.
pub(crate) fn uniform_buffer(
    ctx: &GpuContext,
    label: &'static str,
    bytes: &[u8],
) -> Result<wgpu::Buffer, GpuError> {
    check_size(ctx, label, bytes.len() as u64)?;
    let usage = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
    Ok(upload_buffer(&ctx.device, &ctx.queue, label, bytes, usage))
}

/// A storage buffer holding `bytes`, within the binding limit.
pub(crate) fn storage_buffer(
    ctx: &GpuContext,
    label: &'static str,
    bytes: &[u8],
) -> Result<wgpu::Buffer, GpuError> {
    check_size(ctx, label, bytes.len() as u64)?;
    Ok(upload_buffer(
        &ctx.device,
        &ctx.queue,
        label,
        bytes,
        STORAGE,
    ))
}

/// An uninitialised storage buffer of `bytes`, within the binding limit.
pub(crate) fn scratch_buffer(
    ctx: &GpuContext,
    label: &'static str,
    bytes: usize,
) -> Result<wgpu::Buffer, GpuError> {
    check_size(ctx, label, bytes as u64)?;
    Ok(ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes as u64,
        usage: STORAGE,
        mapped_at_creation: false,
    }))
}

//! The guard's measure on the device that steps the strands: the GPU
//! engine's `stage_measure` (`shaders/physics/measure.wgsl`,
//! [`MeasureStage`]) and its CPU twin [`stage_measure`], the batch
//! engine's measure ([`crate::batch::measure::measure_state`]) at f32, one
//! strand wide.
//!
//! # Why on the device
//!
//! The guard judges every frame from its start and end measures
//! ([`crate::guard`]). Measured on the CPU, the GPU engine must read every
//! strand's state back each frame (32 bytes an element) and sweep it there,
//! a sweep as long as a step's first; measured where the state is, a frame
//! sends back one [`StrandMeasureGpu`] per strand (112 bytes) and the CPU
//! judges from those. The state itself is read back only where a strand
//! failed (its retry runs on the CPU) or a caller asks for it.
//!
//! # How it works
//!
//! One invocation per strand sweeps root to tip as `measure_state` does
//! and sums the same quantities (kinetic, strain-kinetic and elastic
//! energy, momentum, angular momentum, first and second moments of mass,
//! the gravity and drag force with their torque and power, the fastest
//! point relative to the root's rigid motion, whether the head's contact
//! acts at a sample), and Block-diagonal's own kinetic energy where the
//! frame is judged by it (with a record per element for the tip-to-root
//! pass of [`crate::batch::block_kinetic`]). The uniforms then hold the
//! head's motion at the frame's end. One more sum, Σ |q| + |q̇| over every
//! component, is finite exactly where the whole state is: the host's
//! finiteness test without the state. [`StrandMeasureGpu::strand`] turns a
//! strand's sums into the guard's [`StrandMeasure`] by the batch engine's
//! own conversion ([`LaneMeasures::strand`]).
//!
//! The twin and the kernel differ by f32 round-off in the order of their
//! sums and by the contact's lookup (f64 on the CPU, f32 on the GPU), which
//! can decide a sample at the skin's very edge differently:
//! `tests/gpu_measure.rs` states the tolerances.

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use super::engine_twin::OneStrand;
use super::kernels::{dispatch_dims, read_pod, scratch_buffer, submit_pass, uniform_buffer};
use super::layout::Mat3Gpu;
use super::{GpuContext, GpuError};
use crate::batch::contact::NearCells;
use crate::batch::forward::NoContact;
use crate::batch::layout::BatchModel;
use crate::batch::measure::{LaneMeasures, MeasureInputs, MeasureScratch, measure_state};
use crate::batch::vec::V3;
use crate::collision::SignedDistanceField;
use crate::frame_balance::{KineticEnergy, StrandMeasure};
use crate::motion::{RigidMotion, RootPose};
use crate::settings::SimSettings;

/// One strand's measure sums (WGSL `StrandMeasure`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct StrandMeasureGpu {
    /// Kinetic, strain-kinetic, Block-diagonal's own kinetic, elastic, J.
    pub energies: [f32; 4],
    /// Power of the external forces (W), mass (kg), second moment of mass
    /// about the root point (kg m²), fastest point relative to the root's
    /// rigid motion (m/s).
    pub sums: [f32; 4],
    /// Momentum, kg m/s; w: 1 where the head's contact acts at a sample.
    pub momentum: [f32; 4],
    /// Angular momentum about the root point, kg m²/s; w: Σ |q| + |q̇| over
    /// every component (finite exactly where the state is).
    pub angular: [f32; 4],
    /// External force (gravity, drag), N.
    pub force: [f32; 4],
    /// Its torque about the root point, N m.
    pub torque: [f32; 4],
    /// First moment of mass about the root point, kg m.
    pub first_moment: [f32; 4],
}

/// One element's record for Block-diagonal's own kinetic energy (WGSL
/// `BlockRecord`): only the kernel writes and reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BlockRecordGpu {
    /// Velocity the element's rate adds to its end point, m/s (w: the
    /// element's own samples' mass, kg).
    pub u: [f32; 4],
    /// Turn its rate adds to its end frame, rad/s.
    pub beta: [f32; 4],
    /// End point less start point, m.
    pub span: [f32; 4],
    /// Own first moment about the element's start point, kg m.
    pub first: [f32; 4],
    /// Own second moment about the element's start point.
    pub second: Mat3Gpu,
}

fn v3(x: [f32; 4]) -> V3<f32> {
    V3::new(x[0], x[1], x[2])
}

fn f4(x: V3<f32>, w: f32) -> [f32; 4] {
    [x.x, x.y, x.z, w]
}

impl StrandMeasureGpu {
    /// The sums of one strand's lane of the batch engine's measure.
    fn of(m: &LaneMeasures<'_, f32>, state_size: f32) -> Self {
        Self {
            energies: [m.kinetic, m.strain_kinetic, m.block_kinetic, m.elastic],
            sums: [m.power, m.mass, m.second_moment, m.fastest],
            momentum: f4(m.momentum, (m.in_contact & 1) as f32),
            angular: f4(m.angular, state_size),
            force: f4(m.force, 0.0),
            torque: f4(m.torque, 0.0),
            first_moment: f4(m.first_moment, 0.0),
        }
    }

    /// Whether every q and q̇ of the strand is finite.
    pub fn state_is_finite(&self) -> bool {
        self.angular[3].is_finite()
    }

    /// The guard's measure of the strand whose root moves as `motion`,
    /// under `gravity_m_per_s2` (the batch engine's conversion,
    /// [`LaneMeasures::strand`]).
    pub fn strand(&self, motion: &RigidMotion, gravity_m_per_s2: DVec3) -> StrandMeasure {
        let [kinetic, strain_kinetic, block_kinetic, elastic] = self.energies;
        let [power, mass, second_moment, fastest] = self.sums;
        LaneMeasures {
            kinetic,
            strain_kinetic,
            block_kinetic,
            elastic,
            power,
            fastest,
            mass,
            second_moment,
            momentum: v3(self.momentum),
            angular: v3(self.angular),
            force: v3(self.force),
            torque: v3(self.torque),
            first_moment: v3(self.first_moment),
            in_contact: u32::from(self.momentum[3] != 0.0),
            motions: std::slice::from_ref(motion),
            gravity_m_per_s2: DVec3::from_array(
                gravity_m_per_s2.to_array().map(|g| g as f32 as f64),
            ),
        }
        .strand(0)
    }
}

/// The measure's pipeline and buffers on the engine's device.
#[derive(Debug)]
pub struct MeasureStage {
    pipeline: wgpu::ComputePipeline,
    engine_group: wgpu::BindGroup,
    measure_group: wgpu::BindGroup,
    measures: wgpu::Buffer,
    strand_count: usize,
    /// Whether it sums Block-diagonal's own kinetic energy.
    block: bool,
}

impl MeasureStage {
    /// The stage measuring `strand_count` strands of `element_count`
    /// elements in all, built from `module` (the engine's) over the
    /// engine's buffers `engine` (binding, buffer: the uniforms, strands,
    /// constants, q, q̇ and the collider's distances); with `block`, it
    /// sums Block-diagonal's own kinetic energy.
    pub fn new(
        ctx: &GpuContext,
        module: &wgpu::ShaderModule,
        engine: &[(u32, &wgpu::Buffer)],
        strand_count: usize,
        element_count: usize,
        block: bool,
    ) -> Result<Self, GpuError> {
        let device = &ctx.device;
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("stage_measure"),
            layout: None,
            module,
            entry_point: Some("stage_measure"),
            compilation_options: Default::default(),
            cache: None,
        });
        let entries: Vec<wgpu::BindGroupEntry> = engine
            .iter()
            .map(|&(binding, buffer)| wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        let engine_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("stage_measure engine"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let options = uniform_buffer(
            ctx,
            "measure options",
            bytemuck::bytes_of(&[u32::from(block), 0, 0, 0]),
        )?;
        let measures = scratch_buffer(
            ctx,
            "measures",
            strand_count.max(1) * size_of::<StrandMeasureGpu>(),
        )?;
        // Only Block-diagonal's frames write records.
        let records_len = if block { element_count.max(1) } else { 1 };
        let records = scratch_buffer(
            ctx,
            "block records",
            records_len * size_of::<BlockRecordGpu>(),
        )?;
        let measure_group = helixhair_gpu::bind_buffers(
            device,
            "stage_measure",
            &pipeline.get_bind_group_layout(1),
            &[&options, &measures, &records],
        );
        ctx.check()?;
        Ok(Self {
            pipeline,
            engine_group,
            measure_group,
            measures,
            strand_count,
            block,
        })
    }

    /// Whether it sums Block-diagonal's own kinetic energy.
    pub fn sums_block_kinetic(&self) -> bool {
        self.block
    }

    /// Submits the stage over the engine's current state and uniforms.
    /// Nothing waits.
    pub fn submit(&self, ctx: &GpuContext) {
        if self.strand_count == 0 {
            return;
        }
        let dims = dispatch_dims(ctx, (self.strand_count as u32).div_ceil(64));
        let groups = [&self.engine_group, &self.measure_group];
        submit_pass(ctx, "stage_measure", &groups, &[(&self.pipeline, dims)]);
    }

    /// Reads every strand's sums back, in the engine's strand order.
    pub fn read(&self, ctx: &GpuContext) -> Result<Vec<StrandMeasureGpu>, GpuError> {
        let mut all: Vec<StrandMeasureGpu> = read_pod(ctx, &self.measures)?;
        all.truncate(self.strand_count);
        Ok(all)
    }
}

/// WGSL `stage_measure` for one strand (`model` rooted at `root`, state
/// `q`, `v`) with the head at the frame's end as `head` and its `collider`
/// and near cells if any: the batch engine's measure at f32, one strand
/// wide, with the step's contact test, and the sum that tests finiteness.
/// Sums Block-diagonal's own kinetic energy where `judged_by` asks for it.
pub fn stage_measure(
    settings: &SimSettings,
    model: &BatchModel,
    root: &RootPose,
    head: &RigidMotion,
    collider: Option<(&SignedDistanceField, &NearCells)>,
    (q, v): (&[V3<f32>], &[V3<f32>]),
    judged_by: KineticEnergy,
) -> StrandMeasureGpu {
    let OneStrand {
        env,
        motion,
        root_motion,
        contact,
    } = OneStrand::new(settings, model, root, head, collider);
    let touching = contact.as_ref().map(|contact| {
        move |points: &[(V3<f32>, V3<f32>)]| {
            let hit = points
                .iter()
                .any(|&(r, velocity)| contact.touching(r, velocity, 1, |_, _| {}) != 0);
            u32::from(hit)
        }
    });
    let inputs = MeasureInputs {
        env: &env,
        root: &root_motion,
        motions: std::slice::from_ref(&motion),
        touching: touching
            .as_ref()
            .map(|t| t as &dyn Fn(&[(V3<f32>, V3<f32>)]) -> u32),
        judged_by,
    };
    let mut scratch = MeasureScratch::default();
    let measured = measure_state(model, q, v, &inputs, &NoContact, None, &mut scratch);
    let abs_sum = |x: &V3<f32>| x.x.abs() + x.y.abs() + x.z.abs();
    let state_size: f32 = q.iter().zip(v).map(|(k, r)| abs_sum(k) + abs_sum(r)).sum();
    StrandMeasureGpu::of(&measured, state_size)
}

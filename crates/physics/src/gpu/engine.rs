//! [`GpuEngine`]: strands stepped on the GPU by the CPU engines' one step,
//! Exact or Block-diagonal, velocity-implicit with its GMRES, the head's
//! implicit contact at every quadrature sample, and each strand's own
//! constants and element count (an imported groom's strands differ in all
//! of them).
//!
//! # How it works
//!
//! `shaders/physics/engine.wgsl` runs one invocation per strand. Exact:
//! sweep 1 (root to tip: kinematics, forces, the contact's terms), sweep 2
//! (tip to root: the articulated-inertia elimination), sweep 3 (Δv₀ = P⁻¹
//! rhs), then GMRES on (P + hG) Δv = rhs, each iteration one more solve
//! with the stored elimination and one product G z by polarisation, and
//! integration. Block-diagonal: sweep 1, its own velocity terms (one more
//! sweep each way, `batch/block_terms.rs`), one tip-to-root sweep that
//! inverts each element's block with the loads' stiffness, then GMRES on
//! (P_bd + θhG_bd) Δv = rhs, each product G_bd z two more of those sweeps.
//! Every function there keeps the name of its Rust original
//! (`batch/forward.rs`, `batch/step/exact.rs`, `batch/step/block_diagonal.rs`,
//! `batch/block_terms.rs`, `batch/velocity_terms.rs`, `gmres.rs`); the CPU
//! twin ([`super::engine_twin`]) is that Rust code at f32, one strand
//! wide, so the parity tests compare the kernel with the batch engine's
//! own arithmetic.
//!
//! The strands' table is ordered by element count and each entry names its
//! strand ([`StrandGpu::index`]): the invocations of one SIMD group (a
//! warp; llvmpipe's eight lanes) then take strands of one length, and none
//! idles while a longer one finishes. Memory stays in strand order. On
//! the Sintel groom (1 to 9 elements a strand) on lavapipe a step took a
//! median 0.81 of the unordered table's time (six alternated pairs), the
//! results the same to the bit.
//!
//! Buffers: the strands' table ([`StrandGpu`]), the per-element constants,
//! q and q̇ (one vec4 per element, strand after strand, each strand's
//! elements contiguous from [`StrandGpu::first`]), the sweep's element
//! data and elimination (Block-diagonal keeps its inverted blocks there),
//! GMRES's vectors ([`KRYLOV_SLOTS`] vec4 per element: room for the most
//! iterations a step may take, [`crate::gmres::MAX_GMRES`]; Block-diagonal
//! [`BLOCK_SLOTS`], with its own terms' vectors and their sweep's record)
//! and the collider's distances. Each substep writes the uniforms (the head's
//! motion over the step, [`HeadTrajectory::step_motion_at`], as the CPU
//! engines take it) and dispatches one stage; nothing is read back in the
//! frame loop.
//!
//! [`GpuEngine::measure`] measures every strand for the guard on the
//! device ([`super::measure`]); the batch engine judges the frames this
//! steps from those measures ([`crate::engine::EngineKind::Gpu`]). What
//! the CPU engines have and this does not yet: the hair–hair model, and
//! Dense (which [`super::GpuSystem`] steps
//! velocity-explicit, for one shared strand's constants).

use std::borrow::Cow;
use std::ops::Range;

use super::curves::{CurveBlend, CurveStage};
use super::kernels::{
    COMMON_WGSL, GpuState, at_least_one, bind_all, dispatch_dims, read_vec4, scratch_buffer,
    storage_buffer, submit_step, uniform_buffer, wait,
};
use super::layout::{
    ElementConstGpu, ElementDataGpu, EliminationGpu, EngineParamsGpu, Mat3Gpu, StrandGpu,
};
use super::measure::{MeasureStage, StrandMeasureGpu};
use super::{GpuContext, GpuError};
use crate::batch::SubstepOffload;
use crate::batch::layout::BatchModel;
use crate::batch::step::block_implicit::BLOCK_THETA;
use crate::collision::SignedDistanceField;
use crate::frame_balance::{KineticEnergy, StrandMeasure};
use crate::gmres::GMRES_TOLERANCE;
use crate::motion::{HeadTrajectory, RigidMotion, RootPose};
use crate::settings::{Method, SimSettings, StepScheme};

/// `shaders/physics/engine.wgsl`: the engine's step, after `common.wgsl`.
pub const ENGINE_WGSL: &str = include_str!("../../../../shaders/physics/engine.wgsl");

/// `shaders/physics/curves.wgsl`: the drawn centrelines, after
/// `engine.wgsl` ([`super::curves`]).
pub const CURVES_WGSL: &str = include_str!("../../../../shaders/physics/curves.wgsl");

/// `shaders/physics/measure.wgsl`: the guard's measure, after
/// `engine.wgsl` ([`super::measure`]).
pub const MEASURE_WGSL: &str = include_str!("../../../../shaders/physics/measure.wgsl");

/// GMRES's vectors per element in the `krylov` buffer (WGSL `KRYLOV_SLOTS`).
pub const KRYLOV_SLOTS: usize = 22;

/// Vectors per element in the `krylov` buffer for Block-diagonal (WGSL
/// `BLOCK_SLOTS`): GMRES's, its own terms at the rates and at the two
/// polarisation shifts, and their sweep's record of 28.
pub const BLOCK_SLOTS: usize = 53;

/// Loop iterations llvmpipe (lavapipe) lets one invocation run in all
/// before it ends its loops without a word (Mesa's
/// `LP_MAX_TGSI_LOOP_ITERATIONS`, docs/gpu.md).
pub const LAVAPIPE_LOOP_BUDGET: usize = 65_535;

/// Loop iterations of one Block-diagonal step of a strand of `n` elements
/// with `points` quadrature points and at most `iterations` GMRES
/// iterations, at the worst case, counted from `engine.wgsl`: sweep 1
/// and its own terms, the blocks, and per GMRES iteration the
/// preconditioner, the product G_bd z (the velocity product's sweep and
/// two more of the own terms', each n(points + 1), with the shifts and
/// sums, and the contact's coupling, `add_contact_coupling`, two sweeps
/// of n) and Arnoldi's orthogonalisation. (Exact's step stays under the
/// budget at the worst case a style may ask for: `tests/gpu_engine.rs`.)
pub fn block_loop_count(n: usize, points: usize, iterations: usize) -> usize {
    let sweep = n * (points + 1);
    let correction = sweep + n;
    let coupling = 2 * n;
    let product = (n + sweep + n) + (n + 2 * correction + n) + coupling;
    let start = sweep + correction + n + product + n;
    let per_iteration = |j: usize| n + product + n + 2 * n * (j + 1) + 2 * n;
    start + (0..iterations).map(per_iteration).sum::<usize>() + iterations * n + n
}

/// WGSL `METHOD_EXACT` and `METHOD_BLOCK`.
const METHOD_EXACT: u32 = 0;
const METHOD_BLOCK: u32 = 1;

const WORKGROUP: u32 = 64;

/// The full source of the engine's kernel module.
pub fn engine_source() -> String {
    format!("{COMMON_WGSL}\n{ENGINE_WGSL}\n{CURVES_WGSL}\n{MEASURE_WGSL}")
}

fn f4(v: glam::DVec3) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, 0.0]
}

fn mat(m: glam::DMat3) -> Mat3Gpu {
    [f4(m.x_axis), f4(m.y_axis), f4(m.z_axis)]
}

/// Strands stepped on the GPU by the one step (module docs).
#[derive(Debug)]
pub struct GpuEngine {
    ctx: GpuContext,
    settings: SimSettings,
    params: EngineParamsGpu,
    strands: Vec<StrandGpu>,
    /// Each strand's root, where the guard's measure carries it.
    roots: Vec<RootPose>,
    params_buffer: wgpu::Buffer,
    q_buffer: wgpu::Buffer,
    v_buffer: wgpu::Buffer,
    /// The state at the frame's start ([`Self::keep_start`]).
    start_buffers: (wgpu::Buffer, wgpu::Buffer),
    /// The strands' table, constants and collider, which the measure
    /// binds too.
    strands_buffer: wgpu::Buffer,
    elements_buffer: wgpu::Buffer,
    field_buffer: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    module: wgpu::ShaderModule,
    pipeline: wgpu::ComputePipeline,
    /// The drawn centrelines' stage, built on the first ask.
    curves: Option<CurveStage>,
    /// The guard's measure, built on the first ask.
    measure: Option<MeasureStage>,
    time_secs: f64,
}

impl GpuEngine {
    /// Uploads one strand per root, `models[i]` rooted at `roots[i]`, at
    /// rest in its natural shape, with the head `collider` (head
    /// coordinates) if any. `settings.method` must be Exact or
    /// Block-diagonal; the scheme sets GMRES's iterations (none for
    /// velocity-explicit, which Block-diagonal then takes without its own
    /// velocity terms and the loads' stiffness, as the batch engine does).
    pub fn new(
        ctx: GpuContext,
        settings: &SimSettings,
        models: &[BatchModel],
        roots: &[RootPose],
        collider: Option<&SignedDistanceField>,
    ) -> Result<Self, GpuError> {
        settings.validate()?;
        let (method, slots) = match settings.method {
            Method::Exact => (METHOD_EXACT, KRYLOV_SLOTS),
            Method::BlockDiagonal => (METHOD_BLOCK, BLOCK_SLOTS),
            _ => {
                return Err(GpuError::UnsupportedMethod {
                    method: settings.method.label(),
                    runs: "`exact` and `block` (Dense runs on `GpuSystem`)",
                });
            }
        };
        assert_eq!(models.len(), roots.len(), "one model per root");
        let iterations = match settings.scheme {
            StepScheme::VelocityImplicit { corrections } => corrections as usize,
            StepScheme::VelocityExplicit => 0,
        };
        let longest = models.iter().map(BatchModel::elements).max().unwrap_or(0);
        let points = models.first().map_or(0, |m| m.nodes.len());
        let count = block_loop_count(longest, points, iterations.min(crate::gmres::MAX_GMRES));
        if method == METHOD_BLOCK
            && ctx.adapter_name.contains("llvmpipe")
            && count > LAVAPIPE_LOOP_BUDGET
        {
            return Err(GpuError::LoopBudget {
                method: "Block-diagonal",
                elements: longest,
                points,
                iterations,
                count,
                budget: LAVAPIPE_LOOP_BUDGET,
            });
        }
        let mut strands = Vec::with_capacity(roots.len());
        let mut elements = Vec::new();
        let mut natural = Vec::new();
        for (model, root) in models.iter().zip(roots) {
            strands.push(StrandGpu {
                first: elements.len() as u32,
                elements: model.elements() as u32,
                index: strands.len() as u32,
                pad0: 0,
                mass_per_length: model.mass_per_length,
                air_drag: model.air_drag,
                pad1: [0.0; 2],
                position_m: f4(root.position_m),
                head_from_root: mat(root.head_from_root),
            });
            for e in 0..model.elements() {
                let [kx, ky, kz] = model.stiffness[e];
                let [nx, ny, nz] = model.natural[e];
                elements.push(ElementConstGpu {
                    stiffness_length: [kx, ky, kz, model.lengths_m[e]],
                    natural_friction: [nx, ny, nz, model.friction[e]],
                });
                natural.push([nx, ny, nz, 0.0]);
            }
        }
        let mut nodes = [[0.0; 4]; 2];
        let mut weights = [[0.0; 4]; 2];
        if let Some(model) = models.first() {
            for (i, (x, w)) in model.nodes.iter().zip(&model.weights).enumerate() {
                nodes[i / 4][i % 4] = *x;
                weights[i / 4][i % 4] = *w;
            }
        }
        let contact = settings.contact;
        let (field_dims, field_origin_m, field_cell_m, distances) = match collider {
            Some(field) => (
                [
                    field.dims[0] as u32,
                    field.dims[1] as u32,
                    field.dims[2] as u32,
                    0,
                ],
                f4(field.origin_m),
                field.cell_m as f32,
                field.distance_m.iter().map(|&d| d as f32).collect(),
            ),
            None => ([2, 2, 2, 0], [0.0; 4], 1.0, vec![0.0f32]),
        };
        let params = EngineParamsGpu {
            strand_count: roots.len() as u32,
            points: points as u32,
            iterations: iterations as u32,
            has_collider: u32::from(collider.is_some()),
            h_secs: settings.substep_secs() as f32,
            gmres_tolerance: GMRES_TOLERANCE as f32,
            skin_m: contact.skin_m as f32,
            implicit_stiffness_ratio: contact.implicit_stiffness_ratio as f32,
            max_acceleration_m_per_s2: contact.max_acceleration_m_per_s2 as f32,
            field_cell_m,
            method,
            slots: slots as u32,
            field_dims,
            field_origin_m,
            gravity_m_per_s2: f4(settings.gravity_m_per_s2),
            air_velocity_m_per_s: f4(settings.air_velocity_m_per_s),
            nodes,
            weights,
            block_h_secs: (BLOCK_THETA * settings.substep_secs()) as f32,
            ..bytemuck::Zeroable::zeroed()
        };
        // A binding holds at least one element, even with no strands.
        let count = elements.len().max(1);
        let params_buffer = uniform_buffer(&ctx, "engine params", bytemuck::bytes_of(&params))?;
        // The invocations take the strands by element count (WGSL
        // `Strand::index`): one SIMD group, strands of one length.
        let mut table = strands.clone();
        table.sort_by_key(|s| s.elements);
        let strands_buffer = storage_buffer(&ctx, "strands", &at_least_one(&table))?;
        let elements_buffer = storage_buffer(&ctx, "elements", &at_least_one(&elements))?;
        let q_buffer = storage_buffer(&ctx, "q", &at_least_one(&natural))?;
        let v_buffer = scratch_buffer(&ctx, "v", count * 16)?;
        let start_buffers = (
            scratch_buffer(&ctx, "q at the start", count * 16)?,
            scratch_buffer(&ctx, "v at the start", count * 16)?,
        );
        let scratch = scratch_buffer(&ctx, "element data", count * size_of::<ElementDataGpu>())?;
        let elimination = scratch_buffer(&ctx, "elimination", count * size_of::<EliminationGpu>())?;
        let krylov = scratch_buffer(&ctx, "krylov", count * slots * 16)?;
        let field = storage_buffer(&ctx, "field", bytemuck::cast_slice(&distances))?;
        let buffers = [
            &params_buffer,
            &strands_buffer,
            &elements_buffer,
            &q_buffer,
            &v_buffer,
            &scratch,
            &elimination,
            &krylov,
            &field,
        ];
        let device = &ctx.device;
        let (bind_group, pipeline_layout) =
            bind_all(device, "engine", &buffers, |b| matches!(b, 1 | 2 | 8));
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("engine"),
            source: wgpu::ShaderSource::Wgsl(Cow::Owned(engine_source())),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("stage_step"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("stage_step"),
            compilation_options: Default::default(),
            cache: None,
        });
        ctx.check()?;
        Ok(Self {
            ctx,
            settings: settings.clone(),
            params,
            strands,
            roots: roots.to_vec(),
            params_buffer,
            q_buffer,
            v_buffer,
            start_buffers,
            strands_buffer,
            elements_buffer,
            field_buffer: field,
            bind_group,
            module,
            pipeline,
            curves: None,
            measure: None,
            time_secs: 0.0,
        })
    }

    /// The uniforms of a step taken while the head moves as `head`.
    pub fn params_at(&self, head: &RigidMotion) -> EngineParamsGpu {
        EngineParamsGpu {
            head_rotation: mat(head.world_from_body),
            head_position_m: f4(head.position_m),
            head_angular_velocity: f4(head.angular_velocity_rad_per_s),
            head_angular_acceleration: f4(head.angular_acceleration_rad_per_s2),
            head_velocity: f4(head.velocity_m_per_s),
            head_acceleration: f4(head.acceleration_m_per_s2),
            ..self.params
        }
    }

    /// The device it runs on.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
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
        self.strands.len()
    }

    /// Bytes of GPU memory per strand: every per-element buffer (constants,
    /// state, element data, elimination, GMRES's vectors) and the strand's
    /// table entry, averaged over the strands.
    pub fn bytes_per_strand(&self) -> f64 {
        let elements: usize = self.strands.iter().map(|s| s.elements as usize).sum();
        let per_element = size_of::<ElementConstGpu>()
            + 2 * 16
            + size_of::<ElementDataGpu>()
            + size_of::<EliminationGpu>()
            + self.params.slots as usize * 16;
        let strands = self.strands.len().max(1);
        (elements * per_element + strands * size_of::<StrandGpu>()) as f64 / strands as f64
    }

    /// Strand `index`'s elements in the state vectors [`Self::read_state`]
    /// returns (panics if out of range).
    pub fn elements_of(&self, index: usize) -> Range<usize> {
        let s = &self.strands[index];
        s.first as usize..(s.first + s.elements) as usize
    }

    /// The state buffers (q, q̇), one vec4 per element, strand after strand.
    pub fn state_buffers(&self) -> (&wgpu::Buffer, &wgpu::Buffer) {
        (&self.q_buffer, &self.v_buffer)
    }

    /// Uploads a state (one vec4 per element, strand after strand).
    pub fn set_state(&self, q: &[[f32; 4]], v: &[[f32; 4]]) {
        let queue = &self.ctx.queue;
        queue.write_buffer(&self.q_buffer, 0, bytemuck::cast_slice(q));
        queue.write_buffer(&self.v_buffer, 0, bytemuck::cast_slice(v));
    }

    /// Advances one frame: `substeps` submissions of the step, each with
    /// the head's motion over it. No readback.
    pub fn step_frame(&mut self, head: &dyn HeadTrajectory) {
        let h = self.settings.substep_secs();
        for _ in 0..self.settings.substeps {
            self.substep(&head.step_motion_at(self.time_secs, h));
        }
    }

    /// Submits one step of every strand with the head moving as `motion`
    /// over it.
    pub fn substep(&mut self, motion: &RigidMotion) {
        let groups = dispatch_dims(&self.ctx, (self.strands.len() as u32).div_ceil(WORKGROUP));
        let params = self.params_at(motion);
        submit_step(
            &self.ctx,
            (&self.params_buffer, bytemuck::bytes_of(&params)),
            &self.bind_group,
            &[(&self.pipeline, groups)],
        );
        self.time_secs += self.settings.substep_secs();
    }

    /// Waits for every submitted step to finish (for timing).
    pub fn wait(&self) -> Result<(), GpuError> {
        wait(&self.ctx)
    }

    /// Writes `blend`'s curves from the current state into the curves'
    /// points buffer ([`super::curves`], which gives the buffer's layout)
    /// and returns the stage that holds it. The stage is built again only
    /// when the blend changes. Nothing waits: a renderer's passes
    /// submitted after this on the same queue see the points.
    pub fn write_curves(&mut self, blend: &CurveBlend) -> Result<&CurveStage, GpuError> {
        if !self.curves.as_mut().is_some_and(|c| c.holds(blend)) {
            let elements = self.strands.iter().map(|s| s.elements as usize).sum();
            let stage = CurveStage::new(&self.ctx, &self.module, &self.q_buffer, elements, blend)?;
            self.curves = Some(stage);
        }
        let stage = self.curves.as_ref().expect("built above");
        stage.submit(&self.ctx);
        Ok(stage)
    }

    /// The guard's measure of every strand in its current state with the
    /// head at `head` (its motion at the frame's end), in strand order
    /// ([`super::measure`]); Block-diagonal's own kinetic energy is summed
    /// where `judged_by` asks for it. Waits for the steps submitted before
    /// it and reads back one [`StrandMeasureGpu`] per strand.
    pub fn measure(
        &mut self,
        head: &RigidMotion,
        judged_by: KineticEnergy,
    ) -> Result<Vec<StrandMeasureGpu>, GpuError> {
        let block = judged_by == KineticEnergy::BlockDiagonal;
        if self
            .measure
            .as_ref()
            .is_none_or(|m| m.sums_block_kinetic() != block)
        {
            let elements = self.strands.iter().map(|s| s.elements as usize).sum();
            let engine = [
                (0, &self.params_buffer),
                (1, &self.strands_buffer),
                (2, &self.elements_buffer),
                (3, &self.q_buffer),
                (4, &self.v_buffer),
                (8, &self.field_buffer),
            ];
            let stage = MeasureStage::new(
                &self.ctx,
                &self.module,
                &engine,
                self.strands.len(),
                elements,
                block,
            )?;
            self.measure = Some(stage);
        }
        let stage = self.measure.as_ref().expect("built above");
        let params = self.params_at(head);
        self.ctx
            .queue
            .write_buffer(&self.params_buffer, 0, bytemuck::bytes_of(&params));
        stage.submit(&self.ctx);
        stage.read(&self.ctx)
    }

    /// Keeps a copy of the state on the device as the frame's start (where
    /// a failing strand's retry starts from), after the steps submitted
    /// before it. Nothing waits.
    pub fn keep_start(&self) {
        let mut encoder = self
            .ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("keep the start"),
            });
        let (q, v) = &self.start_buffers;
        encoder.copy_buffer_to_buffer(&self.q_buffer, 0, q, 0, None);
        encoder.copy_buffer_to_buffer(&self.v_buffer, 0, v, 0, None);
        self.ctx.queue.submit([encoder.finish()]);
    }

    /// Reads the state [`Self::keep_start`] kept back, as
    /// [`Self::read_state`] reads the current one.
    pub fn read_start(&self) -> Result<GpuState, GpuError> {
        let (q, v) = &self.start_buffers;
        Ok((read_vec4(&self.ctx, q)?, read_vec4(&self.ctx, v)?))
    }

    /// Reads (q, q̇) back: one vec4 per element, strand after strand.
    pub fn read_state(&self) -> Result<GpuState, GpuError> {
        Ok((
            read_vec4(&self.ctx, &self.q_buffer)?,
            read_vec4(&self.ctx, &self.v_buffer)?,
        ))
    }
}

impl SubstepOffload for GpuEngine {
    fn upload(&mut self, q: &[[f32; 4]], v: &[[f32; 4]]) {
        self.set_state(q, v);
    }

    fn substep(&mut self, motion: &RigidMotion) {
        GpuEngine::substep(self, motion);
    }

    fn keep_start(&mut self) {
        GpuEngine::keep_start(self);
    }

    fn download(&mut self) -> Result<GpuState, String> {
        self.read_state().map_err(|e| e.to_string())
    }

    fn download_start(&mut self) -> Result<GpuState, String> {
        self.read_start().map_err(|e| e.to_string())
    }

    fn measure(
        &mut self,
        head: &RigidMotion,
        judged_by: KineticEnergy,
    ) -> Result<Vec<(StrandMeasure, bool)>, String> {
        let measured = GpuEngine::measure(self, head, judged_by).map_err(|e| e.to_string())?;
        let gravity = self.settings.gravity_m_per_s2;
        Ok(measured
            .iter()
            .zip(&self.roots)
            .map(|(m, root)| (m.strand(&head.carry(root), gravity), m.state_is_finite()))
            .collect())
    }
}

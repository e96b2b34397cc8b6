//! The Dense step in f32 (GPU kernel, its CPU twins, `batch::dense`)
//! against known answers: the f64 reference's Dense step and assembled
//! mass matrix, and the Exact step (algebraically the same step matrix,
//! docs/physics.md section 5); and the GPU kernel against its twins over a head
//! shake.
//!
//! Policy: with no adapter the GPU tests print why and pass, unless
//! `HELIXHAIR_REQUIRE_GPU=1` (set by `.ci/run`), where they fail.
#![cfg(feature = "gpu")]

use crate::common;

use common::gpu::context;
use common::{Rng, curl, outward_roots as roots, shake};
use glam::DVec3;
use helixhair_physics::batch::forward::NoContact;
use helixhair_physics::batch::layout::{BatchModel, ElementData, RootMotion, StepEnv};
use helixhair_physics::batch::step::dense::{DenseScratch, step_dense};
use helixhair_physics::batch::step::exact::{Elimination, step_exact_with};
use helixhair_physics::batch::vec::V3;
use helixhair_physics::gpu::dense_twin::{mass_matrix, stage_dense, stage_elements, stage_frames};
use helixhair_physics::gpu::kernels::GpuState;
use helixhair_physics::gpu::layout::{
    DenseOwnGpu, ElementConstGpu, FrameGpu, JacobiansGpu, ParamsGpu, RootPoseGpu, v3, v4,
};
use helixhair_physics::gpu::twin::{model_of, root_state};
use helixhair_physics::gpu::{GpuContext, GpuError, GpuSystem, Stepper};
use helixhair_physics::step::mass::{MassData, dense_mass, mass_blocks};
use helixhair_physics::{
    HairSystem, HeadTrajectory, Method, RigidMotion, RootPose, SimSettings, StepScheme,
    StrandModel, StrandParams,
};

/// GPU Dense against its CPU twins over [`SHAKE_STEPS`] steps of a head
/// shake from a random state: max |Δ| over max |value| for q̇ and q. Both
/// are f32 and differ in operation order and fused multiply-adds.
/// Measured on lavapipe (70 curly strands, N = 10): Δv 4.6e-6, Δq 7.1e-7.
const TRAJECTORY_TOL: f32 = 5e-5;
/// Steps of the head shake (5 s at 60 Hz).
const SHAKE_STEPS: usize = 300;

/// One f32 Dense step (`batch::dense::step_dense`) against one f64 Dense
/// step (`HairSystem`, `Method::Dense`) from the same random state: max
/// |v_f32 − v_f64| over max |v_f64|, the measure and tolerance of
/// `tests/batch_parity.rs` for Exact (f32 round-off amplified by the step
/// matrix's conditioning). Measured: 6.9e-6 (N = 10 and 20, straight and
/// curly, 2 and 4 points).
const F64_ONE_STEP_TOL: f64 = 5e-4;

/// GPU Dense against GPU Exact and the Exact CPU twin after one step from
/// the same random state: max |Δ| over max |value| for q̇. Exact and Dense
/// solve the same step matrix by different eliminations, so they differ by
/// f32 round-off only: the GPU-against-twin tolerance of
/// `tests/gpu_parity.rs`. Measured on lavapipe (N = 5, 10, 20): ≤ 1.2e-6
/// against the Exact kernel, ≤ 1.6e-6 against the Exact twin.
const DENSE_EQUALS_EXACT_TOL: f32 = 5e-5;

/// The assembled f32 mass matrix against the f64 reference's `dense_mass`:
/// max over entries of |M32_ij − M64_ij| / √(d_P d_Q), with P, Q the
/// elements of row i and column j and d_P the largest diagonal entry of
/// element P's block (its bending inertia; Cauchy–Schwarz bounds the
/// block's entries by √(d_P d_Q)). Measured: 8.9e-6.
///
/// Why not each row's own diagonal: the suffix sums are moments about the
/// root point, so an entry is a difference of terms like B_Qᵀ I_b B_Q that
/// are up to (L/ℓ)² larger than the entry; in f32 its error is ε_f32
/// times those terms. A near-tip twist row carries 30× less inertia than
/// its element's bending rows, so against its own diagonal the same
/// absolute error reads 4.5e-4 (entry (24, 24) at N = 10). The f32 Block
/// and Exact paths assemble their blocks from the same sums; the step they
/// give is pinned by `F64_ONE_STEP_TOL`.
const MASS_MATRIX_TOL: f64 = 1e-4;

fn settings(method: Method, points: usize) -> SimSettings {
    SimSettings {
        // The f32 paths step velocity-explicit (docs/gpu.md): the f64
        // reference runs the same scheme.
        scheme: StepScheme::VelocityExplicit,
        method,
        substeps: 1,
        quadrature_points: points,
        air_velocity_m_per_s: DVec3::new(0.3, 0.0, -0.1),
        ..SimSettings::default()
    }
}

/// Strains off the rest shape by ±3 m⁻¹ and rates ±10 m⁻¹/s, one vec4 per
/// element, strand-major.
fn random_state(natural: &[[f32; 4]], seed: u64) -> GpuState {
    let mut rng = Rng::new(seed);
    let q = natural
        .iter()
        .map(|x| {
            let d = rng.vec3(3.0);
            [x[0] + d.x as f32, x[1] + d.y as f32, x[2] + d.z as f32, 0.0]
        })
        .collect();
    let v = natural
        .iter()
        .map(|_| {
            let d = rng.vec3(10.0);
            [d.x as f32, d.y as f32, d.z as f32, 0.0]
        })
        .collect();
    (q, v)
}

fn max_abs(a: &[[f32; 4]]) -> f32 {
    a.iter().flatten().fold(0.0, |m, x| m.max(x.abs()))
}

fn max_diff(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

fn relative(a: &[[f32; 4]], reference: &[[f32; 4]]) -> f32 {
    max_diff(a, reference) / max_abs(reference)
}

/// The Dense twins' buffers for `count` elements of N per strand.
struct TwinBuffers {
    frames: Vec<FrameGpu>,
    jacobians: Vec<JacobiansGpu>,
    own: Vec<DenseOwnGpu>,
    matrix: Vec<f32>,
}

impl TwinBuffers {
    fn new(count: usize, n: usize) -> Self {
        Self {
            frames: vec![bytemuck::Zeroable::zeroed(); count],
            jacobians: vec![bytemuck::Zeroable::zeroed(); count],
            own: vec![bytemuck::Zeroable::zeroed(); count],
            matrix: vec![0.0; count / n * 9 * n * n],
        }
    }
}

#[test]
fn dense_kernel_matches_its_cpu_twins_over_a_head_shake() {
    let Some(ctx) = context() else { return };
    let settings = settings(Method::Dense, 4);
    let n = 10;
    // 70 strands: stage_frames spans two workgroups, one not full.
    let roots = roots(70);
    let mut gpu = GpuSystem::new(ctx, &settings, &curl(n), &roots).expect("GPU system");
    let (natural, _) = gpu.read_state().expect("readback");
    let (mut q, mut v) = random_state(&natural, 4);
    gpu.set_state(&q, &v);
    let elements = gpu.element_constants().to_vec();
    let gpu_roots = gpu.roots().to_vec();
    let mut b = TwinBuffers::new(q.len(), n);
    let head = shake();
    let h = settings.substep_secs();
    for step in 0..SHAKE_STEPS {
        gpu.step_frame(&head);
        let p = gpu.params_at(&head.motion_at(step as f64 * h));
        stage_frames(
            &p,
            &elements,
            &gpu_roots,
            &q,
            &v,
            &mut b.frames,
            &mut b.jacobians,
        );
        stage_elements(&p, &elements, &q, &v, &b.frames, &mut b.own);
        stage_dense(
            &p,
            &elements,
            &mut q,
            &mut v,
            &b.jacobians,
            &b.own,
            &mut b.matrix,
        );
    }
    let (gq, gv) = gpu.read_state().expect("readback");
    let (dv, dq) = (relative(&gv, &v), relative(&gq, &q));
    println!("Dense, {SHAKE_STEPS} steps: Δv {dv:.2e}, Δq {dq:.2e}");
    assert!(gv.iter().chain(&gq).flatten().all(|x| x.is_finite()));
    assert!(
        dv < TRAJECTORY_TOL && dq < TRAJECTORY_TOL,
        "Δv {dv:.2e}, Δq {dq:.2e} (tolerance {TRAJECTORY_TOL:.0e})"
    );
}

/// One f32 Dense step of strand `index` of `reference` (at its current
/// state) with the batch path's arithmetic at width 1.
fn f32_dense_step(reference: &HairSystem, index: usize, head: &RigidMotion) -> Vec<DVec3> {
    let strand = &reference.strands()[index];
    let model = BatchModel::new(strand.model());
    let s = reference.settings();
    let env = StepEnv {
        h_secs: s.substep_secs(),
        gravity_m_per_s2: s.gravity_m_per_s2.to_array(),
        air_velocity_m_per_s: s.air_velocity_m_per_s.to_array(),
    };
    let root = RootMotion::<f32>::gather(&[head.carry(strand.root())]);
    let to32 = |x: &[DVec3]| -> Vec<V3<f32>> {
        x.iter()
            .map(|k| V3::new(k.x as f32, k.y as f32, k.z as f32))
            .collect()
    };
    let (mut q, mut v) = (to32(strand.q()), to32(strand.v()));
    let n = q.len();
    let mut scratch = vec![ElementData::zero(); n];
    let mut dense = DenseScratch::new(n);
    step_dense(
        &model,
        &env,
        &root,
        &mut q,
        &mut v,
        &mut scratch,
        &mut dense,
    );
    v.iter()
        .map(|x| DVec3::new(x.x as f64, x.y as f64, x.z as f64))
        .collect()
}

#[test]
fn f32_dense_step_matches_the_f64_dense_reference() {
    let mut worst: f64 = 0.0;
    for points in [2, 4] {
        for params in [StrandParams::default(), curl(10), curl(20)] {
            let mut reference = HairSystem::new(settings(Method::Dense, points)).expect("valid");
            let roots = roots(5);
            reference.add_group(&params, &roots).expect("valid");
            let mut rng = Rng::new(7);
            for strand in reference.strands_mut() {
                // Rounded to f32 first so both start from the same numbers.
                let q: Vec<DVec3> = strand
                    .q()
                    .iter()
                    .map(|k| (*k + rng.vec3(5.0)).as_vec3().as_dvec3())
                    .collect();
                let v: Vec<DVec3> = q
                    .iter()
                    .map(|_| rng.vec3(20.0).as_vec3().as_dvec3())
                    .collect();
                strand.set_state(&q, &v);
            }
            let head = shake();
            // The step's motion: accelerations averaged over the step.
            let dt_secs = reference.settings().dt_secs;
            let motion = head.step_motion_at(0.0, dt_secs);
            let f32_steps: Vec<Vec<DVec3>> = (0..roots.len())
                .map(|i| f32_dense_step(&reference, i, &motion))
                .collect();
            reference.step_frame(&head);
            for (i, v32) in f32_steps.iter().enumerate() {
                let v64 = reference.strands()[i].v();
                let scale = v64
                    .iter()
                    .map(|x| x.abs().max_element())
                    .fold(0.0, f64::max);
                let err = common::max_diff(v32, v64) / scale;
                worst = worst.max(err);
                assert!(
                    err < F64_ONE_STEP_TOL,
                    "{points} points, N = {}, strand {i}: {err:.2e}",
                    params.elements
                );
            }
        }
    }
    println!("f32 Dense against f64 Dense, one step: {worst:.2e}");
}

/// One step of `method` on the GPU from the state (q, v).
fn gpu_step(ctx: GpuContext, method: Method, n: usize, roots: &[RootPose], seed: u64) -> GpuState {
    let mut gpu = GpuSystem::new(ctx, &settings(method, 4), &curl(n), roots).expect("GPU");
    let (natural, _) = gpu.read_state().expect("readback");
    let (q, v) = random_state(&natural, seed);
    gpu.set_state(&q, &v);
    gpu.step_frame(&shake());
    gpu.read_state().expect("readback")
}

/// The batch engine's explicit Exact step (f32, one strand wide) on
/// `GpuSystem`'s buffers: the answer Dense solves for.
fn exact_on_buffers(
    params: &ParamsGpu,
    elements: &[ElementConstGpu],
    roots: &[RootPoseGpu],
    q: &mut [[f32; 4]],
    v: &mut [[f32; 4]],
) {
    let (model, env) = model_of(params, elements);
    let n = params.elements as usize;
    let mut scratch = vec![ElementData::<f32>::zero(); n];
    let mut elimination = vec![Elimination::<f32>::zero(); n];
    for (strand, pose) in roots.iter().enumerate() {
        let s = root_state(params, pose);
        let root = RootMotion {
            world_from_root: s.frame,
            angular_velocity_rad_per_s: s.angular_velocity,
            angular_acceleration_rad_per_s2: s.angular_acceleration,
            velocity_m_per_s: s.point_velocity,
            acceleration_m_per_s2: s.point_acceleration,
        };
        let range = strand * n..(strand + 1) * n;
        let mut qs: Vec<V3<f32>> = q[range.clone()].iter().map(|x| v3(*x)).collect();
        let mut vs: Vec<V3<f32>> = v[range.clone()].iter().map(|x| v3(*x)).collect();
        step_exact_with::<f32, true, _>(
            &model,
            &env,
            &root,
            &mut qs,
            &mut vs,
            &mut scratch,
            &mut elimination,
            &NoContact,
        );
        for (k, i) in range.enumerate() {
            q[i] = v4(qs[k]);
            v[i] = v4(vs[k]);
        }
    }
}

#[test]
fn gpu_dense_equals_exact_after_one_step() {
    if context().is_none() {
        return;
    }
    let roots = roots(9);
    for n in [5, 10, 20] {
        let dense = gpu_step(context().expect("adapter"), Method::Dense, n, &roots, 5);
        // Exact from the same start, on the same buffers, in f32 on the
        // CPU: the batch engine's explicit step.
        let probe = GpuSystem::new(
            context().expect("adapter"),
            &settings(Method::Dense, 4),
            &curl(n),
            &roots,
        )
        .expect("GPU");
        let (natural, _) = probe.read_state().expect("readback");
        let (mut q, mut v) = random_state(&natural, 5);
        let p = probe.params_at(&shake().motion_at(0.0));
        exact_on_buffers(&p, probe.element_constants(), probe.roots(), &mut q, &mut v);
        let against_exact = relative(&dense.1, &v);
        println!("N = {n}: Dense kernel vs f32 Exact {against_exact:.2e}");
        assert!(dense.1.iter().flatten().all(|x| x.is_finite()));
        assert!(
            against_exact < DENSE_EQUALS_EXACT_TOL,
            "N = {n}: {against_exact:.2e}"
        );
    }
}

#[test]
fn assembled_mass_matrix_matches_the_f64_dense_mass() {
    let mut worst: f64 = 0.0;
    for (params, points) in [(curl(10), 4), (curl(20), 2), (StrandParams::default(), 4)] {
        let settings = settings(Method::Dense, points);
        let model = StrandModel::new(&params, points).expect("valid");
        let n = model.elements();
        let root = roots(1)[0];
        let head = RigidMotion::default();
        let mut rng = Rng::new(21);
        let q: Vec<DVec3> = model
            .natural
            .iter()
            .map(|k| (*k + rng.vec3(5.0)).as_vec3().as_dvec3())
            .collect();
        let v = vec![DVec3::ZERO; n];
        // f64: the reference's kinematics and dense assembly.
        let kin = common::kinematics(&model, &q, &v, &head.carry(&root));
        let mut mass = MassData::default();
        mass_blocks(&model, &kin, &mut mass);
        let m64 = dense_mass(&kin, &mass);
        // f32: the twins' stages, then the kernel's assembly.
        let Some(ctx) = context() else { return };
        let gpu = GpuSystem::new(ctx, &settings, &params, &[root]).expect("GPU");
        let p = gpu.params_at(&head);
        let q32: Vec<[f32; 4]> = q
            .iter()
            .map(|k| [k.x as f32, k.y as f32, k.z as f32, 0.0])
            .collect();
        let v32 = vec![[0.0f32; 4]; n];
        let mut b = TwinBuffers::new(n, n);
        stage_frames(
            &p,
            gpu.element_constants(),
            gpu.roots(),
            &q32,
            &v32,
            &mut b.frames,
            &mut b.jacobians,
        );
        stage_elements(
            &p,
            gpu.element_constants(),
            &q32,
            &v32,
            &b.frames,
            &mut b.own,
        );
        let m32 = mass_matrix(&p, 0, &b.jacobians, &b.own);
        let dim = 3 * n;
        // Each element's largest diagonal entry (its bending inertia).
        let element_scale: Vec<f64> = (0..n)
            .map(|e| {
                (0..3)
                    .map(|k| m64[(3 * e + k, 3 * e + k)])
                    .fold(0.0, f64::max)
            })
            .collect();
        for i in 0..dim {
            for j in 0..dim {
                let scale = (element_scale[i / 3] * element_scale[j / 3]).sqrt();
                let err = (m32[i * dim + j] as f64 - m64[(i, j)]).abs() / scale;
                worst = worst.max(err);
                assert!(
                    err < MASS_MATRIX_TOL,
                    "N = {n}, entry ({i}, {j}): {} vs {} ({err:.2e})",
                    m32[i * dim + j],
                    m64[(i, j)]
                );
            }
        }
    }
    println!("f32 mass matrix against f64 dense_mass: {worst:.2e}");
}

#[test]
fn dense_kernel_refuses_strands_longer_than_its_workgroup_arrays() {
    let Some(ctx) = context() else { return };
    let params = StrandParams {
        elements: 65,
        ..StrandParams::default()
    };
    let err = GpuSystem::new(ctx, &settings(Method::Dense, 2), &params, &roots(1))
        .expect_err("65 elements exceed the kernel's 64");
    assert!(
        matches!(
            err,
            GpuError::TooManyElements {
                elements: 65,
                max: 64
            }
        ),
        "{err}"
    );
}

#[test]
fn stepper_falls_back_to_cpu_exact_when_dense_cannot_run_on_the_gpu() {
    if context().is_none() {
        return;
    }
    // 65 elements: too many for the kernel, so the CPU batch path takes the
    // strands with Exact (Dense's answer in O(N)) and says so.
    let params = StrandParams {
        elements: 65,
        ..StrandParams::default()
    };
    let (stepper, message) =
        Stepper::prefer_gpu(&settings(Method::Dense, 2), &params, &roots(3)).expect("valid");
    match stepper {
        Stepper::Cpu(cpu) => assert_eq!(cpu.settings().method, Method::Exact),
        Stepper::Gpu(_) => panic!("65 elements ran on the GPU"),
    }
    assert!(
        message.contains("at most 64 elements") && message.contains("with Exact"),
        "{message}"
    );
    // Within the limit, Dense runs on the GPU.
    let (stepper, message) =
        Stepper::prefer_gpu(&settings(Method::Dense, 2), &curl(10), &roots(3)).expect("valid");
    assert!(matches!(stepper, Stepper::Gpu(_)), "{message}");
}

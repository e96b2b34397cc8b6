//! GPU kernels against their CPU twins (same f32 arithmetic, same buffers),
//! on whatever adapter the environment gives (lavapipe in CI).
//!
//! Policy: with no adapter the tests print why and pass, unless
//! `HELIXHAIR_REQUIRE_GPU=1` (set by `.ci/run`), where they fail.
#![cfg(feature = "gpu")]

mod common;

use common::Rng;
use glam::DVec3;
use helixhair_physics::gpu::kernels::GpuState;
use helixhair_physics::gpu::layout::{BeyondGpu, FrameGpu, JacobiansGpu, OwnGpu};
use helixhair_physics::gpu::twin::{
    stage_elements, stage_exact, stage_frames, stage_solve, stage_suffix,
};
use helixhair_physics::gpu::{GpuContext, GpuSystem};
use helixhair_physics::{
    HeadTrajectory, Method, NaturalShape, Oscillation, RootPose, SimSettings, StrandParams,
};

/// GPU against CPU twin after one step (Exact) or one frame of 10
/// substeps (Block-diagonal) from a random state: max |Δ| over max |value|,
/// for q̇ and q. Both are f32; they differ in operation order and fused
/// multiply-adds. Measured on lavapipe: Block-diagonal 5e-7, Exact 3e-6.
const ONE_STEP_TOL: f32 = 5e-5;
/// After 30 steps of a head shake, the same measure. Measured on lavapipe:
/// Block-diagonal 5e-7, Exact 6e-6.
const TRAJECTORY_TOL: f32 = 5e-5;

fn context() -> Option<GpuContext> {
    match GpuContext::new_headless() {
        Ok(ctx) => Some(ctx),
        Err(e) if std::env::var("HELIXHAIR_REQUIRE_GPU").as_deref() == Ok("1") => {
            panic!("HELIXHAIR_REQUIRE_GPU=1 but {e}")
        }
        Err(e) => {
            eprintln!("skipping GPU test: {e}");
            None
        }
    }
}

fn roots(count: usize) -> Vec<RootPose> {
    let mut rng = Rng::new(9);
    (0..count)
        .map(|_| {
            let p = rng.vec3(0.1);
            RootPose::from_direction(p, p.normalize() + rng.vec3(0.3), DVec3::Y)
        })
        .collect()
}

fn curl(n: usize) -> StrandParams {
    StrandParams {
        elements: n,
        natural_shape: NaturalShape::Helix {
            radius_m: 0.02,
            step_m: 0.05,
        },
        ..StrandParams::default()
    }
}

fn shake() -> Oscillation {
    Oscillation {
        axis: DVec3::new(0.2, 1.0, 0.1),
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    }
}

/// Runs `steps` steps (Block-diagonal: 10 substeps a frame, so a multiple
/// of 10) on the GPU and on the twins from a random start; returns the
/// (GPU, twin) states.
fn run(ctx: GpuContext, method: Method, strands: usize, steps: usize) -> (GpuState, GpuState) {
    let settings = SimSettings {
        method,
        substeps: if method == Method::BlockDiagonal {
            10
        } else {
            1
        },
        air_velocity_m_per_s: DVec3::new(0.3, 0.0, -0.1),
        ..SimSettings::default()
    };
    let params = curl(10);
    let roots = roots(strands);
    let mut gpu = GpuSystem::new(ctx, &settings, &params, &roots).expect("GPU system");
    let (q0, _) = gpu.read_state().expect("readback");
    let mut rng = Rng::new(4);
    let mut q: Vec<[f32; 4]> = q0
        .iter()
        .map(|x| {
            let d = rng.vec3(3.0);
            [x[0] + d.x as f32, x[1] + d.y as f32, x[2] + d.z as f32, 0.0]
        })
        .collect();
    let mut v: Vec<[f32; 4]> = q0
        .iter()
        .map(|_| {
            let d = rng.vec3(10.0);
            [d.x as f32, d.y as f32, d.z as f32, 0.0]
        })
        .collect();
    gpu.set_state(&q, &v);
    let head = shake();
    let count = q.len();
    let mut frames: Vec<FrameGpu> = vec![bytemuck::Zeroable::zeroed(); count];
    let mut jacobians: Vec<JacobiansGpu> = vec![bytemuck::Zeroable::zeroed(); count];
    let mut own: Vec<OwnGpu> = vec![bytemuck::Zeroable::zeroed(); count];
    let mut beyond: Vec<BeyondGpu> = vec![bytemuck::Zeroable::zeroed(); count];
    let h = settings.substep_secs();
    let elements = gpu.element_constants().to_vec();
    let gpu_roots = gpu.roots().to_vec();
    let mut t = 0.0;
    let mut steps_done = 0;
    while steps_done < steps {
        gpu.step_frame(&head);
        for _ in 0..settings.substeps {
            let p = gpu.params_at(&head.motion_at(t));
            if method == Method::Exact {
                stage_exact(&p, &elements, &gpu_roots, &mut q, &mut v);
            } else {
                stage_frames(
                    &p,
                    &elements,
                    &gpu_roots,
                    &q,
                    &v,
                    &mut frames,
                    &mut jacobians,
                );
                stage_elements(&p, &elements, &q, &v, &frames, &mut own);
                stage_suffix(&p, &own, &mut beyond);
                stage_solve(&p, &elements, &mut q, &mut v, &jacobians, &own, &beyond);
            }
            t += h;
            steps_done += 1;
        }
    }
    (gpu.read_state().expect("readback"), (q, v))
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

fn check(method: Method, steps: usize, tol: f32) {
    let Some(ctx) = context() else { return };
    // 70 strands: more than one workgroup, and not a multiple of 64.
    let ((gq, gv), (cq, cv)) = run(ctx, method, 70, steps);
    let dv = max_diff(&gv, &cv) / max_abs(&cv);
    let dq = max_diff(&gq, &cq) / max_abs(&cq);
    println!("{method:?}, {steps} steps: Δv {dv:.2e}, Δq {dq:.2e}");
    assert!(gv.iter().flatten().all(|x| x.is_finite()));
    assert!(
        dv < tol && dq < tol,
        "{method:?}: Δv {dv:.2e}, Δq {dq:.2e} (tolerance {tol:.0e})"
    );
}

#[test]
fn block_diagonal_kernels_match_their_cpu_twins() {
    check(Method::BlockDiagonal, 10, ONE_STEP_TOL);
    check(Method::BlockDiagonal, 30, TRAJECTORY_TOL);
}

#[test]
fn exact_kernel_matches_its_cpu_twin() {
    check(Method::Exact, 1, ONE_STEP_TOL);
    check(Method::Exact, 30, TRAJECTORY_TOL);
}

//! A device that stops working after it was made (a driver reset, a GPU
//! removed; simulated here with `wgpu::Device::destroy`, which wgpu reports
//! as a lost device) fails the GPU engine's and the renderer's next
//! readback with a message naming the loss, and panics nowhere: wgpu's
//! default error handler panics on the first error, and
//! `helixhair_gpu::GpuContext` replaces it with one that records the
//! problem for `GpuContext::check`.
//!
//! These tests need an adapter (lavapipe will do): they skip without one,
//! and fail where CI requires the GPU (`HELIXHAIR_REQUIRE_GPU=1`).

use glam::{DVec3, Vec3};
use helixhair_gpu::context_or_skip;
use helixhair_physics::batch::layout::BatchModel;
use helixhair_physics::gpu::GpuEngine;
use helixhair_physics::{
    Engine, EngineKind, Method, Oscillation, RigidMotion, RootPose, SimSettings, StrandModel,
    StrandParams,
};
use helixhair_render::head_generate::default_head;
use helixhair_render::{
    HairStrands, Light, OffscreenRenderer, OrbitCamera, RenderSettings, Scene, StrandBuffers,
};

#[test]
fn the_gpu_engine_reports_a_lost_device_instead_of_panicking() {
    let Some(gpu) = context_or_skip("lost device: GPU engine") else {
        return;
    };
    let roots: Vec<RootPose> = (0..4)
        .map(|i| {
            let p = DVec3::new(0.05 * f64::from(i), 0.1, 0.0);
            RootPose::from_direction(p, p, DVec3::Y)
        })
        .collect();
    let settings = SimSettings {
        method: Method::BlockDiagonal,
        ..SimSettings::default()
    };
    let model = StrandModel::new(&StrandParams::default(), settings.quadrature_points)
        .expect("valid parameters");
    let models = vec![BatchModel::new(&model); roots.len()];
    let mut system = GpuEngine::new(gpu.clone(), &settings, &models, &roots, None)
        .expect("the GPU engine builds");
    system.step_frame(&RigidMotion::default());
    system.read_state().expect("a working device reads back");
    gpu.device.destroy();
    system.step_frame(&RigidMotion::default());
    let error = system
        .read_state()
        .expect_err("a destroyed device cannot read back");
    let message = error.to_string();
    assert!(message.contains("stopped working"), "{message}");
}

/// `EngineKind::Gpu` whose device is lost mid-run steps the frame again
/// on the CPU batch engine from its start, says so, and goes on there.
#[test]
fn the_gpu_engine_kind_steps_on_the_cpu_after_losing_its_device() {
    if context_or_skip("lost device: the GPU engine kind").is_none() {
        return;
    }
    let roots: Vec<RootPose> = (0..12)
        .map(|i| {
            let a = f64::from(i) * 0.5;
            let p = DVec3::new(0.1 * a.cos(), 0.05, 0.1 * a.sin());
            RootPose::from_direction(p, p, DVec3::Y)
        })
        .collect();
    let mut engine = Engine::new(EngineKind::Gpu, SimSettings::default()).expect("settings");
    engine
        .add_group(&StrandParams::default(), &roots)
        .expect("valid parameters");
    let shake = Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    engine.step_frame(&shake);
    let note = engine.gpu_note().expect("a GPU engine").to_owned();
    assert!(note.starts_with("physics on the GPU"), "{note}");
    let device = engine.gpu_side().and_then(|side| side.device());
    device.expect("a working device").context().device.destroy();
    for _ in 0..4 {
        engine.step_frame(&shake);
    }
    let note = engine.gpu_note().expect("a GPU engine");
    assert!(note.contains("the GPU was lost"), "{note}");
    assert!(
        note.contains("the CPU batch engine steps the hair"),
        "{note}"
    );
    assert!(engine.is_finite());
    let frames = engine.time_secs() / engine.settings().dt_secs;
    assert!((frames - 5.0).abs() < 1e-9, "{frames} frames stepped");
}

#[test]
fn the_renderer_reports_a_lost_device_instead_of_panicking() {
    let Some(gpu) = context_or_skip("lost device: renderer") else {
        return;
    };
    let head = default_head();
    let mut strands = StrandBuffers::default();
    strands.push_strand([Vec3::new(0.0, 0.1, 0.1), Vec3::new(0.0, -0.1, 0.1)]);
    let hair = HairStrands {
        strands,
        colours: vec![Vec3::new(0.3, 0.2, 0.1)],
        root_width_m: 4e-4,
        tip_width_m: 1e-4,
    };
    let mut renderer = OffscreenRenderer::new(gpu.clone(), RenderSettings::new(32, 32))
        .expect("the renderer builds");
    let scene = Scene {
        hair: &hair,
        head: &head,
        camera: OrbitCamera::default(),
        light: Light::default(),
    };
    renderer.render(&scene).expect("a working device draws");
    gpu.device.destroy();
    let error = renderer
        .render(&scene)
        .expect_err("a destroyed device cannot draw");
    let message = error.to_string();
    assert!(message.contains("stopped working"), "{message}");
}

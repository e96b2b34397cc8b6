//! Ribbons built on the device from points already there
//! (`shaders/ribbons.wgsl`) against their CPU reference on the same
//! points: the head's shell drape ([`HeadShell::drape`]), the pose, then
//! [`ribbon_mesh`]; and the picture drawn from them against the picture of
//! the CPU path.
//!
//! Policy: with no adapter the tests print why and pass, unless
//! `HELIXHAIR_REQUIRE_GPU=1` (set by `.ci/run`), where they fail.

use std::ops::Range;

use glam::{Mat3, Mat4, Quat, Vec3};
use helixhair_gpu::{context_or_skip, read_bytes, upload_buffer};
use helixhair_render::gpu::device_hair::DeviceStrands;
use helixhair_render::gpu::gpu_data::StrandVertex;
use helixhair_render::head_generate::default_head;
use helixhair_render::head_shell::HeadShell;
use helixhair_render::ribbons::ribbon_mesh;
use helixhair_render::{
    HairStrands, HeadMesh, Light, OffscreenRenderer, OrbitCamera, RenderSettings, Scene,
    StrandBuffers,
};

/// Gap kept from the head, metres (the app's drawn hair keeps 1.5 mm).
const GAP_M: f32 = 0.0015;

/// Device against CPU, per vertex, metres for positions: both are f32 and
/// do the same operations (the shell's angles by the same polynomial, not
/// the device's own `atan2`), the matrix product in the device's order.
/// Measured on lavapipe: 3e-8 m.
const POSITION_TOL_M: f32 = 1e-6;
/// Tangents and arc-length fractions, unitless: differences of positions
/// that agree to round-off, over segments down to under a millimetre
/// where the drape presses points together. Measured on lavapipe: 5e-5.
const DIRECTION_TOL: f32 = 1e-4;
/// The two pictures' mean difference per channel, 8-bit levels (below).
const PICTURE_TOL_LEVELS: f64 = 1.0;

/// Strands in head coordinates: from every scalp triangle's centre, first
/// 3 cm *into* the head and then down and back 20 cm, so that the drape
/// has work to do; with a little curl, and one strand of one point.
fn strands_in_head(head: &HeadMesh) -> (Vec<[f32; 4]>, Vec<Range<usize>>, Vec<Vec3>) {
    let (mut points, mut ranges, mut colours) = (Vec::new(), Vec::new(), Vec::new());
    for (i, &t) in head.scalp_triangles.iter().enumerate() {
        let corners = head.mesh.triangle(t as usize);
        let root = corners.iter().sum::<Vec3>() / 3.0;
        let first = points.len();
        let count = 10 + i % 7;
        for k in 0..count {
            let s = k as f32 / (count - 1) as f32;
            let inward = -root.normalize() * 0.03 * (s * 4.0).min(1.0);
            let down = Vec3::new(0.0, -0.2, -0.05) * s;
            let curl = Vec3::new((s * 20.0).sin(), 0.0, (s * 20.0).cos()) * 0.004 * s;
            let p = root + inward + down + curl;
            points.push([p.x, p.y, p.z, 1.0]);
        }
        ranges.push(first..points.len());
        colours.push(Vec3::new(0.3 + 0.001 * i as f32, 0.2, 0.1));
    }
    let lone = points.len();
    points.push([0.0, 0.2, 0.0, 1.0]);
    ranges.push(lone..lone + 1);
    colours.push(Vec3::ONE);
    (points, ranges, colours)
}

/// The CPU path on the same points: drape, pose, as `HairStrands`.
fn cpu_hair(
    points: &[[f32; 4]],
    ranges: &[Range<usize>],
    colours: &[Vec3],
    shell: &HeadShell,
    (rotation, position): (Mat3, Vec3),
) -> HairStrands {
    let mut strands = StrandBuffers::default();
    for range in ranges {
        let mut curve: Vec<Vec3> = points[range.clone()]
            .iter()
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect();
        shell.drape(&mut curve, GAP_M);
        strands.push_strand(curve.iter().map(|&p| rotation * p + position));
    }
    HairStrands {
        strands,
        colours: colours.to_vec(),
        root_width_m: 3e-4,
        tip_width_m: 1e-4,
    }
}

fn front_camera() -> OrbitCamera {
    OrbitCamera {
        yaw_rad: 0.3,
        pitch_rad: 0.1,
        ..OrbitCamera::default()
    }
}

#[test]
fn device_ribbons_match_the_cpu_drape_and_ribbons_and_draw_the_same_picture() {
    let Some(gpu) = context_or_skip("device_ribbons_match_the_cpu") else {
        return;
    };
    let head = default_head();
    let shell = HeadShell::new(&head.mesh);
    let (points, ranges, colours) = strands_in_head(&head);
    let rotation = Mat3::from_quat(Quat::from_axis_angle(
        Vec3::new(0.2, 1.0, 0.1).normalize(),
        0.4,
    ));
    let position = Vec3::new(0.01, -0.02, 0.005);
    let pose = (rotation, position);
    let world_from_head = Mat4::from_mat3(rotation) * Mat4::IDENTITY;
    let world_from_head = Mat4::from_translation(position) * world_from_head;
    let buffer = upload_buffer(
        &gpu.device,
        &gpu.queue,
        "test points",
        bytemuck::cast_slice(&points),
        wgpu::BufferUsages::STORAGE,
    );
    let device_strands = DeviceStrands {
        points: &buffer,
        ranges: &ranges,
        colours: &colours,
        shell: Some((&shell, GAP_M)),
        world_from_head,
        reach_m: 0.25,
        shaping: None,
    };
    let hair = cpu_hair(&points, &ranges, &colours, &shell, pose);
    let posed_head = head.posed(rotation, position);
    // Shadows off: the light's view is fitted differently on the two
    // paths (the device's points are not read back), and only the hair is
    // compared.
    let mut settings = RenderSettings::new(96, 96);
    settings.shadows = false;
    let mut renderer = OffscreenRenderer::new(gpu.clone(), settings).expect("renderer");
    let scene = Scene {
        hair: &hair,
        head: &posed_head,
        camera: front_camera(),
        light: Light::default(),
    };
    let from_device = renderer
        .render_device(&scene, &device_strands)
        .expect("device picture");
    let from_cpu = renderer.render(&scene).expect("cpu picture");

    let bytes = read_bytes(
        &gpu.device,
        &gpu.queue,
        renderer
            .device_ribbons()
            .and_then(|r| r.vertices())
            .expect("vertices"),
    )
    .expect("read");
    let device: &[StrandVertex] = bytemuck::cast_slice(&bytes);
    let (cpu, _) = ribbon_mesh(&hair);
    assert_eq!(device.len(), cpu.len(), "one vertex pair per point");
    let (mut position_err, mut direction_err) = (0.0f32, 0.0f32);
    let max_diff =
        |a: [f32; 3], b: [f32; 3]| (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f32::max);
    let mut pushed = 0;
    for (d, c) in device.iter().zip(&cpu) {
        position_err = position_err.max(max_diff(d.position_m, c.position_m));
        direction_err = direction_err
            .max(max_diff(d.tangent, c.tangent))
            .max((d.params[0] - c.params[0]).abs());
        assert_eq!(d.colour, c.colour);
        assert_eq!(d.params[1..], c.params[1..], "side and seed");
    }
    for range in &ranges {
        let first = Vec3::from_slice(&points[range.start][..3]);
        let last = Vec3::from_slice(&points[range.end - 1][..3]);
        if (last - shell.centre_m()).length() < (first - shell.centre_m()).length() {
            pushed += 1;
        }
    }
    eprintln!(
        "device ribbons: {} vertices, positions {position_err:.2e} m, tangents and fractions \
         {direction_err:.2e}",
        device.len()
    );
    assert!(pushed > 0, "the drape had strands to push out");
    assert!(
        position_err <= POSITION_TOL_M,
        "positions {position_err:e} m"
    );
    assert!(direction_err <= DIRECTION_TOL, "tangents {direction_err:e}");

    // The same ribbons draw the same picture. Ribbons thinner than a
    // pixel cover a random subset of its samples, and a tangent that
    // round-off turns (short segments where the drape presses points
    // together) can change the subset: scattered pixels differ (measured:
    // 2 % of them by more than 8 levels), the picture does not.
    let (mean_difference, differing) = from_device.difference(&from_cpu, 8);
    eprintln!(
        "device ribbons: pictures differ by {mean_difference:.2} levels on average, \
         {differing} pixels by more than 8"
    );
    assert!(
        mean_difference < PICTURE_TOL_LEVELS,
        "pictures differ by {mean_difference} levels"
    );
}

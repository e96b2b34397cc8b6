//! Drawn strands shaped by their guides on the device
//! (`shaders/strand_shape.wgsl`) against their CPU reference on the same
//! points ([`stage_guide_shapes`] then [`stage_shape`], the twins): curls clumped onto
//! a curled guide with a phase and radius of their own, straight strands
//! clumped onto a straight guide, strands following a blend of three
//! guides, one doing both and one left alone. Then the whole device path
//! (shaping, drape, ribbons) against the CPU's through the ribbons'
//! vertices.
//!
//! Policy: with no adapter the tests print why and pass, unless
//! `HELIXHAIR_REQUIRE_GPU=1` (set by `.ci/run`), where they fail.

use std::f32::consts::TAU;
use std::ops::Range;

use glam::{Mat4, Vec3};
use helixhair_gpu::{context_or_skip, read_bytes, upload_buffer};
use helixhair_render::gpu::device_hair::{DeviceRibbons, DeviceStrands};
use helixhair_render::gpu::device_shape::{DeviceShaper, DeviceShaping};
use helixhair_render::gpu::gpu_data::StrandVertex;
use helixhair_render::head_generate::default_head;
use helixhair_render::head_shell::HeadShell;
use helixhair_render::ribbons::ribbon_mesh;
use helixhair_render::strand_shape::{Clump, GuideShape, Shaping, stage_guide_shapes, stage_shape};
use helixhair_render::{HairStrands, StrandBuffers};

/// Device against CPU, per shaped point, metres: the same f32 loops in the
/// same order; the device's own `sin`, `cos`, `sqrt` and fused products
/// differ in the last bits, which the sliding centreline's sum and the
/// curl's turn carry along a strand of up to 161 points of a 12 mm curl.
/// Measured on lavapipe: 3.0e-8 m.
const SHAPE_TOL_M: f32 = 2e-6;

/// Ribbon vertices of the whole device path against the CPU's, metres:
/// [`SHAPE_TOL_M`] carried by the drape and the pose. Measured on
/// lavapipe: 3.0e-8 m.
const RIBBON_TOL_M: f32 = 5e-6;

/// A helix grown from `root` down −y: radius `r`, one turn per `pitch` of
/// fall, starting at `phase`, `n` points over `length` of arc.
fn helix(root: Vec3, r: f32, pitch: f32, phase: f32, length: f32, n: usize) -> Vec<Vec3> {
    let arc_per_turn = ((TAU * r).powi(2) + pitch * pitch).sqrt();
    (0..n)
        .map(|k| {
            let t = TAU * length / arc_per_turn * k as f32 / (n - 1) as f32;
            root + Vec3::new(
                r * ((t + phase).cos() - phase.cos()),
                -pitch * t / TAU,
                r * ((t + phase).sin() - phase.sin()),
            )
        })
        .collect()
}

/// A straight strand from `root` along `direction`, `n` points over
/// `length`, with a little sideways sway.
fn straight(root: Vec3, direction: Vec3, length: f32, n: usize) -> Vec<Vec3> {
    (0..n)
        .map(|k| {
            let s = k as f32 / (n - 1) as f32;
            root + direction * (length * s) + Vec3::new(0.004 * (s * 5.0).sin(), 0.0, 0.0)
        })
        .collect()
}

/// The test's curves (guides first, then drawn strands), their mean
/// strains, the guides' curves and each drawn strand's curve and shaping.
struct Layout {
    curves: Vec<Vec<Vec3>>,
    strains: Vec<f32>,
    guides: Vec<usize>,
    strands: Vec<usize>,
    shapings: Vec<Shaping>,
}

fn layout() -> Layout {
    let top = Vec3::new(0.0, 0.09, 0.0);
    // A 12 mm ringlet (|k| of a helix: 1/√(r² + (pitch/2π)²)), a straight
    // guide and three straight guides to follow.
    let (r, pitch) = (0.012, 0.03);
    let k = 1.0 / (r * r + (pitch / TAU).powi(2)).sqrt();
    let mut curves = vec![
        helix(top, r, pitch, 0.0, 0.25, 161),
        straight(top + Vec3::X * 0.03, Vec3::NEG_Y, 0.3, 13),
        straight(
            top - Vec3::X * 0.02,
            Vec3::new(0.3, -1.0, 0.0).normalize(),
            0.28,
            9,
        ),
        straight(
            top + Vec3::Z * 0.02,
            Vec3::new(0.0, -1.0, 0.4).normalize(),
            0.3,
            17,
        ),
        straight(
            top - Vec3::Z * 0.03,
            Vec3::new(-0.2, -1.0, -0.2).normalize(),
            0.26,
            8,
        ),
    ];
    let mut strains = vec![k, 0.3, 0.0, 0.5, 0.2];
    let guides = vec![0, 1, 2, 3, 4];
    let (mut strands, mut shapings) = (Vec::new(), Vec::new());
    let mut add = |curve: Vec<Vec3>, strain: f32, shaping: Shaping| {
        strands.push(curves.len());
        curves.push(curve);
        strains.push(strain);
        shapings.push(shaping);
    };
    for i in 0..6 {
        let root = top + Vec3::new(0.005 * i as f32, 0.0, 0.004);
        add(
            helix(root, r * 0.9, pitch, 0.4 * i as f32, 0.22, 120 + 7 * i),
            k,
            Shaping {
                clump: Some(Clump {
                    guide: 0,
                    amount: 0.7,
                    phase_rad: 0.1 * i as f32 - 0.3,
                    curl_scale: 0.85 + 0.05 * i as f32,
                }),
                follow: Vec::new(),
            },
        );
    }
    for i in 0..4 {
        let root = top + Vec3::new(0.02 + 0.004 * i as f32, 0.0, -0.01);
        let clump = Clump {
            guide: 1,
            amount: 0.5,
            phase_rad: 0.0,
            curl_scale: 1.0,
        };
        add(
            straight(root, Vec3::new(0.1, -1.0, 0.1).normalize(), 0.27, 11 + i),
            0.4,
            Shaping {
                clump: Some(clump),
                // The last one also follows.
                follow: if i == 3 { vec![(2, 1.0)] } else { Vec::new() },
            },
        );
    }
    for i in 0..5 {
        let root = top + Vec3::new(-0.01, 0.0, 0.003 * i as f32);
        add(
            straight(
                root,
                Vec3::new(-0.3, -1.0, 0.0).normalize(),
                0.29,
                10 + 2 * i,
            ),
            0.1,
            Shaping {
                clump: None,
                follow: vec![(2, 0.5), (3, 0.3), (4, 0.2)],
            },
        );
    }
    add(straight(top, Vec3::NEG_Y, 0.2, 6), 0.0, Shaping::default());
    Layout {
        curves,
        strains,
        guides,
        strands,
        shapings,
    }
}

/// The curves as one points buffer and their ranges.
fn flatten(curves: &[Vec<Vec3>]) -> (Vec<[f32; 4]>, Vec<Range<usize>>) {
    let (mut points, mut ranges) = (Vec::new(), Vec::new());
    for c in curves {
        let first = points.len();
        points.extend(c.iter().map(|p| [p.x, p.y, p.z, 1.0]));
        ranges.push(first..points.len());
    }
    (points, ranges)
}

/// The CPU's shaped drawn strands.
fn cpu_shaped(l: &Layout) -> Vec<Vec<Vec3>> {
    let guides: Vec<GuideShape> = l
        .guides
        .iter()
        .map(|&c| stage_guide_shapes(l.curves[c].clone(), l.strains[c]))
        .collect();
    l.strands
        .iter()
        .zip(&l.shapings)
        .map(|(&c, shaping)| {
            let mut curve = l.curves[c].clone();
            stage_shape(&mut curve, shaping, &guides);
            curve
        })
        .collect()
}

#[test]
fn the_device_shapes_drawn_strands_as_the_cpu_does() {
    let Some(gpu) = context_or_skip("device strand shaping") else {
        return;
    };
    let l = layout();
    let (points, ranges) = flatten(&l.curves);
    let storage = wgpu::BufferUsages::STORAGE;
    let points_buffer = upload_buffer(
        &gpu.device,
        &gpu.queue,
        "test points",
        bytemuck::cast_slice(&points),
        storage,
    );
    let strains_buffer = upload_buffer(
        &gpu.device,
        &gpu.queue,
        "test strains",
        bytemuck::cast_slice(&l.strains),
        storage,
    );
    let shaping = DeviceShaping {
        strains: &strains_buffer,
        curves: &ranges,
        guides: &l.guides,
        strands: &l.strands,
        shapings: &l.shapings,
    };
    let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let mut shaper = DeviceShaper::new(&gpu.device);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let shaped = shaper
        .encode(
            &gpu.device,
            &gpu.queue,
            &points_buffer,
            &shaping,
            &mut encoder,
        )
        .expect("shapes")
        .clone();
    gpu.queue.submit([encoder.finish()]);
    if let Some(e) = pollster::block_on(scope.pop()) {
        panic!("{e}");
    }
    let bytes = read_bytes(&gpu.device, &gpu.queue, &shaped).expect("read");
    let device: &[[f32; 4]] = bytemuck::cast_slice(&bytes);

    let want = cpu_shaped(&l);
    let mut worst = 0.0f32;
    let mut moved = 0.0f32;
    for ((&c, cpu), original) in l
        .strands
        .iter()
        .zip(&want)
        .zip(l.strands.iter().map(|&c| &l.curves[c]))
    {
        for ((d, p), o) in device[ranges[c].clone()].iter().zip(cpu).zip(original) {
            worst = worst.max((Vec3::new(d[0], d[1], d[2]) - *p).abs().max_element());
            moved = moved.max(p.distance(*o));
        }
    }
    eprintln!("shaping: device vs CPU {worst:.2e} m; strands moved up to {moved:.3} m");
    // Shaping did something to compare (clumps move tips by centimetres).
    assert!(moved > 0.01, "shaping moved nothing ({moved} m)");
    assert!(worst <= SHAPE_TOL_M, "device vs CPU {worst:e} m");

    // The last strand is left as it is.
    let last = *l.strands.last().expect("strands");
    for (d, p) in device[ranges[last].clone()].iter().zip(&l.curves[last]) {
        assert_eq!(Vec3::new(d[0], d[1], d[2]), *p);
    }

    // The whole device path: shaped, draped and built into ribbons, read
    // from the same points, against the CPU's ribbons of its own shaped
    // strands.
    let head = default_head();
    let shell = HeadShell::new(&head.mesh);
    let gap_m = 0.0015;
    let strand_ranges: Vec<Range<usize>> = l.strands.iter().map(|&c| ranges[c].clone()).collect();
    let colours = vec![Vec3::new(0.3, 0.2, 0.1); l.strands.len()];
    let strands = DeviceStrands {
        points: &points_buffer,
        ranges: &strand_ranges,
        colours: &colours,
        shell: Some((&shell, gap_m)),
        world_from_head: Mat4::IDENTITY,
        reach_m: 0.3,
        shaping: Some(shaping),
    };
    let mut ribbons = DeviceRibbons::new(&gpu.device);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    ribbons
        .encode(&gpu.device, &gpu.queue, &strands, &mut encoder)
        .expect("ribbons");
    gpu.queue.submit([encoder.finish()]);
    let vertices = ribbons.vertices().expect("built");
    let bytes = read_bytes(&gpu.device, &gpu.queue, vertices).expect("read");
    let device_vertices: &[StrandVertex] = bytemuck::cast_slice(&bytes);
    let mut buffers = StrandBuffers::default();
    for mut curve in want {
        shell.drape(&mut curve, gap_m);
        buffers.push_strand(curve);
    }
    let hair = HairStrands {
        strands: buffers,
        colours: colours.clone(),
        root_width_m: 1e-4,
        tip_width_m: 3.5e-5,
    };
    let (cpu_vertices, _) = ribbon_mesh(&hair);
    assert_eq!(device_vertices.len(), cpu_vertices.len());
    let worst = device_vertices
        .iter()
        .zip(&cpu_vertices)
        .map(|(d, c)| {
            (Vec3::from(d.position_m) - Vec3::from(c.position_m))
                .abs()
                .max_element()
        })
        .fold(0.0f32, f32::max);
    eprintln!("shaped ribbons: device vs CPU {worst:.2e} m");
    assert!(worst <= RIBBON_TOL_M, "ribbons: device vs CPU {worst:e} m");
}

#[test]
fn a_shaping_the_device_cannot_hold_is_refused_before_drawing() {
    use helixhair_render::gpu::device_shape::{ShapeError, shape_table};
    let l = layout();
    let count = l.curves.len();
    assert!(shape_table(count, &l.guides, &l.strands, &l.shapings).is_ok());
    let mut shapings = l.shapings.clone();
    shapings[0].follow = vec![(0, 0.2); 5];
    assert_eq!(
        shape_table(count, &l.guides, &l.strands, &shapings),
        Err(ShapeError::TooManyFollowed(5))
    );
    let mut shapings = l.shapings.clone();
    shapings[2].follow = vec![(99, 1.0)];
    assert_eq!(
        shape_table(count, &l.guides, &l.strands, &shapings),
        Err(ShapeError::Dangling(2))
    );
}

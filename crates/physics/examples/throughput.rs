//! Quick throughput probe of the CPU paths: element-steps per second of the
//! f64 reference (one thread) and the f32 batch path (one thread and all
//! threads) for one strand count, element count and quadrature.
//!
//! `cargo run --release -p helixhair-physics --example throughput -- STRANDS N POINTS`
//!
//! Prints CSV: path, method, strands, elements, points, median element-steps
//! per second over 7 timed batches of at least 0.2 s each.
//!
//! With `--collider`, the roots are spread over the upper two fifths of a
//! sphere of radius 10 cm (a scalp), and the batch rows are measured twice
//! from the same state (the strands draped over the sphere for half a
//! second): without and with the sphere as collider (rows `…+collider`).
//! The share of end points within the contact skin goes to stderr.

use std::sync::Arc;
use std::time::Instant;

use glam::DVec3;
use helixhair_physics::batch::BatchSystem;
use helixhair_physics::collision::{ContactSettings, SignedDistanceField};
use helixhair_physics::{HairSystem, Method, RigidMotion, RootPose, SimSettings, StrandParams};

fn roots(count: usize) -> Vec<RootPose> {
    (0..count)
        .map(|i| {
            let a = i as f64 * 2.399963;
            let dir = DVec3::new(a.cos(), 0.3, a.sin());
            RootPose::from_direction(dir * 0.1, dir, DVec3::Y)
        })
        .collect()
}

/// Radius of the collider sphere, metres: the roots sit on it.
const HEAD_RADIUS_M: f64 = 0.1;

/// `count` roots on the sphere's cap above y = 0.2 R, growing outward and
/// down.
fn scalp_roots(count: usize) -> Vec<RootPose> {
    (0..count)
        .map(|i| {
            let y = 0.2 + 0.8 * (i as f64 + 0.5) / count as f64;
            let a = i as f64 * 2.399963;
            let r = (1.0 - y * y).sqrt();
            let normal = DVec3::new(r * a.cos(), y, r * a.sin());
            let grow = normal + DVec3::new(0.0, -0.8, 0.0);
            RootPose::from_direction(normal * HEAD_RADIUS_M, grow, DVec3::Y)
        })
        .collect()
}

/// A UV sphere of radius [`HEAD_RADIUS_M`] as a signed distance field on a
/// 4 mm grid.
fn head_collider() -> SignedDistanceField {
    let (rings, segments) = (24u32, 48u32);
    let mut positions = Vec::new();
    for i in 0..=rings {
        let polar = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        for j in 0..segments {
            let azimuth = std::f64::consts::TAU * f64::from(j) / f64::from(segments);
            let dir = DVec3::new(
                polar.sin() * azimuth.cos(),
                polar.cos(),
                polar.sin() * azimuth.sin(),
            );
            positions.push(dir * HEAD_RADIUS_M);
        }
    }
    let at = |i: u32, j: u32| i * segments + j % segments;
    let mut triangles = Vec::new();
    // Wound so that the face normals point out; none at the poles' zero
    // area.
    for i in 0..rings {
        for j in 0..segments {
            if i + 1 < rings {
                triangles.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
            }
            if i > 0 {
                triangles.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
            }
        }
    }
    SignedDistanceField::from_triangles(&positions, &triangles, 0.004).expect("a valid sphere")
}

/// Share of the batch's end points within the contact skin of the sphere.
fn contact_share(batch: &BatchSystem) -> f64 {
    let skin_m = ContactSettings::default().skin_m;
    let (mut touching, mut total) = (0usize, 0usize);
    for i in 0..batch.strand_count() {
        for p in &batch.boundary_points_world(i)[1..] {
            total += 1;
            touching += usize::from(p.as_dvec3().length() - HEAD_RADIUS_M < skin_m);
        }
    }
    touching as f64 / total.max(1) as f64
}

fn median_rate(mut step: impl FnMut(), element_steps_per_call: f64) -> f64 {
    step();
    let mut calls = 1usize;
    loop {
        let t = Instant::now();
        for _ in 0..calls {
            step();
        }
        if t.elapsed().as_secs_f64() > 0.2 {
            break;
        }
        calls *= 2;
    }
    let mut rates: Vec<f64> = (0..7)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..calls {
                step();
            }
            element_steps_per_call * calls as f64 / t.elapsed().as_secs_f64()
        })
        .collect();
    rates.sort_by(f64::total_cmp);
    rates[3]
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let strands = args.first().copied().unwrap_or(1000);
    let n = args.get(1).copied().unwrap_or(10);
    let points = args.get(2).copied().unwrap_or(4);
    let params = StrandParams {
        elements: n,
        ..StrandParams::default()
    };
    let collider = std::env::args()
        .any(|a| a == "--collider")
        .then(|| Arc::new(head_collider()));
    let roots = if collider.is_some() {
        scalp_roots(strands)
    } else {
        roots(strands)
    };
    let head = RigidMotion::default();
    let work = (strands * n) as f64;
    // `-- STRANDS N POINTS STEPS`: only step the serial Block-diagonal batch
    // STEPS times, for `perf stat` (cycles per element-step do not depend
    // on what else the machine runs).
    if let Some(&steps) = args.get(3) {
        let method = if args.get(4) == Some(&1) {
            Method::Exact
        } else {
            Method::BlockDiagonal
        };
        let settings = SimSettings {
            method,
            dt_secs: 1.0 / 600.0,
            quadrature_points: points,
            ..SimSettings::default()
        };
        let mut batch = BatchSystem::new(settings).expect("valid settings");
        batch.add_group(&params, &roots).expect("valid params");
        batch.set_parallel(false);
        batch.set_collider(collider.clone());
        let start = Instant::now();
        for _ in 0..steps {
            batch.step_frame(&head);
        }
        let secs = start.elapsed().as_secs_f64();
        assert!(batch.is_finite(), "non-finite state");
        eprintln!("{:.3e} element-steps/s", work * steps as f64 / secs);
        return;
    }
    println!("path,method,strands,elements,points,element_steps_per_sec");
    for method in [Method::BlockDiagonal, Method::Exact] {
        let settings = SimSettings {
            method,
            dt_secs: 1.0 / 600.0,
            quadrature_points: points,
            ..SimSettings::default()
        };
        if strands <= 2000 {
            let mut reference = HairSystem::new(settings.clone()).expect("valid settings");
            reference.add_group(&params, &roots).expect("valid params");
            reference.set_parallel(false);
            let rate = median_rate(|| reference.step_frame(&head), work);
            println!(
                "f64-reference-1-thread,{},{strands},{n},{points},{rate:.4e}",
                method.name()
            );
        }
        let colliders = match &collider {
            Some(c) => vec![None, Some(c.clone())],
            None => vec![None],
        };
        for parallel in [false, true] {
            for collider in &colliders {
                let mut batch = BatchSystem::new(settings.clone()).expect("valid settings");
                batch.add_group(&params, &roots).expect("valid params");
                batch.set_parallel(true);
                if colliders.len() > 1 {
                    // Drape (or, without a collider, fall) for half a second.
                    batch.set_collider(Some(colliders[1].clone().expect("set")));
                    for _ in 0..300 {
                        batch.step_frame(&head);
                    }
                }
                batch.set_collider(collider.clone());
                batch.set_parallel(parallel);
                let rate = median_rate(|| batch.step_frame(&head), work);
                assert!(batch.is_finite(), "non-finite state");
                assert_eq!(batch.guard_reset_count(), 0, "the guard reset strands");
                let path = if parallel {
                    "f32-batch-all-threads"
                } else {
                    "f32-batch-1-thread"
                };
                let tag = if collider.is_some() {
                    eprintln!(
                        "{path} {}: {:.1}% of end points in contact",
                        method.name(),
                        100.0 * contact_share(&batch)
                    );
                    "+collider"
                } else {
                    ""
                };
                println!(
                    "{path}{tag},{},{strands},{n},{points},{rate:.4e}",
                    method.name()
                );
            }
        }
    }
}

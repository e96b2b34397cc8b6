//! Quick throughput probe of the CPU paths: element-steps per second of the
//! f64 reference (one thread) and the f32 batch path (one thread and all
//! threads) for one strand count, element count and quadrature.
//!
//! `cargo run --release -p helixhair-physics --example throughput -- STRANDS N POINTS`
//!
//! Prints CSV: path, method, strands, elements, points, median element-steps
//! per second over 7 timed batches of at least 0.2 s each.

use std::time::Instant;

use glam::DVec3;
use helixhair_physics::batch::BatchSystem;
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
    let roots = roots(strands);
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
        for parallel in [false, true] {
            let mut batch = BatchSystem::new(settings.clone()).expect("valid settings");
            batch.add_group(&params, &roots).expect("valid params");
            batch.set_parallel(parallel);
            let rate = median_rate(|| batch.step_frame(&head), work);
            assert!(batch.is_finite(), "non-finite state");
            let path = if parallel {
                "f32-batch-all-threads"
            } else {
                "f32-batch-1-thread"
            };
            println!("{path},{},{strands},{n},{points},{rate:.4e}", method.name());
        }
    }
}

//! Per-step cost of one strand for each method and element count, single
//! thread: `cargo run --release -p helixhair-physics --example step_cost`
//! times a 20 cm curl; add `-- straight` to time a straight strand, on
//! which every method but the own-element blocks stays finite.
//!
//! Each (method, N) pair runs 15 batches of steps after a warm-up and
//! prints the median seconds per step, with the spread (min and max batch),
//! as CSV on stdout, for the velocity-explicit step and the default
//! velocity-implicit one (`quick`: N = 10 and 20 only). Compare methods as ratios taken from one run: the
//! machine is shared and absolute times drift.

use std::sync::Arc;
use std::time::Instant;

use glam::DVec3;
use helixhair_physics::{
    Method, NaturalShape, RigidMotion, RootPose, StepScheme, Strand, StrandModel, StrandParams,
};

const BATCHES: usize = 15;

fn main() {
    let straight = std::env::args().any(|a| a == "straight");
    let shape = if straight {
        NaturalShape::Straight
    } else {
        NaturalShape::Helix {
            radius_m: 0.02,
            step_m: 0.05,
        }
    };
    let sizes: &[usize] = if std::env::args().any(|a| a == "quick") {
        &[10, 20]
    } else {
        &[5, 10, 20, 50, 100]
    };
    println!("method,scheme,elements,median_secs_per_step,min_secs_per_step,max_secs_per_step");
    for &n in sizes {
        for (method, scheme) in Method::ALL.into_iter().flat_map(|m| {
            [
                StepScheme::VelocityExplicit,
                StepScheme::VelocityImplicit { corrections: 1 },
                StepScheme::default(),
            ]
            .map(|s| (m, s))
        }) {
            let params = StrandParams {
                elements: n,
                natural_shape: shape.clone(),
                ..StrandParams::default()
            };
            let model = Arc::new(StrandModel::new(&params, 4).expect("valid parameters"));
            let root = RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Y);
            let mut strand = Strand::new(model, root, method);
            strand.set_scheme(scheme);
            let motion = RigidMotion::default();
            let gravity = DVec3::new(0.0, -9.81, 0.0);
            let h = 1.0 / 600.0; // small enough for every method to stay finite
            let steps_per_batch = (20_000 / n).max(20);
            for _ in 0..steps_per_batch {
                strand.step(&motion, gravity, DVec3::ZERO, h);
            }
            let mut batches: Vec<f64> = (0..BATCHES)
                .map(|_| {
                    let start = Instant::now();
                    for _ in 0..steps_per_batch {
                        strand.step(&motion, gravity, DVec3::ZERO, h);
                    }
                    start.elapsed().as_secs_f64() / steps_per_batch as f64
                })
                .collect();
            batches.sort_by(f64::total_cmp);
            let finite = if strand.is_finite() {
                ""
            } else {
                " (non-finite)"
            };
            println!(
                "{},{},{n},{:.3e},{:.3e},{:.3e}{finite}",
                method.name(),
                scheme_name(scheme),
                batches[BATCHES / 2],
                batches[0],
                batches[BATCHES - 1]
            );
        }
    }
}

fn scheme_name(scheme: StepScheme) -> String {
    match scheme {
        StepScheme::VelocityExplicit => "explicit".into(),
        StepScheme::VelocityImplicit { corrections } => format!("implicit{corrections}"),
    }
}

//! Cost of the velocity-implicit step against the velocity-explicit one
//! under a head shake, measured in one run: `cargo run --release -p
//! helixhair-physics --example scheme_cost -- [curly|straight] [dt_secs]
//! [repeats]`.
//!
//! Two strands of `curly.ron`'s crown (25 cm, 15 elements; or the straight
//! example's 30 cm, 12 elements) on a 10 cm head shaking 0.5 rad at 1.5 Hz,
//! 600 frames, one substep, guard off, as `shake_probe`, one thread. For each solver
//! two systems, one per scheme, step in turn, 30 frames at a time, so a
//! busy machine slows both alike; the time is the thread's own CPU time
//! (`CLOCK_THREAD_CPUTIME_ID`: on a shared machine wall time also counts
//! the other processes' turns). Each repeat gives both schemes'
//! milliseconds per frame; the table prints the medians over repeats and
//! the median of the per-repeat ratios. Block-diagonal is timed at
//! both schemes too, though it keeps its velocity terms explicit.

use helixhair_physics::{HairSystem, Method, SimSettings, StepScheme, StrandParams};

// The scene of the stable-step tests: roots, shake, the straight strands.
#[allow(dead_code)] // the tests' module; this example uses part of it
#[path = "../tests/common/shake_scene.rs"]
mod shake_scene;

/// Frames each system steps before the other takes its turn.
const BLOCK: u32 = 30;

/// `curly.ron`'s crown, or the straight example's long strands.
fn params(curly: bool) -> StrandParams {
    if curly {
        shake_scene::curly_25_cm()
    } else {
        shake_scene::straight_30_cm()
    }
}

fn system(method: Method, scheme: StepScheme, curly: bool, dt_secs: f64) -> HairSystem {
    let settings = SimSettings {
        method,
        scheme,
        dt_secs,
        substeps: 1,
        ..SimSettings::default()
    };
    let mut sys = HairSystem::new(settings).expect("valid settings");
    sys.set_guard(None);
    // One thread: a thread pool's hand-offs on two strands cost more than
    // the steps on a busy machine, and drown what is measured.
    sys.set_parallel(false);
    sys.add_group(&params(curly), &shake_scene::head_roots())
        .expect("valid strands");
    sys
}

/// Seconds this thread has spent on a CPU.
fn thread_secs() -> f64 {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let curly = args.get(1).map(String::as_str) != Some("straight");
    let dt_secs: f64 = args
        .get(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0 / 60.0);
    let repeats: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(9);
    let shake = shake_scene::ordinary_shake();
    let frames: u32 = 600;
    println!("| solver | velocity-explicit, ms | velocity-implicit, ms | new / old |");
    println!("| --- | --- | --- | --- |");
    for method in [
        Method::Exact,
        Method::Iterative { iterations: 4 },
        Method::Dense,
        Method::BlockDiagonal,
    ] {
        let (mut old, mut new, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
        let mut finite = [true; 2];
        for _ in 0..repeats {
            let mut systems = [
                system(method, StepScheme::VelocityExplicit, curly, dt_secs),
                system(method, StepScheme::default(), curly, dt_secs),
            ];
            let mut secs = [0.0; 2];
            for _ in 0..frames / BLOCK {
                for (sys, s) in systems.iter_mut().zip(&mut secs) {
                    let started = thread_secs();
                    for _ in 0..BLOCK {
                        sys.step_frame(&shake);
                    }
                    *s += thread_secs() - started;
                }
            }
            for (f, sys) in finite.iter_mut().zip(&systems) {
                *f &= sys.is_finite();
            }
            let ms = secs.map(|s| 1e3 * s / f64::from(frames));
            old.push(ms[0]);
            new.push(ms[1]);
            ratio.push(ms[1] / ms[0]);
        }
        let note = |f: bool| if f { "" } else { " (blew up)" };
        println!(
            "| {} | {:.3}{} | {:.3}{} | {:.2} |",
            method.name(),
            median(old),
            note(finite[0]),
            median(new),
            note(finite[1]),
            median(ratio)
        );
    }
}

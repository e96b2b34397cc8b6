//! Probe: `shake_probe`'s scene on the f32 batch engine (Exact): the
//! straight, wavy or curly example's strands on two roots of a 10 cm head,
//! head shake 0.5 rad at 1.5 Hz, guard off. Prints whether the run stayed
//! finite, the fastest boundary point per second, and the physics time per
//! frame (median of `repeats` runs).
//!
//! `cargo run --release -p helixhair-physics --example batch_shake_probe --
//! [straight|wavy|curly] [explicit|CORRECTIONS] [dt_secs] [repeats] [copies]`
//!
//! `copies` repeats the two roots (default 4: one full batch of 8 lanes).

#[path = "../tests/common/shake_scene.rs"]
#[allow(dead_code)]
mod shake_scene;

use helixhair_physics::batch::BatchSystem;
use helixhair_physics::{Method, RootPose, SimSettings, StepScheme, StrandParams};
use shake_scene::{head_roots, ordinary_shake, strands_named};

/// One run of `frames` frames: (finite, physics seconds, fastest point in
/// the last second, m/s).
fn run(settings: &SimSettings, params: &StrandParams, roots: &[RootPose]) -> (bool, f64, f64) {
    let mut sys = BatchSystem::new(settings.clone()).expect("valid settings");
    sys.set_guard(None);
    sys.add_group(params, roots).expect("valid params");
    let shake = ordinary_shake();
    let frames = (10.0 / settings.dt_secs).round() as usize;
    let per_second = (1.0 / settings.dt_secs).round() as usize;
    let mut physics_secs = 0.0;
    let mut fastest = 0.0f32;
    let mut prev: Vec<_> = (0..roots.len())
        .map(|i| sys.boundary_points_world(i))
        .collect();
    for f in 0..frames {
        let started = std::time::Instant::now();
        sys.step_frame(&shake);
        physics_secs += started.elapsed().as_secs_f64();
        if !sys.is_finite() {
            println!("  frame {f}: NOT FINITE");
            return (false, physics_secs, f64::NAN);
        }
        let last_second = f + per_second >= frames;
        for (i, p) in prev.iter_mut().enumerate() {
            let now = sys.boundary_points_world(i);
            if last_second {
                for (a, b) in now.iter().zip(p.iter()) {
                    fastest = fastest.max((*a - *b).length() / settings.dt_secs as f32);
                }
            }
            *p = now;
        }
    }
    (true, physics_secs / frames as f64, f64::from(fastest))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let shape = args.get(1).map(String::as_str).unwrap_or("straight");
    let scheme = match args.get(2).map(String::as_str) {
        Some("explicit") => StepScheme::VelocityExplicit,
        Some(k) => StepScheme::VelocityImplicit {
            corrections: k.parse().expect("corrections: a number or `explicit`"),
        },
        None => StepScheme::default(),
    };
    let dt_secs = args
        .get(3)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0 / 60.0);
    let repeats: usize = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(1);
    let copies: usize = args.get(5).and_then(|s| s.parse().ok()).unwrap_or(4);
    let settings = SimSettings {
        method: Method::Exact,
        scheme,
        dt_secs,
        substeps: 1,
        ..SimSettings::default()
    };
    let two = head_roots();
    let roots: Vec<RootPose> = two.iter().cycle().take(2 * copies).copied().collect();
    let params = strands_named(shape);
    let mut times = Vec::new();
    for _ in 0..repeats.max(1) {
        let (finite, secs, fastest) = run(&settings, &params, &roots);
        println!(
            "{shape} {scheme:?} dt {dt_secs:.5} s: {}, fastest point in the last second \
             {fastest:.2} m/s, {:.4} ms per frame",
            if finite { "finite" } else { "BLEW UP" },
            secs * 1e3
        );
        times.push(secs);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "median physics time: {:.4} ms per frame ({} strands)",
        times[times.len() / 2] * 1e3,
        roots.len()
    );
}

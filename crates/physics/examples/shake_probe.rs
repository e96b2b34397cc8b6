//! Probe: a 30 cm straight strand under a head shake (0.5 rad at 1.5 Hz),
//! guard off; prints the largest point speed relative to the root per second
//! and whether the run stayed finite.
//!
//! `cargo run --release -p helixhair-physics --example shake_probe -- [method] [substeps] [straight|wavy|curly] [explicit|CORRECTIONS] [dt_secs]`

#[path = "../tests/common/shake_scene.rs"]
#[allow(dead_code)]
mod shake_scene;

use glam::DVec3;
use helixhair_physics::{HairSystem, Method, SimSettings, StepScheme};
use shake_scene::{head_roots, ordinary_shake, strands_named};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let method = args
        .get(1)
        .and_then(|m| Method::from_name(m))
        .unwrap_or(Method::Exact);
    let substeps: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let shape = args.get(3).map(String::as_str).unwrap_or("straight");
    let params = strands_named(shape);
    let scheme = match args.get(4).map(String::as_str) {
        Some("explicit") => StepScheme::VelocityExplicit,
        Some(k) => StepScheme::VelocityImplicit {
            corrections: k.parse().expect("corrections"),
        },
        None => StepScheme::default(),
    };
    let settings = SimSettings {
        method,
        scheme,
        dt_secs: args
            .get(5)
            .and_then(|s| s.parse().ok())
            .unwrap_or(1.0 / 60.0),
        substeps,
        ..SimSettings::default()
    };
    let mut sys = HairSystem::new(settings).unwrap();
    sys.set_guard(None);
    let roots = head_roots();
    sys.add_group(&params, &roots).unwrap();
    let shake = ordinary_shake();
    let frames = 600;
    let mut physics_secs = 0.0;
    let mut max_speed = 0.0f64;
    let mut prev: Vec<Vec<DVec3>> = (0..roots.len())
        .map(|i| sys.boundary_points_world(i))
        .collect();
    for f in 0..frames {
        let started = std::time::Instant::now();
        sys.step_frame(&shake);
        physics_secs += started.elapsed().as_secs_f64();
        for (i, p) in prev.iter_mut().enumerate() {
            let now = sys.boundary_points_world(i);
            for (a, b) in now.iter().zip(p.iter()) {
                max_speed = max_speed.max((*a - *b).length() / sys.settings().dt_secs);
            }
            *p = now;
        }
        if !sys.is_finite() {
            println!("frame {f}: NOT FINITE");
            return;
        }
        if (f + 1) % 60 == 0 {
            let e = sys.energies();
            println!(
                "t = {:.1} s  max point speed (world, finite diff) {:.3} m/s  E = {:.3e} J",
                (f + 1) as f64 / 60.0,
                max_speed,
                e.total_j()
            );
            max_speed = 0.0;
        }
    }
    println!(
        "physics: {:.3} ms per frame",
        1e3 * physics_secs / f64::from(frames)
    );
}

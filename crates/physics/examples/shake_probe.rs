//! Probe: a 30 cm straight strand under a head shake (0.5 rad at 1.5 Hz),
//! guard off; prints the largest point speed relative to the root per second
//! and whether the run stayed finite.
//!
//! `cargo run --release -p helixhair-physics --example shake_probe -- [method] [substeps] [straight|wavy|curly] [explicit|CORRECTIONS] [dt_secs]`

use glam::DVec3;
use helixhair_physics::{
    ElementLayout, HairSystem, Method, NaturalShape, Oscillation, RootPose, SimSettings,
    StepScheme, StrandParams,
};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let method = args
        .get(1)
        .and_then(|m| Method::from_name(m))
        .unwrap_or(Method::Exact);
    let substeps: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let shape = args.get(3).map(String::as_str).unwrap_or("straight");
    let wavy = shape == "wavy";
    let curly = shape == "curly";
    let params = if curly {
        // assets/styles/curly.ron's crown.
        StrandParams {
            length_m: 0.25,
            elements: 15,
            ellipticity: 1.35,
            natural_shape: NaturalShape::Helix {
                radius_m: 0.012,
                step_m: 0.03,
            },
            ..StrandParams::default()
        }
    } else {
        StrandParams {
            length_m: 0.3,
            elements: 12,
            layout: ElementLayout::Graded {
                tip_to_root_ratio: 3.0,
            },
            radius_m: 40e-6,
            natural_shape: if wavy {
                NaturalShape::Helix {
                    radius_m: 0.025,
                    step_m: 0.12,
                }
            } else {
                NaturalShape::Straight
            },
            ..StrandParams::default()
        }
    };
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
    let roots = [
        RootPose::from_direction(
            DVec3::new(0.0966, 0.0259, 0.0),
            DVec3::new(0.9659, 0.2588, 0.0),
            DVec3::Z,
        ),
        RootPose::from_direction(
            DVec3::new(0.0, 0.0866, 0.05),
            DVec3::new(0.0, 0.866, 0.5),
            DVec3::X,
        ),
    ];
    sys.add_group(&params, &roots).unwrap();
    let shake = Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
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

//! Probe: per frame, the energy a strand gains that no force put in
//! (`frame_balance`), against its kinetic energy, for a short strand
//! released horizontally (still head) and a 30 cm strand under a head shake.
//!
//! `cargo run --release -p helixhair-physics --example energy_probe -- METHOD [still|shake] [seconds]`

use std::sync::Arc;

use glam::DVec3;
use helixhair_physics::frame_balance::{MeasureInputs, SteppedFrame, unexplained_energy_j};
use helixhair_physics::motion::HeadTrajectory;
use helixhair_physics::{
    ElementLayout, Method, Oscillation, RigidMotion, RootPose, Strand, StrandModel, StrandParams,
};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let method = args
        .get(1)
        .and_then(|m| Method::from_name(m))
        .unwrap_or(Method::Exact);
    let shake = args.get(2).map(|s| s == "shake").unwrap_or(false);
    let seconds: f64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(15.0);
    let params = if shake {
        StrandParams {
            length_m: 0.3,
            elements: 12,
            layout: ElementLayout::Graded {
                tip_to_root_ratio: 3.0,
            },
            radius_m: 40e-6,
            ..StrandParams::default()
        }
    } else {
        StrandParams {
            length_m: std::env::var("LENGTH_M")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(0.1),
            elements: std::env::var("ELEMENTS")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(10),
            ..StrandParams::default()
        }
    };
    let model = Arc::new(StrandModel::new(&params, 4).unwrap());
    let root = if shake {
        RootPose::from_direction(
            DVec3::new(0.0966, 0.0259, 0.0),
            DVec3::new(0.9659, 0.2588, 0.0),
            DVec3::Z,
        )
    } else {
        RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Y)
    };
    let head: Box<dyn HeadTrajectory> = if shake {
        Box::new(Oscillation {
            axis: DVec3::Y,
            amplitude_rad: 0.5,
            frequency_hz: 1.5,
        })
    } else {
        Box::new(RigidMotion::default())
    };
    let mut strand = Strand::new(model.clone(), root, method);
    let g = DVec3::new(0.0, -9.81, 0.0);
    let inputs = MeasureInputs {
        gravity_m_per_s2: g,
        air_velocity_m_per_s: DVec3::ZERO,
        contact: None,
    };
    let h = 1.0 / 60.0;
    let mut t = 0.0;
    let motion = head.motion_at(t).carry(&root);
    let mut last = strand.measure(&motion, &inputs);
    let e0 = last.energy_j;
    let mut worst_ratio: f64 = f64::NEG_INFINITY;
    let mut worst_abs: f64 = f64::NEG_INFINITY;
    let frames = (seconds * 60.0) as usize;
    for f in 0..frames {
        let motion = head.motion_at(t).carry(&root);
        strand.step(&motion, g, DVec3::ZERO, h);
        t += h;
        let motion = head.motion_at(t).carry(&root);
        let now = strand.measure(&motion, &inputs);
        let gain = unexplained_energy_j(
            &last,
            &now,
            SteppedFrame {
                dt_secs: h,
                substeps: 1,
            },
        );
        let scale = last.kinetic_j + now.kinetic_j;
        worst_abs = worst_abs.max(gain);
        if scale > 0.0 {
            worst_ratio = worst_ratio.max(gain / scale);
        }
        if (f + 1) % 60 == 0 || !now.energy_j.is_finite() {
            println!(
                "t = {t:5.2} s  E − E0 = {:+.3e} J  T = {:.3e} J  fastest {:.3} m/s  worst gain/T so far {worst_ratio:+.3e}, abs {worst_abs:+.3e} J",
                now.energy_j - e0,
                now.kinetic_j,
                now.fastest_relative_m_per_s
            );
            worst_ratio = f64::NEG_INFINITY;
            worst_abs = f64::NEG_INFINITY;
            if !now.energy_j.is_finite() {
                return;
            }
        }
        last = now;
    }
}

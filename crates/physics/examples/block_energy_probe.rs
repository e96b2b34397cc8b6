//! Probe: Block-diagonal's own energy T_bd + V (T_bd = ½ q̇ᵀ M_bd q̇, the
//! truncated inertia it solves with) frame by frame, for a short strand
//! released horizontally with a still head, with the velocity terms of the
//! whole system (the velocity-explicit scheme: the old step) and with those
//! of Block-diagonal's own Lagrangian (the default scheme), guard off.
//!
//! `cargo run --release -p helixhair-physics --example block_energy_probe -- [length_m] [elements] [dt_secs] [seconds] [straight|curl]`
//!
//! A frame's gain counts when it passes 1e-12 of T_bd + |U| + |U_g|.

use std::sync::Arc;

use glam::DVec3;
use helixhair_physics::energy::energies;
use helixhair_physics::step::mass::{MassData, mass_blocks};
use helixhair_physics::{
    Method, RigidMotion, RootPose, StepScheme, Strand, StrandModel, StrandParams,
};

/// T_bd + V of the strand (joules), T_bd alone, and the energies' size
/// T_bd + |U| + |U_g| (what round-off is relative to).
fn block_energy(
    strand: &Strand,
    root: &RigidMotion,
    g: DVec3,
    mass: &mut MassData,
) -> (f64, f64, f64) {
    let kin = strand.kinematics(root);
    mass_blocks(strand.model(), &kin, mass);
    let t_bd: f64 = strand
        .v()
        .iter()
        .zip(&mass.diagonal)
        .map(|(v, b)| 0.5 * v.dot(*b * *v))
        .sum();
    let e = energies(strand.model(), strand.q(), &kin, root.position_m, g);
    (
        t_bd + e.elastic_j + e.gravity_j,
        t_bd,
        t_bd + e.elastic_j.abs() + e.gravity_j.abs(),
    )
}

/// A gain below this fraction of the energies' size is round-off.
const ROUNDOFF: f64 = 1e-12;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize, default: f64| args.get(i).and_then(|s| s.parse().ok()).unwrap_or(default);
    let mut params = StrandParams {
        length_m: arg(1, 0.1),
        elements: arg(2, 10.0) as usize,
        ..StrandParams::default()
    };
    if args.get(5).map(String::as_str) == Some("curl") {
        // tests/failure_modes.rs's hanging curl.
        params.natural_shape = helixhair_physics::NaturalShape::Helix {
            radius_m: 0.02,
            step_m: 0.05,
        };
        params.internal_friction = 2e-10;
        params.air_drag = 1e-5;
    }
    let h = arg(3, 1.0 / 60.0);
    let seconds = arg(4, 15.0);
    let model = Arc::new(StrandModel::new(&params, 4).expect("valid parameters"));
    let root = RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Y);
    let still = RigidMotion::default().carry(&root);
    let g = DVec3::new(0.0, -9.81, 0.0);
    for (label, scheme) in [
        (
            "whole system's velocity terms (old)",
            StepScheme::VelocityExplicit,
        ),
        (
            "Block-diagonal's own Lagrangian (new)",
            StepScheme::default(),
        ),
    ] {
        let mut strand = Strand::new(model.clone(), root, Method::BlockDiagonal);
        strand.set_scheme(scheme);
        let mut mass = MassData::default();
        let (e0, _, _) = block_energy(&strand, &still, g, &mut mass);
        let mut last = e0;
        let (mut grew, mut largest_gain, mut largest_relative) = (0, 0.0f64, 0.0f64);
        let frames = (seconds / h).round() as usize;
        for _ in 0..frames {
            strand.step(&RigidMotion::default(), g, DVec3::ZERO, h);
            let (e, t_bd, size) = block_energy(&strand, &still, g, &mut mass);
            let gain = e - last;
            if !e.is_finite() {
                println!("{label}: not finite");
                break;
            }
            if gain > ROUNDOFF * size {
                grew += 1;
                largest_gain = largest_gain.max(gain);
                largest_relative = largest_relative.max(gain / t_bd.max(f64::MIN_POSITIVE));
            }
            last = e;
        }
        let (e, t_bd, _) = block_energy(&strand, &still, g, &mut mass);
        let t = strand.energies(&still, g).kinetic_j;
        println!(
            "{label}: T_bd + V grew on {grew} of {frames} frames (largest gain {largest_gain:.2e} J, {largest_relative:.2e} of T_bd); after {seconds} s: E − E0 = {:+.3e} J, T_bd = {t_bd:.2e} J, T = {t:.2e} J",
            e - e0
        );
    }
}

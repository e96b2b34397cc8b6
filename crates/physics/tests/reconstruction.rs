//! Reconstruction against known answers: the golden value of docs/physics.md
//! section 2, an independent ODE integration of the frame equations, and
//! the helix radius and pitch of a constant-strain strand.

use crate::common;

use common::*;
use glam::{DMat3, DVec3};
use helixhair_physics::geometry::helix::{centreline_and_jacobian, rotation};
use helixhair_physics::natural_shape::{helix_radius_and_step, helix_strains};

/// The golden value is quoted to 7 decimals.
const GOLDEN_TOL: f64 = 1e-7;
/// Closed form against a fine RK4 integration of n' = Ω × n, r' = n₀.
const ODE_TOL: f64 = 1e-12;

#[test]
fn golden_value_matches_the_brief() {
    let k = DVec3::new(5.0, 40.0, 10.0);
    let (r, _) = centreline_and_jacobian(0.05, k);
    let n0 = rotation(0.05 * k).col(0);
    let want_r = DVec3::new(0.0214811, 0.0119613, -0.0335858);
    let want_n0 = DVec3::new(-0.4630442, 0.3827399, -0.7994374);
    assert!((r - want_r).abs().max_element() < GOLDEN_TOL, "{r}");
    assert!((n0 - want_n0).abs().max_element() < GOLDEN_TOL, "{n0}");
}

/// RK4 on the frame equations in material form: R' = R[k]×, r' = R e₀.
fn integrate(k: DVec3, length: f64, steps: usize) -> (DVec3, DMat3) {
    let skew = helixhair_physics::geometry::helix::skew(k);
    let h = length / steps as f64;
    let (mut r, mut frame) = (DVec3::ZERO, DMat3::IDENTITY);
    let f = |m: DMat3| (m * skew, m.col(0));
    for _ in 0..steps {
        let (k1, v1) = f(frame);
        let (k2, v2) = f(frame + k1 * (h / 2.0));
        let (k3, v3) = f(frame + k2 * (h / 2.0));
        let (k4, v4) = f(frame + k3 * h);
        frame += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
        r += (v1 + v2 * 2.0 + v3 * 2.0 + v4) * (h / 6.0);
    }
    (r, frame)
}

#[test]
fn closed_form_matches_ode_integration_from_straight_to_tight() {
    for k in [
        DVec3::ZERO,
        DVec3::new(1e-7, 0.0, 1e-7),
        DVec3::new(0.0, 3.0, 0.0),
        DVec3::new(5.0, 40.0, 10.0),
        DVec3::new(-80.0, 20.0, -150.0),
        DVec3::new(300.0, -200.0, 100.0),
    ] {
        let (r, _) = centreline_and_jacobian(0.05, k);
        let frame = rotation(0.05 * k);
        let (r_ode, frame_ode) = integrate(k, 0.05, 40_000);
        assert!(
            (r - r_ode).abs().max_element() < ODE_TOL,
            "k = {k}: {r} vs {r_ode}"
        );
        assert!(frame.abs_diff_eq(frame_ode, ODE_TOL), "k = {k}");
    }
}

#[test]
fn constant_strains_trace_the_helix_of_given_radius_and_step() {
    // A helix of radius 1 cm and step 2 cm, 5 elements: every centreline
    // point lies at distance R from the axis, and one turn advances P.
    let (radius, step) = (0.01, 0.02);
    let k = helix_strains(radius, step);
    let (r_back, p_back) = helix_radius_and_step(k);
    assert!((r_back - radius).abs() < 1e-15 && (p_back - step).abs() < 1e-15);
    let omega = k.length();
    let turn = std::f64::consts::TAU / omega; // arc length of one turn
    let mut p = params(2.0 * turn, 5);
    p.natural_shape = helixhair_physics::NaturalShape::Helix {
        radius_m: radius,
        step_m: step,
    };
    let m = model(&p, 3);
    let kin = kinematics(&m, &m.natural, &[DVec3::ZERO; 5], &at_rest(DMat3::IDENTITY));
    // The axis runs along Ω/|Ω| = k/|k| (root frame = I); from any point the
    // axis lies a distance R along ±(axis × tangent).
    let axis = k.normalize();
    let towards_axis = axis.cross(DVec3::X).normalize();
    let distances_from = |centre: DVec3| -> Vec<f64> {
        kin.points_m
            .iter()
            .map(|p| {
                let d = *p - centre;
                (d - d.dot(axis) * axis).length()
            })
            .collect()
    };
    let on_axis = [radius, -radius]
        .into_iter()
        .map(|r| distances_from(towards_axis * r))
        .find(|d| (d[1] - radius).abs() < 1e-9)
        .expect("one side of the root point holds the axis");
    for d in on_axis {
        assert!((d - radius).abs() < 1e-12, "distance {d} from the axis");
    }
    // Two turns advance 2P along the axis.
    let rise = (kin.points_m[5] - kin.points_m[0]).dot(axis);
    assert!((rise - 2.0 * step).abs() < 1e-12, "rise {rise}");
}

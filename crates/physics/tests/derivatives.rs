//! Analytic derivatives against central finite differences, and the mass
//! matrix and gravity force against the energies they come from
//! (docs/physics.md sections 4 and 7).

use crate::common;

use common::*;
use glam::{DMat3, DVec3};
use helixhair_physics::energy::energies;
use helixhair_physics::geometry::helix::skew;
use helixhair_physics::motion::HeadTrajectory;
use helixhair_physics::step::mass::{MassData, dense_mass, mass_blocks};
use helixhair_physics::{Oscillation, RigidMotion};

/// Central differences with step ε err by O(ε²) plus round-off O(u/ε).
const FD_STEP: f64 = 1e-6;
/// Agreement of a Jacobian entry (metres per m⁻¹) with its central difference.
const JACOBIAN_TOL: f64 = 1e-9;
/// Agreement of velocities (m/s) with a central difference in time.
const VELOCITY_TOL: f64 = 1e-8;
/// Agreement of accelerations (m/s²) with a second difference in time.
const ACCELERATION_TOL: f64 = 1e-4;
/// Relative agreement of quadratic forms computed two ways (round-off only).
const ROUNDOFF_REL: f64 = 1e-12;

fn curly_setup(
    seed: u64,
) -> (
    helixhair_physics::StrandModel,
    Vec<DVec3>,
    Vec<DVec3>,
    RigidMotion,
) {
    let mut rng = Rng::new(seed);
    let mut p = params(0.12, 6);
    p.layout = helixhair_physics::ElementLayout::Graded {
        tip_to_root_ratio: 3.0,
    };
    let m = model(&p, 3);
    let q = random_strains(&mut rng, 6, 60.0);
    let v = random_strains(&mut rng, 6, 20.0);
    (m, q, v, at_rest(rng.rotation()))
}

#[test]
fn jacobians_match_finite_differences() {
    let (m, q, v, root) = curly_setup(1);
    let kin = kinematics(&m, &q, &v, &root);
    let points = m.quadrature.len();
    for e in 0..m.elements() {
        for j in 0..3 {
            let mut qp = q.clone();
            let mut qm = q.clone();
            qp[e][j] += FD_STEP;
            qm[e][j] -= FD_STEP;
            let kp = kinematics(&m, &qp, &v, &root);
            let km = kinematics(&m, &qm, &v, &root);
            for (i, s) in kin.samples.iter().enumerate() {
                let fd = (kp.samples[i].position_m - km.samples[i].position_m) / (2.0 * FD_STEP);
                let owner = i / points;
                let analytic = if owner < e {
                    DVec3::ZERO
                } else if owner == e {
                    s.jacobian.col(j)
                } else {
                    let jac = &kin.elements[e];
                    (jac.a - skew(s.position_m) * jac.b).col(j)
                };
                assert!(
                    (fd - analytic).abs().max_element() < JACOBIAN_TOL,
                    "element {e} coordinate {j} sample {i}: {analytic} vs {fd}"
                );
            }
        }
    }
}

#[test]
fn velocities_and_free_accelerations_match_time_differences() {
    // A head shaking with the strand's strains moving at constant rate:
    // along q(t) = q₀ + t q̇, q̈ = 0, so r̈ is exactly the free acceleration.
    let (m, q, v, _) = curly_setup(2);
    let head = Oscillation {
        axis: DVec3::new(0.2, 1.0, 0.1),
        amplitude_rad: 0.6,
        frequency_hz: 1.3,
    };
    let root_pose = helixhair_physics::RootPose::from_direction(
        DVec3::new(0.05, 0.08, 0.0),
        DVec3::new(1.0, 0.5, 0.2),
        DVec3::Y,
    );
    let t0 = 0.37;
    let world = |t: f64| -> Vec<DVec3> {
        let root = head.motion_at(t).carry(&root_pose);
        let qt: Vec<DVec3> = q.iter().zip(&v).map(|(q, v)| *q + (t - t0) * *v).collect();
        let kin = kinematics(&m, &qt, &v, &root);
        kin.samples
            .iter()
            .map(|s| s.position_m + root.position_m)
            .collect()
    };
    let root = head.motion_at(t0).carry(&root_pose);
    let kin = kinematics(&m, &q, &v, &root);
    let dt = 1e-4;
    let (before, now, after) = (world(t0 - dt), world(t0), world(t0 + dt));
    for (i, s) in kin.samples.iter().enumerate() {
        let fd_v = (after[i] - before[i]) / (2.0 * dt);
        let fd_a = (after[i] - 2.0 * now[i] + before[i]) / (dt * dt);
        // O(dt²) truncation: the velocity check is scaled accordingly.
        assert!(
            (s.velocity_m_per_s - fd_v).abs().max_element() < VELOCITY_TOL * 1e2,
            "sample {i}"
        );
        assert!(
            (s.free_acceleration_m_per_s2 - fd_a).abs().max_element() < ACCELERATION_TOL,
            "sample {i}: {} vs {fd_a}",
            s.free_acceleration_m_per_s2
        );
    }
}

#[test]
fn velocities_match_strain_differences_with_a_fixed_root() {
    let (m, q, v, root) = curly_setup(3);
    let kin = kinematics(&m, &q, &v, &root);
    let shifted = |sign: f64| -> Vec<DVec3> {
        let qs: Vec<DVec3> = q
            .iter()
            .zip(&v)
            .map(|(q, v)| *q + sign * FD_STEP * *v)
            .collect();
        kinematics(&m, &qs, &v, &root)
            .samples
            .iter()
            .map(|s| s.position_m)
            .collect()
    };
    let (p, n) = (shifted(1.0), shifted(-1.0));
    for (i, s) in kin.samples.iter().enumerate() {
        let fd = (p[i] - n[i]) / (2.0 * FD_STEP);
        assert!(
            (s.velocity_m_per_s - fd).abs().max_element() < VELOCITY_TOL,
            "sample {i}"
        );
    }
}

fn mass_data(
    m: &helixhair_physics::StrandModel,
    kin: &helixhair_physics::step::reconstruct::Kinematics,
) -> MassData {
    let mut out = MassData::default();
    mass_blocks(m, kin, &mut out);
    out
}

#[test]
fn mass_matrix_is_symmetric_and_gives_the_kinetic_energy() {
    let (m, q, _, root) = curly_setup(4);
    let mut rng = Rng::new(40);
    for _ in 0..5 {
        let v = random_strains(&mut rng, m.elements(), 30.0);
        let kin = kinematics(&m, &q, &v, &root);
        let mass = dense_mass(&kin, &mass_data(&m, &kin));
        let asym = (&mass - mass.transpose()).abs().max();
        assert!(asym <= ROUNDOFF_REL * mass.abs().max(), "asymmetry {asym}");
        let vv = nalgebra::DVector::from_iterator(3 * v.len(), v.iter().flat_map(|x| x.to_array()));
        let quadratic = 0.5 * vv.dot(&(&mass * &vv));
        let t = energies(&m, &q, &kin, DVec3::ZERO, DVec3::ZERO).kinetic_j;
        assert!(
            (quadratic - t).abs() <= ROUNDOFF_REL * t,
            "½vᵀMv = {quadratic}, T = {t}"
        );
    }
}

#[test]
fn suffix_sum_mass_equals_brute_force_assembly() {
    // M = Σ_samples w ρS Jᵀ J with J built column by column from the
    // sample's own and beyond Jacobians: an O(N²) sum with no moments.
    let (m, q, v, root) = curly_setup(5);
    let kin = kinematics(&m, &q, &v, &root);
    let mass = dense_mass(&kin, &mass_data(&m, &kin));
    let n = m.elements();
    let points = m.quadrature.len();
    let mut brute = nalgebra::DMatrix::<f64>::zeros(3 * n, 3 * n);
    for (i, s) in kin.samples.iter().enumerate() {
        let owner = i / points;
        let cols: Vec<DMat3> = (0..n)
            .map(|e| match e.cmp(&owner) {
                std::cmp::Ordering::Greater => DMat3::ZERO,
                std::cmp::Ordering::Equal => s.jacobian,
                std::cmp::Ordering::Less => {
                    kin.elements[e].a - skew(s.position_m) * kin.elements[e].b
                }
            })
            .collect();
        let w = s.weight_m * m.mass_per_length;
        for a in 0..n {
            for b in 0..n {
                let block = cols[a].transpose() * cols[b] * w;
                for (i, j) in (0..3).flat_map(|i| (0..3).map(move |j| (i, j))) {
                    brute[(3 * a + i, 3 * b + j)] += block.col(j)[i];
                }
            }
        }
    }
    let diff = (&mass - &brute).abs().max();
    assert!(
        diff <= ROUNDOFF_REL * 10.0 * brute.abs().max(),
        "max diff {diff}"
    );
}

#[test]
fn gravity_force_is_minus_the_gradient_of_its_potential() {
    let (m, q, _, root) = curly_setup(6);
    let zero = vec![DVec3::ZERO; m.elements()];
    let gravity = DVec3::new(0.3, -9.81, 1.2);
    let forces = forces_under_gravity(&m, &q, &zero, &root, gravity);
    let potential = |q: &[DVec3]| {
        energies(
            &m,
            q,
            &kinematics(&m, q, &zero, &root),
            DVec3::ZERO,
            gravity,
        )
        .gravity_j
    };
    let scale = forces
        .iter()
        .map(|f| f.abs().max_element())
        .fold(0.0, f64::max);
    for e in 0..m.elements() {
        for j in 0..3 {
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[e][j] += FD_STEP;
            qm[e][j] -= FD_STEP;
            let fd = -(potential(&qp) - potential(&qm)) / (2.0 * FD_STEP);
            assert!(
                (forces[e][j] - fd).abs() < 1e-7 * scale,
                "element {e} coordinate {j}: {} vs {fd}",
                forces[e][j]
            );
        }
    }
}

/// Relative error of the default 4-point rule against an 8-point rule on
/// elements turning by up to 4 rad (measured 6.4e-5 at 4 rad).
const FOUR_POINT_TOL: f64 = 1e-4;

#[test]
fn four_gauss_points_suffice_for_the_mass_matrix() {
    // Straight elements: the integrands are polynomials, exact to round-off.
    // Curled elements up to x = ℓ|k| = 4 rad (a 5 mm coil on 2 cm
    // elements): within FOUR_POINT_TOL.
    for (turn_rad, tol) in [(0.0, 1e-13), (1.0, FOUR_POINT_TOL), (4.0, FOUR_POINT_TOL)] {
        let strain = turn_rad / 0.02;
        let mut p = params(0.1, 5);
        p.natural_shape = helixhair_physics::NaturalShape::Uniform {
            twist_per_m: 0.3 * strain,
            curvature1_per_m: strain,
            curvature2_per_m: 0.0,
        };
        let zero = vec![DVec3::ZERO; 5];
        let root = at_rest(DMat3::IDENTITY);
        let matrices: Vec<_> = [
            helixhair_physics::SimSettings::default().quadrature_points,
            8,
        ]
        .iter()
        .map(|&pts| {
            let m = model(&p, pts);
            let kin = kinematics(&m, &m.natural, &zero, &root);
            dense_mass(&kin, &mass_data(&m, &kin))
        })
        .collect();
        let rel = (&matrices[0] - &matrices[1]).abs().max() / matrices[1].abs().max();
        assert!(
            rel < tol,
            "turn {turn_rad} rad: default vs 8 points differ by {rel}"
        );
    }
}

#[test]
fn bounce_velocity_and_acceleration_are_the_derivatives_of_its_position() {
    let head = helixhair_physics::Bounce {
        direction: DVec3::new(0.0, 2.0, 0.5),
        amplitude_m: 0.03,
        frequency_hz: 2.2,
    };
    let (t0, dt) = (0.41, 1e-4);
    let at = |t: f64| head.motion_at(t).position_m;
    let m = head.motion_at(t0);
    let fd_v = (at(t0 + dt) - at(t0 - dt)) / (2.0 * dt);
    let fd_a = (at(t0 + dt) - 2.0 * at(t0) + at(t0 - dt)) / (dt * dt);
    assert!((m.velocity_m_per_s - fd_v).abs().max_element() < VELOCITY_TOL * 1e2);
    assert!((m.acceleration_m_per_s2 - fd_a).abs().max_element() < ACCELERATION_TOL);
    assert_eq!(m.world_from_body, DMat3::IDENTITY);
}

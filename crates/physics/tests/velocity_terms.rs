//! The velocity terms' product G x = −(∂Q/∂q̇) x (docs/physics.md, the
//! velocity-implicit step) against the forces it differentiates: central
//! differences of the generalized forces Q in q̇, exact up to round-off
//! because Q is quadratic in q̇. Both ways of forming the product must
//! match: the Jacobians' rates (what the step uses) and the polarisation of
//! two jet sweeps.

use crate::common;

use common::*;
use glam::{DMat3, DVec3};
use helixhair_physics::RigidMotion;
use helixhair_physics::step::reconstruct::{Kinematics, reconstruct, reconstruct_with_rates};
use helixhair_physics::step::velocity_terms::{Derivative, VelocityTerms};

/// Agreement relative to the largest entry of G x (round-off only).
const ROUNDOFF_REL: f64 = 1e-9;

#[test]
fn product_matches_differences_of_the_forces() {
    for (seed, elements, curl) in [(3, 6, 60.0), (4, 10, 150.0), (5, 4, 0.0)] {
        let mut rng = Rng::new(seed);
        let m = graded_model(0.2, elements);
        let q = random_strains(&mut rng, elements, curl);
        let v = random_strains(&mut rng, elements, 30.0);
        let x = random_strains(&mut rng, elements, 10.0);
        // A head turning and accelerating: the root-rotation terms count.
        let root = RigidMotion {
            position_m: rng.vec3(0.1),
            world_from_body: rng.rotation(),
            velocity_m_per_s: rng.vec3(0.5),
            angular_velocity_rad_per_s: rng.vec3(4.0),
            acceleration_m_per_s2: rng.vec3(3.0),
            angular_acceleration_rad_per_s2: rng.vec3(20.0),
        };
        // −(∂Q/∂q̇) x by central differences (exact for a quadratic).
        let shift = |sign: f64| -> Vec<DVec3> {
            let vs: Vec<DVec3> = v.iter().zip(&x).map(|(v, x)| *v + sign * *x).collect();
            forces_under_gravity(&m, &q, &vs, &root, DVec3::new(0.0, -9.81, 0.0))
        };
        let (plus, minus) = (shift(1.0), shift(-1.0));
        let expected: Vec<DVec3> = plus
            .iter()
            .zip(&minus)
            .map(|(p, m)| -(*p - *m) * 0.5)
            .collect();
        let scale = expected
            .iter()
            .map(|g| g.abs().max_element())
            .fold(0.0, f64::max);
        assert!(scale > 0.0);

        let mut kin = Kinematics::default();
        reconstruct_with_rates(&m, &q, &v, &root, &mut kin);
        let mut terms = VelocityTerms::default();
        for derivative in [Derivative::JacobianRates, Derivative::Polarisation] {
            let mut got = vec![DVec3::ZERO; elements];
            terms.apply(derivative, &m, &kin, &q, &v, &root, &x, &mut got);
            let err = max_diff(&got, &expected);
            assert!(
                err <= ROUNDOFF_REL * scale,
                "seed {seed} {derivative:?}: error {err:.3e} of {scale:.3e}"
            );
        }
    }
}

/// A rates-free reconstruction leaves the rates empty, and the rates leave
/// everything else as it was.
#[test]
fn rates_add_to_the_reconstruction_without_changing_it() {
    let mut rng = Rng::new(9);
    let m = model(&params(0.1, 5), 3);
    let q = random_strains(&mut rng, 5, 50.0);
    let v = random_strains(&mut rng, 5, 10.0);
    let root = at_rest(DMat3::IDENTITY);
    let (mut plain, mut rated) = (Kinematics::default(), Kinematics::default());
    reconstruct(&m, &q, &v, &root, &mut plain);
    reconstruct_with_rates(&m, &q, &v, &root, &mut rated);
    assert!(plain.jacobian_rates.is_empty() && plain.element_rates.is_empty());
    assert_eq!(rated.jacobian_rates.len(), rated.samples.len());
    assert_eq!(rated.element_rates.len(), 5);
    rated.jacobian_rates.clear();
    rated.element_rates.clear();
    assert_eq!(plain, rated);
}

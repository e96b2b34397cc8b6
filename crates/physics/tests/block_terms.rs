//! Block-diagonal's own velocity terms in the step's generic code
//! ([`helixhair_physics::batch::block_terms`]) against the f64 reference's
//! ([`helixhair_physics::step::block_velocity_terms`], itself checked
//! against the truncated energy's Lagrangian by differences in
//! `tests/block_velocity_terms.rs`): at f64 the same correction to
//! round-off, at f32 within f32's.

use crate::common::{Rng, params, random_strains};
use glam::{DMat3, DVec3};
use helixhair_physics::batch::block_terms::{BlockElement, block_correction};
use helixhair_physics::batch::lanes::Real;
use helixhair_physics::batch::layout::RootMotion;
use helixhair_physics::batch::vec::V3;
use helixhair_physics::batch::velocity_terms::coefficients_of;
use helixhair_physics::step::block_velocity_terms::BlockVelocityTerms;
use helixhair_physics::step::reconstruct::{Kinematics, reconstruct_with_rates};
use helixhair_physics::{NaturalShape, RigidMotion, StrandModel};

/// |generic − reference| over the correction's largest component, f64:
/// two arrangements of the same sums. Measured: at most 2.4e-14.
const F64_TOL: f64 = 1e-12;
/// The same at f32: the correction is a difference of two sets of velocity
/// forces (F_true − F_bd) taken with moments about the root, so it loses
/// the digits the two share. Measured: at most 1.4e-6.
const F32_TOL: f64 = 1e-5;

fn generic<T: Real>(
    model: &StrandModel,
    root: &RigidMotion,
    q: &[DVec3],
    v: &[DVec3],
) -> Vec<DVec3> {
    let n = q.len();
    let to = |x: &[DVec3]| -> Vec<V3<T>> {
        x.iter()
            .map(|d| V3::new(T::splat_f64(d.x), T::splat_f64(d.y), T::splat_f64(d.z)))
            .collect()
    };
    let (q, v) = (to(q), to(v));
    let root = RootMotion::<T>::gather(std::slice::from_ref(root));
    let mut coefficients = Vec::new();
    coefficients_of(model, &q, &mut coefficients);
    let mut buffer = vec![BlockElement::zero(); n];
    let mut out = vec![V3::zero(); n];
    block_correction(model, &root, &q, &v, &coefficients, &mut buffer, &mut out);
    out.iter()
        .map(|x| DVec3::new(x.x.lane_f64(0), x.y.lane_f64(0), x.z.lane_f64(0)))
        .collect()
}

fn reference(model: &StrandModel, root: &RigidMotion, q: &[DVec3], v: &[DVec3]) -> Vec<DVec3> {
    let mut kin = Kinematics::default();
    reconstruct_with_rates(model, q, v, root, &mut kin);
    let mut out = vec![DVec3::ZERO; q.len()];
    BlockVelocityTerms::default().correction(model, &kin, v, root, &mut out);
    out
}

fn relative_gap(a: &[DVec3], b: &[DVec3]) -> f64 {
    let scale = b.iter().map(|x| x.abs().max_element()).fold(0.0, f64::max);
    let gap = a
        .iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0, f64::max);
    gap / scale
}

#[test]
fn the_generic_correction_is_the_references() {
    let mut rng = Rng::new(7);
    let (mut worst64, mut worst32): (f64, f64) = (0.0, 0.0);
    for (shape, length_m, n) in [
        (NaturalShape::Straight, 0.3, 10),
        (
            NaturalShape::Helix {
                radius_m: 0.01,
                step_m: 0.02,
            },
            0.25,
            12,
        ),
        (
            NaturalShape::Uniform {
                twist_per_m: 5.0,
                curvature1_per_m: 40.0,
                curvature2_per_m: -10.0,
            },
            0.2,
            6,
        ),
    ] {
        let mut p = params(length_m, n);
        p.natural_shape = shape;
        let model = StrandModel::new(&p, 4).expect("valid");
        for trial in 0..4 {
            let q: Vec<DVec3> = model
                .natural
                .iter()
                .zip(random_strains(&mut rng, n, 5.0))
                .map(|(k, d)| *k + d)
                .collect();
            let v = random_strains(&mut rng, n, 20.0);
            let root = RigidMotion {
                position_m: rng.vec3(0.1),
                world_from_body: if trial == 0 {
                    DMat3::IDENTITY
                } else {
                    rng.rotation()
                },
                velocity_m_per_s: rng.vec3(0.5),
                angular_velocity_rad_per_s: rng.vec3(4.0),
                acceleration_m_per_s2: rng.vec3(3.0),
                angular_acceleration_rad_per_s2: rng.vec3(20.0),
            };
            let truth = reference(&model, &root, &q, &v);
            let gap64 = relative_gap(&generic::<f64>(&model, &root, &q, &v), &truth);
            let gap32 = relative_gap(&generic::<f32>(&model, &root, &q, &v), &truth);
            eprintln!("N = {n} trial {trial}: f64 {gap64:.2e}, f32 {gap32:.2e}");
            worst64 = worst64.max(gap64);
            worst32 = worst32.max(gap32);
        }
    }
    assert!(worst64 < F64_TOL, "f64: {worst64:.2e}");
    assert!(worst32 < F32_TOL, "f32: {worst32:.2e}");
}

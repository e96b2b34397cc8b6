//! Block-diagonal's Lagrangian velocity terms (docs/physics.md), as the
//! step's generic code computes them ([`block_correction`]), against the
//! energy they come from: F_bd = Ṁ_bd q̇ − ∂T_bd/∂q with
//! T_bd = ½ Σ q̇_Qᵀ M_QQ(q) q̇_Q, both derivatives by central differences of
//! the mass stage's diagonal blocks.

use crate::common;

use common::*;
use glam::DMat3;
use glam::DVec3;
use helixhair_physics::batch::block_terms::{BlockElement, block_correction};
use helixhair_physics::batch::lanes::Real;
use helixhair_physics::batch::layout::RootMotion;
use helixhair_physics::batch::vec::V3;
use helixhair_physics::batch::velocity_terms::coefficients_of;
use helixhair_physics::step::mass::{MassData, mass_blocks};
use helixhair_physics::step::reconstruct::{Kinematics, reconstruct_with_rates};
use helixhair_physics::step::velocity_terms::{Derivative, VelocityTerms};
use helixhair_physics::{NaturalShape, RigidMotion, StrandModel};

/// Central differences with step ε (relative): O(ε²) truncation.
const FD_STEP: f64 = 1e-5;
/// Agreement relative to the largest component of F_bd.
const FD_REL: f64 = 1e-6;

/// `still` with the head moving and turning at random.
fn shaken(rng: &mut Rng, still: RigidMotion) -> RigidMotion {
    RigidMotion {
        velocity_m_per_s: rng.vec3(0.5),
        angular_velocity_rad_per_s: rng.vec3(4.0),
        acceleration_m_per_s2: rng.vec3(3.0),
        angular_acceleration_rad_per_s2: rng.vec3(20.0),
        ..still
    }
}

fn blocks(m: &helixhair_physics::StrandModel, q: &[DVec3], root: &RigidMotion) -> MassData {
    let zero = vec![DVec3::ZERO; q.len()];
    let kin = kinematics(m, q, &zero, root);
    let mut mass = MassData::default();
    mass_blocks(m, &kin, &mut mass);
    mass
}

fn block_kinetic(
    m: &helixhair_physics::StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    root: &RigidMotion,
) -> f64 {
    let mass = blocks(m, q, root);
    v.iter()
        .zip(&mass.diagonal)
        .map(|(v, b)| 0.5 * v.dot(*b * *v))
        .sum()
}

/// F_bd of the step's generic code at f64: its correction F_true − F_bd
/// ([`block_correction`]) taken from F_true's strain-rate part, which with
/// a still head is ½ G q̇ (G q̇ = 2∫ρS Jᵀ J̇q̇, the assembled arrangement's
/// derivative, tests/velocity_terms.rs), and the correction itself.
fn generic_block_forces(
    m: &helixhair_physics::StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    root: &RigidMotion,
) -> (Vec<DVec3>, Vec<DVec3>) {
    let correction = generic_correction::<f64>(m, root, q, v);
    let still = at_rest(root.world_from_body);
    let mut kin = Kinematics::default();
    reconstruct_with_rates(m, q, v, &still, &mut kin);
    let mut g_v = vec![DVec3::ZERO; q.len()];
    VelocityTerms::default().apply(
        Derivative::JacobianRates,
        m,
        &kin,
        q,
        v,
        &still,
        v,
        &mut g_v,
    );
    let f_bd = g_v
        .iter()
        .zip(&correction)
        .map(|(g, c)| *g * 0.5 - *c)
        .collect();
    (f_bd, correction)
}

/// Block-diagonal's correction F_true − F_bd by the step's generic code
/// at width one in `T`, widened to f64.
pub fn generic_correction<T: Real>(
    model: &helixhair_physics::StrandModel,
    root: &RigidMotion,
    q: &[DVec3],
    v: &[DVec3],
) -> Vec<DVec3> {
    let to = |x: &[DVec3]| -> Vec<V3<T>> {
        x.iter()
            .map(|d| V3::new(T::splat_f64(d.x), T::splat_f64(d.y), T::splat_f64(d.z)))
            .collect()
    };
    let (q, v) = (to(q), to(v));
    let root = RootMotion::<T>::gather(std::slice::from_ref(root));
    let mut coefficients = Vec::new();
    coefficients_of(model, &q, &mut coefficients);
    let mut buffer = vec![BlockElement::zero(); q.len()];
    let mut out = vec![V3::zero(); q.len()];
    block_correction(model, &root, &q, &v, &coefficients, &mut buffer, &mut out);
    out.iter()
        .map(|x| DVec3::new(x.x.lane_f64(0), x.y.lane_f64(0), x.z.lane_f64(0)))
        .collect()
}

#[test]
fn block_forces_match_the_lagrangian_of_the_truncated_energy() {
    for (seed, elements, curl) in [(11, 5, 60.0), (12, 8, 150.0), (13, 4, 0.0)] {
        let mut rng = Rng::new(seed);
        let m = graded_model(0.15, elements);
        let q = random_strains(&mut rng, elements, curl);
        let v = random_strains(&mut rng, elements, 20.0);
        let still = at_rest(rng.rotation());
        // Ṁ_bd q̇ along the motion, ∂T_bd/∂q by coordinate.
        let along = |sign: f64| -> MassData {
            let qs: Vec<DVec3> = q
                .iter()
                .zip(&v)
                .map(|(q, v)| *q + sign * FD_STEP * *v)
                .collect();
            blocks(&m, &qs, &still)
        };
        let (plus, minus) = (along(1.0), along(-1.0));
        let mut expected: Vec<DVec3> = (0..elements)
            .map(|e| (plus.diagonal[e] - minus.diagonal[e]) * v[e] / (2.0 * FD_STEP))
            .collect();
        for e in 0..elements {
            for j in 0..3 {
                let mut qp = q.clone();
                let mut qm = q.clone();
                qp[e][j] += FD_STEP;
                qm[e][j] -= FD_STEP;
                let d = (block_kinetic(&m, &qp, &v, &still) - block_kinetic(&m, &qm, &v, &still))
                    / (2.0 * FD_STEP);
                expected[e][j] -= d;
            }
        }
        let scale = expected
            .iter()
            .map(|g| g.abs().max_element())
            .fold(0.0, f64::max);
        let (got, correction) = generic_block_forces(&m, &q, &v, &still);
        let err = max_diff(&got, &expected);
        println!("seed {seed}: |F_bd − FD| = {err:.2e} of {scale:.2e}");
        assert!(
            err <= FD_REL * scale,
            "seed {seed}: error {err:.3e} of {scale:.3e}"
        );
        // The same strand with its head turning and moving: both parts of
        // the correction are the strain rates' alone, so it must not
        // change (to round-off).
        let moving = shaken(&mut rng, still);
        let turned = generic_correction::<f64>(&m, &moving, &q, &v);
        let size = correction
            .iter()
            .map(|c| c.abs().max_element())
            .fold(0.0, f64::max);
        let moved = max_diff(&turned, &correction);
        println!("seed {seed}: a moving head changes the correction by {moved:.2e} of {size:.2e}");
        assert!(
            moved <= 1e-12 * size,
            "seed {seed}: {moved:.3e} of {size:.3e}"
        );
    }
}

/// T_bd + V of a strand (joules) and the energies' size T_bd + |U| + |U_g|.
fn block_energy(s: &helixhair_physics::Strand, root: &RigidMotion) -> (f64, f64) {
    let kin = s.kinematics(root);
    let mut mass = MassData::default();
    mass_blocks(s.model(), &kin, &mut mass);
    let t_bd: f64 = s
        .v()
        .iter()
        .zip(&mass.diagonal)
        .map(|(v, b)| 0.5 * v.dot(*b * *v))
        .sum();
    let e = helixhair_physics::energy::energies(s.model(), s.q(), &kin, DVec3::ZERO, GRAVITY);
    (
        t_bd + e.elastic_j + e.gravity_j,
        t_bd + e.elastic_j.abs() + e.gravity_j.abs(),
    )
}

const GRAVITY: DVec3 = DVec3::new(0.0, -9.81, 0.0);

/// The straight example's crown strand (`assets/styles/straight.ron`):
/// 30 cm, 12 elements graded 3:1, 40 µm. With its velocity terms frozen at
/// the step's start Block-diagonal threw it about on a still head at
/// 60 Hz (points at 20 m/s after 1.5 s); implicit, it settles.
fn straight_example() -> helixhair_physics::StrandParams {
    helixhair_physics::StrandParams {
        length_m: 0.3,
        elements: 12,
        layout: helixhair_physics::ElementLayout::Graded {
            tip_to_root_ratio: 3.0,
        },
        radius_m: 40e-6,
        ellipticity: 1.0,
        ..helixhair_physics::StrandParams::default()
    }
}
/// A frame's gain in T_bd + V below this fraction of the energies' size is
/// round-off.
const ROUNDOFF: f64 = 1e-12;
/// Kinetic energy of a strand at rest (issue 12's threshold), joules.
const AT_REST_J: f64 = 1e-12;

/// Issue 12's symptom: a short straight strand released horizontally with
/// a still head, at 60 Hz, must come to rest under Block-diagonal, and its
/// own energy T_bd + V must never grow; likewise a hanging curl that blew
/// up at 60 Hz with the whole system's velocity terms
/// (tests/failure_modes.rs). Guard off: the solver alone.
#[test]
fn block_diagonal_energy_never_grows_with_a_still_head() {
    let mut curl = params(0.2, 10);
    curl.natural_shape = helixhair_physics::NaturalShape::Helix {
        radius_m: 0.02,
        step_m: 0.05,
    };
    curl.internal_friction = 2e-10;
    curl.air_drag = 1e-5;
    for (label, p, seconds) in [
        ("10 cm released horizontally", params(0.1, 10), 15.0_f64),
        ("20 cm curl", curl, 2.0),
        (
            "30 cm straight, the straight example's",
            straight_example(),
            5.0,
        ),
    ] {
        let mut s = strand(&p, helixhair_physics::Method::BlockDiagonal);
        let at_root = at_rest(glam::DMat3::IDENTITY);
        let h = 1.0 / 60.0;
        let (mut last, _) = block_energy(&s, &at_root);
        let mut grew = 0;
        for _ in 0..(seconds / h).round() as usize {
            s.step(&at_root, GRAVITY, DVec3::ZERO, h);
            let (e, size) = block_energy(&s, &at_root);
            assert!(e.is_finite(), "{label}: not finite");
            if e - last > ROUNDOFF * size {
                grew += 1;
            }
            last = e;
        }
        let kinetic = s.energies(&at_root, GRAVITY).kinetic_j;
        println!("{label}: T_bd + V grew on {grew} frames; T = {kinetic:.2e} J after {seconds} s");
        assert_eq!(grew, 0, "{label}: T_bd + V grew on {grew} frames");
        if seconds >= 15.0 {
            assert!(
                kinetic < AT_REST_J,
                "{label}: still moving, T = {kinetic} J"
            );
        }
    }
}

/// The guard's measure of Block-diagonal's own strain kinetic energy
/// (suffix moments, O(N), the measure both engines share, here at f64) is
/// ½ Σ q̇_Qᵀ M_QQ q̇_Q with the mass stage's diagonal blocks, at any head
/// pose and motion (T_bd is the strain rates' alone).
#[test]
fn measured_block_kinetic_energy_is_the_diagonal_blocks() {
    use helixhair_physics::step::forces::ForceInputs;
    use helixhair_physics::step::generic::measure_strand;
    for (seed, elements, curl) in [(31, 5, 60.0), (32, 9, 150.0), (33, 1, 0.0)] {
        let mut rng = Rng::new(seed);
        let m = model(&params(0.2, elements), 3);
        let q = random_strains(&mut rng, elements, curl);
        let v = random_strains(&mut rng, elements, 20.0);
        let still = at_rest(rng.rotation());
        let expected = block_kinetic(&m, &q, &v, &still);
        let moving = RigidMotion {
            velocity_m_per_s: rng.vec3(0.5),
            angular_velocity_rad_per_s: rng.vec3(4.0),
            ..still
        };
        for root in [still, moving] {
            let forces = ForceInputs {
                root: &root,
                gravity_m_per_s2: DVec3::ZERO,
                air_velocity_m_per_s: DVec3::ZERO,
                external_n_per_m: &[],
                contact: None,
                volume: None,
            };
            let got = measure_strand(&m, &q, &v, &forces, None).block_kinetic_j;
            println!("seed {seed}: T_bd {got:.6e} against {expected:.6e}");
            assert!((got - expected).abs() <= 1e-12 * expected, "seed {seed}");
        }
    }
}

/// |f32 − f64| of Block-diagonal's correction over its largest component:
/// the correction is a difference of two sets of velocity forces
/// (F_true − F_bd) taken with moments about the root, so it loses the
/// digits the two share. Measured: at most 1.4e-6.
const F32_TOL: f64 = 1e-5;

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
fn the_f32_correction_is_the_f64_one_to_f32_round_off() {
    let mut rng = Rng::new(7);
    let mut worst32: f64 = 0.0;
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
            let f64_correction = generic_correction::<f64>(&model, &root, &q, &v);
            let gap32 = relative_gap(
                &generic_correction::<f32>(&model, &root, &q, &v),
                &f64_correction,
            );
            println!("N = {n} trial {trial}: f32 {gap32:.2e}");
            worst32 = worst32.max(gap32);
        }
    }
    assert!(worst32 < F32_TOL, "f32: {worst32:.2e}");
}

//! The velocity-implicit step on the f32 batch engine: the head shake that
//! reset strands, and the new step against the f64 reference's.

use crate::common;

use common::shake_scene::{ShakeThenStill, head_roots, ordinary_shake, straight_30_cm};
use common::{Rng, kinematics, model, outward_roots, shake};
use glam::DVec3;
use helixhair_physics::batch::BatchSystem;
use helixhair_physics::energy::{Energies, energies};
use helixhair_physics::motion::HeadTrajectory;
use helixhair_physics::{
    HairSystem, Method, NaturalShape, RootPose, SimSettings, StepScheme, StrandParams,
};

const IMPLICIT: StepScheme = StepScheme::VelocityImplicit { corrections: 8 };

fn batch(settings: SimSettings, params: &StrandParams, roots: &[RootPose]) -> BatchSystem {
    let mut batch = BatchSystem::new(settings).expect("valid settings");
    batch.add_group(params, roots).expect("valid params");
    batch
}

fn exact(scheme: StepScheme) -> SimSettings {
    SimSettings {
        method: Method::Exact,
        scheme,
        ..SimSettings::default()
    }
}

/// The energies of every batch strand, in f64 from its f32 state.
fn batch_energies(
    batch: &BatchSystem,
    params: &StrandParams,
    roots: &[RootPose],
    head: &dyn HeadTrajectory,
) -> Energies {
    let settings = batch.settings();
    let m = model(params, settings.quadrature_points);
    let motion = head.motion_at(batch.time_secs());
    let mut total = Energies::default();
    for (i, root) in roots.iter().enumerate() {
        let root = motion.carry(root);
        let (q, v) = (batch.q(i), batch.v(i));
        let kin = kinematics(&m, &q, &v, &root);
        total.accumulate(&energies(
            &m,
            &q,
            &kin,
            root.position_m,
            settings.gravity_m_per_s2,
        ));
    }
    total
}

/// Energy a frame may gain with the head still, relative to the sizes of
/// the energies (|kinetic| + |elastic| + |gravitational|): f32 round-off.
/// The state is rounded to f32 (relative 6e-8) every step, and a straight
/// strand's step amplifies round-off about 1e3 times (its twist rows carry
/// almost no inertia: `batch_parity.rs` measured 1e-4 relative on one
/// step's rates); on the energy, a sum of squares of such rates and of
/// heights, that is below 1e-6. Measured: the energy fell on every frame
/// after the shake, by at least 1.5e-5 of the energies' size.
const F32_ENERGY_GAIN: f64 = 1e-6;

#[test]
fn a_straight_30_cm_strand_survives_an_ordinary_shake_at_60_hz_on_the_batch_engine() {
    // The batch engine stepped velocity-explicit: under this shake the guard
    // reset the straight example's strands 6 times in 300 frames at one
    // substep (the wavy ones 31 times).
    let head = ShakeThenStill::ordinary();
    let params = straight_30_cm();
    let roots = head_roots();
    let mut hair = batch(exact(IMPLICIT), &params, &roots);
    let mut energies = Vec::new();
    for _ in 0..(6 * 60) {
        hair.step_frame(&head);
        assert!(hair.is_finite(), "went non-finite");
        assert_eq!(
            hair.guard_reset_count(),
            0,
            "the guard reset {:?}",
            hair.last_guard_resets()
        );
        if hair.time_secs() > head.shake_secs + 1e-9 {
            energies.push(batch_energies(&hair, &params, &roots, &head));
        }
    }
    let mut worst: f64 = f64::NEG_INFINITY;
    for pair in energies.windows(2) {
        let size = pair[0].kinetic_j.abs() + pair[0].elastic_j.abs() + pair[0].gravity_j.abs();
        let gain = (pair[1].total_j() - pair[0].total_j()) / size;
        worst = worst.max(gain);
        assert!(
            gain <= F32_ENERGY_GAIN,
            "energy grew from {} to {} J ({gain:.1e} of the energies' size)",
            pair[0].total_j(),
            pair[1].total_j()
        );
    }
    let first = energies.first().expect("frames after the shake");
    let last = energies.last().expect("frames after the shake");
    println!(
        "after the shake: total {:.3e} J -> {:.3e} J, kinetic {:.1e} -> {:.1e} J; \
         largest gain per frame {worst:.1e} of the energies' size",
        first.total_j(),
        last.total_j(),
        first.kinetic_j,
        last.kinetic_j
    );
    assert!(last.kinetic_j < first.kinetic_j);
}

#[test]
fn the_explicit_batch_step_fails_on_the_same_shake() {
    // The control for the test above: what the velocity terms cure on the
    // batch engine (blown up, or caught by the guard).
    let mut hair = batch(
        exact(StepScheme::VelocityExplicit),
        &straight_30_cm(),
        &head_roots(),
    );
    let shake = ordinary_shake();
    let failed = (0..300).any(|_| {
        hair.step_frame(&shake);
        !hair.is_finite() || hair.guard_reset_count() > 0
    });
    assert!(failed, "the explicit step should fail within 5 s");
}

fn roots(count: usize, rng: &mut Rng) -> Vec<RootPose> {
    (0..count)
        .map(|_| {
            let position = rng.vec3(0.1);
            RootPose::from_direction(position, position.normalize() + rng.vec3(0.3), DVec3::Y)
        })
        .collect()
}

fn curl() -> StrandParams {
    StrandParams {
        natural_shape: NaturalShape::Helix {
            radius_m: 0.02,
            step_m: 0.05,
        },
        ..StrandParams::default()
    }
}

fn max_abs(a: &[DVec3]) -> f64 {
    a.iter().map(|x| x.abs().max_element()).fold(0.0, f64::max)
}

fn max_diff(a: &[DVec3], b: &[DVec3]) -> f64 {
    common::max_diff(a, b)
}

/// One step from the same random state: max |v_batch − v_f64| over
/// max |v_f64|, against the f64 reference's velocity-implicit Exact step
/// (the same GMRES, in f64). Only f32 round-off separates them: the
/// explicit step matches to 1e-4 (`batch_parity.rs`'s ONE_STEP_TOL is
/// 5e-4). Measured: 7.4e-6 (straight), 1.1e-6 (curl).
const ONE_STEP_TOL: f64 = 1e-4;

/// The same against Dense's exact solve of (P + hG) Δv = rhs: GMRES stops
/// at a residual of 1e-5 of |rhs| (`gmres::GMRES_TOLERANCE`), and the step
/// matrix's conditioning carries that into the rates, f32 round-off on
/// top. Measured: 8.3e-5 (straight), 2.1e-5 (curl); at a residual of 1e-3
/// they were 1.3e-3 and 4.6e-4.
const ONE_STEP_DENSE_TOL: f64 = 3e-4;

fn one_step_error(params: &StrandParams, reference_method: Method) -> f64 {
    let mut rng = Rng::new(7);
    let roots = roots(11, &mut rng);
    let settings = SimSettings {
        air_velocity_m_per_s: DVec3::new(0.3, 0.0, -0.1),
        ..exact(IMPLICIT)
    };
    let mut reference = HairSystem::new(SimSettings {
        method: reference_method,
        ..settings.clone()
    })
    .expect("valid settings");
    reference.set_guard(None);
    reference.add_group(params, &roots).expect("valid params");
    let mut hair = batch(settings, params, &roots);
    hair.set_guard(None);
    for i in 0..roots.len() {
        let (q, v) = common::f32_random_state(&mut rng, reference.strands()[i].q());
        reference.strands_mut()[i].set_state(&q, &v);
        hair.set_state(i, &q, &v);
    }
    let head = shake();
    reference.step_frame(&head);
    hair.step_frame(&head);
    (0..roots.len())
        .map(|i| {
            let v_ref = reference.strands()[i].v();
            max_diff(&hair.v(i), v_ref) / max_abs(v_ref)
        })
        .fold(0.0, f64::max)
}

#[test]
fn one_implicit_step_matches_the_f64_reference() {
    for (name, params) in [("straight", StrandParams::default()), ("curl", curl())] {
        for (method, tol) in [
            (Method::Exact, ONE_STEP_TOL),
            (Method::Dense, ONE_STEP_DENSE_TOL),
        ] {
            let err = one_step_error(&params, method);
            println!("{name} against f64 {method:?}: {err:.2e}");
            assert!(err < tol, "{name} against {method:?}: {err:.2e}");
        }
    }
}

/// After one second of head shake at 1/60 s, one substep: max |q_batch −
/// q_f64| over the strain scale max |q_f64 − qⁿ|, both velocity-implicit
/// Exact. Measured: 3.3e-7 (straight), 8.6e-7 (curl); the explicit step's
/// bound in `batch_parity.rs` is 2e-5, and this one is 1e-5.
const TRAJECTORY_TOL: f64 = 1e-5;

#[test]
fn a_second_of_head_shake_matches_the_f64_implicit_step() {
    let mut rng = Rng::new(3);
    let roots = roots(9, &mut rng);
    for (name, params) in [("straight", StrandParams::default()), ("curl", curl())] {
        let settings = SimSettings {
            air_velocity_m_per_s: DVec3::new(0.3, 0.0, -0.1),
            ..exact(IMPLICIT)
        };
        let mut reference = HairSystem::new(settings.clone()).expect("valid settings");
        reference.set_guard(None);
        reference.add_group(&params, &roots).expect("valid params");
        let mut hair = batch(settings, &params, &roots);
        hair.set_guard(None);
        let head = shake();
        for _ in 0..60 {
            reference.step_frame(&head);
            hair.step_frame(&head);
        }
        assert!(reference.is_finite() && hair.is_finite(), "{name}");
        let err = (0..roots.len())
            .map(|i| {
                let s = &reference.strands()[i];
                max_diff(&hair.q(i), s.q()) / max_diff(s.q(), &s.model().natural)
            })
            .fold(0.0, f64::max);
        println!("{name}: {err:.2e}");
        assert!(err < TRAJECTORY_TOL, "{name}: {err:.2e}");
    }
}

#[test]
fn implicit_lanes_do_not_interact_and_threads_do_not_matter() {
    // Each lane runs its own GMRES (its own dot products, rotations and
    // stopping test) inside the batch's SIMD arithmetic: a strand's result
    // must not depend on its neighbours, nor on the thread that steps it.
    let mut rng = Rng::new(11);
    let roots = roots(21, &mut rng);
    let params = StrandParams {
        length_m: 0.3,
        ..curl()
    };
    let mut serial = batch(exact(IMPLICIT), &params, &roots);
    serial.set_parallel(false);
    let mut parallel = serial.clone();
    parallel.set_parallel(true);
    let mut alone = batch(exact(IMPLICIT), &params, &roots[20..]);
    for _ in 0..30 {
        serial.step_frame(&shake());
        parallel.step_frame(&shake());
        alone.step_frame(&shake());
    }
    for i in 0..roots.len() {
        assert_eq!(serial.q(i), parallel.q(i), "strand {i}");
        assert_eq!(serial.v(i), parallel.v(i), "strand {i}");
    }
    assert_eq!(serial.q(20), alone.q(0));
    assert_eq!(serial.v(20), alone.v(0));
}

#[test]
fn zero_corrections_is_the_explicit_step_bit_for_bit() {
    // `VelocityImplicit { corrections: 0 }` is the explicit answer in the
    // reference; the batch engine takes the explicit step's code for it.
    let roots = outward_roots(9);
    let mut explicit = batch(exact(StepScheme::VelocityExplicit), &curl(), &roots);
    let mut zero = batch(
        exact(StepScheme::VelocityImplicit { corrections: 0 }),
        &curl(),
        &roots,
    );
    for _ in 0..20 {
        explicit.step_frame(&shake());
        zero.step_frame(&shake());
    }
    for i in 0..roots.len() {
        assert_eq!(explicit.q(i), zero.q(i));
    }
}

#[test]
fn long_curly_strands_run_with_no_guard_event_on_the_batch_engine() {
    // The reference's check (`stable_step.rs`) on the batch engine: the
    // default window style dragged to 0.66 m (curly, 15 elements, Exact,
    // still head), which the reference's explicit step had gain energy on
    // 21 frames in 2 s.
    let params = StrandParams {
        length_m: 0.66,
        elements: 15,
        ellipticity: 1.35,
        natural_shape: NaturalShape::Helix {
            radius_m: 0.012,
            step_m: 0.03,
        },
        ..StrandParams::default()
    };
    let mut hair = batch(exact(IMPLICIT), &params, &outward_roots(16));
    let still = helixhair_physics::RigidMotion::default();
    for _ in 0..120 {
        hair.step_frame(&still);
        assert_eq!(
            hair.guard_reset_count(),
            0,
            "the guard reset {:?}",
            hair.last_guard_resets()
        );
    }
    assert!(hair.is_finite());
}

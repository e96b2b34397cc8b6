//! Strands of different constants packed into one batch
//! (`batch::lane_model`, `BatchSystem`'s packing): each matches its own
//! f64 reference, packing changes no bit of any strand's result, and the
//! guard's reset of one lane puts back only that strand, in its own
//! natural shape.

use crate::common;

use std::sync::Arc;

use common::sphere::{RADIUS_M, sphere_field};
use common::{Rng, max_diff, outward_roots, shake};
use glam::DVec3;
use helixhair_physics::batch::{BatchSystem, LaneUse};
use helixhair_physics::guard::{GuardAction, GuardCause};
use helixhair_physics::{
    ElementLayout, HairSystem, Method, NaturalShape, RootPose, SimSettings, StepScheme,
    StrandParams,
};

/// Elements of every strand here: packing needs one N.
const ELEMENTS: usize = 6;

/// One step from a random state, velocity-explicit: max |v_f32 − v_f64|
/// over max |v_f64|; `batch_parity.rs`'s ONE_STEP_TOL, there for one
/// strand kind per batch. Measured on the mixed batch: 2.5e-6
/// (Block-diagonal), 2.0e-5 (Exact).
const EXPLICIT_ONE_STEP_TOL: f64 = 5e-4;
/// After a second of head shake, velocity-explicit: max |q_f32 − q_f64|
/// over max |q_f64 − qⁿ|; `batch_parity.rs`'s TRAJECTORY_TOL. Measured:
/// 9.4e-7 (Exact).
const EXPLICIT_TRAJECTORY_TOL: f64 = 2e-5;
/// One velocity-implicit Exact step, as `ONE_STEP_TOL` of
/// `batch_stable_step.rs`. Measured: 2.1e-5.
const IMPLICIT_ONE_STEP_TOL: f64 = 1e-4;
/// A second of shake, velocity-implicit Exact, as `TRAJECTORY_TOL` of
/// `batch_stable_step.rs`. Measured: 7.0e-7.
const IMPLICIT_TRAJECTORY_TOL: f64 = 1e-5;

/// Eight strands of [`ELEMENTS`] elements that share nothing else:
/// lengths 8 to 30 cm, uniform and graded elements, straight, curled and
/// per-element rest shapes, and stiffness, radius, density, friction and
/// drag spread over their ranges.
fn eight_kinds() -> Vec<StrandParams> {
    let base = StrandParams {
        elements: ELEMENTS,
        ..StrandParams::default()
    };
    let mut rng = Rng::new(17);
    let per_element: Vec<[f64; 3]> = (0..ELEMENTS).map(|_| (rng.vec3(20.0)).to_array()).collect();
    vec![
        StrandParams {
            length_m: 0.3,
            ..base.clone()
        },
        StrandParams {
            length_m: 0.08,
            youngs_modulus_pa: 8e9,
            ..base.clone()
        },
        StrandParams {
            length_m: 0.25,
            natural_shape: NaturalShape::Helix {
                radius_m: 0.02,
                step_m: 0.05,
            },
            ..base.clone()
        },
        StrandParams {
            length_m: 0.15,
            natural_shape: NaturalShape::Helix {
                radius_m: 0.008,
                step_m: -0.02,
            },
            radius_m: 50e-6,
            ellipticity: 1.6,
            ..base.clone()
        },
        StrandParams {
            length_m: 0.2,
            layout: ElementLayout::Graded {
                tip_to_root_ratio: 3.0,
            },
            density_kg_per_m3: 2500.0,
            ..base.clone()
        },
        StrandParams {
            length_m: 0.12,
            natural_shape: NaturalShape::PerElement(per_element),
            internal_friction: 1e-9,
            ..base.clone()
        },
        StrandParams {
            length_m: 0.22,
            air_drag: 1e-4,
            shear_modulus_pa: 2e9,
            natural_shape: NaturalShape::Uniform {
                twist_per_m: 5.0,
                curvature1_per_m: 10.0,
                curvature2_per_m: -4.0,
            },
            ..base.clone()
        },
        StrandParams {
            length_m: 0.18,
            radius_m: 20e-6,
            youngs_modulus_pa: 1e9,
            ..base
        },
    ]
}

fn settings(method: Method, scheme: StepScheme) -> SimSettings {
    SimSettings {
        method,
        scheme,
        // Block-diagonal blows up under a shake at 60 Hz (docs/solvers.md);
        // batch_parity.rs steps it at 1/600 s.
        substeps: if method == Method::BlockDiagonal {
            10
        } else {
            1
        },
        air_velocity_m_per_s: DVec3::new(0.3, 0.0, -0.1),
        ..SimSettings::default()
    }
}

/// Each strand added on its own, as an imported groom adds them.
fn packed(settings: SimSettings, kinds: &[StrandParams], roots: &[RootPose]) -> BatchSystem {
    let mut batch = BatchSystem::new(settings).expect("valid settings");
    for (params, root) in kinds.iter().zip(roots) {
        batch.add_group(params, &[*root]).expect("valid params");
    }
    batch
}

/// The f64 reference and the packed batch, both without a guard: the
/// arithmetic is compared, not the guards' policy.
fn systems(method: Method, scheme: StepScheme, roots: &[RootPose]) -> (HairSystem, BatchSystem) {
    let kinds = eight_kinds();
    let mut reference = HairSystem::new(settings(method, scheme)).expect("valid settings");
    reference.set_guard(None);
    for (params, root) in kinds.iter().zip(roots) {
        reference.add_group(params, &[*root]).expect("valid params");
    }
    let mut batch = packed(settings(method, scheme), &kinds, roots);
    batch.set_guard(None);
    (reference, batch)
}

fn max_abs(a: &[DVec3]) -> f64 {
    a.iter().map(|x| x.abs().max_element()).fold(0.0, f64::max)
}

#[test]
fn eight_strands_added_one_by_one_fill_one_batch() {
    let roots = outward_roots(9);
    let mut kinds = eight_kinds();
    kinds.push(kinds[2].clone());
    let batch = packed(SimSettings::default(), &kinds, &roots);
    assert_eq!(
        batch.lanes_used(),
        LaneUse {
            batches: 2,
            strands: 9,
            padding: 7
        }
    );
    // A strand of another element count opens its own batch.
    let mut batch = batch;
    let other = StrandParams {
        elements: ELEMENTS + 1,
        ..StrandParams::default()
    };
    let index = batch.add_group(&other, &roots[..1]).expect("valid params");
    assert_eq!(index, 9..10);
    assert_eq!(batch.lanes_used().batches, 3);
    assert_eq!(batch.q(9).len(), ELEMENTS + 1);
}

/// One step from the same random state (strains ±5 m⁻¹ off each strand's
/// rest shape, rates ±20 m⁻¹/s, a head shake): the worst strand's
/// max |v_f32 − v_f64| over max |v_f64|.
fn one_step_error(method: Method, scheme: StepScheme) -> f64 {
    let mut rng = Rng::new(7);
    let roots = outward_roots(8);
    let (mut reference, mut batch) = systems(method, scheme, &roots);
    for i in 0..roots.len() {
        let (q, v) = common::f32_random_state(&mut rng, reference.strands()[i].q());
        reference.strands_mut()[i].set_state(&q, &v);
        batch.set_state(i, &q, &v);
    }
    reference.step_frame(&shake());
    batch.step_frame(&shake());
    (0..roots.len())
        .map(|i| {
            let v_ref = reference.strands()[i].v();
            max_diff(&batch.v(i), v_ref) / max_abs(v_ref)
        })
        .fold(0.0, f64::max)
}

/// After a second of head shake from rest: the worst strand's
/// max |q_f32 − q_f64| over its strain scale max |q_f64 − qⁿ|.
fn trajectory_error(method: Method, scheme: StepScheme) -> f64 {
    let roots = outward_roots(8);
    let (mut reference, mut batch) = systems(method, scheme, &roots);
    for _ in 0..60 {
        reference.step_frame(&shake());
        batch.step_frame(&shake());
    }
    assert!(reference.is_finite(), "reference {method:?}");
    assert!(batch.is_finite(), "batch {method:?}");
    (0..roots.len())
        .map(|i| {
            let s = &reference.strands()[i];
            max_diff(&batch.q(i), s.q()) / max_diff(s.q(), &s.model().natural)
        })
        .fold(0.0, f64::max)
}

#[test]
fn each_strand_of_a_mixed_batch_matches_its_own_f64_reference() {
    let explicit = StepScheme::VelocityExplicit;
    let implicit = StepScheme::VelocityImplicit { corrections: 8 };
    // One step on every solver the batch runs.
    let one_step = [
        (Method::BlockDiagonal, explicit, EXPLICIT_ONE_STEP_TOL),
        (Method::Exact, explicit, EXPLICIT_ONE_STEP_TOL),
        (Method::Exact, implicit, IMPLICIT_ONE_STEP_TOL),
    ];
    for (method, scheme, tol) in one_step {
        let err = one_step_error(method, scheme);
        println!("{method:?} {scheme:?}: one step {err:.2e}");
        assert!(err < tol, "{method:?} {scheme:?}: one step {err:.2e}");
    }
    // A second of shake on Exact only: the f64 reference's own
    // Block-diagonal blows up on these strands within it, even at 1/600 s
    // (docs/solvers.md: its truncated matrix gains energy).
    let trajectory = [
        (explicit, EXPLICIT_TRAJECTORY_TOL),
        (implicit, IMPLICIT_TRAJECTORY_TOL),
    ];
    for (scheme, tol) in trajectory {
        let err = trajectory_error(Method::Exact, scheme);
        println!("Exact {scheme:?}: a second {err:.2e}");
        assert!(err < tol, "Exact {scheme:?}: a second {err:.2e}");
    }
}

#[test]
fn a_strand_packed_with_seven_others_steps_bit_for_bit_as_alone() {
    // Velocity-implicit Exact (each lane runs its own GMRES), the guard on
    // and a collider the strands fall onto: every per-lane path. No wind:
    // with it, the f64 reference's own guard flags the high-drag strand.
    let kinds = eight_kinds();
    let roots: Vec<RootPose> = (0..8)
        .map(|i| {
            let a = i as f64 * 0.8;
            let dir = DVec3::new(a.cos() * 0.6, 0.8, a.sin() * 0.6);
            let tangent = DVec3::Y.cross(dir).cross(dir).normalize_or(DVec3::X);
            RootPose::from_direction(dir * RADIUS_M, -tangent, dir)
        })
        .collect();
    let settings = SimSettings {
        air_velocity_m_per_s: DVec3::ZERO,
        ..settings(
            Method::Exact,
            StepScheme::VelocityImplicit { corrections: 8 },
        )
    };
    let collider = Arc::new(sphere_field().0);
    let mut all = packed(settings.clone(), &kinds, &roots);
    all.set_collider(Some(collider.clone()));
    let mut alone: Vec<BatchSystem> = (0..8)
        .map(|i| {
            let mut one = packed(settings.clone(), &kinds[i..=i], &roots[i..=i]);
            one.set_collider(Some(collider.clone()));
            one
        })
        .collect();
    for _ in 0..40 {
        all.step_frame(&shake());
        for one in &mut alone {
            one.step_frame(&shake());
        }
    }
    assert!(all.is_finite());
    // A healthy run: the guard measured every lane and touched none.
    assert_eq!(all.guard_reset_count(), 0);
    for (i, one) in alone.iter().enumerate() {
        assert_eq!(all.q(i), one.q(0), "strand {i}");
        assert_eq!(all.v(i), one.v(0), "strand {i}");
        assert_eq!(all.boundary_points_world(i), one.boundary_points_world(0));
    }
}

#[test]
fn the_guard_resets_one_lane_of_a_mixed_batch_to_its_own_start_at_rest() {
    let kinds = eight_kinds();
    let roots = outward_roots(8);
    let settings = settings(
        Method::Exact,
        StepScheme::VelocityImplicit { corrections: 8 },
    );
    let mut hit = packed(settings, &kinds, &roots);
    for _ in 0..10 {
        hit.step_frame(&shake());
    }
    let mut untouched = hit.clone();
    // Strand 3 (a tight curl) goes bad: a rate that is not a number.
    let mut broken = hit.v(3);
    broken[2].y = f64::NAN;
    let start = hit.q(3);
    hit.set_state(3, &start, &broken);
    hit.step_frame(&shake());
    untouched.step_frame(&shake());
    let events = hit.last_guard_events();
    assert_eq!(events.len(), 1, "{events:?}");
    assert_eq!(events[0].strand, 3);
    assert_eq!(events[0].action, GuardAction::Reset);
    assert_eq!(events[0].cause, GuardCause::NotFinite);
    // No retry can pass from a rate that is not a number: its own shape at
    // the frame's start, at rest.
    assert_eq!(hit.q(3), start);
    assert_eq!(hit.v(3), vec![DVec3::ZERO; ELEMENTS]);
    // Its neighbours in the batch did not notice.
    for i in (0..8).filter(|&i| i != 3) {
        assert_eq!(hit.q(i), untouched.q(i), "strand {i}");
        assert_eq!(hit.v(i), untouched.v(i), "strand {i}");
    }
}

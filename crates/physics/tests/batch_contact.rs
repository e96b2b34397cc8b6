//! The head collider on the f32 batch path (`batch::contact`): one step in
//! contact against the f64 reference's step, a strand draped
//! over a sphere against the sphere and against the f64 reference, and the
//! collider changing nothing when it is absent or out of reach.

use crate::common;

use std::sync::Arc;

use common::sphere::{RADIUS_M, icosphere, sphere_field};
use common::*;
use glam::DVec3;
use helixhair_physics::batch::BatchSystem;
use helixhair_physics::batch::contact::{NearCells, SkinTest};
use helixhair_physics::collision::{ContactInputs, ContactSettings, SignedDistanceField};
use helixhair_physics::{
    Bounce, HairSystem, HeadTrajectory, Method, RigidMotion, RootPose, SimSettings, StepScheme,
    StrandParams,
};

/// One step of a strand resting on the sphere and set moving: the f32
/// batch step's Δv against the f64 reference's, max |ΔΔv| / max |Δv|. Both
/// step the same implicit contact at the same quadrature samples; what is
/// left is f32 round-off in the sweeps and the elimination (about 1e-7
/// relative per operation, over tens of operations per element and the
/// contact's point inertias) and the f32 state the batch reads. Measured
/// 9.6e-6 (the step without the contact is 47 times Δv off).
const CONTACT_STEP_TOL: f64 = 1e-4;

#[test]
fn one_step_in_contact_matches_the_f64_reference_step() {
    let (mut settings, p) = drape_settings();
    // The velocity-explicit step, and one substep: the step itself is
    // compared, not GMRES's stopping point.
    settings.scheme = StepScheme::VelocityExplicit;
    settings.substeps = 1;
    let field = Arc::new(sphere_field().0);
    let still = RigidMotion::default();
    let mut reference = HairSystem::new(settings.clone()).expect("valid settings");
    reference.set_guard(None);
    reference
        .add_group(&p, &[top_root()])
        .expect("valid params");
    reference.set_collider(Some(field.clone()));
    // Settle onto the sphere: the strand rests in the skin, held by the
    // contact against gravity.
    for _ in 0..120 {
        reference.step_frame(&still);
    }
    let f32_round =
        |x: &[DVec3]| -> Vec<DVec3> { x.iter().map(|k| k.as_vec3().as_dvec3()).collect() };
    let q0 = f32_round(reference.strands()[0].q());
    // Then set every element moving (up to 3 m⁻¹/s per strain): the step
    // has work to do against the contact's spring and damper, not only the
    // cancelling forces of a rest.
    let mut rng = Rng::new(5);
    let moving: Vec<DVec3> = reference.strands()[0]
        .v()
        .iter()
        .map(|v| *v + rng.vec3(3.0))
        .collect();
    let v0 = f32_round(&moving);
    let mut batch = BatchSystem::new(settings).expect("valid settings");
    batch.set_guard(None);
    batch.add_group(&p, &[top_root()]).expect("valid params");
    batch.set_collider(Some(field));
    let mut free = batch.clone();
    free.set_collider(None);
    reference.strands_mut()[0].set_state(&q0, &v0);
    batch.set_state(0, &q0, &v0);
    free.set_state(0, &q0, &v0);
    reference.step_frame(&still);
    batch.step_frame(&still);
    free.step_frame(&still);
    let delta = |v: &[DVec3]| -> Vec<DVec3> { v.iter().zip(&v0).map(|(a, b)| *a - *b).collect() };
    let expected = delta(reference.strands()[0].v());
    let got = delta(&batch.v(0));
    let without = delta(&free.v(0));
    let scale = max_abs(&expected);
    let err = max_diff(&got, &expected) / scale;
    let contact_share = max_diff(&without, &expected) / scale;
    println!("Δv: batch against reference {err:.2e}; without contact {contact_share:.2e}");
    assert!(
        contact_share > 0.1,
        "the contact barely acts: {contact_share:.2e}"
    );
    assert!(err < CONTACT_STEP_TOL, "{err:.2e}");
}

fn max_abs(a: &[DVec3]) -> f64 {
    a.iter().map(|x| x.abs().max_element()).fold(0.0, f64::max)
}

/// The drape of `collision.rs`: 15 cm strands rooted on top of the sphere,
/// growing sideways, Exact at 240 Hz, light friction and drag.
fn drape_settings() -> (SimSettings, StrandParams) {
    let settings = SimSettings {
        method: Method::Exact,
        substeps: 4,
        ..SimSettings::default()
    };
    let mut p = params(0.15, 10);
    p.internal_friction = 2e-10;
    p.air_drag = 1e-5;
    (settings, p)
}

fn top_root() -> RootPose {
    RootPose::from_direction(DVec3::new(0.0, RADIUS_M, 0.0), DVec3::X, DVec3::Y)
}

/// Lowest analytic signed distance to the sphere (centred on the head) of
/// boundary points 2.. (the root and the first end point sit on the scalp).
fn lowest_above_sphere(points: &[DVec3], centre: DVec3) -> f64 {
    points[2..]
        .iter()
        .map(|q| (*q - centre).length() - RADIUS_M)
        .fold(f64::INFINITY, f64::min)
}

/// How far the batch path's resting drape may lie from the f64 path's,
/// metres. Both step one contact law at the same quadrature samples, so
/// the drapes differ by f32 round-off: positions 10 cm from the origin
/// carry about 1e-8 m, and the rest is an equilibrium that does not
/// accumulate it (measured 8.6e-9 m; when the batch engine pushed at
/// element end points instead, 1.48 mm). 10 µm leaves room for another
/// CPU's fused products and libm.
const DRAPE_SHAPE_TOL_M: f64 = 1e-5;

#[test]
fn a_strand_draped_over_a_sphere_rests_on_it_near_the_f64_drape() {
    let (settings, p) = drape_settings();
    let field = Arc::new(sphere_field().0);
    let still = RigidMotion::default();
    let mut batch = BatchSystem::new(settings.clone()).expect("valid settings");
    batch.add_group(&p, &[top_root()]).expect("valid params");
    let mut falls = batch.clone();
    batch.set_collider(Some(field.clone()));
    assert!(batch.collider().is_some());
    let mut reference = HairSystem::new(settings).expect("valid settings");
    reference.set_guard(None);
    reference
        .add_group(&p, &[top_root()])
        .expect("valid params");
    // Both engines step the same implicit contact (default settings).
    reference.set_collider(Some(field));
    for _ in 0..180 {
        batch.step_frame(&still);
        falls.step_frame(&still);
        reference.step_frame(&still);
    }
    assert!(batch.is_finite());
    assert_eq!(batch.guard_reset_count(), 0);
    let through = lowest_above_sphere(
        &falls
            .boundary_points_world(0)
            .iter()
            .map(|x| x.as_dvec3())
            .collect::<Vec<_>>(),
        DVec3::ZERO,
    );
    assert!(through < -0.01, "without the collider it falls: {through}");
    let points: Vec<DVec3> = batch
        .boundary_points_world(0)
        .iter()
        .map(|x| x.as_dvec3())
        .collect();
    // Each end point sinks g h² / α = 0.04 mm into the 2 mm skin, and the
    // mesh lies up to 0.3 mm inside the sphere: the points rest above the
    // true sphere, within the skin (measured 1.54 mm above it).
    let resting = lowest_above_sphere(&points, DVec3::ZERO);
    println!("resting {resting:.2e} m above the sphere");
    assert!(resting > 0.0, "rests {resting} m from the sphere");
    assert!(resting < 0.002, "floats {resting} m above the sphere");
    let gaps: Vec<f64> = points
        .iter()
        .zip(reference.boundary_points_world(0))
        .map(|(a, b)| (*a - b).length())
        .collect();
    println!("gaps along the strand, root to tip: {gaps:?} m");
    let shape_gap = gaps.iter().copied().fold(0.0, f64::max);
    println!("largest gap to the f64 drape: {shape_gap:.2e} m");
    assert!(shape_gap < DRAPE_SHAPE_TOL_M, "{shape_gap} m");
    // At rest: the speed bound of the settled strand is small.
    let v = batch.v(0);
    let speed = helixhair_physics::guard::speed_bound_m_per_s(&model(&p, 4), &v);
    assert!(speed < 1e-2, "still moving at up to {speed} m/s");
}

/// How deep a strand pressed by a moving head may go below the true
/// sphere: 1 cm, a tenth of the head's radius (as `collision.rs`).
const PRESSED_PENETRATION_M: f64 = 0.01;

#[test]
fn a_jumping_head_pushes_hair_aside_without_flinging_it() {
    let (settings, p) = drape_settings();
    let bounce = Bounce {
        direction: DVec3::Y,
        amplitude_m: 0.04,
        frequency_hz: 4.0,
    };
    let field = Arc::new(sphere_field().0);
    let mut batch = BatchSystem::new(settings.clone()).expect("valid settings");
    batch.add_group(&p, &[top_root()]).expect("valid params");
    batch.set_collider(Some(field.clone()));
    let mut reference = HairSystem::new(settings).expect("valid settings");
    reference.set_guard(None);
    reference
        .add_group(&p, &[top_root()])
        .expect("valid params");
    reference.set_collider(Some(field));
    let (mut lowest, mut lowest_reference) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..120 {
        batch.step_frame(&bounce);
        reference.step_frame(&bounce);
        let centre = bounce.motion_at(batch.time_secs()).position_m;
        let points: Vec<DVec3> = batch
            .boundary_points_world(0)
            .iter()
            .map(|x| x.as_dvec3())
            .collect();
        lowest = lowest.min(lowest_above_sphere(&points, centre));
        let points = reference.boundary_points_world(0);
        lowest_reference = lowest_reference.min(lowest_above_sphere(&points, centre));
    }
    // For comparison only: the f64 path, contact at every sample.
    println!("lowest {lowest:.2e} m (f64 reference {lowest_reference:.2e} m)");
    assert_eq!(batch.guard_reset_count(), 0);
    assert!(batch.is_finite());
    assert!(
        lowest > -PRESSED_PENETRATION_M,
        "sank {lowest} m into the moving sphere"
    );
    let speed = helixhair_physics::guard::speed_bound_m_per_s(&model(&p, 4), &batch.v(0));
    assert!(speed < 20.0, "flung at {speed} m/s");
}

/// 21 roots spread over the sphere's upper half (three batches, the last
/// padded), growing outward and down.
fn scalp_roots() -> Vec<RootPose> {
    (0..21)
        .map(|i| {
            let a = i as f64 * 2.399963;
            let up = 0.3 + 0.7 * (i as f64 / 21.0);
            let normal = DVec3::new(a.cos() * (1.0 - up * up).sqrt(), up, a.sin()).normalize();
            let grow = (normal + DVec3::new(0.0, -0.8, 0.0)).normalize();
            RootPose::from_direction(normal * RADIUS_M, grow, DVec3::Y)
        })
        .collect()
}

fn states(system: &BatchSystem) -> Vec<(Vec<DVec3>, Vec<DVec3>)> {
    (0..system.strand_count())
        .map(|i| (system.q(i), system.v(i)))
        .collect()
}

#[test]
fn serial_and_parallel_are_bit_identical_with_a_collider() {
    for method in [Method::BlockDiagonal, Method::Exact] {
        let settings = SimSettings {
            method,
            substeps: 10,
            ..SimSettings::default()
        };
        let mut serial = BatchSystem::new(settings).expect("valid settings");
        serial
            .add_group(&StrandParams::default(), &scalp_roots())
            .expect("valid params");
        serial.set_parallel(false);
        let mut no_collider = serial.clone();
        serial.set_collider(Some(Arc::new(sphere_field().0)));
        let mut parallel = serial.clone();
        parallel.set_parallel(true);
        for _ in 0..60 {
            serial.step_frame(&shake());
            parallel.step_frame(&shake());
            no_collider.step_frame(&shake());
        }
        assert!(serial.is_finite(), "{method:?}");
        assert_eq!(states(&serial), states(&parallel), "{method:?}");
        assert_ne!(
            states(&serial),
            states(&no_collider),
            "{method:?}: the collider never touched the hair"
        );
    }
}

/// The sphere's field moved `offset_m` away from the head's centre.
fn field_at(offset_m: DVec3) -> SignedDistanceField {
    let (v, f) = icosphere(RADIUS_M, 2);
    let v: Vec<DVec3> = v.iter().map(|p| *p + offset_m).collect();
    SignedDistanceField::from_triangles(&v, &f, 0.004).expect("a valid mesh")
}

#[test]
fn without_a_collider_in_reach_the_step_is_bit_identical() {
    for method in [Method::BlockDiagonal, Method::Exact] {
        let settings = SimSettings {
            method,
            substeps: 10,
            ..SimSettings::default()
        };
        let mut plain = BatchSystem::new(settings).expect("valid settings");
        plain
            .add_group(&StrandParams::default(), &scalp_roots())
            .expect("valid params");
        // A collider set and taken away again.
        let mut removed = plain.clone();
        removed.set_collider(Some(Arc::new(sphere_field().0)));
        removed.set_collider(None);
        assert!(removed.collider().is_none());
        // A collider 5 m away: every end point's lookup misses the grid.
        let mut far = plain.clone();
        far.set_collider(Some(Arc::new(field_at(DVec3::new(5.0, 0.0, 0.0)))));
        for _ in 0..60 {
            plain.step_frame(&shake());
            removed.step_frame(&shake());
            far.step_frame(&shake());
        }
        assert_eq!(states(&plain), states(&removed), "{method:?}");
        assert_eq!(states(&plain), states(&far), "{method:?}");
    }
}

#[test]
fn a_point_in_a_cell_that_is_not_near_feels_exactly_no_force() {
    // The cull of `batch::contact` must skip only points whose force is
    // zero; and it must skip most points a few cells off the surface.
    let (field, _) = sphere_field();
    let settings = ContactSettings::default();
    let near = NearCells::new(&field);
    let head = RigidMotion::default();
    let inputs = ContactInputs {
        collider: &field,
        head: &head,
        settings,
        h_secs: 1.0 / 240.0,
    };
    let mut rng = Rng::new(23);
    let (mut skipped, mut touching) = (0, 0);
    for _ in 0..20_000 {
        let dir = rng.vec3(1.0).normalize_or(DVec3::X);
        let p = dir * (RADIUS_M + 0.02 * rng.next());
        let v = rng.vec3(1.0);
        let force = inputs.force(p, v, 5e-6);
        if !SkinTest::new(inputs, &near).may_feel(p, v, false) {
            assert_eq!(force, DVec3::ZERO, "skipped a point in contact at {p}");
            skipped += 1;
        }
        touching += usize::from(force != DVec3::ZERO);
    }
    println!("skipped {skipped}, touching {touching} of 20000");
    assert!(touching > 1000 && skipped > 5000, "{skipped}, {touching}");
}

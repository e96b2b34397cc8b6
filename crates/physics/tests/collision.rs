//! The head collider against known answers: the signed distance to a
//! sphere is |p| − R, and a strand draped over a sphere rests on it.

mod common;

use std::sync::Arc;

use common::*;
use glam::DVec3;
use helixhair_physics::collision::{CollisionError, SignedDistanceField};
use helixhair_physics::guard::speed_bound_m_per_s;
use helixhair_physics::{Bounce, HairSystem, Method, RigidMotion, RootPose, SimSettings};

use common::sphere::{CELL_M, RADIUS_M, icosphere, sphere_field};

#[test]
fn the_field_of_an_icosphere_is_the_distance_to_the_sphere() {
    let (field, sag) = sphere_field();
    // Faceting (the mesh is up to `sag` inside the sphere) plus trilinear
    // interpolation of a curved field, at most h²/R across a cell.
    let tol = sag + CELL_M * CELL_M / RADIUS_M;
    let mut rng = Rng::new(3);
    for _ in 0..2000 {
        let dir = rng.vec3(1.0).normalize_or(DVec3::X);
        let r = RADIUS_M + rng.next() * 2.0 * CELL_M;
        let p = dir * r;
        let (d, gradient) = field.sample(p).expect("inside the grid");
        assert!(
            (d - (r - RADIUS_M)).abs() <= tol,
            "r = {r}: {d} (tol {tol})"
        );
        assert!(gradient.dot(dir) > 0.95, "gradient {gradient} at {dir}");
    }
    // Far inside and far outside keep their signs.
    assert!(field.sample(DVec3::ZERO).expect("in grid").0 < 0.0);
    let corner = field.origin_m + DVec3::splat(CELL_M * 0.5);
    assert!(field.sample(corner).expect("in grid").0 > 0.0);
    assert!(field.sample(DVec3::splat(1.0)).is_none());
}

#[test]
fn broken_meshes_are_refused_with_the_reason() {
    let (v, f) = icosphere(RADIUS_M, 0);
    let err = |v: &[DVec3], f: &[[u32; 3]], cell| SignedDistanceField::from_triangles(v, f, cell);
    assert_eq!(err(&v, &[], CELL_M), Err(CollisionError::Empty));
    assert!(matches!(
        err(&v, &[[0, 1, 99]], CELL_M),
        Err(CollisionError::IndexOutOfRange {
            triangle: 0,
            vertex: 99,
            ..
        })
    ));
    let mut nan = v.clone();
    nan[4].y = f64::NAN;
    assert_eq!(
        err(&nan, &f, CELL_M),
        Err(CollisionError::NotFinite { vertex: 4 })
    );
    assert!(matches!(
        err(&v, &f, 0.0),
        Err(CollisionError::BadGrid { .. })
    ));
    assert!(matches!(
        err(&v, &f, 1e-6),
        Err(CollisionError::BadGrid { .. })
    ));
}

/// A 15 cm strand rooted on top of the sphere, growing sideways, stepped
/// for `secs` under `head`; returns the lowest signed distance (analytic)
/// of its boundary points over all frames and at the end, and the system.
fn drape(
    collide: bool,
    head: &dyn helixhair_physics::HeadTrajectory,
    secs: f64,
) -> (f64, f64, HairSystem) {
    let settings = SimSettings {
        method: Method::Exact,
        substeps: 4,
        ..SimSettings::default()
    };
    let mut system = HairSystem::new(settings).expect("valid settings");
    system.set_guard(None);
    let mut p = params(0.15, 10);
    p.internal_friction = 2e-10;
    p.air_drag = 1e-5;
    let root = RootPose::from_direction(DVec3::new(0.0, RADIUS_M, 0.0), DVec3::X, DVec3::Y);
    system.add_group(&p, &[root]).expect("valid params");
    if collide {
        system.set_collider(Some(Arc::new(sphere_field().0)));
    }
    let (mut lowest, mut last) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..(secs * 60.0) as usize {
        system.step_frame(head);
        let centre = head.motion_at(system.time_secs()).position_m;
        let points = system.boundary_points_world(0);
        last = points[2..]
            .iter()
            .map(|q| (*q - centre).length() - RADIUS_M)
            .fold(f64::INFINITY, f64::min);
        lowest = lowest.min(last);
    }
    (lowest, last, system)
}

/// How deep a strand pressed by a moving head may go below the true
/// sphere: 1 cm, a tenth of the head's radius (pressed, not through).
const PRESSED_PENETRATION_M: f64 = 0.01;

#[test]
fn a_strand_draped_over_a_sphere_rests_on_it() {
    let still = RigidMotion::default();
    let (_, through, _) = drape(false, &still, 3.0);
    assert!(
        through < -PRESSED_PENETRATION_M,
        "without the collider it should fall through: {through}"
    );
    // At rest, each sample sinks g h² / α = 0.7 mm (h = 1/240 s, α = 0.25)
    // into its 2 mm skin, and the mesh lies up to 0.3 mm inside the sphere:
    // the strand rests above the true sphere, within the skin.
    let (_, resting, system) = drape(true, &still, 3.0);
    assert!(resting > 0.0, "rests {resting} m from the sphere");
    assert!(resting < 0.002, "floats {resting} m above the sphere");
    assert!(system.is_finite());
}

#[test]
fn a_jumping_head_pushes_hair_aside_without_flinging_it() {
    // The head bounces 4 cm at 4 Hz: up to 25 m/s² (2.6 g) into the hair.
    let bounce = Bounce {
        direction: DVec3::Y,
        amplitude_m: 0.04,
        frequency_hz: 4.0,
    };
    let (lowest, _, system) = drape(true, &bounce, 2.0);
    let s = &system.strands()[0];
    assert!(system.is_finite());
    assert!(
        lowest > -PRESSED_PENETRATION_M,
        "sank {lowest} m into the moving sphere"
    );
    assert!(speed_bound_m_per_s(s.model(), s.v()) < 20.0, "flung");
}

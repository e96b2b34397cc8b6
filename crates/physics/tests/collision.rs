//! The head collider against known answers: the signed distance to a
//! sphere is |p| − R, the winding number of a sphere with a hole is the
//! solid angle it covers, and a strand draped over a sphere rests on it.

use crate::common;

use std::sync::Arc;

use common::*;
use glam::DVec3;
use helixhair_physics::collision::{
    CollisionError, SIGN_BLOCK_CELLS, SignedDistanceField, WindingNumber,
};
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

/// An icosphere of radius [`RADIUS_M`] with the triangles whose centres lie
/// above latitude `cos_cap` (a cap of half-angle acos(cos_cap) about +y)
/// removed: an open surface, as a bust is cut open below the chest.
fn sphere_with_hole(cos_cap: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (v, f) = icosphere(RADIUS_M, 4);
    let kept = f
        .into_iter()
        .filter(|t| {
            let centre = (v[t[0] as usize] + v[t[1] as usize] + v[t[2] as usize]) / 3.0;
            centre.normalize().y < cos_cap
        })
        .collect();
    (v, kept)
}

#[test]
fn the_winding_number_is_the_solid_angle_the_surface_covers() {
    // Closed sphere: 1 inside, 0 outside, exactly (up to the far-field
    // dipoles' error).
    let (v, f) = icosphere(RADIUS_M, 3);
    let closed = WindingNumber::new(&v, &f);
    let mut rng = Rng::new(11);
    let mut worst: f64 = 0.0;
    for _ in 0..500 {
        let dir = rng.vec3(1.0).normalize_or(DVec3::X);
        let inner = closed.at(dir * RADIUS_M * 0.9 * rng.next().abs());
        let outer = closed.at(dir * RADIUS_M * (1.1 + 3.0 * rng.next().abs()));
        worst = worst.max((inner - 1.0).abs()).max(outer.abs());
    }
    println!("closed sphere: winding number within {worst:.1e} of 0 or 1");
    assert!(worst < WINDING_TOL, "{worst}");
    // A sphere missing a cap of half-angle θ covers 1 − (1 − cos θ)/2 of
    // the sphere of directions seen from its centre. The cap's rim follows
    // the triangles, a few degrees from the circle at θ.
    for cap_deg in [30.0f64, 60.0, 90.0] {
        let cos_cap = cap_deg.to_radians().cos();
        let (v, f) = sphere_with_hole(cos_cap);
        let expected = 1.0 - (1.0 - cos_cap) / 2.0;
        let w = WindingNumber::new(&v, &f).at(DVec3::ZERO);
        assert!(
            (w - expected).abs() < RIM_TOL,
            "cap {cap_deg}°: {w}, expected {expected}"
        );
    }
}

#[test]
fn an_open_surface_still_has_an_inside() {
    // A sphere cut open by a 60° cap: the hole is wide (7 cm across on an
    // 8 cm sphere), as a bust's cut below the chest is.
    let (v, f) = sphere_with_hole(60f64.to_radians().cos());
    let field = SignedDistanceField::from_triangles(&v, &f, CELL_M).expect("a valid mesh");
    // Deep inside and just under the surface, away from the hole: inside,
    // at the distance to the sphere.
    let tol = CELL_M * CELL_M / RADIUS_M + 0.002;
    let mut rng = Rng::new(5);
    for _ in 0..2000 {
        let dir = rng.vec3(1.0).normalize_or(DVec3::NEG_Y);
        if dir.y > 0.0 {
            continue; // the hole's side
        }
        let r = RADIUS_M + rng.next() * CELL_M;
        let (d, _) = field.sample(dir * r).expect("inside the grid");
        assert!((d - (r - RADIUS_M)).abs() <= tol, "r = {r}: {d}");
        let (deep, _) = field.sample(dir * RADIUS_M * 0.5).expect("inside the grid");
        assert!(deep < 0.0, "{deep} at half the radius along {dir}");
    }
    assert!(field.sample(DVec3::ZERO).expect("in grid").0 < 0.0);
    let corner = field.origin_m + DVec3::splat(CELL_M * 0.5);
    assert!(field.sample(corner).expect("in grid").0 > 0.0);
}

#[test]
fn the_field_takes_its_sign_from_the_winding_number_at_every_point_off_the_film() {
    // The field evaluates the winding number only in blocks the surface
    // passes through or whose corners disagree; every other block takes its
    // corners' sign. Point by point, that must be the winding number's own
    // sign, except near the film spanning the hole: there the winding
    // number passes 1/2 smoothly in open space (on the hole's disk, at
    // y = R cos θ, it is exactly 1/2), where inside and outside are a
    // matter of definition, and a block across the film may keep its
    // corners' side.
    let cos_cap = 0.5f64; // a 60° cap
    let (v, f) = sphere_with_hole(cos_cap);
    let field = SignedDistanceField::from_triangles(&v, &f, CELL_M).expect("a valid mesh");
    let winding = WindingNumber::new(&v, &f);
    let film = |p: DVec3| {
        let (y0, rho0) = (
            RADIUS_M * cos_cap,
            RADIUS_M * (1.0 - cos_cap * cos_cap).sqrt(),
        );
        let rho = DVec3::new(p.x, 0.0, p.z).length();
        (rho - rho0).max(0.0).hypot(p.y - y0)
    };
    let reach = 3f64.sqrt() * SIGN_BLOCK_CELLS as f64 * CELL_M + RIM_STAIRCASE_M;
    let (mut checked, mut differ, mut differ_off_film) = (0, 0, 0);
    for z in 0..field.dims[2] {
        for y in 0..field.dims[1] {
            for x in 0..field.dims[0] {
                let d = field.at(x, y, z);
                if d == 0.0 {
                    continue;
                }
                let p = field.origin_m + DVec3::new(x as f64, y as f64, z as f64) * field.cell_m;
                checked += 1;
                if (d < 0.0) != winding.inside(p) {
                    differ += 1;
                    if film(p) > reach {
                        differ_off_film += 1;
                        println!("the sign differs at {p}, {} m off the film", film(p));
                    }
                }
            }
        }
    }
    println!("{checked} grid points: {differ} signs differ from the winding number's");
    assert_eq!(
        differ_off_film, 0,
        "{differ} differ, {differ_off_film} off the film"
    );
}

/// How far the open sphere's rim, which follows whole triangles, strays
/// from the circle at the cap's angle: a tenth of the radius (a level-4
/// icosphere's edges are about 0.08 R).
const RIM_STAIRCASE_M: f64 = 0.1 * RADIUS_M;

/// How far the fast winding number of a closed sphere may be from exactly
/// 1 (inside) or 0 (outside): the far-field dipoles' error (measured at
/// most 3.1e-2 at these points, inside, where every group of the tree
/// adds its own), a tenth of the margin to the 1/2 that decides the sign.
const WINDING_TOL: f64 = 0.05;

/// How far the winding number at the centre of a sphere with a cap cut off
/// may be from 1 − (1 − cos θ)/2: the dipoles' error as above, plus the
/// cut following whole triangles, a degree or two from the circle at θ
/// (the exact solid-angle sum of the same triangles, computed apart,
/// differs from the formula by 3e-4, 5e-4 and 6.6e-3 at 30°, 60° and 90°).
const RIM_TOL: f64 = WINDING_TOL + 0.01;

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

/// One step of a free point of mass ρS per unit length, half into its
/// skin above `field`'s sphere, against the implicit contact:
/// (ρS + h gain n nᵀ) Δv = h push n, whose solution is
/// Δv = h push n / (ρS + h gain |n|²) (n is the field's gradient, unit
/// length to the field's interpolation). Returns the point's velocity
/// along n̂ at the step's end, m/s (negative: still approaching), n, and
/// the point's distance d as the field reads it.
fn free_point_after_one_step(
    field: &SignedDistanceField,
    approach_m_per_s: f64,
) -> (f64, DVec3, f64) {
    use helixhair_physics::collision::{ContactInputs, ContactSettings};
    let settings = ContactSettings::default();
    let inputs = ContactInputs {
        collider: field,
        head: &RigidMotion::default(),
        settings,
        h_secs: H_SECS,
    };
    let p = DVec3::new(0.0, RADIUS_M + 0.5 * settings.skin_m, 0.0);
    let v = DVec3::new(0.0, -approach_m_per_s, 0.0);
    let contact = inputs
        .implicit_force(p, v, RHO_S)
        .expect("a point approaching inside the skin is in contact");
    let n = contact.normal;
    assert!(n.normalize().dot(DVec3::Y) > 0.99, "normal {n}");
    let push = contact.force_n_per_m.dot(n) / n.length_squared();
    let dv = n * (H_SECS * push / (RHO_S + H_SECS * contact.gain * n.length_squared()));
    let (d, _) = field.sample(p).expect("inside the grid");
    ((v + dv).dot(n.normalize()), n, d)
}

/// The step of [`free_point_after_one_step`], seconds: 60 Hz.
const H_SECS: f64 = 1.0 / 60.0;
/// Its mass per unit length, kg/m (a 35 µm hair's order).
const RHO_S: f64 = 1.3e-4;

#[test]
fn a_point_the_head_meets_at_speed_is_stopped_not_thrown_back() {
    // A rigid surface gives a point at most its own approach speed back
    // (restitution at most 1); the critically damped contact gives less.
    // Slow points are under the cap (a_max = 300 m/s² gives 5 m/s in one
    // step at 60 Hz); from about 0.6 m/s on the predicted push is capped,
    // and the old law, the cap as a constant force with no term in the
    // step matrix, threw a point meeting the head at 1 m/s back at 4 m/s.
    let (field, _) = sphere_field();
    for approach_m_per_s in [0.05, 0.2, 0.6, 1.0, 2.0, 5.0, 20.0] {
        let (v_end, _, _) = free_point_after_one_step(&field, approach_m_per_s);
        assert!(
            v_end <= 0.5 * approach_m_per_s && v_end >= -approach_m_per_s,
            "met at {approach_m_per_s} m/s, left at {v_end} m/s"
        );
    }
    // At 1 m/s by hand (α = 4, the point d ≈ 1 mm into its 2 mm skin, a
    // its approach along n): per ρS the predicted push is
    // 4(skin − d − h a)/h² − 4a/h (about 494 m/s²), capped to 300, and the
    // gain h k + c = 8/h = 480 /s scaled by 300 / push, so the point keeps
    // approaching at about 0.15 m/s (the old law: 4 m/s back out).
    let (v_end, n, d) = free_point_after_one_step(&field, 1.0);
    let h = H_SECS;
    let a = -n.y;
    let push = 4.0 * (0.002 - d - h * a) / (h * h) - 4.0 * a / h;
    assert!(push > 300.0, "{push}: capped at 1 m/s");
    let gain = 8.0 / h * 300.0 / push;
    let by_hand =
        -n.y / n.length() + h * 300.0 * n.length() / (1.0 + h * gain * n.length_squared());
    assert!(
        (v_end - by_hand).abs() < 1e-12 && (v_end + 0.15).abs() < 0.01,
        "{v_end} m/s, by hand {by_hand}"
    );
}

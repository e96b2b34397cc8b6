//! The batch contact's lane screen (`batch::lane_screen`) may only skip
//! points the exact test (`SkinTest::may_feel`) rejects: a skipped point
//! that would have felt the head would change the physics. Checked on a
//! moving, turned head against the exact test at random points near and
//! far, at the grid's edges, with huge and non-finite values, and on both
//! the implicit and the explicit contact.

use crate::common;

use common::Rng;
use common::sphere::{RADIUS_M, sphere_field};
use glam::DVec3;
use helixhair_physics::RigidMotion;
use helixhair_physics::batch::contact::lane_screen::LaneScreen;
use helixhair_physics::batch::contact::{NearCells, SkinTest};
use helixhair_physics::batch::lanes::{LANES, Lanes, Real};
use helixhair_physics::batch::vec::V3;
use helixhair_physics::collision::{ContactInputs, ContactSettings};

fn lanes(points: &[DVec3; LANES]) -> V3<Lanes> {
    V3::new(
        Lanes::from_fn(|i| points[i].x as f32),
        Lanes::from_fn(|i| points[i].y as f32),
        Lanes::from_fn(|i| points[i].z as f32),
    )
}

/// A point relative to its root: mostly around the head, some far, some
/// absurd.
fn point(rng: &mut Rng, root: DVec3, head: &RigidMotion) -> DVec3 {
    let pick = rng.next();
    let near_surface = |rng: &mut Rng| {
        let dir = rng.vec3(1.0).normalize_or(DVec3::X);
        head.position_m + dir * (RADIUS_M + 0.03 * (rng.next() - 0.3)) - root
    };
    match pick {
        p if p < 0.7 => near_surface(rng),
        p if p < 0.85 => rng.vec3(0.5),
        p if p < 0.9 => rng.vec3(1e4),
        p if p < 0.93 => DVec3::splat(f64::NAN),
        p if p < 0.96 => DVec3::new(f64::INFINITY, 0.0, f64::NEG_INFINITY),
        _ => rng.vec3(1e37),
    }
}

/// A head somewhere near the origin, turned, moving and turning at random.
fn moving_head(rng: &mut Rng) -> RigidMotion {
    RigidMotion {
        position_m: rng.vec3(0.3),
        world_from_body: rng.rotation(),
        velocity_m_per_s: rng.vec3(2.0),
        angular_velocity_rad_per_s: rng.vec3(6.0),
        ..RigidMotion::default()
    }
}

#[test]
fn the_lane_screen_never_skips_a_point_the_exact_test_keeps() {
    let (field, _) = sphere_field();
    let settings = ContactSettings::default();
    let near = NearCells::new(&field);
    let mut rng = Rng::new(41);
    let (mut kept, mut skipped, mut exact_kept) = (0usize, 0usize, 0usize);
    for trial in 0..400 {
        let head = moving_head(&mut rng);
        let inputs = ContactInputs {
            collider: &field,
            head: &head,
            settings,
            h_secs: 1.0 / 60.0,
        };
        let test = SkinTest::new(inputs, &near);
        let roots: [DVec3; LANES] = std::array::from_fn(|_| {
            let dir = rng.vec3(1.0).normalize_or(DVec3::Y);
            head.position_m + dir * RADIUS_M
        });
        let screen = LaneScreen::new(&test, &roots);
        for _ in 0..50 {
            let points: [DVec3; LANES] = std::array::from_fn(|i| point(&mut rng, roots[i], &head));
            let velocities: [DVec3; LANES] = std::array::from_fn(|_| match rng.next() {
                x if x < 0.9 => rng.vec3(3.0),
                x if x < 0.95 => rng.vec3(1e30),
                _ => DVec3::new(f64::NAN, 1.0, 0.0),
            });
            let (p, v) = (lanes(&points), lanes(&velocities));
            for implicit in [true, false] {
                let mask = screen.may_feel(&near, p, v, implicit);
                for (lane, root) in roots.iter().enumerate() {
                    // The exact test sees the f32 point, widened, as the
                    // step does.
                    let f32_point = DVec3::new(
                        f64::from(p.x.lane(lane)),
                        f64::from(p.y.lane(lane)),
                        f64::from(p.z.lane(lane)),
                    );
                    let f32_velocity = DVec3::new(
                        f64::from(v.x.lane(lane)),
                        f64::from(v.y.lane(lane)),
                        f64::from(v.z.lane(lane)),
                    );
                    let exact = test.may_feel(*root + f32_point, f32_velocity, implicit);
                    let screened = mask & (1 << lane) != 0;
                    assert!(
                        screened || !exact,
                        "trial {trial}: lane {lane} skipped a point the exact test keeps \
                         (point {f32_point}, velocity {f32_velocity}, implicit {implicit})"
                    );
                    exact_kept += usize::from(exact);
                    kept += usize::from(screened);
                    skipped += usize::from(!screened);
                }
            }
        }
    }
    println!("screen kept {kept}, skipped {skipped}; exact kept {exact_kept}");
    // Not a vacuous pass: the exact test keeps many of these points (most
    // are within 3 cm of the surface), and the screen skips most of those
    // it rejects (a point it cannot skip is within a cell of a near cell).
    let exact_rejected = kept + skipped - exact_kept;
    assert!(exact_kept > 10_000, "exact kept {exact_kept}");
    assert!(
        skipped > exact_rejected / 2,
        "skipped {skipped} of the {exact_rejected} the exact test rejects"
    );
}

#[test]
fn the_exact_test_keeps_every_point_the_contact_law_pushes() {
    // The exact test is the contact law's own screen: a point it rejects
    // must get no force from `ContactInputs::implicit_force` (nor from
    // `force`), also one moving fast across the curved surface, whose
    // predicted distance d + h v·n is nearer than the distance of where it
    // is headed (a convex surface puts p + h v further out).
    let (field, _) = sphere_field();
    let near = NearCells::new(&field);
    let mut rng = Rng::new(97);
    let (mut pushed, mut rejected) = (0usize, 0usize);
    for _ in 0..200 {
        let head = moving_head(&mut rng);
        let settings = ContactSettings {
            skin_m: 0.02 * rng.next(),
            ..ContactSettings::default()
        };
        let inputs = ContactInputs {
            collider: &field,
            head: &head,
            settings,
            h_secs: 1.0 / 60.0,
        };
        let test = SkinTest::new(inputs, &near);
        for _ in 0..250 {
            let dir = rng.vec3(1.0).normalize_or(DVec3::X);
            let p = head.position_m + dir * (RADIUS_M + 0.1 * rng.next());
            let v = rng.vec3(8.0);
            let rho_s = 1e-5;
            if inputs.implicit_force(p, v, rho_s).is_some() {
                pushed += 1;
                assert!(
                    test.may_feel(p, v, true),
                    "implicit push at {p} moving {v} rejected"
                );
            } else if !test.may_feel(p, v, true) {
                rejected += 1;
            }
            if inputs.force(p, v, rho_s) != DVec3::ZERO {
                assert!(test.may_feel(p, v, false), "push at {p} rejected");
            }
        }
    }
    println!("law pushed {pushed}; the test rejected {rejected} others");
    assert!(pushed > 5_000, "pushed {pushed}");
    assert!(rejected > 10_000, "rejected {rejected}");
}

//! The stable step (velocity-implicit step, implicit contact, a guard that
//! measures): one test per symptom the step had, each opening with what
//! went wrong.

use crate::common;

use std::sync::Arc;

use common::shake_scene::{ShakeThenStill, head_roots, ordinary_shake, straight_30_cm};
use common::sphere::{RADIUS_M, sphere_field};
use common::*;
use glam::DVec3;
use helixhair_physics::batch::BatchSystem;
use helixhair_physics::motion::HeadTrajectory;
use helixhair_physics::{
    Bounce, HairSystem, Method, NaturalShape, RigidMotion, RootPose, SimSettings, StepScheme,
    StrandParams,
};

fn system(settings: SimSettings, params: &StrandParams, roots: &[RootPose]) -> HairSystem {
    let mut system = HairSystem::new(settings).expect("valid settings");
    system.add_group(params, roots).expect("valid params");
    system
}

#[test]
fn a_straight_30_cm_strand_survives_an_ordinary_shake_at_60_hz_and_then_settles() {
    // It blew up: non-finite after 1.3 s at 1/60 s with Exact, because the
    // centrifugal and Coriolis terms were explicit in the step; the example
    // styles hid it with 4 substeps.
    let head = ShakeThenStill::ordinary();
    for method in [Method::Exact, Method::Dense] {
        let settings = SimSettings {
            method,
            substeps: 1,
            ..SimSettings::default()
        };
        let mut hair = system(settings, &straight_30_cm(), &head_roots());
        let mut energies = Vec::new();
        for _ in 0..(6 * 60) {
            hair.step_frame(&head);
            assert!(hair.is_finite(), "{method:?} went non-finite");
            assert!(
                hair.last_guard_events().is_empty(),
                "{method:?}: {}",
                hair.last_guard_events()[0]
            );
            if hair.time_secs() > head.shake_secs + 1e-9 {
                energies.push(hair.energies().total_j());
            }
        }
        // Still head: the energy never grows (round-off of the sum aside).
        for pair in energies.windows(2) {
            assert!(
                pair[1] <= pair[0] + 1e-12 * pair[0].abs(),
                "{method:?}: energy grew from {} to {} J",
                pair[0],
                pair[1]
            );
        }
    }
}

#[test]
fn the_velocity_explicit_step_blows_up_on_the_same_shake() {
    // The control for the test above: what the velocity terms cure.
    let shake = ordinary_shake();
    let settings = SimSettings {
        method: Method::Exact,
        scheme: StepScheme::VelocityExplicit,
        ..SimSettings::default()
    };
    let mut hair = system(settings, &straight_30_cm(), &head_roots());
    hair.set_guard(None);
    let blew_up = (0..120).any(|_| {
        hair.step_frame(&shake);
        !hair.is_finite()
    });
    assert!(blew_up, "the explicit step should blow up within 2 s");
}

#[test]
fn long_curly_strands_run_with_no_guard_event() {
    // The default window style with its length dragged to 0.66 m (curly,
    // 15 elements, Exact, still head) had the guard reset strands 90–109
    // times in 2 s: its speed bound read 50 m/s where the fastest point
    // moved at 1 m/s. The guard now measures true speeds and energy.
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
    for substeps in [1, 2] {
        let settings = SimSettings {
            method: Method::Exact,
            substeps,
            ..SimSettings::default()
        };
        let mut hair = system(settings, &params, &outward_roots(16));
        let still = RigidMotion::default();
        for _ in 0..120 {
            hair.step_frame(&still);
            assert!(
                hair.last_guard_events().is_empty(),
                "{substeps} substeps: {}",
                hair.last_guard_events()[0]
            );
        }
        assert!(hair.is_finite());
    }
}

/// Kinetic energy below which a strand counts as at rest, joules.
const AT_REST_J: f64 = 1e-12;

#[test]
fn a_short_strand_released_horizontally_comes_to_rest_or_is_reported() {
    // Block-diagonal was said to keep such a strand whipping for ever with
    // a still head, unseen by a guard that bounded speed. With every solver,
    // on both engines, it now comes to rest, or the guard reports the
    // energy it gained.
    let params = params(0.1, 10);
    let still = RigidMotion::default();
    let root = horizontal_root();
    for method in Method::ALL {
        let settings = SimSettings {
            method,
            ..SimSettings::default()
        };
        let mut hair = system(settings, &params, &[root]);
        let mut events = 0;
        for _ in 0..(15 * 60) {
            hair.step_frame(&still);
            events += hair.last_guard_events().len();
        }
        let kinetic = hair.energies().kinetic_j;
        println!("reference {method:?}: T = {kinetic:.2e} J, {events} guard events");
        assert!(
            kinetic < AT_REST_J || events > 0,
            "{method:?}: T = {kinetic} J"
        );
    }
    for method in [Method::Exact, Method::BlockDiagonal] {
        let settings = SimSettings {
            method,
            ..SimSettings::default()
        };
        let mut batch = BatchSystem::new(settings).expect("valid settings");
        batch.add_group(&params, &[root]).expect("valid params");
        let mut events = 0;
        for _ in 0..(15 * 60) {
            batch.step_frame(&still);
            events += batch.last_guard_resets().len() + batch.last_guard_pins().len();
        }
        let m = model(&params, SimSettings::default().quadrature_points);
        let kin = kinematics(&m, &batch.q(0), &batch.v(0), &still.carry(&root));
        let kinetic =
            helixhair_physics::energy::energies(&m, &batch.q(0), &kin, DVec3::ZERO, DVec3::ZERO)
                .kinetic_j;
        println!("batch {method:?}: T = {kinetic:.2e} J, {events} guard events");
        assert!(
            kinetic < AT_REST_J || events > 0,
            "batch {method:?}: T = {kinetic} J"
        );
    }
}

/// Roots on the top of the sphere head, growing sideways so the strands
/// lie over it.
fn roots_on_top() -> Vec<RootPose> {
    (0..6)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 6.0;
            let out = DVec3::new(a.cos(), 0.0, a.sin());
            let position = DVec3::new(0.3 * out.x, 1.0, 0.3 * out.z).normalize() * RADIUS_M;
            RootPose::from_direction(position, out + DVec3::Y * 0.2, DVec3::Y)
        })
        .collect()
}

/// Lowest analytic signed distance to the sphere (centred on the head's
/// position) of boundary points 2.. of every strand.
fn lowest_above_sphere(hair: &HairSystem, centre: DVec3) -> f64 {
    (0..hair.strands().len())
        .flat_map(|i| hair.boundary_points_world(i).into_iter().skip(2))
        .map(|p| (p - centre).length() - RADIUS_M)
        .fold(f64::INFINITY, f64::min)
}

/// How deep resting or bounced hair may go below the sphere, metres: the
/// icosphere's facets lie up to `sag` inside the sphere, and the field's
/// trilinear samples are a grid cell (4 mm) apart, so half a millimetre
/// of analytic penetration is the collider's own resolution.
const SKULL_TOL_M: f64 = 5e-4;

/// How deep hair under a bouncing head may go below the sphere, metres:
/// 1.5 mm (measured 1.1 mm; the explicit penalty let it sink about 5 mm,
/// and capping the implicit push without taking its term out of the step
/// matrix let it sink 8 mm).
const BOUNCED_TOL_M: f64 = 1.5e-3;

#[test]
fn hair_resting_on_the_head_stays_out_of_the_skull_and_never_trips_the_guard() {
    // The explicit penalty let resting hair sit in a skin g h²/α deep
    // (11 mm at 60 Hz) and a bouncing head push hair about 5 mm into the
    // skull. Implicit contact is 16 times stiffer, and the guard must not
    // mistake landing on the head for a blow-up (its first energy test
    // did, at every contact stiffness), resting or bounced.
    let (field, sag) = sphere_field();
    let field = Arc::new(field);
    let params = params(0.2, 10);
    let settings = SimSettings::default();
    let mut hair = system(settings.clone(), &params, &roots_on_top());
    hair.set_collider(Some(field.clone()));
    let still = RigidMotion::default();
    // Hair slides over the frictionless sphere for a few seconds first.
    for _ in 0..(10 * 60) {
        hair.step_frame(&still);
        if let Some(e) = hair.last_guard_events().first() {
            panic!("the guard stepped in on hair settling on the head: {e}");
        }
    }
    let lowest = lowest_above_sphere(&hair, DVec3::ZERO);
    assert_eq!(
        hair.guard_event_count(),
        0,
        "the guard stepped in on resting hair"
    );
    // Motion at rest: the largest step of any boundary point over a
    // second, and the largest second difference |p(k+1) − 2p(k) + p(k−1)|
    // (zero for steady creep, the size of a flicker in the skin).
    let mut frames: Vec<Vec<DVec3>> = Vec::new();
    for _ in 0..60 {
        hair.step_frame(&still);
        frames.push((0..6).flat_map(|i| hair.boundary_points_world(i)).collect());
    }
    let mut jitter: f64 = 0.0;
    let mut creep: f64 = 0.0;
    for w in frames.windows(3) {
        for ((a, b), c) in w[0].iter().zip(&w[1]).zip(&w[2]) {
            jitter = jitter.max((*c - *b * 2.0 + *a).length());
            creep = creep.max((*c - *b).length());
        }
    }
    println!(
        "resting: lowest {lowest:.2e} m above the sphere; per frame: moved up to {creep:.2e} m, \
         second difference up to {jitter:.2e} m (facet sag {sag:.2e} m)"
    );
    // Not asserted, reported: with no friction model, strands creep round
    // the sphere (measured 3.6e-4 m a frame after 10 s, second differences
    // up to 6.0e-5 m); friction between hair and scalp is future work.
    assert!(
        lowest > -SKULL_TOL_M,
        "resting hair is {lowest} m inside the skull"
    );
    assert_eq!(hair.guard_event_count(), 0);

    // A bouncing head (a walk): 1.5 cm at 2 Hz.
    let bounce = Bounce {
        direction: DVec3::Y,
        amplitude_m: 0.015,
        frequency_hz: 2.0,
    };
    let mut hair = system(settings, &params, &roots_on_top());
    hair.set_collider(Some(field));
    let mut lowest = f64::INFINITY;
    for _ in 0..(3 * 60) {
        hair.step_frame(&bounce);
        let centre = bounce.motion_at(hair.time_secs()).position_m;
        lowest = lowest.min(lowest_above_sphere(&hair, centre));
    }
    println!(
        "bouncing: lowest {lowest:.2e} m above the sphere, {} guard events",
        hair.guard_event_count()
    );
    assert!(
        lowest > -BOUNCED_TOL_M,
        "bounced hair went {lowest} m into the skull"
    );
    assert_eq!(hair.guard_event_count(), 0);
    assert!(hair.is_finite());
}

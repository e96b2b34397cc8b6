//! Tests of growing roots on the scalp and of the drawn hair.

use std::path::Path;

use glam::{DVec3, Vec3};
use helixhair_render::head_generate::default_head;
use helixhair_render::head_shell::HeadShell;

use crate::hair::drawn::{drape_over, drawn_hair_full, root_width_m};
use crate::hair::layout::DEFAULT_DRAWN_STRANDS;
use crate::head::coil::{CoilLeadIn, coil_along};
use crate::head::groom::{Groom, combed_direction, grow_scalp_roots, root_strains, scalp_roots};
use crate::sim::build::SimOverrides;
use crate::sim::headless::HeadlessSim;
use crate::style::Style;

const STYLE: &str = r#"(
    version: 1,
    name: "t",
    groups: [
        (name: "top", scalp: (count: 30, comb: (0.0, 0.0, -1.0), lift_deg: 20.0, region: (towards: (0.0, 1.0, 0.0), to_deg: 45.0)),
         render: (count: 200)),
        (name: "one", roots: [(position_m: (0.0, 0.0, -0.1), direction: (0.0, 0.0, -1.0))], render: (count: 10)),
        (name: "bare", roots: [(position_m: (0.1, 0.0, 0.0), direction: (1.0, 0.0, 0.0))]),
    ],
)"#;

fn style() -> Style {
    Style::from_ron(STYLE, Path::new("t.ron")).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_combed_root_leans_along_the_comb_at_its_lift() {
    let d = combed_direction(DVec3::Y, DVec3::new(0.0, -5.0, -2.0), 30.0);
    assert!((d.length() - 1.0).abs() < 1e-12);
    assert!(
        (d.dot(DVec3::Y) - 0.5).abs() < 1e-12,
        "30° off the surface: {d}"
    );
    assert!(d.z < 0.0 && d.x.abs() < 1e-12, "towards the comb: {d}");
    // A comb along the normal still gives a direction at the lift angle.
    let d = combed_direction(DVec3::Y, DVec3::Y, 30.0);
    assert!((d.dot(DVec3::Y) - 0.5).abs() < 1e-12, "{d}");
}

/// The centreline of a strand with uniform strains `k` rooted at the
/// origin with `direction` and `reference`, at arc length `s_m`: one
/// helix, in closed form (`helixhair_physics::geometry::helix`).
fn helix_point(direction: DVec3, reference: DVec3, k: DVec3, s_m: f64) -> DVec3 {
    let frame = helixhair_physics::RootPose::from_direction(DVec3::ZERO, direction, reference);
    frame.head_from_root * helixhair_physics::geometry::helix::centreline_and_jacobian(s_m, k).0
}

#[test]
fn a_coil_grown_along_its_growth_advances_along_it_and_stays_off_the_scalp() {
    use helixhair_physics::natural_shape::helix_strains;
    // The groomed coily (5 mm, 8 mm per turn) and curly (12 mm, 30 mm)
    // examples' helices, and a wave (25 mm, 120 mm), at steep and shallow
    // lifts, on a scalp whose normal is +y, combed back.
    for (radius_m, step_m) in [(0.005, 0.008), (0.012, 0.03), (0.025, 0.12)] {
        let k = helix_strains(radius_m, step_m);
        let turn_m = std::f64::consts::TAU / k.length();
        for lift_deg in [88.0, 50.0, 5.0] {
            let growth = combed_direction(DVec3::Y, DVec3::NEG_Z, lift_deg);
            let (direction, reference) =
                coil_along(growth, DVec3::Y, k).expect("a helix has an axis");
            let case = format!("r {radius_m} m, step {step_m} m, lift {lift_deg}°");
            // Known answers of a helix: after whole turns the centreline has
            // moved along its axis by whole steps, and the tangent makes the
            // pitch angle with the axis, cos α = τ/|k|.
            for turns in [1.0, 3.0] {
                let moved = helix_point(direction, reference, k, turns * turn_m);
                let expected = growth * turns * step_m;
                assert!(
                    moved.distance(expected) < 1e-9,
                    "{case}: after {turns} turns at {moved}, not {expected}"
                );
            }
            assert!(
                (direction.dot(growth) - k.x / k.length()).abs() < 1e-12,
                "{case}"
            );
            // No point of the first three turns below the root's tangent
            // plane: the loops stand off the scalp.
            let lowest = (0..=600)
                .map(|i| helix_point(direction, reference, k, 3.0 * turn_m * i as f64 / 600.0).y)
                .fold(f64::INFINITY, f64::min);
            assert!(
                lowest > -1e-12,
                "{case}: a loop dips {lowest} m below the root"
            );
        }
    }
    // Straight or untwisted hair has no axis to follow.
    assert_eq!(coil_along(DVec3::Y, DVec3::Y, DVec3::ZERO), None);
    assert_eq!(
        coil_along(DVec3::Y, DVec3::Y, DVec3::new(0.0, 50.0, 0.0)),
        None
    );
}

#[test]
fn a_coil_with_its_lead_in_leaves_the_root_along_its_growth_then_coils_along_it() {
    use helixhair_physics::geometry::helix::{centreline_and_jacobian, rotation};
    use helixhair_physics::natural_shape::helix_strains;
    // The groomed coily and curly examples' helices and elements.
    for (radius_m, step_m, element_m) in [(0.005, 0.008, 0.25 / 30.0), (0.012, 0.03, 0.25 / 15.0)] {
        let k = helix_strains(radius_m, step_m);
        let lead_in = CoilLeadIn::new(k, element_m).expect("a helix has an axis");
        // A bend: no twist, and it turns the frame by the pitch angle.
        assert_eq!(lead_in.strains_per_m.x, 0.0);
        let pitch_angle = (k.x / k.length()).acos();
        assert!((lead_in.strains_per_m.length() * element_m - pitch_angle).abs() < 1e-12);
        let turn_m = std::f64::consts::TAU / k.length();
        for lift_deg in [88.0, 50.0, 5.0] {
            let growth = combed_direction(DVec3::Y, DVec3::NEG_Z, lift_deg);
            let case = format!("r {radius_m} m, step {step_m} m, lift {lift_deg}°");
            let (direction, reference) = lead_in.root_frame(growth, DVec3::Y).expect("a frame");
            assert!(
                direction.distance(growth) < 1e-12,
                "{case}: leaves along {direction}"
            );
            // The strand through its first element (closed form), then the
            // helix from that element's end frame.
            let root =
                helixhair_physics::RootPose::from_direction(DVec3::ZERO, direction, reference);
            let bend = lead_in.strains_per_m;
            let start = root.head_from_root * centreline_and_jacobian(element_m, bend).0;
            let frame = root.head_from_root * rotation(bend * element_m);
            let point = |s_m: f64| start + frame * centreline_and_jacobian(s_m, k).0;
            for turns in [1.0, 3.0] {
                let moved = point(turns * turn_m) - start;
                let expected = growth * turns * step_m;
                assert!(
                    moved.distance(expected) < 1e-9,
                    "{case}: {moved}, not {expected}"
                );
            }
            // Off the root's tangent plane from the lead-in's end on.
            let lowest = (0..=600)
                .map(|i| point(3.0 * turn_m * i as f64 / 600.0).y)
                .fold(f64::INFINITY, f64::min);
            assert!(lowest > 0.0, "{case}: a loop at {lowest} m");
        }
    }
    // The grown style carries the bend as its first element's strains.
    let style = Style::from_ron(
        r#"(version: 1, name: "c", groups: [(name: "g",
            params: (elements: 10, natural_shape: Helix(radius_m: 0.005, step_m: 0.008)),
            scalp: (count: 5, lift_deg: 80.0, curl_axis: Growth))])"#,
        Path::new("c.ron"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let lead_in = CoilLeadIn::for_group(&style.groups[0]).expect("a coil grown along its growth");
    let grown = grow_scalp_roots(&style, &default_head());
    let strains = grown.groups[0].params.natural_shape.strains(10);
    assert_eq!(strains[0], lead_in.strains_per_m);
    assert!(
        strains[1..]
            .iter()
            .all(|s| *s == lead_in.helix_strains_per_m)
    );
}

#[test]
fn scalp_roots_lie_in_their_region_and_grow_outwards() {
    let head = default_head();
    let style = style();
    let placement = style.groups[0].scalp.as_ref().expect("scalp");
    let roots = scalp_roots(placement, &head, root_strains(&style.groups[0]), None);
    assert_eq!(roots.len(), 30);
    for root in &roots {
        assert!(
            root.position_m.angle_between(DVec3::Y).to_degrees() < 47.0,
            "{}",
            root.position_m
        );
        let out = -root.direction.dot(root.reference);
        assert!((out - 20f64.to_radians().sin()).abs() < 1e-6, "lift: {out}");
        assert!(root.direction.z < 0.05, "combed back: {}", root.direction);
    }
    let grown = grow_scalp_roots(&style, &head);
    let counts: Vec<usize> = grown.groups.iter().map(|g| g.roots.len()).collect();
    assert_eq!(counts, [30, 1, 1]);
    assert!(grown.groups.iter().all(|g| g.scalp.is_none()));
    // The headless simulation grows them on the default head itself.
    let sim = HeadlessSim::new(&style, SimOverrides::default()).expect("builds");
    assert_eq!(sim.engine().strand_count(), 32);
}

#[test]
fn drawn_hair_has_the_styled_counts_and_stays_outside_the_head() {
    let groom = Groom::new(style(), default_head());
    let shell = &groom.shell;
    // Without a collider the guides fall through the head; the drawn
    // strands still drape over it.
    let mut sim = HeadlessSim::new(&groom.grown, SimOverrides::default()).expect("builds");
    sim.run(30).expect("finite");
    let hair = drawn_hair_full(&groom, sim.engine());
    // 200 and 10 as styled; the group without `render` gets the default.
    let want = 200 + 10 + DEFAULT_DRAWN_STRANDS;
    assert_eq!(hair.strands.strand_count(), want);
    assert_eq!(hair.colours.len(), want);
    assert!(hair.root_width_m >= root_width_m(100_000));
    for strand in hair.strands.iter() {
        for &p in &strand[1..] {
            let d = p - shell.centre_m();
            assert!(
                d.length() >= shell.radius_m(d.normalize()) + 1e-3,
                "{p} inside the head"
            );
        }
    }
}

#[test]
fn draping_keeps_outside_points_where_they_are() {
    let shell = HeadShell::new(&default_head().mesh);
    let line: Vec<Vec3> = (0..5)
        .map(|k| Vec3::new(0.5, 0.0, 0.1 * k as f32))
        .collect();
    let mut draped = line.clone();
    drape_over(&mut draped, &shell);
    assert_eq!(draped, line);
}

#[test]
fn simulated_guides_rest_on_the_head_through_its_collider() {
    let groom = Groom::new(style(), default_head());
    let collider = std::sync::Arc::new(groom.collider().expect("the default head is closed"));
    let inside = collider.sample(DVec3::ZERO).map(|(d, _)| d);
    assert!(
        inside.is_some_and(|d| d < 0.0),
        "the head's centre is inside: {inside:?}"
    );
    let mut sim = HeadlessSim::new(&groom.grown, SimOverrides::default()).expect("builds");
    sim.engine_mut().set_collider(Some(collider.clone()));
    sim.run(60).expect("stays finite");
    // Hair falling onto the head stops at its surface, within the contact
    // penalty's give: about g h² / α = 11 mm at rest for one 1/60 s step
    // (ContactSettings), more while a falling strand is caught; without the
    // collider strands fall right through (tens of centimetres).
    let deepest = (0..sim.engine().strand_count())
        .flat_map(|i| sim.engine().boundary_points_world(i))
        .filter_map(|p| collider.sample(p).map(|(d, _)| d))
        .fold(f64::MAX, f64::min);
    assert!(
        deepest > -0.03,
        "a guide point is {deepest} m inside the head"
    );
}

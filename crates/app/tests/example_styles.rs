//! The example styles in `assets/styles/` load and are what their comments
//! say: a few groups, 20 to 60 strands, roots on a 0.1 m scalp sphere
//! growing along its outward normal, hair parameters in the measured ranges
//! of `docs/physics.md`.

use std::path::PathBuf;

use helixhair_app::Style;
use helixhair_physics::NaturalShape;

/// Radius of the scalp sphere the roots sit on, metres.
const SCALP_RADIUS_M: f64 = 0.1;

/// Roots are written with four decimals: 0.1 mm, and 1e-4 on unit vectors.
const WRITTEN_TOL: f64 = 2e-4;

fn styles_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/styles")
}

fn load(name: &str) -> Style {
    Style::load(&styles_dir().join(format!("{name}.ron"))).unwrap_or_else(|e| panic!("{e}"))
}

const NAMES: [&str; 4] = ["straight", "wavy", "curly", "coily"];

#[test]
fn every_example_loads_with_a_sensible_size() {
    for name in NAMES {
        let style = load(name);
        assert_eq!(style.name, name);
        assert!(
            (3..=8).contains(&style.groups.len()),
            "{name}: {} groups",
            style.groups.len()
        );
        let strands = style.strand_count();
        assert!((20..=60).contains(&strands), "{name}: {strands} strands");
    }
}

#[test]
fn roots_sit_on_the_scalp_and_grow_outwards() {
    for name in NAMES {
        for group in load(name).groups {
            for root in &group.roots {
                let r = root.position_m.length();
                assert!(
                    (r - SCALP_RADIUS_M).abs() < WRITTEN_TOL,
                    "{name}/{}: |p| = {r}",
                    group.name
                );
                let normal = root.position_m / r;
                let direction = root.direction.normalize();
                assert!(
                    (direction - normal).length() < 2.0 * WRITTEN_TOL / SCALP_RADIUS_M,
                    "{name}/{}",
                    group.name
                );
                assert!(
                    root.position_m.y > 0.0,
                    "{name}/{}: above the equator",
                    group.name
                );
            }
        }
    }
}

/// Curl radius and curvature of a group's natural shape (∞ and 0 when
/// straight).
fn curl(shape: &NaturalShape) -> (f64, f64) {
    match shape {
        NaturalShape::Straight => (f64::INFINITY, 0.0),
        NaturalShape::Helix { radius_m, step_m } => {
            let c = step_m / std::f64::consts::TAU;
            (*radius_m, radius_m / (radius_m * radius_m + c * c))
        }
        other => panic!("the examples use Straight or Helix, not {other:?}"),
    }
}

#[test]
fn hair_parameters_lie_in_the_measured_ranges() {
    // docs/physics.md section 3: radius 25-60 µm; natural curvature 20-200 1/m;
    // ellipticity 1 (straight) rising to 1.6 and beyond (coily).
    let mut last_ellipticity = 0.0;
    for name in NAMES {
        let style = load(name);
        let first = &style.groups[0].params;
        assert!(
            first.ellipticity >= last_ellipticity,
            "{name}: ellipticity grows with curl"
        );
        last_ellipticity = first.ellipticity;
        for group in &style.groups {
            let p = &group.params;
            assert!(
                (25e-6..=60e-6).contains(&p.radius_m),
                "{name}/{}",
                group.name
            );
            let (radius, curvature) = curl(&p.natural_shape);
            match name {
                "straight" => assert_eq!(curvature, 0.0),
                _ => assert!(
                    (20.0..=200.0).contains(&curvature),
                    "{name}/{}: κ = {curvature}",
                    group.name
                ),
            }
            if name == "coily" {
                assert!(
                    (0.004..=0.006).contains(&radius),
                    "coily curl radius {radius}"
                );
                assert!(p.ellipticity >= 1.6, "coily ellipticity {}", p.ellipticity);
            }
        }
    }
}

#[test]
fn the_guard_stays_silent_on_every_example_style_under_a_head_shake() {
    // The examples run at the default internal friction now that the guard
    // exists; they must not need it with their own solver and step.
    let shake = helixhair_physics::Oscillation {
        axis: glam::DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    for name in ["straight", "wavy", "curly", "coily"] {
        let style = load(name);
        let mut sim = helixhair_app::HeadlessSim::new(&style, Default::default()).expect("builds");
        let system = sim
            .engine_mut()
            .reference_mut()
            .expect("the examples run on the reference engine");
        for _ in 0..120 {
            system.step_frame(&shake);
        }
        assert!(system.is_finite(), "{name}");
        assert_eq!(
            system.guard_event_count(),
            0,
            "{name}: the guard stepped in"
        );
    }
}

#[test]
fn the_full_head_runs_on_the_batch_engine_and_survives_a_head_shake() {
    // The batch engine has no guard: the full-head example must stay finite
    // under the same shake on its own.
    use helixhair_physics::engine::EngineKind;
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/styles/groomed/full_head.ron");
    let style = Style::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(style.engine, EngineKind::Batch);
    let mut sim = helixhair_app::HeadlessSim::new(&style, Default::default()).expect("builds");
    let engine = sim.engine_mut();
    assert_eq!(engine.kind(), EngineKind::Batch);
    assert!(
        (2000..=5000).contains(&engine.strand_count()),
        "a few thousand strands: {}",
        engine.strand_count()
    );
    let shake = helixhair_physics::Oscillation {
        axis: glam::DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    for _ in 0..120 {
        engine.step_frame(&shake);
    }
    assert!(engine.is_finite());
}

//! The two engines behind one interface: they agree on a head shake, carry
//! the same state, and name the solvers each runs.

use glam::DVec3;
use helixhair_physics::{
    Engine, EngineKind, Method, Oscillation, RootPose, SimSettings, StepScheme, StrandParams,
};

fn roots() -> Vec<RootPose> {
    (0..11)
        .map(|i| {
            let a = i as f64 * 0.5;
            let position = DVec3::new(0.1 * a.cos(), 0.05, 0.1 * a.sin());
            RootPose::from_direction(position, position, DVec3::Y)
        })
        .collect()
}

fn engine(kind: EngineKind) -> Engine {
    // The batch engine steps velocity-explicit (docs/gpu.md): the
    // reference runs the same scheme for the comparison.
    let settings = SimSettings {
        scheme: StepScheme::VelocityExplicit,
        ..SimSettings::default()
    };
    let mut engine = Engine::new(kind, settings).expect("valid settings");
    engine
        .add_group(&StrandParams::default(), &roots())
        .expect("valid params");
    engine
}

/// After a second of head shake with Exact, the f32 engine's tips lie
/// within this of the f64 engine's, metres: f32 round-off only,
/// measured at most 1.8e-7 m on these 20 cm strands; 1e-6 m keeps a
/// margin of five without hiding a real difference (a wrong root or
/// element would be centimetres off).
const TIP_TOL_M: f64 = 1e-6;

#[test]
fn both_engines_agree_on_a_head_shake_with_exact() {
    let head = Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    let (mut reference, mut batch) = (engine(EngineKind::Reference), engine(EngineKind::Batch));
    assert_eq!(reference.strand_count(), batch.strand_count());
    assert_eq!(reference.element_count(), batch.element_count());
    for _ in 0..60 {
        reference.step_frame(&head);
        batch.step_frame(&head);
    }
    assert!(reference.is_finite() && batch.is_finite());
    assert!((reference.time_secs() - batch.time_secs()).abs() < 1e-9);
    for i in 0..reference.strand_count() {
        let a = *reference.boundary_points_world(i).last().expect("a tip");
        let b = *batch.boundary_points_world(i).last().expect("a tip");
        assert!((a - b).length() < TIP_TOL_M, "strand {i}: {a} vs {b}");
    }
    // Energies: the batch engine's, rebuilt in f64, match the reference.
    let (e_ref, e_batch) = (reference.energies(), batch.energies());
    let scale = e_ref.gravity_j.abs();
    assert!((e_ref.total_j() - e_batch.total_j()).abs() < 1e-4 * scale);
}

#[test]
fn state_round_trips_through_either_engine() {
    let (mut reference, mut batch) = (engine(EngineKind::Reference), engine(EngineKind::Batch));
    let q: Vec<DVec3> = (0..10).map(|e| DVec3::new(1.0, e as f64, -2.0)).collect();
    let v = vec![DVec3::splat(0.5); 10];
    reference.set_state(3, &q, &v);
    batch.set_state(3, &q, &v);
    assert_eq!(reference.q(3), q);
    assert_eq!(batch.q(3), q, "these values are exact in f32");
    assert_eq!(batch.v(3), v);
    let (a, b) = (
        reference.boundary_points_world(3),
        batch.boundary_points_world(3),
    );
    for (p, r) in a.iter().zip(&b) {
        assert!((*p - *r).length() < 1e-6, "{p} vs {r}");
    }
}

#[test]
fn the_batch_engine_refuses_other_solvers() {
    for method in Method::ALL {
        let settings = SimSettings {
            method,
            ..SimSettings::default()
        };
        let result = Engine::new(EngineKind::Batch, settings);
        assert_eq!(result.is_ok(), EngineKind::Batch.runs(method), "{method:?}");
        if let Err(e) = result {
            assert_eq!(e.field, "method");
        }
    }
    assert!(
        Method::ALL
            .into_iter()
            .all(|m| EngineKind::Reference.runs(m))
    );
}

#[test]
fn engine_names_round_trip() {
    for kind in EngineKind::ALL {
        assert_eq!(EngineKind::from_name(kind.label()), Some(kind));
    }
    assert_eq!(EngineKind::from_name("Batch"), None);
}

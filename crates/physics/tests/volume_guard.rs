//! No false alarms from the hair–hair model: the guard's energy balance
//! counts the model's force as the step applies it, on both engines, up to
//! the style's limits.
//!
//! Two things read as energy from nowhere before (`docs/volume.md`,
//! "The guard and the model"): the balance took the frozen grid velocity as
//! a world velocity while the step pulls toward it relative to the head
//! (`volume::friction`), and it summed the external forces' work by the
//! trapezoid rule where the velocity-implicit step does h F₁·ṙ₁
//! (`frame_balance`, "The external forces' rule"). Measured on this scene
//! (the small head, 48 curls, shaken for 4 s) before the fix: friction
//! 200/s flagged 44 strand-frames in the first 120; pressure 10 m²/s², 7.

use crate::common;

use common::shake;
use common::volume_scene::small_head;
use helixhair_physics::engine::{Engine, EngineKind};
use helixhair_physics::guard::GuardEvent;
use helixhair_physics::volume::InteractionSettings;
use helixhair_physics::{Method, SimSettings};

/// The guard's events over 4 s of shake (240 frames) of the small head
/// with the model's friction `mu` (1/s) and pressure `p` (m²/s²).
fn events_under_a_shake(kind: EngineKind, mu: f64, p: f64, substeps: u32) -> Vec<GuardEvent> {
    let (params, roots) = small_head(12, 4);
    let settings = SimSettings {
        method: Method::Exact,
        substeps,
        interaction: InteractionSettings {
            enabled: true,
            friction_per_s: mu,
            pressure_m2_per_s2: p,
            ..InteractionSettings::default()
        },
        ..SimSettings::default()
    };
    let mut engine = Engine::new(kind, settings).unwrap();
    engine.add_group(&params, &roots).unwrap();
    let head = shake();
    let mut events = Vec::new();
    for _ in 0..240 {
        engine.step_frame(&head);
        let last = match (engine.reference(), engine.batch()) {
            (Some(reference), _) => reference.last_guard_events(),
            (_, Some(batch)) => batch.last_guard_events(),
            _ => &[],
        };
        events.extend_from_slice(last);
    }
    events
}

/// Each term at the top of its range with the other at its default, and
/// both strong together short of the top: no guard event on either
/// engine, with one substep and with two.
#[test]
fn the_model_at_its_limits_raises_no_guard_events() {
    let limits = [(200.0, 0.2), (5.0, 10.0), (50.0, 3.0), (20.0, 1.0)];
    for substeps in [1, 2] {
        for (mu, p) in limits {
            for kind in [EngineKind::Reference, EngineKind::Batch] {
                let events = events_under_a_shake(kind, mu, p, substeps);
                let first: Vec<String> = events.iter().take(3).map(|e| e.to_string()).collect();
                assert!(
                    events.is_empty(),
                    "{kind:?}, μ = {mu}/s, P = {p} m²/s², {substeps} substeps: {} events: {first:?}",
                    events.len()
                );
            }
        }
    }
}

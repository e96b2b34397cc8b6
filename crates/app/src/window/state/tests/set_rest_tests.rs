//! Tests of [`super::set_rest`] (kept apart to keep the module short).

use glam::DVec3;

use super::super::default_style::default_style;
use super::*;

/// Frames the head turns for before the button is pressed: mid-turn, the
/// hair lags behind the head, so its shape is far from the rest it had
/// (stopped there with its old rest shape, it moves 12 mm).
const POSE_FRAMES: usize = 5;

/// Stiff short hair (radius 60 µm, 10 cm: ρSgL³/EI ≈ 3.6, so poses off
/// the hanging one are stable equilibria once set as rest), caught while
/// its head turns 1.2 rad and the hair swings after it.
fn posed_app() -> AppState {
    let mut style = default_style(6);
    for g in &mut style.groups {
        g.params.radius_m = 6e-5;
        g.params.length_m = 0.1;
        g.params.elements = 8;
    }
    let mut app = AppState::new(style, None).unwrap();
    app.head.target.turn_rad = 1.2;
    app.head.target.offset_m = DVec3::new(0.0, 0.01, 0.0);
    for _ in 0..POSE_FRAMES {
        app.step_frame();
    }
    app
}

/// Largest tip distance from `start` over `frames` frames, metres.
fn drift_from(app: &mut AppState, start: &[DVec3], frames: usize) -> f64 {
    let mut worst: f64 = 0.0;
    for _ in 0..frames {
        app.step_frame();
        for (a, b) in start.iter().zip(app.sim.tips_m()) {
            worst = worst.max((b - *a).length());
        }
    }
    worst
}

/// Frames the hair is watched for after freezing: two seconds at 60 Hz.
const WATCH_FRAMES: usize = 120;

/// How far a frozen tip may move in those frames: 1 mm, the import's own
/// criterion for a groom holding its shape (issue 11).
const HELD_M: f64 = 1e-3;

#[test]
fn after_set_as_rest_the_hair_stays_put_on_a_still_head() {
    let mut app = posed_app();
    let before = app.doc.style().clone();
    // The tips as the user sees them when pressing the button.
    let shown = app.sim.tips_m();
    app.set_current_shape_as_rest();
    let message = app.message.clone().unwrap();
    assert!(
        message.starts_with("current shape set as rest for 6 strands (6 held exactly"),
        "{message}"
    );
    let drift = drift_from(&mut app, &shown, WATCH_FRAMES);
    assert!(drift < HELD_M, "frozen tips moved {drift} m");

    // Without it (the head stopped and the strands stopped the same way,
    // the old rest shape kept) the same hair moves far more: the check
    // above is not of hair that would have stayed anyway.
    let mut control = posed_app();
    let shown = control.sim.tips_m();
    control.head.hold();
    control.sim.stop();
    let sag = drift_from(&mut control, &shown, WATCH_FRAMES);
    assert!(sag > 5.0 * HELD_M, "unfrozen tips moved only {sag} m");

    // One undo step restores the style.
    assert!(app.doc.undo());
    assert_eq!(app.doc.style(), &before);
}

/// Issue #32, item 4: setting the current shape as rest used to turn every
/// group into imported strands, dropping its scalp placement, drawn
/// strands, curl and length controls. It now keeps each strand's shape as
/// an edit and everything else as it was.
#[test]
fn set_as_rest_keeps_the_placement_drawn_strands_and_controls() {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/styles/groomed/wavy.ron");
    let style = Style::load(&path).unwrap();
    assert!(
        style
            .groups
            .iter()
            .any(|g| g.scalp.is_some() && g.render.is_some()),
        "the example has placed, drawn groups"
    );
    let mut app = AppState::new(style.clone(), Some(&path)).unwrap();
    for _ in 0..3 {
        app.step_frame();
    }
    let strands = app.sim.engine().strand_count();
    app.set_current_shape_as_rest();
    let message = app.message.clone().unwrap();
    assert!(
        message.starts_with("current shape set as rest"),
        "{message}"
    );
    let after = app.doc.style().clone();
    let mut edited = 0;
    for (a, b) in after.groups.iter().zip(&style.groups) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.params, b.params, "{}: controls kept", a.name);
        assert_eq!(a.roots, b.roots);
        assert_eq!(a.scalp, b.scalp, "{}: placement kept", a.name);
        assert_eq!(a.render, b.render, "{}: drawn strands kept", a.name);
        assert_eq!(a.imported.is_some(), b.imported.is_some());
        assert!(a.edits.iter().all(|e| e.rest.is_some()));
        edited += a.edits.len();
    }
    assert_eq!(edited, strands, "every simulated strand keeps its shape");
    assert_eq!(app.sim.engine().strand_count(), strands);
    // The saved style reloads to the same style.
    let text = after.to_ron().unwrap();
    assert_eq!(Style::from_ron(&text, &path).unwrap(), after);
}

//! Tests of [`super::app_state`] (kept apart to keep the module short).

use helixhair_physics::NaturalShape;

use super::super::default_style::default_style;
use super::*;

fn app() -> AppState {
    AppState::new(default_style(8), None).unwrap()
}

#[test]
fn a_slider_drag_is_one_undo_step_and_the_title_marks_it() {
    let mut app = app();
    assert!(!app.doc.title().contains('*'));
    for k in 1..=5 {
        app.doc.style_mut().groups[0].params.ellipticity = 1.0 + 0.1 * f64::from(k);
        app.doc.settle(true);
        app.step_frame();
    }
    app.doc.settle(false);
    assert!(app.doc.title().contains('*'), "{}", app.doc.title());
    assert!(app.doc.undo());
    assert_eq!(app.doc.style().groups[0].params.ellipticity, 1.35);
    assert!(!app.doc.title().contains('*'));
    assert!(app.doc.redo());
    assert_eq!(app.doc.style().groups[0].params.ellipticity, 1.5);
}

#[test]
fn an_invalid_edit_is_reported_and_not_simulated() {
    let mut app = app();
    app.step_frame();
    app.doc.style_mut().groups[0].params.radius_m = f64::NAN;
    app.step_frame();
    let error = app.invalid.clone().unwrap();
    assert!(error.contains("radius_m"), "{error}");
    assert!(app.sim.engine().is_finite());
    app.doc.undo();
    app.step_frame();
    assert!(app.invalid.is_none());
}

#[test]
fn a_malformed_file_changes_nothing_and_names_line_and_field() {
    let mut app = app();
    let dir = std::env::temp_dir().join(format!("helixhair-app-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.ron");
    let good = default_style(3).to_ron().unwrap();
    std::fs::write(
        &bad,
        good.replace("ellipticity: 1.35", "ellipticity: \"oval\""),
    )
    .unwrap();
    let before = app.doc.style().clone();
    app.load(&bad);
    let message = app.message.clone().unwrap();
    assert!(message.contains("bad.ron:"), "{message}");
    assert!(message.contains("ellipticity"), "{message}");
    assert_eq!(*app.doc.style(), before);
    // Saving then loading gives the same style back, with a clean title.
    let file = dir.join("mine.ron");
    app.save(Some(&file));
    assert!(
        app.doc.title().starts_with("mine.ron —"),
        "{}",
        app.doc.title()
    );
    app.doc.edit(|s| s.name = "other".into());
    app.load(&file);
    assert_eq!(*app.doc.style(), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn presets_apply_as_one_step_and_the_hair_follows() {
    let mut app = app();
    let coily = app.presets[3].clone();
    app.apply_preset(0, &coily);
    app.step_frame();
    assert_eq!(
        app.sim.engine().strand_model(0).elements(),
        coily.params.elements
    );
    assert!(matches!(
        app.doc.style().groups[0].params.natural_shape,
        NaturalShape::Helix { .. }
    ));
    app.doc.undo();
    assert_ne!(app.doc.style().groups[0].params, coily.params);
}

#[test]
fn a_head_shake_moves_the_hair_and_compare_reads_a_difference() {
    let mut app = app();
    app.set_compare(Some(CompareMethods::default()));
    for _ in 0..30 {
        app.step_frame();
    }
    let still = app.sim.tips_m();
    app.play(Clip::Shake);
    for _ in 0..30 {
        app.step_frame();
    }
    let moved = tip_difference_m(&still, &app.sim.tips_m()).1;
    assert!(moved > 0.01, "tips moved only {moved} m");
    let (rms, _) = app.readouts.last().unwrap().difference_m.unwrap();
    assert!(rms.is_finite() && rms > 0.0, "{rms}");
    assert!(app.readouts.last().unwrap().energies.unwrap().kinetic_j > 0.0);
}

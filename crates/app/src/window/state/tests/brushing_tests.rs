//! Tests of [`super::brushing`]: a stroke made as the window makes it
//! (begun where the pointer meets the hair, dragged frame by frame,
//! released), its undo, its cancel and its recording.

use glam::DVec3;

use super::super::default_style::default_style;
use super::*;
use crate::brush::strokes::StrokeFile;
use crate::brush::strokes::Tool;
use crate::window::state::brush_state::ToolKind;

/// Frames the default hair hangs before styling: two seconds.
const HANG_FRAMES: usize = 120;

/// Frames the comb is dragged over: half a second.
const DRAG_FRAMES: usize = 30;

/// How far forward (+z, the face's side) the comb drags, metres.
const COMB_FORWARD_M: f64 = 0.06;

/// A settled default style, the Comb picked: the app and the strand whose
/// tip lies furthest to +x (the comb's target), with every tip.
fn combing_app() -> (AppState, usize, Vec<DVec3>) {
    let mut app = AppState::new(default_style(16), None).unwrap();
    for _ in 0..HANG_FRAMES {
        app.step_frame();
    }
    app.set_tool(ToolKind::Comb);
    let tips = app.sim.tips_m();
    let side = (0..tips.len())
        .max_by(|&a, &b| tips[a].x.total_cmp(&tips[b].x))
        .unwrap();
    (app, side, tips)
}

/// Drags the brush from `from` by `by` over [`DRAG_FRAMES`] frames.
fn drag(app: &mut AppState, from: DVec3, by: DVec3) {
    assert!(app.begin_stroke(from), "{:?}", app.message);
    for k in 1..=DRAG_FRAMES {
        app.move_brush(from + by * (k as f64 / DRAG_FRAMES as f64));
        app.step_frame();
    }
}

#[test]
fn a_comb_stroke_moves_the_hair_it_passes_keeps_it_there_and_is_one_undo_step() {
    let (mut app, side, hung) = combing_app();
    app.brush.settings.radius_m = 0.03;
    assert_eq!(app.sim.kind(), EngineKind::Reference);
    let before = app.doc.style().clone();
    drag(&mut app, hung[side], DVec3::Z * COMB_FORWARD_M);
    let dragged = app.sim.tips_m()[side].z - hung[side].z;
    app.end_stroke();
    let message = app.message.clone().unwrap();
    assert!(dragged > 0.02, "the comb carried the tip {dragged} m");
    assert!(message.starts_with("Comb: "), "{message}");
    // The combed strand's shape is its rest now: an edit with a rest shape.
    let edits: usize = app.doc.style().groups.iter().map(|g| g.edits.len()).sum();
    assert!(edits >= 1, "{message}");
    assert!(
        app.doc
            .style()
            .groups
            .iter()
            .flat_map(|g| &g.edits)
            .all(|e| e.rest.is_some())
    );
    // Two seconds later it is still where the comb left it (frozen: to
    // within a millimetre); a strand across the head is where it was.
    for _ in 0..HANG_FRAMES {
        app.step_frame();
    }
    let tips = app.sim.tips_m();
    let forward = tips[side].z - hung[side].z;
    assert!(
        (forward - dragged).abs() < 1e-3,
        "{forward} m forward, {dragged} m at release"
    );
    let far = (0..tips.len())
        .min_by(|&a, &b| hung[a].x.total_cmp(&hung[b].x))
        .unwrap();
    let moved = tips[far].distance(hung[far]);
    assert!(moved < 1e-3, "a strand across the head moved {moved} m");
    // One undo step takes the whole stroke back.
    assert!(app.doc.undo());
    assert_eq!(app.doc.style(), &before);
}

#[test]
fn escape_during_a_stroke_restores_its_start() {
    let (mut app, side, hung) = combing_app();
    let before = app.doc.style().clone();
    let shown = app.sim.tips_m();
    drag(&mut app, hung[side], DVec3::Z * COMB_FORWARD_M);
    assert!(app.sim.tips_m()[side].distance(shown[side]) > 0.01);
    app.cancel_stroke();
    assert!(app.brush.active.is_none());
    assert_eq!(app.sim.tips_m(), shown);
    assert_eq!(app.doc.style(), &before);
}

#[test]
fn recorded_strokes_are_written_in_head_coordinates_after_each_stroke() {
    let (mut app, side, hung) = combing_app();
    let dir = std::env::temp_dir().join(format!("helixhair-brush-rec-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("strokes.ron");
    app.brush.record_to(&path);
    drag(&mut app, hung[side], DVec3::Z * COMB_FORWARD_M);
    app.end_stroke();
    let file = StrokeFile::load(&path).expect("the recording reads back");
    assert_eq!(file.strokes.len(), 1);
    let stroke = &file.strokes[0];
    assert_eq!(stroke.tool, Tool::Comb);
    // The default head is still at the origin: head and world agree.
    let start = stroke.path[0];
    let end = *stroke.path.last().unwrap();
    assert!(
        start.distance(hung[side]) < 1e-9,
        "{start} vs {}",
        hung[side]
    );
    assert!((end - start - DVec3::Z * COMB_FORWARD_M).length() < 1e-9);
    assert!((stroke.seconds - DRAG_FRAMES as f64 / 60.0).abs() < 1e-9);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn orbit_puts_the_run_back_on_the_styles_engine() {
    let mut style = default_style(4);
    style.engine = EngineKind::Batch;
    let mut app = AppState::new(style, None).unwrap();
    app.set_tool(ToolKind::Cut);
    assert_eq!(app.sim.kind(), EngineKind::Reference);
    app.set_tool(ToolKind::Orbit);
    assert_eq!(app.sim.kind(), EngineKind::Batch);
}

#[test]
fn a_strand_masked_on_the_scalp_is_kept_from_the_comb_and_the_mask_is_recorded() {
    let (mut app, side, hung) = combing_app();
    let dir = std::env::temp_dir().join(format!("helixhair-brush-mask-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("strokes.ron");
    app.brush.record_to(&path);
    // Mask the side strand at its root (a brush on the scalp).
    let root = app.sim.engine().boundary_points_world(side)[0];
    app.brush.settings.radius_m = 0.01;
    assert!(app.paint_mask(root, false) >= 1);
    // Then comb through its tip: it stays where it hung.
    app.brush.settings.radius_m = 0.03;
    let before = app.doc.style().clone();
    drag(&mut app, hung[side], DVec3::Z * COMB_FORWARD_M);
    app.end_stroke();
    let tip = app.sim.tips_m()[side];
    assert!(
        tip.distance(hung[side]) < 1e-3,
        "the masked tip moved to {tip}"
    );
    let edited: Vec<_> = app.doc.style().groups[0]
        .edits
        .iter()
        .map(|e| e.strand)
        .collect();
    let number = app.sim.strands()[side].strand;
    assert!(!edited.contains(&number), "{edited:?}");
    // It was the only strand the comb reached (as unmasked, in the first
    // test): the style is as it was.
    assert_eq!(app.doc.style(), &before);
    let file = StrokeFile::load(&path).unwrap();
    assert!(
        file.strokes[0]
            .masked
            .iter()
            .any(|m| m.strand as usize == number)
    );
    // Unmasking takes it back out of the mask.
    app.brush.settings.radius_m = 0.01;
    assert!(app.paint_mask(root, true) >= 1);
    assert!(app.brush.masked.is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

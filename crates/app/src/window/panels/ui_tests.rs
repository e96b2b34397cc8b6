//! Tests of the panels ([`super::ui`]), drawn by egui without a window:
//! a frame is `Context::run_ui` with a screen-sized input, and typing is
//! keyboard events fed to it.

use std::path::PathBuf;

use helixhair_physics::{Method, NaturalShape};

use super::super::value_slider::{Look, slider};
use super::*;
use crate::window::state::app_state::AppState;
use crate::window::state::default_style::default_style;

/// A 1280×800 frame's input with `events`.
fn input(events: Vec<egui::Event>) -> egui::RawInput {
    egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(1280.0, 800.0),
        )),
        events,
        ..Default::default()
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("helixhair-ui-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A style with a value beyond every slider's track as it was (length
/// 1.5 m over 1 m, 100 elements over 60, a 0.5 m curl over 20 cm, zero
/// friction and drag under the logarithmic tracks, 500 CG iterations over
/// 50, a 1e-5 s step under 1e-4 s, upward gravity, 50 m/s wind), and
/// gravity beyond today's track too.
fn style_beyond_the_sliders() -> crate::style::Style {
    let mut style = default_style(2);
    style.name = "beyond".into();
    style.sim.method = Method::Iterative { iterations: 500 };
    style.sim.dt_secs = 1e-5;
    style.sim.gravity_m_per_s2.y = 100.0;
    style.sim.air_velocity_m_per_s.x = 50.0;
    let base = style.groups[0].clone();
    style.groups.clear();
    let shapes = [
        NaturalShape::Helix {
            radius_m: 0.5,
            step_m: 0.5,
        },
        NaturalShape::Uniform {
            twist_per_m: 500.0,
            curvature1_per_m: -700.0,
            curvature2_per_m: 900.0,
        },
        NaturalShape::Straight,
    ];
    for (k, shape) in shapes.into_iter().enumerate() {
        let mut group = base.clone();
        group.name = format!("g{k}");
        group.params.length_m = 1.5;
        group.params.elements = 100;
        group.params.internal_friction = 0.0;
        group.params.air_drag = 0.0;
        group.params.natural_shape = shape;
        style.groups.push(group);
    }
    style.validate().expect("the style is valid");
    style
}

#[test]
fn expanding_every_group_and_saving_gives_the_file_back_byte_for_byte() {
    let dir = scratch("beyond");
    let opened = dir.join("beyond.ron");
    std::fs::write(&opened, style_beyond_the_sliders().to_ron().unwrap()).unwrap();
    let mut app = AppState::new(style_beyond_the_sliders(), Some(&opened)).unwrap();
    app.toggle_pause();
    assert!(app.is_paused());
    let mut view = ViewState::new(3000);
    view.open_groups = Some(true);
    let ctx = egui::Context::default();
    for _ in 0..4 {
        let _ = ctx.run_ui(input(Vec::new()), |ui| draw(ui, &mut app, &mut view));
        app.settle_edits(false);
        app.step_frame();
    }
    assert!(
        !app.doc().title().contains('*'),
        "showing the style changed it: {}",
        app.doc().title()
    );
    let saved = dir.join("saved.ron");
    app.save(Some(&saved));
    assert_eq!(
        std::fs::read_to_string(&saved).unwrap(),
        std::fs::read_to_string(&opened).unwrap()
    );
    // The guide count field shows 3,000 as it is.
    assert_eq!(view.guides, 3000);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// One slider alone in a window; the text `typed` is typed into its
/// number field (Tab, Tab focuses it) and confirmed with Enter.
fn type_into_slider(start: f64, typed: &str) -> (f64, Vec<String>) {
    let ctx = egui::Context::default();
    let mut value = start;
    let mut notes = Vec::new();
    let key = |key| egui::Event::Key {
        key,
        physical_key: None,
        pressed: true,
        repeat: false,
        modifiers: egui::Modifiers::NONE,
    };
    let frames = vec![
        vec![],
        vec![key(egui::Key::Tab)],
        vec![key(egui::Key::Tab)],
        vec![egui::Event::Text(typed.into())],
        vec![key(egui::Key::Enter)],
        vec![],
    ];
    for events in frames {
        let _ = ctx.run_ui(input(events), |ui| {
            egui::CentralPanel::default().show(ui, |ui| {
                slider(
                    ui,
                    &mut notes,
                    "length",
                    &mut value,
                    0.001..=2.0,
                    Look::unit(" m"),
                );
            });
        });
    }
    (value, notes)
}

#[test]
fn typed_text_that_is_not_a_number_says_so_and_changes_nothing() {
    let (value, notes) = type_into_slider(0.2, "abc");
    assert_eq!(value, 0.2);
    // egui parses the text when Enter is pressed and again as the field
    // loses focus the next frame: the same message, shown on one line.
    assert!(!notes.is_empty());
    for note in &notes {
        assert_eq!(
            note,
            "length: `abc` is not a number; the value is unchanged"
        );
    }
}

#[test]
fn a_typed_value_is_taken_as_typed_not_clamped() {
    let (value, notes) = type_into_slider(0.2, "1.7");
    assert_eq!(value, 1.7);
    assert!(notes.is_empty(), "{notes:?}");
    let (value, _) = type_into_slider(0.2, "5");
    assert_eq!(value, 5.0, "clamped to the track");
}

#[test]
fn a_typed_value_out_of_the_format_is_taken_back_with_its_allowed_range() {
    let mut app = AppState::new(default_style(4), None).unwrap();
    let before = app.doc().style().clone();
    let mut edited = before.clone();
    edited.groups[0].params.length_m = 5.0;
    app.propose_style(edited);
    assert_eq!(*app.doc().style(), before);
    let note = app.message().expect("a message");
    assert!(note.contains("groups[0].params.length_m"), "{note}");
    assert!(note.contains("(0, 2]"), "{note}");
    assert!(note.contains('5'), "{note}");
}

#[test]
fn group_titles_count_listed_and_grown_strands() {
    let mut group = default_style(3).groups[0].clone();
    assert_eq!(strand_count_words(&group), "3 strands");
    group.scalp = Some(crate::style::groom::ScalpPlacement {
        count: 120,
        comb: glam::DVec3::NEG_Z,
        lift_deg: 25.0,
        seed: 1,
        region: None,
        curl_axis: Default::default(),
    });
    assert_eq!(
        strand_count_words(&group),
        "3 listed + 120 grown on the scalp"
    );
    group.roots.clear();
    assert_eq!(strand_count_words(&group), "120 strands grown on the scalp");
}

#[test]
fn group_titles_count_imported_strands() {
    // Regression: an imported groom opened in the window read
    // "group `imported` (0 strands)" while 35 strands were simulated.
    let mut group = default_style(3).groups[0].clone();
    let strand = crate::style::imported::ImportedStrand {
        root: group.roots[0],
        element_length_m: 0.01,
        strains: vec![glam::DVec3::ZERO; 4],
        natural: vec![glam::DVec3::ZERO; 4],
        guide: true,
        stiffness_scale: 1.0,
    };
    group.roots.clear();
    let mut strands = vec![strand.clone(); 5];
    strands[4].guide = false;
    group.imported = Some(crate::style::imported::ImportedStrands {
        source: "g.obj".into(),
        head: None,
        collider: None,
        strands,
    });
    assert_eq!(
        strand_count_words(&group),
        "5 imported strands, 4 simulated"
    );
}

#[test]
fn an_imported_group_says_what_its_strands_take_from_the_groom() {
    // The group panel showed the generic shape sliders (0.20 m, 10
    // elements) for a groom whose strands each keep their own.
    let root = default_style(1).groups[0].roots[0];
    let strand = |elements: usize, element_length_m: f64| crate::style::imported::ImportedStrand {
        root,
        element_length_m,
        strains: vec![glam::DVec3::ZERO; elements],
        natural: vec![glam::DVec3::ZERO; elements],
        guide: true,
        stiffness_scale: 1.0,
    };
    let mut strands = vec![strand(4, 0.01), strand(6, 0.02), strand(5, 0.01)];
    strands[2].guide = false;
    strands[1].stiffness_scale = 3.0;
    let imported = crate::style::imported::ImportedStrands {
        source: "sintel.tfx".into(),
        head: None,
        collider: None,
        strands,
    };
    let line = super::super::imported_summary::imported_summary(&imported);
    assert!(
        line.starts_with(
            "imported from sintel.tfx: 3 strands (2 simulated), 4–6 elements, 4.0–12.0 cm long."
        ),
        "{line}"
    );
    assert!(
        line.ends_with("with the moduli raised for 1 to hold their shape."),
        "{line}"
    );
}

#[test]
fn the_guide_field_follows_the_styles_count_when_it_changes() {
    // Issue 32, item 5: after opening another style the field still held
    // the last style's count.
    let mut app = AppState::new(default_style(12), None).unwrap();
    app.toggle_pause();
    assert!(app.is_paused());
    let mut view = ViewState::new(12);
    let ctx = egui::Context::default();
    let _ = ctx.run_ui(input(Vec::new()), |ui| draw(ui, &mut app, &mut view));
    view.guides = 40;
    let _ = ctx.run_ui(input(Vec::new()), |ui| draw(ui, &mut app, &mut view));
    assert_eq!(view.guides, 40, "what the user typed stays");
    app.edit_style(|s| *s = default_style(7));
    let _ = ctx.run_ui(input(Vec::new()), |ui| draw(ui, &mut app, &mut view));
    assert_eq!(view.guides, 7, "a new style's count replaces it");
}

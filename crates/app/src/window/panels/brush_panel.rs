//! The brush's controls: the tool row (beside the tool bar) and the Brush
//! section of the right panel (radius, strength, falloff, the picked
//! tool's own values, the selection mask, and stroke recording).
//!
//! Every range here is the stroke format's own
//! ([`crate::brush::strokes`]), so a stroke made in the window always
//! replays headless.

use egui::{Slider, Ui};

use crate::brush::strokes::MAX_RADIUS_M;
use crate::style::strand_edit::{MIN_ELEMENT_LENGTH_M, STIFFNESS_SCALE_RANGE};
use crate::window::state::app_state::AppState;
use crate::window::state::brush_state::ToolKind;

/// Smallest brush radius the slider reaches, metres (a few strands).
const MIN_BRUSH_RADIUS_M: f64 = 0.003;

/// Largest brush radius the slider reaches, metres (half a head; the
/// format allows up to [`MAX_RADIUS_M`], typed).
const MAX_BRUSH_RADIUS_M: f64 = 0.2;

/// One button per tool, the picked one highlighted, its key in the hover
/// text.
pub fn tool_row(ui: &mut Ui, app: &mut AppState) {
    for kind in ToolKind::ALL {
        let picked = app.brush().settings.kind == kind;
        let hint = format!("{} (key {:?})", kind.hint(), kind.key());
        if ui
            .selectable_label(picked, kind.label())
            .on_hover_text(hint)
            .clicked()
            && !picked
        {
            app.set_tool(kind);
        }
    }
}

/// A slider of a length kept in metres and shown in millimetres.
fn millimetres(ui: &mut Ui, value_m: &mut f64, range_m: (f64, f64), label: &str) {
    let mut mm = *value_m * 1e3;
    let response = ui.add(
        Slider::new(&mut mm, range_m.0 * 1e3..=range_m.1 * 1e3)
            .logarithmic(true)
            .suffix(" mm")
            .text(label),
    );
    if response.changed() {
        *value_m = (mm * 1e-3).clamp(range_m.0, range_m.1);
    }
}

/// The Brush section: settings of the picked tool.
pub fn brush_controls(ui: &mut Ui, app: &mut AppState) {
    ui.heading("Brush");
    let kind = app.brush().settings.kind;
    if kind == ToolKind::Orbit {
        ui.small("Pick a tool in the tool bar (Comb, Grab, Cut, …) to style by hand.");
    } else {
        ui.small(kind.hint());
        ui.small("Left drag: brush. Right drag: orbit. Esc: cancel the stroke.");
    }
    let mut settings = app.brush().settings.clone();
    let s = &mut settings;
    millimetres(
        ui,
        &mut s.radius_m,
        (MIN_BRUSH_RADIUS_M, MAX_BRUSH_RADIUS_M.min(MAX_RADIUS_M)),
        "radius",
    );
    ui.add(Slider::new(&mut s.strength, 0.0..=1.0).text("strength"));
    ui.add(Slider::new(&mut s.falloff, 0.0..=1.0).text("falloff"));
    match kind {
        ToolKind::Cut => millimetres(
            ui,
            &mut s.cut_length_m,
            (MIN_ELEMENT_LENGTH_M, 2.0),
            "cut to",
        ),
        ToolKind::Grow => millimetres(
            ui,
            &mut s.grow_length_m,
            (MIN_ELEMENT_LENGTH_M, 2.0),
            "grow to",
        ),
        ToolKind::Curl => {
            millimetres(ui, &mut s.curl_radius_m, (0.002, 0.2), "curl radius");
            let mut step_mm = s.curl_step_m * 1e3;
            if ui
                .add(
                    Slider::new(&mut step_mm, -200.0..=200.0)
                        .suffix(" mm")
                        .text("curl step"),
                )
                .changed()
            {
                s.curl_step_m = step_mm * 1e-3;
            }
        }
        ToolKind::Stiffness => {
            ui.add(
                Slider::new(
                    &mut s.stiffness_scale,
                    STIFFNESS_SCALE_RANGE.0..=STIFFNESS_SCALE_RANGE.1,
                )
                .logarithmic(true)
                .text("stiffness ×"),
            );
        }
        ToolKind::Part => {
            ui.add(
                Slider::new(&mut s.part_angle_deg, 0.0..=90.0)
                    .suffix("°")
                    .text("turn at the line"),
            );
        }
        _ => {}
    }
    if matches!(
        kind,
        ToolKind::Comb | ToolKind::Grab | ToolKind::Smooth | ToolKind::Part
    ) {
        ui.checkbox(
            &mut s.freeze,
            "keep the new shape (freeze at the stroke's end)",
        );
    }
    mask(ui, app.doc().style(), &mut settings.masked_groups);
    app.set_brush_settings(settings);
    ui.horizontal(|ui| {
        ui.label(format!(
            "{} strands masked on the scalp",
            app.brush().masked.len()
        ));
        if !app.brush().masked.is_empty() && ui.button("clear mask").clicked() {
            app.clear_mask();
        }
    });
    recording(ui, app);
    if let Some(last) = &app.brush().last {
        ui.small(format!("last stroke: {}", last.describe()));
    }
}

/// The selection mask: which groups the brush may touch.
fn mask(ui: &mut Ui, style: &crate::style::Style, masked: &mut Vec<String>) {
    let names = style.group_names();
    if names.len() < 2 {
        return;
    }
    ui.label("the brush touches:");
    ui.horizontal_wrapped(|ui| {
        for name in names {
            let mut on = !masked.contains(&name);
            if ui.checkbox(&mut on, &name).changed() {
                if on {
                    masked.retain(|m| *m != name);
                } else {
                    masked.push(name);
                }
            }
        }
    });
}

/// Start or stop recording strokes to a file beside the style.
fn recording(ui: &mut Ui, app: &mut AppState) {
    match &app.brush().recording {
        Some(r) => {
            ui.small(format!(
                "recording {} strokes to {}",
                r.file.strokes.len(),
                r.path.display()
            ));
            if ui.button("stop recording strokes").clicked() {
                app.stop_recording_strokes();
            }
        }
        None => {
            if ui
                .button("record strokes")
                .on_hover_text("write every stroke to a file `helixhair groom --strokes` replays")
                .clicked()
            {
                let path = strokes_path_for(app.doc().path());
                app.record_strokes_to(&path);
            }
        }
    }
}

/// Where strokes are recorded: `NAME.strokes.ron` beside the style's file,
/// or `strokes.ron` in the working folder for an unsaved style.
pub fn strokes_path_for(style: Option<&std::path::Path>) -> std::path::PathBuf {
    match style {
        Some(p) => p.with_extension("strokes.ron"),
        None => std::path::PathBuf::from("strokes.ron"),
    }
}

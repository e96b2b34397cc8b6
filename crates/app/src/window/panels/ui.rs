//! The window's layout: a tool bar on top, the style on the left, head and
//! readouts on the right, messages at the bottom, and the 3D view (or the
//! compare view's two) filling the rest.
//!
//! The 3D pictures are textures the renderer drew this frame; the view
//! only shows them and turns pointer gestures into camera and head moves
//! ([`crate::window::present::viewport`]). Keyboard shortcuts: Ctrl+Z undo, Ctrl+Shift+Z or
//! Ctrl+Y redo, Ctrl+S save, Ctrl+O open, Ctrl+E export the frame, F frame
//! the head, Space pause, 1 to 4 play nod, shake, turn, jerk;
//! the brush tools' keys ([`crate::window::state::brush_state::ToolKind::key`])
//! pick them, and Esc cancels a stroke ([`super::brush_input`]).

use egui::{Key, Modifiers, PointerButton, Sense, Ui};

use super::brush_input::brush_input;
use super::brush_panel::brush_controls;
use super::files::file_menu::{
    dropped as dropped_file, export_dialog_for, file_windows, open_picker, picked,
};
use super::files::file_picker::PickerMode;
use super::imported_summary::group_shapes_strands;
use super::readout_panel::readouts;
use super::style_panel::{count_field, group_params, sim_settings};
use super::tool_bar::tool_bar;
use super::view_state::ViewState;
use crate::window::live::head_motion::Clip;
use crate::window::present::viewport::{framed_camera, move_head, orbit, pan, turn_head};
use crate::window::state::app_state::AppState;
use crate::window::state::brush_state::ToolKind;
use crate::window::state::default_style::{grown_count, regrow_roots};
use crate::window::state::presets::Preset;
use crate::window::state::unsaved::{AfterAnswer, confirm_dialog};

/// Draws the whole window for one frame.
pub fn draw(ui: &mut Ui, app: &mut AppState, view: &mut ViewState) {
    if view.framed_on_m != app.head().pivot_m {
        view.framed_on_m = app.head().pivot_m;
        view.camera = framed_camera(view.framed_on_m);
    }
    shortcuts(ui.ctx(), app, view);
    egui::Panel::top("tools").show(ui, |ui| tool_bar(ui, app, view));
    egui::Panel::bottom("messages").show(ui, |ui| {
        if let Some(e) = app.invalid() {
            ui.colored_label(
                egui::Color32::from_rgb(255, 120, 90),
                format!("not simulated: {e}"),
            );
        }
        if let Some(guard) = app.guard().sentence() {
            let colour = if app.guard().losses() > 0 {
                egui::Color32::from_rgb(255, 190, 90)
            } else {
                ui.visuals().text_color()
            };
            ui.colored_label(colour, guard);
        }
        ui.label(app.message().unwrap_or("ready"));
    });
    egui::Panel::left("style")
        .default_size(330.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| style_column(ui, app, view));
        });
    egui::Panel::right("readouts")
        .default_size(330.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                if app.brush().settings.kind != ToolKind::Orbit {
                    brush_controls(ui, app);
                    ui.separator();
                }
                head_controls(ui, app);
                ui.separator();
                if app.brush().settings.kind == ToolKind::Orbit {
                    brush_controls(ui, app);
                    ui.separator();
                }
                readouts(ui, app);
            });
        });
    egui::CentralPanel::no_frame().show(ui, |ui| view_area(ui, app, view));
    super::density_view::show(ui.ctx(), app);
    if let Some(picker) = &mut view.picker {
        let (chosen, keep) = picker.show(ui.ctx());
        let mode = picker.mode;
        if !keep {
            view.picker = None;
        }
        if let Some(path) = chosen {
            picked(app, &mut view.files, mode, path);
        }
    }
    let dropped = ui
        .ctx()
        .input(|i| i.raw.dropped_files.first().map(|f| f.path().to_owned()));
    if let Some(path) = dropped {
        dropped_file(app, &mut view.files, path);
    }
    file_windows(ui.ctx(), app, &mut view.files);
    if let Some(answer) = confirm_dialog(ui.ctx(), app)
        && app.answer_leave(answer) == AfterAnswer::PickSaveAs
    {
        view.picker = Some(open_picker(
            app,
            view.files.last_folder.as_deref(),
            PickerMode::SaveAs,
        ));
    }
}

fn shortcuts(ctx: &egui::Context, app: &mut AppState, view: &mut ViewState) {
    let typing = ctx.egui_wants_keyboard_input();
    ctx.input_mut(|i| {
        if i.consume_key(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z)
            || i.consume_key(Modifiers::COMMAND, Key::Y)
        {
            app.redo();
        }
        if i.consume_key(Modifiers::COMMAND, Key::Z) {
            app.undo();
        }
        if i.consume_key(Modifiers::COMMAND, Key::S) {
            app.save(None);
        }
        if i.consume_key(Modifiers::COMMAND, Key::O) {
            view.picker = Some(open_picker(
                app,
                view.files.last_folder.as_deref(),
                PickerMode::Open,
            ));
        }
        if i.consume_key(Modifiers::COMMAND, Key::E) && view.files.job.is_none() {
            view.files.export = Some(export_dialog_for(app, false));
        }
        if !typing {
            let clips = [Key::Num1, Key::Num2, Key::Num3, Key::Num4];
            for (clip, key) in Clip::ALL.into_iter().zip(clips) {
                if i.consume_key(Modifiers::NONE, key) {
                    app.play(clip);
                }
            }
        }
        if !typing && i.consume_key(Modifiers::NONE, Key::F) {
            view.camera = framed_camera(app.head().pivot_m);
        }
        if !typing && i.consume_key(Modifiers::NONE, Key::Space) {
            app.toggle_pause();
        }
        if i.consume_key(Modifiers::NONE, Key::Escape) {
            app.cancel_stroke();
            view.brush_plane_m = None;
        }
        if !typing {
            for kind in ToolKind::ALL {
                if i.consume_key(Modifiers::NONE, kind.key()) {
                    app.set_tool(kind);
                }
            }
        }
    });
}

fn style_column(ui: &mut Ui, app: &mut AppState, view: &mut ViewState) {
    let mut edited = app.doc().style().clone();
    let mut notes = Vec::new();
    ui.heading("Simulation");
    sim_settings(ui, &mut edited, &mut notes);
    // The field follows the style's count when that changes (a load, an
    // undo, a regrow), and keeps what the user typed otherwise.
    let grown = grown_count(&edited);
    if view.guides_seen.is_some_and(|seen| seen != grown) {
        view.guides = grown;
    }
    view.guides_seen = Some(grown);
    let mut buttons = Vec::new();
    ui.horizontal(|ui| {
        count_field(ui, "guide strands", &mut view.guides, MAX_GUIDES);
        if ui.button("regrow on scalp").clicked() {
            buttons.push(StyleButton::Regrow(view.guides));
        }
    });
    ui.horizontal(|ui| {
        ui.heading("Groups");
        if ui.small_button("expand all").clicked() {
            view.open_groups = Some(true);
        }
        if ui.small_button("collapse all").clicked() {
            view.open_groups = Some(false);
        }
    });
    let open_groups = view.open_groups.take();
    let groups = edited.groups.len();
    for g in 0..groups {
        let group = &edited.groups[g];
        let title = format!("group `{}` ({})", group.name, strand_count_words(group));
        egui::CollapsingHeader::new(title)
            .id_salt(("group", g))
            .default_open(g == 0)
            .open(open_groups)
            .show(ui, |ui| {
                // A preset is mostly a curl, which an imported strand does
                // not take (its rest shape is the groom's).
                if group_shapes_strands(&edited.groups[g]) {
                    buttons.extend(preset_row(ui, app, view, g));
                }
                group_params(ui, &mut edited.groups[g], &mut notes);
            });
    }
    if let Some(last) = notes.pop() {
        app.say(last);
    }
    // The widgets' copy goes to the state, which refuses a typed value out
    // of the format's range; a button's whole edit follows as its own step.
    app.propose_style(edited);
    for button in buttons {
        match button {
            StyleButton::Regrow(count) => {
                let head = app.head_mesh().clone();
                app.edit_style(|s| regrow_roots(s, &head, count));
            }
            StyleButton::ApplyPreset(g, preset) => app.apply_preset(g, &preset),
            StyleButton::SavePreset(g, name) => app.save_user_preset(g, &name),
        }
    }
}

/// A button of the style column, acted on after the widgets' edits are in
/// (a whole-style change of its own, so an undo step of its own).
enum StyleButton {
    /// "regrow on scalp" with this many guide strands.
    Regrow(usize),
    /// A preset applied to a group.
    ApplyPreset(usize, Preset),
    /// A group's parameters saved as the user's preset of this name.
    SavePreset(usize, String),
}

/// Most guide strands the "regrow on scalp" field accepts (as `--guides`
/// and a group's `scalp.count`).
const MAX_GUIDES: usize = 5000;

/// How many strands a group has, in words: listed roots, roots grown on
/// the scalp, or both.
pub fn strand_count_words(group: &crate::style::StrandGroup) -> String {
    if let Some(imported) = &group.imported {
        let guides = imported.guides().count();
        let all = imported.strands.len();
        let roots = group.roots.len();
        let extra = if roots > 0 {
            format!(" + {roots} listed")
        } else {
            String::new()
        };
        return if guides == all {
            format!("{all} imported strands{extra}")
        } else {
            format!("{all} imported strands, {guides} simulated{extra}")
        };
    }
    let listed = group.roots.len();
    match &group.scalp {
        None => format!("{listed} strands"),
        Some(scalp) if listed == 0 => format!("{} strands grown on the scalp", scalp.count),
        Some(scalp) => format!("{listed} listed + {} grown on the scalp", scalp.count),
    }
}

/// The preset buttons, the preset name field and "save as preset".
fn preset_row(ui: &mut Ui, app: &AppState, view: &mut ViewState, g: usize) -> Option<StyleButton> {
    let mut pressed = None;
    ui.horizontal_wrapped(|ui| {
        ui.label("preset:");
        let presets: Vec<_> = app.presets().cloned().collect();
        for p in presets {
            let hint = format!(
                "this group's parameters; the style's substeps (all groups) rise to at least {}",
                p.min_substeps
            );
            if ui.button(&p.name).on_hover_text(hint).clicked() {
                pressed = Some(StyleButton::ApplyPreset(g, p.clone()));
            }
        }
    });
    ui.horizontal(|ui| {
        ui.label("preset name");
        ui.text_edit_singleline(&mut view.preset_name);
        if ui.button("save as preset").clicked() {
            let name = view.preset_name.trim().to_string();
            if !name.is_empty() {
                pressed = Some(StyleButton::SavePreset(g, name));
            }
        }
    });
    pressed
}

fn head_controls(ui: &mut Ui, app: &mut AppState) {
    ui.heading("Head");
    ui.horizontal(|ui| {
        for clip in Clip::ALL {
            if ui.button(clip.name()).clicked() {
                app.play(clip);
            }
        }
    });
    // The sliders are the user's own pose; a clip moves the head on top of
    // it, so say which one plays.
    match app.head().playing(app.now_secs()) {
        Some(what) => ui.label(format!("playing: {what} (on top of the pose below)")),
        None => ui.label("playing: nothing"),
    };
    let mut pose = app.head().target;
    ui.add(
        egui::Slider::new(&mut pose.turn_rad, -1.4..=1.4)
            .text("turn")
            .suffix(" rad"),
    );
    ui.add(
        egui::Slider::new(&mut pose.tilt_rad, -0.7..=0.7)
            .text("tilt")
            .suffix(" rad"),
    );
    if ui.button("centre head").clicked() {
        pose = Default::default();
    }
    app.set_head_pose(pose);
    if ui
        .button("set current shape as rest")
        .on_hover_text("freeze the hair as it is now: its shape becomes the equilibrium (undoable)")
        .clicked()
    {
        app.set_current_shape_as_rest();
    }
    ui.small("Alt + left drag turns the head, Alt + right drag moves it.");
}

fn view_area(ui: &mut Ui, app: &mut AppState, view: &mut ViewState) {
    let rect = ui.available_rect_before_wrap();
    let ppp = ui.ctx().pixels_per_point();
    let halves = if app.compare().is_some() { 2 } else { 1 };
    let width_pt = rect.width() / halves as f32;
    view.view_px = [
        ((width_pt * ppp) as u32).max(1),
        ((rect.height() * ppp) as u32).max(1),
    ];
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    for (k, texture) in view.textures.iter().take(halves).enumerate() {
        if let Some(id) = texture {
            let sub = egui::Rect::from_min_size(
                rect.min + egui::vec2(width_pt * k as f32, 0.0),
                egui::vec2(width_pt, rect.height()),
            );
            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter().image(*id, sub, uv, egui::Color32::WHITE);
        }
    }
    if let Some((_, m)) = app.compare() {
        for (k, method) in [m.left, m.right].into_iter().enumerate() {
            ui.painter().text(
                rect.min + egui::vec2(width_pt * k as f32 + 8.0, 8.0),
                egui::Align2::LEFT_TOP,
                method.label(),
                egui::FontId::proportional(16.0),
                egui::Color32::WHITE,
            );
        }
    }
    let delta = response.drag_delta();
    let alt = ui.input(|i| i.modifiers.alt);
    let shift = ui.input(|i| i.modifiers.shift);
    let height = rect.height();
    let brushing = app.brush().settings.kind != ToolKind::Orbit;
    if brushing && !alt {
        let view_rect = egui::Rect::from_min_size(rect.min, egui::vec2(width_pt, rect.height()));
        brush_input(ui, app, view, &response, view_rect);
    } else {
        view.brush_at_m = None;
    }
    if brushing && response.dragged_by(PointerButton::Secondary) && !alt && !shift {
        orbit(&mut view.camera, delta.x, delta.y);
    } else if (alt || !brushing) && response.dragged_by(PointerButton::Primary) {
        if alt {
            let mut pose = app.head().target;
            turn_head(&mut pose, delta.x, delta.y);
            app.set_head_pose(pose);
        } else if shift {
            pan(&mut view.camera, delta.x, delta.y, height);
        } else {
            orbit(&mut view.camera, delta.x, delta.y);
        }
    }
    let pans = if brushing {
        (response.dragged_by(PointerButton::Secondary) && shift)
            || response.dragged_by(PointerButton::Middle)
    } else {
        response.dragged_by(PointerButton::Secondary) || response.dragged_by(PointerButton::Middle)
    };
    if pans {
        if alt {
            let mut pose = app.head().target;
            move_head(&mut pose, &view.camera, delta.x, delta.y, height);
            app.set_head_pose(pose);
        } else {
            pan(&mut view.camera, delta.x, delta.y, height);
        }
    }
    if response.hovered() {
        let (scroll, zoom) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
        let factor = (-scroll * 0.002).exp() / zoom;
        if (factor - 1.0).abs() > 1e-6 {
            view.camera.zoom(factor);
        }
    }
}

#[cfg(test)]
#[path = "ui_tests.rs"]
mod tests;

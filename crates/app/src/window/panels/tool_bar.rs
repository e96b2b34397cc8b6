//! The tool bar: the File menu ([`super::files::file_menu`]), Save, history,
//! pause and the compare view's solvers; below it the brush tools
//! ([`super::brush_panel`]).

use egui::Ui;
use helixhair_physics::Method;

use super::brush_panel::tool_row;
use super::files::file_menu::{file_menu, open_picker, stop_recording};
use super::files::file_picker::PickerMode;
use super::view_state::ViewState;
use crate::window::state::app_state::{AppState, CompareMethods};

pub(super) fn tool_bar(ui: &mut Ui, app: &mut AppState, view: &mut ViewState) {
    ui.horizontal(|ui| {
        file_menu(ui, app, &mut view.picker, &mut view.files);
        if ui.button("Save").clicked() {
            if app.doc().path().is_some() {
                app.save(None);
            } else {
                view.picker = Some(open_picker(
                    app,
                    view.files.last_folder.as_deref(),
                    PickerMode::SaveAs,
                ));
            }
        }
        if app.head().recorder.is_some() && ui.button("Stop recording").clicked() {
            stop_recording(app, &mut view.files);
        }
        ui.separator();
        let (can_undo, can_redo) = app.doc().can_undo_redo();
        if ui
            .add_enabled(can_undo, egui::Button::new("Undo"))
            .clicked()
        {
            app.undo();
        }
        if ui
            .add_enabled(can_redo, egui::Button::new("Redo"))
            .clicked()
        {
            app.redo();
        }
        ui.separator();
        let pause = if app.is_paused() { "Play" } else { "Pause" };
        if ui.button(pause).clicked() {
            app.toggle_pause();
        }
        ui.separator();
        let mut on = app.compare().is_some();
        if ui.checkbox(&mut on, "compare solvers").changed() {
            app.set_compare(on.then(CompareMethods::default));
        }
        if let Some(&(_, methods)) = app.compare() {
            let mut m = methods;
            method_combo(ui, "left", &mut m.left);
            method_combo(ui, "right", &mut m.right);
            if m != methods {
                app.set_compare(Some(m));
            }
        }
        ui.separator();
        ui.label(app.doc().title());
    });
    ui.horizontal(|ui| {
        ui.label("tool:");
        tool_row(ui, app);
    });
}

fn method_combo(ui: &mut Ui, label: &str, method: &mut Method) {
    egui::ComboBox::from_label(label)
        .selected_text(method.label())
        .show_ui(ui, |ui| {
            for m in Method::ALL {
                ui.selectable_value(method, m, m.label());
            }
        });
}

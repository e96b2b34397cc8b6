//! The tool bar: files, history, pause and the compare view's solvers.

use egui::Ui;
use helixhair_physics::Method;

use super::app_state::{AppState, CompareMethods};
use super::file_picker::{FilePicker, PickerMode};
use super::ui::ViewState;

pub(super) fn open_picker(app: &AppState, mode: PickerMode) -> FilePicker {
    let (folder, name) = match app.doc.path() {
        Some(p) => (
            p.parent().map(|d| d.to_owned()).unwrap_or_default(),
            p.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
        ),
        None => (
            std::env::current_dir().unwrap_or_default(),
            format!("{}.ron", app.doc.style().name),
        ),
    };
    FilePicker::new(mode, folder, name)
}

pub(super) fn tool_bar(ui: &mut Ui, app: &mut AppState, view: &mut ViewState) {
    ui.horizontal(|ui| {
        if ui.button("Open…").clicked() {
            view.picker = Some(open_picker(app, PickerMode::Open));
        }
        if ui.button("Save").clicked() {
            if app.doc.path().is_some() {
                app.save(None);
            } else {
                view.picker = Some(open_picker(app, PickerMode::SaveAs));
            }
        }
        if ui.button("Save as…").clicked() {
            view.picker = Some(open_picker(app, PickerMode::SaveAs));
        }
        ui.separator();
        let (can_undo, can_redo) = app.doc.can_undo_redo();
        if ui
            .add_enabled(can_undo, egui::Button::new("Undo"))
            .clicked()
        {
            app.doc.undo();
        }
        if ui
            .add_enabled(can_redo, egui::Button::new("Redo"))
            .clicked()
        {
            app.doc.redo();
        }
        ui.separator();
        let pause = if app.paused { "Play" } else { "Pause" };
        if ui.button(pause).clicked() {
            app.paused = !app.paused;
        }
        ui.separator();
        let mut on = app.compare.is_some();
        if ui.checkbox(&mut on, "compare solvers").changed() {
            app.set_compare(on.then(CompareMethods::default));
        }
        if let Some((_, methods)) = app.compare {
            let mut m = methods;
            method_combo(ui, "left", &mut m.left);
            method_combo(ui, "right", &mut m.right);
            if m != methods {
                app.set_compare(Some(m));
            }
        }
        ui.separator();
        ui.label(app.doc.title());
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

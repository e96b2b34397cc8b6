//! A small file dialog drawn by egui: a folder's sub-folders and `.ron`
//! files, and a name field.
//!
//! A native dialog (`rfd`) needs GTK or an XDG desktop portal over D-Bus,
//! neither of which a bare X server (CI's Xvfb) has, and pulls in a large
//! dependency tree; this picker works wherever the window does. Styles can
//! also be dropped on the window.

use std::path::{Path, PathBuf};

use egui::Ui;

/// What the picker is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PickerMode {
    /// Choose a style to load.
    Open,
    /// Choose where to save.
    SaveAs,
}

/// The picker's state while it is open.
#[derive(Clone, Debug)]
pub struct FilePicker {
    /// What it is for.
    pub mode: PickerMode,
    folder: PathBuf,
    name: String,
}

/// Sub-folders and `.ron` files of `folder`, sorted, folders first.
pub fn list_folder(folder: &Path) -> (Vec<PathBuf>, Vec<PathBuf>) {
    let mut folders = Vec::new();
    let mut files = Vec::new();
    if let Ok(entries) = std::fs::read_dir(folder) {
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "ron") {
                files.push(path);
            }
        }
    }
    folders.sort();
    files.sort();
    (folders, files)
}

impl FilePicker {
    /// A picker starting in `folder`, with `name` in the name field.
    pub fn new(mode: PickerMode, folder: PathBuf, name: String) -> Self {
        Self { mode, folder, name }
    }

    /// Draws the picker; returns the chosen path once confirmed, and
    /// whether it should stay open.
    pub fn show(&mut self, ctx: &egui::Context) -> (Option<PathBuf>, bool) {
        let mut chosen = None;
        let mut open = true;
        let title = match self.mode {
            PickerMode::Open => "Open style",
            PickerMode::SaveAs => "Save style as",
        };
        egui::Window::new(title)
            .collapsible(false)
            .default_width(420.0)
            .show(ctx, |ui| {
                chosen = self.contents(ui, &mut open);
            });
        let keep = open && chosen.is_none();
        (chosen, keep)
    }

    fn contents(&mut self, ui: &mut Ui, open: &mut bool) -> Option<PathBuf> {
        let mut chosen = None;
        ui.label(self.folder.display().to_string());
        let (folders, files) = list_folder(&self.folder);
        egui::ScrollArea::vertical()
            .max_height(260.0)
            .show(ui, |ui| {
                if let Some(parent) = self.folder.parent().map(Path::to_owned)
                    && ui.button("⬆ ..").clicked()
                {
                    self.folder = parent;
                }
                for f in &folders {
                    let name = f.file_name().map(|n| n.to_string_lossy().into_owned());
                    if ui
                        .button(format!("📁 {}", name.unwrap_or_default()))
                        .clicked()
                    {
                        self.folder = f.clone();
                    }
                }
                for f in &files {
                    let name = f
                        .file_name()
                        .map(|n| n.to_string_lossy().into_owned())
                        .unwrap_or_default();
                    let response = ui.selectable_label(self.name == name, &name);
                    if response.clicked() {
                        self.name = name;
                    }
                    if response.double_clicked() {
                        chosen = Some(f.clone());
                    }
                }
            });
        ui.horizontal(|ui| {
            ui.label("file name");
            ui.text_edit_singleline(&mut self.name);
        });
        ui.horizontal(|ui| {
            let verb = match self.mode {
                PickerMode::Open => "Open",
                PickerMode::SaveAs => "Save",
            };
            if ui.button(verb).clicked() && !self.name.trim().is_empty() {
                let mut name = self.name.trim().to_string();
                if self.mode == PickerMode::SaveAs && !name.ends_with(".ron") {
                    name.push_str(".ron");
                }
                chosen = Some(self.folder.join(name));
            }
            if ui.button("Cancel").clicked() {
                *open = false;
            }
        });
        chosen
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_folders_then_style_files_only() {
        let dir = std::env::temp_dir().join(format!("helixhair-picker-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        for f in ["b.ron", "a.ron", "notes.txt"] {
            std::fs::write(dir.join(f), "").unwrap();
        }
        let (folders, files) = list_folder(&dir);
        assert_eq!(folders, vec![dir.join("sub")]);
        assert_eq!(files, vec![dir.join("a.ron"), dir.join("b.ron")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! A small file dialog drawn by egui: a folder's sub-folders and the files
//! the dialog is for (`.ron` styles and motion files, or grooms), and a
//! name field.
//!
//! A native dialog (`rfd`) needs GTK or an XDG desktop portal over D-Bus,
//! neither of which a bare X server (CI's Xvfb) has, and pulls in a large
//! dependency tree; this picker works wherever the window does. Styles can
//! also be dropped on the window.
//!
//! As a desktop dialog does, it is modal (clicks do not reach the window
//! behind), Enter confirms and Esc cancels, a typed folder is opened
//! rather than picked, and writing over an existing file asks first
//! ([`resolve`]). Where it starts is the caller's
//! ([`crate::window::panels::files::file_menu::open_picker`]: the last folder
//! used).

use std::path::{Path, PathBuf};

use egui::Ui;

/// What the picker is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PickerMode {
    /// Choose a style to load.
    Open,
    /// Choose where to save.
    SaveAs,
    /// Choose a groom to import (File → Import groom…).
    ImportGroom,
    /// Choose a motion file to play.
    PlayMotion,
    /// Choose where to save the recorded head motion.
    SaveMotion,
}

impl PickerMode {
    /// The extensions listed (lower case, no dot).
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            PickerMode::ImportGroom => &helixhair_formats::Format::EXTENSIONS,
            _ => &["ron"],
        }
    }

    /// Whether the picker names a file to write (`.ron` added if missing).
    fn saves(self) -> bool {
        matches!(self, PickerMode::SaveAs | PickerMode::SaveMotion)
    }

    fn title_and_verb(self) -> (&'static str, &'static str) {
        match self {
            PickerMode::Open => ("Open style", "Open"),
            PickerMode::SaveAs => ("Save style as", "Save"),
            PickerMode::ImportGroom => (
                "Import groom (.tfx, .hair, .usda, .usdc, .usd, .usdz, .abc, .obj)",
                "Import",
            ),
            PickerMode::PlayMotion => ("Play motion file", "Play"),
            PickerMode::SaveMotion => ("Save head motion as", "Save"),
        }
    }
}

/// The picker's state while it is open.
#[derive(Clone, Debug)]
pub struct FilePicker {
    /// What it is for.
    pub mode: PickerMode,
    folder: PathBuf,
    name: String,
    /// A file to write that exists, waiting for "replace it?".
    replacing: Option<PathBuf>,
}

/// What confirming the name field does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Resolved {
    /// Nothing (an empty name).
    Nothing,
    /// Opens this folder (the name is a folder).
    Enter(PathBuf),
    /// Picks this file.
    Pick(PathBuf),
    /// Asks before writing over this existing file.
    AskReplace(PathBuf),
}

/// What confirming `name` (relative to `folder`, or absolute) does in a
/// picker for `mode`: a folder is entered, a file to write gets `.ron` if
/// it has no extension and is asked about if it exists.
pub fn resolve(mode: PickerMode, folder: &Path, name: &str) -> Resolved {
    let name = name.trim();
    if name.is_empty() {
        return Resolved::Nothing;
    }
    let path = folder.join(name);
    if path.is_dir() {
        return Resolved::Enter(path);
    }
    if !mode.saves() {
        return Resolved::Pick(path);
    }
    let path = if path.extension().is_none() {
        path.with_extension("ron")
    } else {
        path
    };
    if path.exists() {
        Resolved::AskReplace(path)
    } else {
        Resolved::Pick(path)
    }
}

/// Sub-folders and files of `folder` with one of `extensions` (any case),
/// sorted, folders first.
pub fn list_folder(folder: &Path, extensions: &[&str]) -> (Vec<PathBuf>, Vec<PathBuf>) {
    let mut folders = Vec::new();
    let mut files = Vec::new();
    if let Ok(entries) = std::fs::read_dir(folder) {
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| {
                extensions
                    .iter()
                    .any(|x| e.to_string_lossy().eq_ignore_ascii_case(x))
            }) {
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
        Self {
            mode,
            folder,
            name,
            replacing: None,
        }
    }

    /// The folder shown.
    pub fn folder(&self) -> &Path {
        &self.folder
    }

    /// Puts `name` in the name field.
    pub fn set_name(&mut self, name: String) {
        self.name = name;
    }

    /// Draws the picker; returns the chosen path once confirmed, and
    /// whether it should stay open.
    pub fn show(&mut self, ctx: &egui::Context) -> (Option<PathBuf>, bool) {
        let mut chosen = None;
        let mut open = true;
        let (title, _) = self.mode.title_and_verb();
        let modal = egui::Modal::new(egui::Id::unique("file picker")).show(ctx, |ui| {
            ui.set_width(440.0);
            ui.heading(title);
            chosen = match self.replacing.clone() {
                Some(path) => self.ask_replace(ui, path),
                None => self.contents(ui, &mut open),
            };
        });
        if modal.should_close() && chosen.is_none() {
            if self.replacing.is_some() {
                self.replacing = None;
            } else {
                open = false;
            }
        }
        let keep = open && chosen.is_none();
        (chosen, keep)
    }

    fn contents(&mut self, ui: &mut Ui, open: &mut bool) -> Option<PathBuf> {
        let mut chosen = None;
        ui.label(self.folder.display().to_string());
        let (folders, files) = list_folder(&self.folder, self.mode.extensions());
        egui::ScrollArea::vertical()
            .max_height(260.0)
            .show(ui, |ui| {
                // Plain text: egui's fonts have no folder or arrow icons
                // (they drew as boxes).
                if let Some(parent) = self.folder.parent().map(Path::to_owned)
                    && ui.button("../  (the folder above)").clicked()
                {
                    self.folder = parent;
                }
                for f in &folders {
                    let name = f.file_name().map(|n| n.to_string_lossy().into_owned());
                    if ui
                        .button(format!("{}/", name.unwrap_or_default()))
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
        ui.small("a name, a path, or a folder to open; Enter confirms, Esc cancels");
        ui.horizontal(|ui| {
            let (_, verb) = self.mode.title_and_verb();
            let enter = ui.input(|i| i.key_pressed(egui::Key::Enter));
            if ui.button(verb).clicked() || enter {
                match resolve(self.mode, &self.folder, &self.name) {
                    Resolved::Nothing => {}
                    Resolved::Enter(folder) => {
                        self.folder = folder;
                        self.name.clear();
                    }
                    Resolved::Pick(path) => chosen = Some(path),
                    Resolved::AskReplace(path) => self.replacing = Some(path),
                }
            }
            if ui.button("Cancel").clicked() {
                *open = false;
            }
        });
        chosen
    }

    /// "Replace it?" for an existing file to write.
    fn ask_replace(&mut self, ui: &mut Ui, path: PathBuf) -> Option<PathBuf> {
        ui.label(format!("{} exists. Replace it?", path.display()));
        let mut chosen = None;
        ui.horizontal(|ui| {
            if ui.button("Replace").clicked() {
                chosen = Some(path);
                self.replacing = None;
            }
            if ui.button("Back").clicked() {
                self.replacing = None;
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
        for f in ["b.ron", "a.ron", "notes.txt", "g.TFX", "h.hair"] {
            std::fs::write(dir.join(f), "").unwrap();
        }
        let (folders, files) = list_folder(&dir, PickerMode::Open.extensions());
        assert_eq!(folders, vec![dir.join("sub")]);
        assert_eq!(files, vec![dir.join("a.ron"), dir.join("b.ron")]);
        let (_, grooms) = list_folder(&dir, PickerMode::ImportGroom.extensions());
        assert_eq!(grooms, vec![dir.join("g.TFX"), dir.join("h.hair")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_typed_folder_is_entered_and_an_existing_file_to_write_is_asked_about() {
        // Issue 32, item 9.
        let dir = std::env::temp_dir().join(format!("helixhair-resolve-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("grooms")).unwrap();
        std::fs::write(dir.join("mine.ron"), "").unwrap();
        let import = PickerMode::ImportGroom;
        assert_eq!(
            resolve(import, &dir, "grooms"),
            Resolved::Enter(dir.join("grooms"))
        );
        let absolute = dir.join("grooms").display().to_string();
        assert_eq!(
            resolve(import, Path::new("/"), &absolute),
            Resolved::Enter(dir.join("grooms"))
        );
        assert_eq!(
            resolve(import, &dir, "g.tfx"),
            Resolved::Pick(dir.join("g.tfx"))
        );
        assert_eq!(resolve(import, &dir, "  "), Resolved::Nothing);
        let save = PickerMode::SaveAs;
        assert_eq!(
            resolve(save, &dir, "new"),
            Resolved::Pick(dir.join("new.ron"))
        );
        assert_eq!(
            resolve(save, &dir, "mine"),
            Resolved::AskReplace(dir.join("mine.ron"))
        );
        assert_eq!(
            resolve(save, &dir, "mine.ron"),
            Resolved::AskReplace(dir.join("mine.ron"))
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

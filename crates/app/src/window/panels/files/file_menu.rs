//! The File menu and what it opens: styles in and out, hair out as curve
//! files ([`crate::window::jobs::export_job`]), grooms in ([`crate::window::jobs::import_job`]), and the
//! head's motion recorded, saved and played back
//! ([`crate::window::live::motion_recorder`], docs/motion-format.md).
//!
//! Everything that drops the edited style (Open…, a dropped style, an
//! imported groom opening as a style) goes through
//! [`AppState::request_leave`], which asks first when edits are unsaved.
//! One file job runs at a time; while it runs, a progress window with
//! Cancel shows and the window goes on simulating and drawing.

use std::path::{Path, PathBuf};

use egui::Ui;

use crate::export::{DEFAULT_POINTS_PER_STRAND, StrandChoice};
use crate::motion::file::Motion;
use crate::motion::playback::Playback;

use super::export_dialog::{DEFAULT_RECORD_FRAMES, DialogAnswer, ExportDialog, export_dialog};
use super::file_picker::{FilePicker, PickerMode};
use super::import_dialog::{ImportAnswer, ImportDialog, import_dialog, open_material};
use crate::window::jobs::export_job::{ExportRequest, start_export};
use crate::window::jobs::import_job::{import_extension, start_import};
use crate::window::jobs::job::{Job, JobDone, progress_ui};
use crate::window::state::app_state::AppState;
use crate::window::state::unsaved::Leave;

/// The File menu's windows between frames.
#[derive(Debug, Default)]
pub struct FileWindows {
    /// The export dialog, while open.
    pub export: Option<ExportDialog>,
    /// The import dialog (which head the groom goes on), while open.
    pub import: Option<ImportDialog>,
    /// The file job running.
    pub job: Option<Job<JobDone>>,
    /// The last head motion recorded, until saved or replaced.
    pub recorded: Option<Motion>,
    /// The folder of the last file chosen in a picker: the next starts
    /// there.
    pub last_folder: Option<PathBuf>,
}

/// A picker for `mode` with the style's file name, in the folder last
/// chosen in a picker this session (`last_folder`), else the style file's
/// folder, else the home folder (not the working folder, which is the
/// source checkout under `cargo run`).
pub fn open_picker(app: &AppState, last_folder: Option<&Path>, mode: PickerMode) -> FilePicker {
    let name = match app.doc().path() {
        Some(p) => p
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
        None => format!("{}.ron", app.doc().style().name),
    };
    let folder = start_folder(last_folder, app.doc().path());
    FilePicker::new(mode, folder, name)
}

/// Where a picker starts: `last_folder`, else `style`'s folder, else the
/// home folder, else the working folder.
pub fn start_folder(last_folder: Option<&Path>, style: Option<&Path>) -> PathBuf {
    let style_folder = style
        .and_then(Path::parent)
        .filter(|d| !d.as_os_str().is_empty());
    last_folder
        .or(style_folder)
        .map(Path::to_owned)
        .or_else(|| std::env::var_os("HOME").map(PathBuf::from))
        .unwrap_or_else(|| std::env::current_dir().unwrap_or_default())
}

/// A file next to the style's (or in the working folder) named after the
/// style, with `extension`.
fn beside_style(app: &AppState, extension: &str) -> PathBuf {
    let (folder, stem) = match app.doc().path() {
        Some(p) => (
            p.parent().map(Path::to_owned).unwrap_or_default(),
            p.file_stem()
                .map_or_else(|| "hair".into(), |s| s.to_string_lossy().into_owned()),
        ),
        None => (
            std::env::current_dir().unwrap_or_default(),
            app.doc().style().name.clone(),
        ),
    };
    folder.join(format!("{stem}.{extension}"))
}

fn picker(app: &AppState, files: &FileWindows, mode: PickerMode, name: String) -> FilePicker {
    let mut p = open_picker(app, files.last_folder.as_deref(), mode);
    p.set_name(name);
    p
}

/// The File menu (in the tool bar).
pub fn file_menu(
    ui: &mut Ui,
    app: &mut AppState,
    picker_slot: &mut Option<FilePicker>,
    files: &mut FileWindows,
) {
    ui.menu_button("File", |ui| {
        if ui.button("Open…").clicked() {
            *picker_slot = Some(open_picker(
                app,
                files.last_folder.as_deref(),
                PickerMode::Open,
            ));
        }
        if ui.button("Save").clicked() {
            if app.doc().path().is_some() {
                app.save(None);
            } else {
                *picker_slot = Some(open_picker(
                    app,
                    files.last_folder.as_deref(),
                    PickerMode::SaveAs,
                ));
            }
        }
        if ui.button("Save as…").clicked() {
            *picker_slot = Some(open_picker(
                app,
                files.last_folder.as_deref(),
                PickerMode::SaveAs,
            ));
        }
        ui.separator();
        let idle = files.job.is_none();
        if ui
            .add_enabled(idle, egui::Button::new("Import groom…"))
            .clicked()
        {
            *picker_slot = Some(picker(app, files, PickerMode::ImportGroom, String::new()));
        }
        for (animation, label) in [(false, "Export frame…"), (true, "Record animation…")] {
            if ui.add_enabled(idle, egui::Button::new(label)).clicked() {
                files.export = Some(export_dialog_for(app, animation));
            }
        }
        ui.separator();
        motion_items(ui, app, picker_slot, files);
    });
}

/// The export dialog as File → "Export frame…" (or, with `animation`,
/// "Record animation…") opens it: a `.usda` beside the style.
pub fn export_dialog_for(app: &AppState, animation: bool) -> ExportDialog {
    ExportDialog {
        animation,
        path: beside_style(app, "usda").display().to_string(),
        strands: StrandChoice::Simulated,
        points_per_strand: DEFAULT_POINTS_PER_STRAND,
        frames: DEFAULT_RECORD_FRAMES,
        clip: None,
        frame_secs: app.sim().engine().settings().dt_secs,
    }
}

fn motion_items(
    ui: &mut Ui,
    app: &mut AppState,
    picker_slot: &mut Option<FilePicker>,
    files: &mut FileWindows,
) {
    match &app.head().recorder {
        None => {
            if ui.button("Record head motion").clicked() {
                app.record_head_motion();
            }
        }
        Some(rec) => {
            let label = format!("Stop recording ({:.1} s)", rec.duration_secs());
            if ui.button(label).clicked() {
                stop_recording(app, files);
            }
        }
    }
    if ui
        .add_enabled(
            files.recorded.is_some(),
            egui::Button::new("Save head motion…"),
        )
        .clicked()
    {
        let name = beside_style(app, "motion.ron");
        let name = name
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        *picker_slot = Some(picker(app, files, PickerMode::SaveMotion, name));
    }
    if ui.button("Play motion file…").clicked() {
        *picker_slot = Some(picker(app, files, PickerMode::PlayMotion, String::new()));
    }
}

/// Ends the recording and keeps it for "Save head motion…".
pub fn stop_recording(app: &mut AppState, files: &mut FileWindows) {
    let Some(rec) = app.take_head_recording() else {
        return;
    };
    files.recorded = rec.motion("recorded in the window");
    app.say(match &files.recorded {
        Some(m) => format!(
            "recorded {} keys over {:.2} s: File > Save head motion… to keep them",
            m.keys.len(),
            m.duration_secs()
        ),
        None => "nothing recorded (the simulation was paused)".into(),
    });
}

/// Acts on a path chosen in the picker.
pub fn picked(app: &mut AppState, files: &mut FileWindows, mode: PickerMode, path: PathBuf) {
    files.last_folder = path.parent().map(Path::to_owned);
    match mode {
        PickerMode::Open => app.request_leave(Leave::Open(path)),
        PickerMode::SaveAs => app.saved_as(&path),
        PickerMode::ImportGroom => start_import_job(app, files, path),
        PickerMode::PlayMotion => play_motion_file(app, &path),
        PickerMode::SaveMotion => {
            app.say(match &files.recorded {
                Some(m) => match m.save(&path) {
                    Ok(()) => format!("head motion saved to {}", path.display()),
                    Err(e) => e.to_string(),
                },
                None => "no head motion recorded".into(),
            });
        }
    }
}

/// Plays a motion file from now (errors name the file, line and field).
pub fn play_motion_file(app: &mut AppState, path: &Path) {
    match Playback::File(path.to_owned()).load() {
        Ok(playback) => {
            app.play_head_motion(playback);
            app.say(format!("playing {}", path.display()));
        }
        Err(e) => app.say(e.to_string()),
    }
}

/// A file dropped on the window: a groom is imported, anything else is
/// opened as a style.
pub fn dropped(app: &mut AppState, files: &mut FileWindows, path: PathBuf) {
    if import_extension(&path) {
        start_import_job(app, files, path);
    } else {
        app.request_leave(Leave::Open(path));
    }
}

/// Asks which head `groom` goes on ([`ImportDialog`]); the import starts
/// when the user answers.
fn start_import_job(app: &mut AppState, files: &mut FileWindows, groom: PathBuf) {
    if files.job.is_some() {
        app.say("another file job is running; wait for it or cancel it");
        return;
    }
    let material = open_material(app.doc().style());
    files.import = Some(ImportDialog::new(&groom, material));
}

/// The export dialog, the progress window, and a finished job's result.
pub fn file_windows(ctx: &egui::Context, app: &mut AppState, files: &mut FileWindows) {
    if let Some(dialog) = &mut files.export {
        match export_dialog(ctx, dialog) {
            DialogAnswer::Stay => {}
            DialogAnswer::Cancel => files.export = None,
            DialogAnswer::Go => {
                let request = ExportRequest {
                    path: PathBuf::from(dialog.path.trim()),
                    strands: dialog.strands,
                    points_per_strand: dialog.points_per_strand,
                    frames: if dialog.animation { dialog.frames } else { 0 },
                    clip: dialog.clip.filter(|_| dialog.animation),
                };
                match start_export(app, &request) {
                    Ok(job) => {
                        files.job = Some(job);
                        files.export = None;
                    }
                    Err(e) => app.say(format!("{e:#}")),
                }
            }
        }
    }
    if let Some(dialog) = &mut files.import {
        match import_dialog(ctx, dialog) {
            ImportAnswer::Stay => {}
            ImportAnswer::Cancel => files.import = None,
            ImportAnswer::Go => {
                let (head, collider) = (dialog.head_path(), dialog.collider_path());
                match start_import(&dialog.groom, head, collider, dialog.material()) {
                    Ok(job) => files.job = Some(job),
                    Err(e) => app.say(format!("{e:#}")),
                }
                files.import = None;
            }
        }
    }
    let Some(job) = &mut files.job else {
        return;
    };
    if progress_ui(ctx, &job.label, &job.progress) {
        job.cancel();
    }
    let Some(result) = job.poll() else {
        ctx.request_repaint();
        return;
    };
    files.job = None;
    match result {
        Ok(JobDone::Exported(outcome)) => app.say(outcome.summary()),
        Ok(JobDone::Imported(style, warnings)) => {
            app.request_leave(Leave::Open(style));
            if !warnings.is_empty() {
                // After the open, which starts the status line afresh.
                app.say(format!("imported with warnings: {}", warnings.join("; ")));
            }
        }
        Err(e) => app.say(format!("{e:#}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_picker_starts_in_the_last_folder_then_the_styles_then_home() {
        // Issue 32, item 9: every dialog started in the working folder (the
        // source checkout) and forgot the last folder.
        let last = Path::new("/data/grooms");
        let style = Path::new("/work/styles/bob.ron");
        assert_eq!(start_folder(Some(last), Some(style)), last);
        assert_eq!(start_folder(None, Some(style)), Path::new("/work/styles"));
        if let Some(home) = std::env::var_os("HOME") {
            assert_eq!(start_folder(None, None), PathBuf::from(home));
            assert_eq!(
                start_folder(None, Some(Path::new("bob.ron"))),
                PathBuf::from(std::env::var_os("HOME").unwrap())
            );
        }
    }
}

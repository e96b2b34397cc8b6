//! How the panels see [`AppState`] and ask it for changes.
//!
//! The panels draw from read-only views of the state (the document, the
//! runs, the head, the readouts) and never write its fields: each change is
//! a request here, and the state decides. A style edit, for one, comes as
//! a whole edited copy ([`AppState::propose_style`]): it is applied only if
//! it keeps a valid style valid, so a typed value out of the format's range
//! is taken back with a message naming the field, and the runs never see
//! it. Brush settings and the head's pose are small values edited the same
//! way: copied, changed by the widgets, handed back.
//!
//! The other requests live beside the state they change: loading, saving
//! and presets in [`super::app_state`], strokes and the mask in
//! [`super::brushing`], "set current shape as rest" in [`super::set_rest`],
//! leaving with unsaved changes in [`super::unsaved`].

use std::path::Path;
use std::sync::Arc;

use helixhair_render::HeadMesh;

use super::app_state::{AppState, CompareMethods};
use super::brush_state::{BrushSettings, BrushState};
use super::document::StyleDoc;
use super::guard_status::GuardStatus;
use super::presets::Preset;
use super::readouts::Readouts;
use super::unsaved::Leave;
use crate::head::of_style::HeadFiles;
use crate::motion::playback::HeadPlayback;
use crate::style::Style;
use crate::window::live::head_motion::{HeadDriver, ManualPose};
use crate::window::live::live_sim::LiveSim;
use crate::window::live::motion_recorder::MotionRecorder;

/// Read-only views.
impl AppState {
    /// The style being edited, its file and its history.
    pub fn doc(&self) -> &StyleDoc {
        &self.doc
    }

    /// The main run.
    pub fn sim(&self) -> &LiveSim {
        &self.sim
    }

    /// The main run, to hand its engine the window's device.
    pub fn sim_mut(&mut self) -> &mut LiveSim {
        &mut self.sim
    }

    /// The compare view's second run and its methods, when on.
    pub fn compare(&self) -> Option<&(LiveSim, CompareMethods)> {
        self.compare.as_ref()
    }

    /// The head's motion: pose, clip, recorder, pivot.
    pub fn head(&self) -> &HeadDriver {
        &self.head
    }

    /// The head mesh, head coordinates.
    pub fn head_mesh(&self) -> &Arc<HeadMesh> {
        &self.head_mesh
    }

    /// The files of the head mesh and of the mesh collided with (`None`:
    /// the default head).
    pub fn head_files(&self) -> Option<&HeadFiles> {
        self.head_files.as_ref()
    }

    /// Live numbers.
    pub fn readouts(&self) -> &Readouts {
        &self.readouts
    }

    /// Whether the physics is paused.
    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// Why the edited style is not being simulated, if it is invalid.
    pub fn invalid(&self) -> Option<&str> {
        self.invalid.as_deref()
    }

    /// The last message for the user.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// The built-in presets, then the user's.
    pub fn presets(&self) -> impl Iterator<Item = &Preset> {
        self.presets.iter().chain(&self.user_presets)
    }

    /// The action waiting for "save your changes?", if any.
    pub fn leaving(&self) -> Option<&Leave> {
        self.leaving.as_ref()
    }

    /// Whether the window should close (the user asked, nothing unsaved).
    pub fn wants_to_quit(&self) -> bool {
        self.quit
    }

    /// What the stability guard did since the last edit, in words.
    pub fn guard(&self) -> &GuardStatus {
        &self.guard
    }

    /// The brush: tool, settings, the stroke under way, the recording.
    pub fn brush(&self) -> &BrushState {
        &self.brush
    }
}

/// Requests.
impl AppState {
    /// Shows `text` on the status line (until the style changes).
    pub fn say(&mut self, text: impl Into<String>) {
        self.message = Some(text.into());
    }

    /// Records the wall time between two displayed frames, seconds.
    pub fn record_frame_time(&mut self, secs: f64) {
        self.readouts.record_frame(secs);
    }

    /// Records how the frame's hair was drawn ([`Readouts::record_drawing`]).
    pub fn record_drawing(&mut self, on_device: Option<usize>) {
        self.readouts.record_drawing(on_device);
    }

    /// Pauses a running simulation, or runs a paused one.
    pub fn toggle_pause(&mut self) {
        self.paused = !self.paused;
    }

    /// Undoes the last edit, if any.
    pub fn undo(&mut self) {
        self.doc.undo();
    }

    /// Redoes the last undone edit, if any.
    pub fn redo(&mut self) {
        self.doc.redo();
    }

    /// Applies `change` to the style as one undo step.
    pub fn edit_style(&mut self, change: impl FnOnce(&mut Style)) {
        self.doc.edit(change);
    }

    /// Makes `edited` (the widgets' copy of the style) the style, unless it
    /// would turn a valid style invalid: then nothing changes and the
    /// message says which field and its range ("not applied: …"). Sliders
    /// cannot leave the format's ranges, so only typed values are refused.
    /// Edits in one drag become one undo step ([`StyleDoc::settle`]).
    pub fn propose_style(&mut self, edited: Style) {
        if *self.doc.style() == edited {
            return;
        }
        let was_valid = self.doc.validity().is_ok();
        let before = std::mem::replace(self.doc.style_mut(), edited);
        if was_valid && let Err(problem) = self.doc.validity() {
            *self.doc.style_mut() = before;
            self.say(format!("not applied: {problem}"));
        }
    }

    /// Closes the current undo step once the pointer is released.
    pub fn settle_edits(&mut self, dragging: bool) {
        self.doc.settle(dragging);
    }

    /// Uses `settings` for the brush from now on (the next stroke).
    pub fn set_brush_settings(&mut self, settings: BrushSettings) {
        self.brush.settings = settings;
    }

    /// Unmasks every strand masked on the scalp.
    pub fn clear_mask(&mut self) {
        self.brush.masked.clear();
    }

    /// Records every stroke from now on to `path`.
    pub fn record_strokes_to(&mut self, path: &Path) {
        self.brush.record_to(path);
        self.say(format!("recording strokes to {}", path.display()));
    }

    /// Stops recording strokes (what was recorded is on disk already).
    pub fn stop_recording_strokes(&mut self) {
        self.brush.recording = None;
    }

    /// Shows and exports with `mesh` as the head from now on (tests: the
    /// simulation keeps its collider).
    #[cfg(test)]
    pub fn use_head_mesh(&mut self, mesh: Arc<HeadMesh>) {
        self.head_mesh = mesh;
    }

    /// Holds the head in `pose` (the user's own; a clip plays on top).
    pub fn set_head_pose(&mut self, pose: ManualPose) {
        self.head.target = pose;
    }

    /// Starts recording the head's motion.
    pub fn record_head_motion(&mut self) {
        self.head.recorder = Some(MotionRecorder::default());
        self.say("recording the head's motion: drag it with Alt");
    }

    /// Ends the head's recording and hands it over, if one was running.
    pub fn take_head_recording(&mut self) -> Option<MotionRecorder> {
        self.head.recorder.take()
    }

    /// Plays a loaded motion on the head from now.
    pub fn play_head_motion(&mut self, playback: HeadPlayback) {
        let now = self.now_secs();
        self.head.play_motion(playback, now);
    }
}

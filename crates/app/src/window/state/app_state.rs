//! Everything the window shows and edits, with no window: the style
//! document, the running simulation (and the compare view's second run),
//! the head, presets and readouts. Tests drive it directly.
//!
//! Per displayed frame, [`AppState::step_frame`]:
//!
//! 1. checks the edited style; if it is valid, brings both runs in line
//!    with it ([`LiveSim::sync`], state kept); if not, the runs go on with
//!    the last valid style and the error is shown;
//! 2. steps the runs on the same head motion ([`HeadDriver::frame`]) and
//!    then advances the head;
//! 3. records times, energies, the runs' difference and guard messages.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use helixhair_physics::Method;
use helixhair_physics::engine::EngineKind;
use helixhair_render::HeadMesh;

use crate::head::of_style::HeadFiles;
use crate::style::Style;

use super::brush_state::BrushState;
use super::document::StyleDoc;
use super::guard_status::GuardStatus;
use super::head_of_style::{StyleHead, simulate_on, style_head};
use super::presets::{
    Preset, apply_preset, built_in_presets, load_user_presets, save_user_presets, user_presets_path,
};
use super::readouts::{PhysicsSample, Readouts};
use super::unsaved::Leave;
use crate::window::live::head_motion::{Clip, HeadDriver};
use crate::window::live::live_sim::{LiveSim, tip_difference_m};

/// The compare view's setting: which solver each side runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CompareMethods {
    /// Left view.
    pub left: Method,
    /// Right view.
    pub right: Method,
}

impl Default for CompareMethods {
    /// Dense (the whole mass matrix, solved directly: O(N³)) against Exact
    /// (the same matrix solved in O(N), with its velocity-implicit GMRES):
    /// two solvers that run every bundled style and preset at 60 Hz. The
    /// seed paper's Figure 1 pairs Dense with Block-diagonal, which today
    /// blows up under the guard on ordinary styles (a 15 cm wavy style:
    /// 162 interventions in its first second); it stays one pick away.
    fn default() -> Self {
        Self {
            left: Method::Dense,
            right: Method::Exact,
        }
    }
}

/// The application's state. Its fields are the state module's own: the
/// panels read them through [`AppState`]'s accessors and ask for changes
/// through its methods ([`super::requests`]), which keep what belongs
/// together together (an edit that would make the style invalid is not
/// applied; a message is posted with the style it is about).
#[derive(Debug)]
pub struct AppState {
    /// The style being edited.
    pub(in crate::window::state) doc: StyleDoc,
    /// The main run.
    pub(in crate::window::state) sim: LiveSim,
    /// The compare view's second run and its methods, when on.
    pub(in crate::window::state) compare: Option<(LiveSim, CompareMethods)>,
    /// The head's motion.
    pub(in crate::window::state) head: HeadDriver,
    /// The head mesh, head coordinates.
    pub(in crate::window::state) head_mesh: Arc<HeadMesh>,
    /// The files of `head_mesh` and of the mesh collided with (`None`: the
    /// default head).
    pub(in crate::window::state) head_files: Option<HeadFiles>,
    /// Live numbers.
    pub(in crate::window::state) readouts: Readouts,
    /// Physics paused.
    pub(in crate::window::state) paused: bool,
    /// Why the edited style is not being simulated, if it is invalid.
    pub(in crate::window::state) invalid: Option<String>,
    /// The last message for the user (load and save errors, notices).
    pub(in crate::window::state) message: Option<String>,
    /// Built-in presets.
    pub(in crate::window::state) presets: Vec<Preset>,
    /// The user's presets and their file.
    pub(in crate::window::state) user_presets: Vec<Preset>,
    /// Where the user's presets are saved.
    pub(in crate::window::state) user_presets_path: PathBuf,
    /// An action waiting for "save your changes?" ([`super::unsaved`]).
    pub(in crate::window::state) leaving: Option<Leave>,
    /// The window should close (the user asked, and nothing is unsaved).
    pub(in crate::window::state) quit: bool,
    /// What the stability guard did since the last edit, in words.
    pub(in crate::window::state) guard: GuardStatus,
    /// The GPU engine's last note ([`helixhair_physics::Engine::gpu_note`])
    /// as posted: a new one that is not "on the GPU" (a fallback) goes to
    /// the status line once.
    gpu_note_seen: Option<String>,
    /// The brush: tool, settings, the stroke under way, the recording.
    pub(in crate::window::state) brush: BrushState,
    /// The message as last seen and the style it was posted on: once the
    /// style changes, the message is about a style that is gone.
    message_posted: (Option<String>, Option<Style>),
}

impl AppState {
    /// Starts on `style` (valid), from file `path` if it came from one.
    pub fn new(style: Style, path: Option<&Path>) -> Result<Self, String> {
        let mut doc = StyleDoc::new(style);
        if let Some(path) = path {
            // Reloading gives the document its file and a clean state.
            doc.load(path).map_err(|e| e.to_string())?;
        }
        // The head the style names (an imported groom's), else the default
        // one; the simulation is built once, on it.
        let mut message = None;
        let head = style_head(&doc).unwrap_or_else(|e| {
            message = Some(format!("the style's head is not used: {e}"));
            StyleHead::default_head()
        });
        let mut driver = HeadDriver::default();
        driver.pivot_m = head.pivot_m;
        let sim = match simulate_on(&doc, &head) {
            Ok(sim) => sim,
            Err(e) => {
                // No collider (or none from this mesh): simulate without.
                message = Some(e);
                LiveSim::new(doc.style(), head.mesh.clone(), None, None)
                    .map_err(|e| e.to_string())?
            }
        };
        let user_presets_path = user_presets_path();
        let user_presets = load_user_presets(&user_presets_path).unwrap_or_else(|e| {
            message = Some(format!("{e:#}"));
            Vec::new()
        });
        Ok(Self {
            doc,
            sim,
            compare: None,
            head: driver,
            head_mesh: head.mesh,
            head_files: head.files,
            readouts: Readouts::default(),
            paused: false,
            invalid: None,
            message,
            presets: built_in_presets(),
            user_presets,
            user_presets_path,
            leaving: None,
            quit: false,
            guard: GuardStatus::default(),
            gpu_note_seen: None,
            brush: BrushState::default(),
            message_posted: (None, None),
        })
    }

    /// Clears a status message posted before the last edit: it spoke of
    /// the style before it (a message posted with an edit stays until
    /// the next one).
    fn retire_stale_message(&mut self) {
        let style = self.doc.style();
        if self.message != self.message_posted.0 {
            self.message_posted = (self.message.clone(), Some(style.clone()));
        } else if self.message.is_some() && self.message_posted.1.as_ref() != Some(style) {
            self.message = None;
            self.message_posted = (None, None);
        }
    }

    /// Simulated time, seconds.
    pub fn now_secs(&self) -> f64 {
        self.sim.now_secs()
    }

    /// Plays a built-in head motion from now.
    pub fn play(&mut self, clip: Clip) {
        let now = self.now_secs();
        self.head.play(clip, now);
    }

    /// Turns the compare view on (both runs start from the main run's
    /// current state, on the reference engine: the solvers it compares are
    /// not all on the batch engine) or off (back to the style's engine).
    pub fn set_compare(&mut self, methods: Option<CompareMethods>) {
        let reference = Some(EngineKind::Reference);
        let result = match methods {
            Some(m) => self
                .sim
                .set_overrides(reference, Some(m.left))
                .and_then(|()| {
                    let mut right = self.sim.clone();
                    right.set_overrides(reference, Some(m.right))?;
                    self.compare = Some((right, m));
                    Ok(())
                }),
            None => {
                self.compare = None;
                self.sim.set_overrides(None, None)
            }
        };
        if let Err(e) = result {
            self.message = Some(e.to_string());
        }
    }

    /// Loads a style file; on error nothing changes and the message names
    /// file, line and field.
    pub fn load(&mut self, path: &Path) {
        self.cancel_stroke();
        self.message = match self.doc.load(path) {
            Ok(()) => {
                // Nothing of the last style's runs carries over: its
                // readouts and guard lines, the guard's count, the compare
                // view.
                self.readouts = Readouts::default();
                self.guard = GuardStatus::default();
                if self.compare.is_some() {
                    self.set_compare(None);
                }
                Some(format!("loaded {}", path.display()))
            }
            Err(e) => Some(e.to_string()),
        };
        self.adopt_head();
    }

    /// Saves the style (to `path`, or its file).
    pub fn save(&mut self, path: Option<&Path>) {
        self.message = Some(match self.doc.save(path) {
            Ok(p) => format!("saved {}", p.display()),
            Err(e) => e,
        });
    }

    /// Applies a preset to group `group` as one undo step.
    /// The message says so when the preset also raised the style's
    /// substeps, which every group shares.
    pub fn apply_preset(&mut self, group: usize, preset: &Preset) {
        let substeps = self.doc.style().sim.substeps;
        self.doc.edit(|s| apply_preset(s, group, preset));
        let now = self.doc.style().sim.substeps;
        let name = &preset.name;
        self.message = Some(if now != substeps {
            format!(
                "preset `{name}` applied; the style's substeps (all groups) rose from {substeps} \
                 to {now}, the fewest it is stable with"
            )
        } else {
            format!("preset `{name}` applied")
        });
    }

    /// Saves group `group`'s parameters as the user's preset `name`
    /// (replacing one of the same name).
    pub fn save_user_preset(&mut self, group: usize, name: &str) {
        let Some(g) = self.doc.style().groups.get(group) else {
            return;
        };
        let preset = Preset {
            name: name.to_string(),
            params: g.params.clone(),
            min_substeps: self.doc.style().sim.substeps,
        };
        self.user_presets.retain(|p| p.name != name);
        self.user_presets.push(preset);
        self.message = Some(
            match save_user_presets(&self.user_presets_path, &self.user_presets) {
                Ok(()) => format!("preset `{name}` saved"),
                Err(e) => format!("{e:#}"),
            },
        );
    }

    /// One displayed frame of physics (see the module docs).
    pub fn step_frame(&mut self) {
        self.retire_stale_message();
        self.invalid = self.doc.validity().err();
        if self.invalid.is_none() {
            let style = self.doc.style();
            for sim in std::iter::once(&mut self.sim).chain(self.compare.as_mut().map(|(s, _)| s)) {
                if let Err(e) = sim.sync(style) {
                    self.invalid = Some(e.to_string());
                }
            }
        }
        if self.paused {
            return;
        }
        let frame = self.head.frame(self.sim.now_secs());
        self.head.record(&frame);
        let started = Instant::now();
        if self.brush.active.is_some() {
            self.drag_stroke();
        } else {
            self.sim.step(&frame);
        }
        if let Some((right, _)) = &mut self.compare {
            right.step(&frame);
        }
        let wall_secs = started.elapsed().as_secs_f64();
        self.head.advance(self.sim.engine().settings().dt_secs);
        let difference_m = self
            .compare
            .as_ref()
            .map(|(right, _)| tip_difference_m(&self.sim.tips_m(), &right.tips_m()));
        let mut element_steps = self.sim.element_steps_per_frame();
        if let Some((right, _)) = &self.compare {
            element_steps += right.element_steps_per_frame();
        }
        let sample = PhysicsSample {
            time_secs: self.sim.now_secs(),
            wall_secs,
            stages: self.sim.stage_times(),
            element_steps,
            energies: self.sim.energies(),
            difference_m,
        };
        let label = match &self.compare {
            Some((_, m)) => m.left.label(),
            None => String::new(),
        };
        self.readouts
            .record_physics(sample, self.sim.guard_events(), &label);
        let guard = self.sim.guard_frame();
        self.guard.record(self.doc.style(), &guard);
        if let Some(note) = self.sim.engine().gpu_note()
            && self.gpu_note_seen.as_deref() != Some(note)
        {
            if !note.starts_with("physics on the GPU") {
                self.message = Some(format!("GPU engine: {note}."));
            }
            self.gpu_note_seen = Some(note.to_owned());
        }
        if let Some((right, m)) = &self.compare {
            let events = right.guard_events().to_vec();
            self.readouts
                .record_physics_events(&events, &m.right.label());
        }
    }
}

#[cfg(test)]
#[path = "tests/app_state_tests.rs"]
mod tests;

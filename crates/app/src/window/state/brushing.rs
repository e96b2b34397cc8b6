//! Strokes in the window: picking a tool, and a stroke begun, dragged,
//! ended or cancelled ([`AppState`]'s brush methods; the state they keep
//! is [`super::brush_state`]).
//!
//! A stroke in the window is the same [`StrokeRun`] `helixhair groom`
//! replays, hosted by the live run with the head held still
//! ([`StillHead`]): pressing in the view begins it where the pointer meets
//! the hair or the scalp, each frame of the drag steps the physics with
//! the brush at the pointer, and releasing finishes it. Its changes reach
//! the style as per-strand edits, one undo step per stroke; Esc during a
//! stroke puts the hair and the style back as they were at its start.
//!
//! The brush pushes hair only on the reference engine (the strands that
//! take external forces), so while a brush tool is picked the run is on
//! the reference engine, the hair's state carried over; picking Orbit
//! goes back to the style's engine. The head stops where it is when a
//! stroke begins ([`crate::window::live::head_motion::HeadDriver::hold`]):
//! styling is done on a still head, as in a salon.

use glam::DVec3;
use helixhair_physics::engine::EngineKind;

use crate::brush::stroke_run::StrokeRun;
use crate::brush::strokes::{MAX_STROKE_SECS, StrandRef};
use crate::style::ron_file::RonFile;
use crate::window::live::still_head::StillHead;

use super::app_state::AppState;
use super::brush_state::{ActiveStroke, ToolKind, WINDOW_SETTLE_SECS};

impl AppState {
    /// Picks a tool; a brush tool puts the run on the reference engine (its
    /// strands take the brush's forces), Orbit puts it back on the style's.
    pub fn set_tool(&mut self, kind: ToolKind) {
        if self.brush.active.is_some() {
            self.cancel_stroke();
        }
        self.brush.settings.kind = kind;
        let engine = (kind != ToolKind::Orbit).then_some(EngineKind::Reference);
        if self.compare.is_none()
            && let Err(e) = self.sim.set_overrides(engine, None)
        {
            self.message = Some(e.to_string());
        }
    }

    /// Begins a stroke of the picked tool with the brush at `at_m` (world);
    /// false (with a message saying why) when no stroke can begin.
    pub fn begin_stroke(&mut self, at_m: DVec3) -> bool {
        let why_not = if self.compare.is_some() {
            Some("the brush works on one run: turn the compare view off first")
        } else if self.invalid.is_some() {
            Some("fix the style first: it is not being simulated")
        } else {
            None
        };
        if let Some(why) = why_not {
            self.message = Some(why.into());
            return false;
        }
        // A style loaded since the tool was picked runs on its own engine.
        if self.sim.kind() != EngineKind::Reference
            && let Err(e) = self.sim.set_overrides(Some(EngineKind::Reference), None)
        {
            self.message = Some(e.to_string());
            return false;
        }
        let names = self.doc.style().group_names();
        let Some(settings) = self.brush.settings.stroke(&names, &self.brush.masked) else {
            return false;
        };
        self.head.hold();
        let before = self.sim.clone();
        let host = StillHead {
            head: self.head.frame(self.sim.now_secs()),
            sim: &mut self.sim,
        };
        let run = StrokeRun::begin(&host, &settings, at_m);
        self.brush.active = Some(ActiveStroke {
            run,
            before,
            centre_m: at_m,
            last_centre_m: at_m,
        });
        true
    }

    /// Masks (or, with `unmask`, unmasks) every strand whose root lies
    /// within the brush's radius of `at_m` (world); returns how many
    /// changed.
    pub fn paint_mask(&mut self, at_m: DVec3, unmask: bool) -> usize {
        let radius_m = self.brush.settings.radius_m;
        let engine = self.sim.engine();
        let groups = &self.sim.grown_style().groups;
        let mut changed = 0;
        for (i, strand) in self.sim.strands().iter().enumerate() {
            let Some(root) = engine.boundary_points_world(i).first().copied() else {
                continue;
            };
            if root.distance(at_m) > radius_m {
                continue;
            }
            let which = StrandRef {
                group: groups[strand.group].name.clone(),
                strand: strand.strand as u32,
            };
            changed += usize::from(if unmask {
                self.brush.masked.remove(&which)
            } else {
                self.brush.masked.insert(which)
            });
        }
        changed
    }

    /// Moves the brush of the stroke under way to `at_m` (world); the next
    /// physics frame drags it there.
    pub fn move_brush(&mut self, at_m: DVec3) {
        if let Some(active) = &mut self.brush.active {
            active.centre_m = at_m;
        }
    }

    /// One physics frame of the stroke under way (in place of the plain
    /// step): the brush moved from its last place to where the pointer put
    /// it over the frame.
    pub(super) fn drag_stroke(&mut self) {
        let Some(active) = &mut self.brush.active else {
            return;
        };
        let dt = self.sim.engine().settings().dt_secs;
        let velocity = (active.centre_m - active.last_centre_m) / dt;
        active.last_centre_m = active.centre_m;
        let mut host = StillHead {
            head: self.head.frame(self.sim.now_secs()),
            sim: &mut self.sim,
        };
        if let Err(e) = active.run.drag(&mut host, active.centre_m, velocity) {
            self.message = Some(format!("stroke stopped: {e:#}"));
            self.cancel_stroke();
        }
    }

    /// Ends the stroke under way: its changes become one undo step of the
    /// style, and the stroke joins the recording.
    pub fn end_stroke(&mut self) {
        let Some(active) = self.brush.active.take() else {
            return;
        };
        let dt = self.sim.engine().settings().dt_secs;
        let drives = active.run.drives();
        let settle_frames = match self.brush.settings.kind {
            ToolKind::Part | ToolKind::Smooth | ToolKind::Curl => {
                (WINDOW_SETTLE_SECS / dt).round() as usize
            }
            _ => 0,
        };
        let head_pose = *self.sim.engine().head();
        let mut host = StillHead {
            head: self.head.frame(self.sim.now_secs()),
            sim: &mut self.sim,
        };
        let (mut stroke, outcome) = match active.run.finish(&mut host, settle_frames) {
            Ok(done) => done,
            Err(e) => {
                self.sim = active.before;
                self.message = Some(format!("stroke not applied: {e:#}"));
                return;
            }
        };
        // The strokes' edits into the document, as one undo step.
        let edited = self.sim.built_style().clone();
        self.doc.edit(|s| {
            for (group, from) in s.groups.iter_mut().zip(&edited.groups) {
                group.edits = from.edits.clone();
            }
        });
        let mut message = outcome.describe();
        if outcome.frozen.unstable > 0 {
            message += "; unstable strands will fall from their shape";
        }
        // Recorded in head coordinates, timed as made.
        stroke.path = stroke
            .path
            .iter()
            .map(|p| head_pose.world_from_body.transpose() * (*p - head_pose.position_m))
            .collect();
        if drives {
            stroke.seconds = (outcome.frames as f64 * dt).min(MAX_STROKE_SECS);
        }
        if let Some(recording) = &mut self.brush.recording {
            recording.file.strokes.push(stroke);
            let header = "HelixHair brush strokes, recorded in the window; replay with `helixhair groom --strokes`";
            match recording.file.save(&recording.path, header) {
                Ok(()) => {
                    message += &format!(
                        "; {} strokes recorded to {}",
                        recording.file.strokes.len(),
                        recording.path.display()
                    )
                }
                Err(e) => message += &format!("; recording failed: {e}"),
            }
        }
        self.message = Some(message);
        self.brush.last = Some(outcome);
    }

    /// Cancels the stroke under way: the hair and the style as they were at
    /// its start.
    pub fn cancel_stroke(&mut self) {
        if let Some(active) = self.brush.active.take() {
            self.sim = active.before;
            self.message = Some("stroke cancelled".into());
        }
    }
}

#[cfg(test)]
#[path = "tests/brushing_tests.rs"]
mod tests;

//! One stroke as it happens: begun where the brush touches, dragged frame
//! by frame with the physics running, and finished, leaving its changes in
//! the style. The window feeds it the pointer's brush centre each frame;
//! `helixhair groom` feeds it a stroke file's path at constant speed
//! ([`crate::brush::session::GroomSession::apply`]); both run this code.
//!
//! # Forces
//!
//! The comb is a velocity-matching drag: a point of weight w under the
//! brush feels ρS μ w (v_brush − v) per unit length, μ =
//! [`COMB_DRAG_PER_S`] × strength, so the hair under the brush is carried
//! along at the brush's speed within a few frames, as a comb's teeth carry
//! it, and the rest of each strand follows through the physics. The grab is
//! a damped spring from each point it took to that point's place moved with
//! the brush (stiffness [`GRAB_STIFFNESS_PER_S2`], damping
//! [`GRAB_DAMPING_PER_S`], per unit mass). Both are explicit forces over a
//! step h = 1/60 s: μh = 1 and kh² = 0.11, inside the explicit limits
//! (2 and 4).
//!
//! The other tools act once, at the stroke's end, on every strand the
//! swept brush reached ([`crate::brush::tools`]); while they are dragged
//! the physics runs as usual and the path is recorded.

use std::time::Instant;

use glam::DVec3;

use crate::brush::freeze::RestCounts;
use crate::brush::host::{BrushHost, reached_strands, step_with_forces, strands_allowed};
use crate::brush::sphere::Reach;
use crate::brush::strokes::{Stroke, Tool};
use crate::brush::tools::{self, indices};

/// The comb's drag rate at full strength, 1/s: μh = 1 at 60 Hz, so a free
/// point under the brush would take the brush's velocity in one step, the
/// strongest explicit drag that does not overshoot (2 is its stability
/// limit). At 40/s a comb dragged 6 cm through a hanging tip carried it
/// 1.2 cm; at 60/s, 2.2 cm (the strand's weight pulls it back out of the
/// brush).
pub const COMB_DRAG_PER_S: f64 = 60.0;

/// The grab's spring per unit mass at full strength, 1/s²: a natural
/// frequency of about 3 Hz, so a grabbed lock follows a hand's drag.
pub const GRAB_STIFFNESS_PER_S2: f64 = 400.0;

/// The grab's damping per unit mass at full strength, 1/s (0.7 of
/// critical at [`GRAB_STIFFNESS_PER_S2`]).
pub const GRAB_DAMPING_PER_S: f64 = 28.0;

/// Closest two recorded path points may lie, metres: a brush held still
/// adds no points, so a recorded path is not thousands of repeats.
pub const PATH_SPACING_M: f64 = 0.001;

/// What one stroke did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StrokeOutcome {
    /// The tool's name.
    pub tool: &'static str,
    /// Strands the brush reached.
    pub touched: usize,
    /// Strands whose parameters or shape the stroke changed.
    pub changed: usize,
    /// Strands frozen, by outcome.
    pub frozen: RestCounts,
    /// Frames the physics ran.
    pub frames: usize,
    /// Wall time, seconds.
    pub wall_secs: f64,
    /// Of it, the freeze's (the sag-free solves and the engine's rebuild),
    /// seconds.
    pub freeze_secs: f64,
    /// Guard interventions during the stroke.
    pub guard_events: usize,
}

impl StrokeOutcome {
    /// One line for a report.
    pub fn describe(&self) -> String {
        let mut line = format!(
            "{}: {} strands reached, {} changed",
            self.tool, self.touched, self.changed
        );
        if self.frozen.total() > 0 {
            line += &format!(
                ", {} frozen in {:.2} s ({})",
                self.frozen.total(),
                self.freeze_secs,
                self.frozen.describe()
            );
        }
        line += &format!("; {} frames in {:.2} s", self.frames, self.wall_secs);
        if self.guard_events > 0 {
            line += &format!("; the guard stepped in {} times", self.guard_events);
        }
        line
    }
}

/// A stroke under way.
#[derive(Clone, Debug)]
pub struct StrokeRun {
    /// The stroke's settings and the path so far.
    stroke: Stroke,
    /// Grab: per strand, the points held at the start, each with its
    /// weight and offset from the brush centre.
    held: Vec<Vec<(f64, DVec3)>>,
    /// Strands the brush's forces reached.
    moved: Vec<bool>,
    /// Strands the stroke may touch (its groups, less its masked strands).
    allowed: Vec<bool>,
    /// Whether dragging adds to the path (a stroke made live), or the
    /// path was given whole (a stroke replayed from a file).
    recording: bool,
    outcome: StrokeOutcome,
    started: Instant,
}

impl StrokeRun {
    /// Begins `settings` (its tool, radius, strength, falloff, freeze and
    /// groups; its path is ignored) with the brush at `at` (world).
    pub fn begin(host: &impl BrushHost, settings: &Stroke, at: DVec3) -> Self {
        let stroke = Stroke {
            path: vec![at],
            ..settings.clone()
        };
        Self::new(host, stroke, true)
    }

    /// Begins `stroke` as recorded, its whole path given (a Grab takes hold
    /// at the path's start): [`StrokeRun::drag`] then moves the brush
    /// without adding to the path.
    pub fn replay(host: &impl BrushHost, stroke: &Stroke) -> Self {
        Self::new(host, stroke.clone(), false)
    }

    fn new(host: &impl BrushHost, stroke: Stroke, recording: bool) -> Self {
        let at = stroke.path.first().copied().unwrap_or(DVec3::ZERO);
        let count = host.strands().len();
        let allowed = strands_allowed(host, &stroke);
        let held = match stroke.tool {
            Tool::Grab => {
                let reach = Reach::sphere(at, stroke.radius_m, stroke.falloff);
                let eligible = reached_strands(host, &reach, |i| allowed[i]);
                let mut held = vec![Vec::new(); count];
                for (i, _) in eligible {
                    let (root, kin) = host.engine().kinematics(i);
                    held[i] = kin
                        .samples
                        .iter()
                        .map(|s| {
                            let p = root.position_m + s.position_m;
                            (reach.weight(p), p - at)
                        })
                        .collect();
                }
                held
            }
            _ => Vec::new(),
        };
        Self {
            outcome: StrokeOutcome {
                tool: stroke.tool.name(),
                ..StrokeOutcome::default()
            },
            stroke,
            held,
            recording,
            allowed,
            moved: vec![false; count],
            started: Instant::now(),
        }
    }

    /// The stroke as made so far (its path recorded).
    pub fn stroke(&self) -> &Stroke {
        &self.stroke
    }

    /// Whether the tool drives the hair while it is dragged.
    pub fn drives(&self) -> bool {
        matches!(self.stroke.tool, Tool::Comb | Tool::Grab)
    }

    /// One frame with the brush at `centre` moving at `velocity` (world,
    /// m/s): Comb and Grab push the hair, the other tools let the physics
    /// run. The centre joins the recorded path.
    pub fn drag(
        &mut self,
        host: &mut impl BrushHost,
        centre: DVec3,
        velocity: DVec3,
    ) -> anyhow::Result<()> {
        if self.recording
            && self
                .stroke
                .path
                .last()
                .is_none_or(|last| last.distance(centre) >= PATH_SPACING_M)
        {
            self.stroke.path.push(centre);
        }
        let stroke = &self.stroke;
        let strength = stroke.strength;
        let reach = Reach::sphere(centre, stroke.radius_m, stroke.falloff);
        let held = &self.held;
        let allowed = &self.allowed;
        let (touched, events) = match stroke.tool {
            Tool::Comb | Tool::Grab => step_with_forces(
                host,
                |i, j, p, v| {
                    let relative = velocity - v;
                    match stroke.tool {
                        Tool::Grab => held[i].get(j).map_or(DVec3::ZERO, |&(w, offset)| {
                            let to_target = centre + offset - p;
                            w * strength
                                * (GRAB_STIFFNESS_PER_S2 * to_target
                                    + GRAB_DAMPING_PER_S * relative)
                        }),
                        _ => reach.weight(p) * strength * COMB_DRAG_PER_S * relative,
                    }
                },
                |i| allowed.get(i).copied().unwrap_or(false),
            )?,
            _ => (Vec::new(), host.step_frame()),
        };
        for i in touched {
            self.moved[i] = true;
        }
        self.outcome.frames += 1;
        self.outcome.guard_events += events;
        Ok(())
    }

    /// Ends the stroke: Comb and Grab freeze the strands they moved (when
    /// the stroke says so); the other tools act on every strand the swept
    /// brush reached, the hair settling `settle_frames` frames where the
    /// tool needs it (a parting, a curl, a smoothing). Returns the stroke
    /// as made and what it did.
    pub fn finish(
        mut self,
        host: &mut impl BrushHost,
        settle_frames: usize,
    ) -> anyhow::Result<(Stroke, StrokeOutcome)> {
        let stroke = self.stroke.clone();
        let out = &mut self.outcome;
        let frozen = |host: &mut _, which: &[usize], out: &mut StrokeOutcome| {
            let (counts, secs) = tools::freeze(host, which)?;
            out.frozen = counts;
            out.freeze_secs = secs;
            anyhow::Ok(())
        };
        let settled = |host: &mut _, out: &mut StrokeOutcome| {
            out.guard_events += tools::settle(host, settle_frames)?;
            out.frames += settle_frames;
            anyhow::Ok(())
        };
        match &stroke.tool {
            Tool::Comb | Tool::Grab => {
                let moved: Vec<usize> = (0..self.moved.len()).filter(|&i| self.moved[i]).collect();
                out.touched = moved.len();
                out.changed = moved.len();
                if stroke.freeze {
                    frozen(host, &moved, out)?;
                }
            }
            Tool::Freeze => {
                let reached = tools::reached(host, &stroke);
                out.touched = reached.len();
                out.changed = reached.len();
                frozen(host, &indices(&reached), out)?;
                settled(host, out)?;
            }
            Tool::Smooth => {
                let reached = tools::reached(host, &stroke);
                out.touched = reached.len();
                out.changed = tools::smooth(host, &reached, stroke.strength);
                settled(host, out)?;
                if stroke.freeze {
                    frozen(host, &indices(&reached), out)?;
                }
            }
            Tool::Part { angle_deg } => {
                let parted = tools::part(host, &stroke, *angle_deg)?;
                out.touched = parted.len();
                out.changed = parted.len();
                settled(host, out)?;
                if stroke.freeze {
                    frozen(host, &parted, out)?;
                }
            }
            Tool::Curl { radius_m, step_m } => {
                let reached = tools::reached(host, &stroke);
                out.touched = reached.len();
                out.changed = reached.len();
                out.guard_events += tools::curl(
                    host,
                    &reached,
                    stroke.strength,
                    (*radius_m, *step_m),
                    settle_frames,
                )?;
                out.frames += settle_frames;
            }
            Tool::Cut { .. } | Tool::Grow { .. } | Tool::Stiffness { .. } => {
                let reached = tools::reached(host, &stroke);
                out.touched = reached.len();
                out.changed = tools::paint(host, &stroke.tool, &reached, stroke.strength)?;
                settled(host, out)?;
            }
        }
        out.wall_secs = self.started.elapsed().as_secs_f64();
        Ok((stroke, self.outcome))
    }
}

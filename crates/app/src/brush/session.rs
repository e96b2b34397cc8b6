//! A styling session: a style's hair simulated on its head while strokes
//! act on it, and the style it leaves behind.
//!
//! # How it works
//!
//! The session grows the style on its head and simulates it on the f64
//! reference engine (the engine whose strands take external forces: the
//! brush's drag and springs), colliding with the head, the head still. Each
//! stroke ([`crate::brush::strokes::Stroke`]) then either drives the hair
//! while the physics runs (Comb, Grab), or changes strands' parameters at
//! once (Cut, Grow, Curl, Stiffness, Part), or their shapes (Smooth,
//! Freeze), and the hair settles for the rest of the stroke's time, so the
//! next stroke meets it at rest. Settling is the physics with a drag
//! ([`SETTLE_DRAG_PER_S`]) that brings swinging hair to rest within a
//! second; the session starts with [`START_SETTLE_SECS`] of it, from the
//! style's hair as it hangs.
//!
//! Every change is kept as a per-strand edit of the style
//! ([`crate::style::strand_edit`]): the session edits the grown style (whose
//! strand numbers the edits name) and hands the same edits to the style as
//! written, which keeps its placements and drawn strands. A change of
//! parameters rebuilds the engine from the edited style through the one
//! builder ([`crate::sim::strands`]), every strand's state carried over (by
//! arc length where a cut or growth changed its elements), so the session
//! is the style: reloading the saved style starts each edited strand where
//! the session left it (a frozen strand in its frozen shape).
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
//! step h = 1/60 s: μh = 0.67 and kh² = 0.11, inside the explicit limits
//! (2 and 4) with room.

use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context as _, anyhow};
use glam::DVec3;
use helixhair_physics::collision::SignedDistanceField;
use helixhair_physics::engine::{Engine, EngineKind};
use helixhair_physics::natural_shape::helix_strains;
use helixhair_physics::{NaturalShape, StrandParams};
use rayon::prelude::*;

use crate::brush::freeze::{RestCounts, freeze_strands};
use crate::brush::sphere::{Reach, closest_on_segment};
use crate::brush::strokes::{Stroke, Tool};
use crate::head::groom::Groom;
use crate::sim::headless::{HeadlessSim, SimOverrides};
use crate::sim::resample::{resample_by_arc_length, resample_per_element};
use crate::sim::strands::{StyleStrand, style_strands};
use crate::style::Style;
use crate::style::strand_edit::{StrandEdit, edit_mut, elements_for_length};

/// The comb's drag rate at full strength, 1/s: the hair under the brush
/// reaches the brush's speed within about two frames at 60 Hz.
pub const COMB_DRAG_PER_S: f64 = 40.0;

/// The grab's spring per unit mass at full strength, 1/s²: a natural
/// frequency of about 3 Hz, so a grabbed lock follows a hand's drag.
pub const GRAB_STIFFNESS_PER_S2: f64 = 400.0;

/// The grab's damping per unit mass at full strength, 1/s (0.7 of
/// critical at [`GRAB_STIFFNESS_PER_S2`]).
pub const GRAB_DAMPING_PER_S: f64 = 28.0;

/// The drag that settles the hair between strokes and before the first,
/// 1/s: a swing of hanging hair at 1 Hz is then damped at 0.64 of
/// critical and a slow creep over the head (0.3 Hz) at 2, so both come to
/// rest within about two seconds instead of swinging for many, and each
/// stroke meets the hair at rest.
pub const SETTLE_DRAG_PER_S: f64 = 8.0;

/// Simulated time the session lets the hair settle before the first
/// stroke, seconds.
pub const START_SETTLE_SECS: f64 = 3.0;

/// The steps a painted curl is blended in over (see [`GroomSession`]'s
/// Curl): ten, each a sixth of the way at most through a tight curl's
/// strain change in the default half second, slow enough that no strand
/// whips.
pub const CURL_RAMP_STEPS: usize = 10;

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

/// A style's hair on its head, styled stroke by stroke.
pub struct GroomSession {
    /// The style as written and grown, with the edits made so far.
    groom: Groom,
    /// The simulation of the grown style.
    sim: HeadlessSim,
    /// The head's collider, kept for rebuilds.
    collider: Option<Arc<SignedDistanceField>>,
    /// The engine's strands: group and number of each.
    strands: Vec<StyleStrand>,
    /// Guard interventions in the session.
    guard_total: usize,
    /// Wall time spent freezing in the session, seconds.
    freeze_secs: f64,
}

impl GroomSession {
    /// A session on `groom` (a style grown on its head) simulated by
    /// `sim` (built from it, colliding with the head). The session runs
    /// the reference engine whatever the style says: its strands take the
    /// brush's forces.
    pub fn new(groom: Groom, sim: HeadlessSim) -> anyhow::Result<Self> {
        let collider = sim.engine().collider().cloned();
        let mut session = Self {
            strands: style_strands(&groom.grown, |_, g| g.params.clone()),
            groom,
            sim,
            collider,
            guard_total: 0,
            freeze_secs: 0.0,
        };
        if session.sim.engine().kind() != EngineKind::Reference {
            session.rebuild(&[])?;
        }
        // The artist starts from the hair at rest, as it hangs. A strand
        // with a rest shape (imported sag-free, or frozen) starts in an
        // equilibrium already; one in its natural shape falls into its own.
        if session.strands.iter().any(|s| s.rest_strains.is_none()) {
            session.settle(session.frames_of(START_SETTLE_SECS))?;
        }
        Ok(session)
    }

    /// The style as written, with every edit the strokes made.
    pub fn style(&self) -> Style {
        let mut style = self.groom.style.clone();
        for (written, grown) in style.groups.iter_mut().zip(&self.groom.grown.groups) {
            written.edits = grown.edits.clone();
        }
        style
    }

    /// The simulation.
    pub fn sim(&self) -> &HeadlessSim {
        &self.sim
    }

    /// Applies one stroke, the physics running for its time.
    pub fn apply(&mut self, stroke: &Stroke) -> anyhow::Result<StrokeOutcome> {
        let start = Instant::now();
        let events_before = self.guard_total;
        let freeze_before = self.freeze_secs;
        let mut outcome = StrokeOutcome {
            tool: stroke.tool.name(),
            ..StrokeOutcome::default()
        };
        let frames = self.frames_of(stroke.seconds);
        match &stroke.tool {
            Tool::Comb | Tool::Grab => {
                let moved = self.drive(stroke, frames)?;
                outcome.touched = moved.len();
                outcome.changed = moved.len();
                if stroke.freeze {
                    outcome.frozen = self.freeze(&moved)?;
                }
            }
            Tool::Freeze => {
                let reached = self.reached(stroke);
                outcome.touched = reached.len();
                outcome.changed = reached.len();
                outcome.frozen = self.freeze(&indices(&reached))?;
                self.settle(frames)?;
            }
            Tool::Smooth => {
                let reached = self.reached(stroke);
                outcome.touched = reached.len();
                outcome.changed = self.smooth(&reached, stroke.strength);
                self.settle(frames)?;
                if stroke.freeze {
                    outcome.frozen = self.freeze(&indices(&reached))?;
                }
            }
            Tool::Part { angle_deg } => {
                let parted = self.part(stroke, *angle_deg)?;
                outcome.touched = parted.len();
                outcome.changed = parted.len();
                self.settle(frames)?;
                if stroke.freeze {
                    outcome.frozen = self.freeze(&parted)?;
                }
            }
            Tool::Curl { radius_m, step_m } => {
                let reached = self.reached(stroke);
                outcome.touched = reached.len();
                outcome.changed = reached.len();
                self.curl(&reached, stroke.strength, *radius_m, *step_m, frames)?;
            }
            Tool::Cut { .. } | Tool::Grow { .. } | Tool::Stiffness { .. } => {
                let reached = self.reached(stroke);
                outcome.touched = reached.len();
                outcome.changed = self.paint(&stroke.tool, &reached, stroke.strength)?;
                self.settle(frames)?;
            }
        }
        outcome.frames = frames;
        outcome.wall_secs = start.elapsed().as_secs_f64();
        outcome.guard_events = self.guard_total - events_before;
        outcome.freeze_secs = self.freeze_secs - freeze_before;
        Ok(outcome)
    }

    /// Frames in `seconds` of simulated time.
    fn frames_of(&self, seconds: f64) -> usize {
        (seconds / self.sim.engine().settings().dt_secs).round() as usize
    }

    /// Steps `frames` frames with no brush.
    fn settle(&mut self, frames: usize) -> anyhow::Result<()> {
        for _ in 0..frames {
            self.step_with_forces(|_, _, _, v| -SETTLE_DRAG_PER_S * v, |_| true)?;
        }
        Ok(())
    }

    /// Steps one frame with an external force per unit mass on every
    /// quadrature sample of the strands of the groups `in_group` accepts:
    /// `accel(strand, sample, position, velocity)` (world, m/s²; the head
    /// is still, so world velocities are the hair's own). Returns the
    /// strands that felt a force.
    fn step_with_forces(
        &mut self,
        accel: impl Fn(usize, usize, DVec3, DVec3) -> DVec3 + Sync,
        in_group: impl Fn(&str) -> bool + Sync,
    ) -> anyhow::Result<Vec<usize>> {
        // Each strand's forces from its own reconstruction: independent, so
        // in parallel over strands (a whole groom reconstructs every frame).
        let engine = self.sim.engine();
        let groups = &self.groom.grown.groups;
        let forces: Vec<Vec<DVec3>> = self
            .strands
            .par_iter()
            .enumerate()
            .map(|(i, strand)| {
                if !in_group(&groups[strand.group].name) {
                    return Vec::new();
                }
                let (root, kin) = engine.kinematics(i);
                let rho_s = engine.strand_model(i).mass_per_length;
                let per_sample: Vec<DVec3> = kin
                    .samples
                    .iter()
                    .enumerate()
                    .map(|(j, s)| {
                        rho_s * accel(i, j, root.position_m + s.position_m, s.velocity_m_per_s)
                    })
                    .collect();
                if per_sample.iter().any(|f| *f != DVec3::ZERO) {
                    per_sample
                } else {
                    Vec::new()
                }
            })
            .collect();
        let touched = (0..forces.len())
            .filter(|&i| !forces[i].is_empty())
            .collect();
        let system = self
            .sim
            .engine_mut()
            .reference_mut()
            .ok_or_else(|| anyhow!("the brush needs the reference engine"))?;
        for (strand, f) in system.strands_mut().iter_mut().zip(&forces) {
            strand.set_external_forces(f);
        }
        self.step();
        if let Some(system) = self.sim.engine_mut().reference_mut() {
            for strand in system.strands_mut() {
                strand.set_external_forces(&[]);
            }
        }
        Ok(touched)
    }

    /// Lets the hair settle for `secs` of simulated time (the physics with
    /// the settling drag, [`SETTLE_DRAG_PER_S`]).
    pub fn settle_for(&mut self, secs: f64) -> anyhow::Result<()> {
        self.settle(self.frames_of(secs))
    }

    /// Steps one frame, counting the guard's interventions in it (each
    /// retry, reset or pin once; the engine's own list of the frame, not
    /// the run's kept report, which is capped).
    fn step(&mut self) {
        self.sim.step();
        let engine = self.sim.engine();
        self.guard_total += engine
            .reference()
            .map_or(0, |r| r.last_guard_events().len())
            + engine.batch().map_or(0, |b| b.last_guard_events().len());
    }

    /// The guard's interventions in the session so far (retries, resets
    /// and pins).
    pub fn guard_events(&self) -> usize {
        self.guard_total
    }

    fn engine(&self) -> &Engine {
        self.sim.engine()
    }

    /// Strands the stroke may touch (its groups) reached by `reach`, each
    /// with the largest weight of its points.
    fn weights(&self, stroke: &Stroke, reach: &Reach) -> Vec<(usize, f64)> {
        let engine = self.engine();
        // Every strand's reconstruction: in parallel, as the drive's.
        self.strands
            .par_iter()
            .enumerate()
            .filter(|(_, s)| stroke.touches_group(&self.groom.grown.groups[s.group].name))
            .filter_map(|(i, _)| {
                let (root, kin) = engine.kinematics(i);
                let weight = kin
                    .points_m
                    .iter()
                    .chain(kin.samples.iter().map(|s| &s.position_m))
                    .map(|p| reach.weight(root.position_m + *p))
                    .fold(0.0, f64::max);
                (weight > 0.0).then_some((i, weight))
            })
            .collect()
    }

    /// The strands the stroke's swept brush reaches now, with weights.
    fn reached(&self, stroke: &Stroke) -> Vec<(usize, f64)> {
        let reach = Reach {
            path: stroke.path.clone(),
            radius_m: stroke.radius_m,
            falloff: stroke.falloff,
        };
        self.weights(stroke, &reach)
    }

    /// Comb or grab: the brush moved along its path over `frames`, the
    /// physics running; returns the strands it moved.
    fn drive(&mut self, stroke: &Stroke, frames: usize) -> anyhow::Result<Vec<usize>> {
        let mut moved = vec![false; self.strands.len()];
        // Grab: the points the brush holds at its start, each with its
        // weight and offset from the brush centre.
        let start = stroke.centre_at(0.0);
        let held: Vec<Vec<(f64, DVec3)>> = match stroke.tool {
            Tool::Grab => {
                let reach = Reach::sphere(start, stroke.radius_m, stroke.falloff);
                let eligible = self.weights(stroke, &reach);
                let mut held = vec![Vec::new(); self.strands.len()];
                for (i, _) in eligible {
                    let (root, kin) = self.engine().kinematics(i);
                    held[i] = kin
                        .samples
                        .iter()
                        .map(|s| {
                            let p = root.position_m + s.position_m;
                            (reach.weight(p), p - start)
                        })
                        .collect();
                }
                held
            }
            _ => Vec::new(),
        };
        let strength = stroke.strength;
        for frame in 0..frames {
            let t = (frame as f64 + 0.5) / frames as f64;
            let centre = stroke.centre_at(t);
            let brush_velocity = stroke.velocity_at(t);
            let reach = Reach::sphere(centre, stroke.radius_m, stroke.falloff);
            let tool = &stroke.tool;
            let touched = self.step_with_forces(
                |i, j, p, v| {
                    let relative = brush_velocity - v;
                    match tool {
                        Tool::Grab => held[i].get(j).map_or(DVec3::ZERO, |&(w, offset)| {
                            let to_target = centre + offset - p;
                            w * strength
                                * (GRAB_STIFFNESS_PER_S2 * to_target
                                    + GRAB_DAMPING_PER_S * relative)
                        }),
                        _ => reach.weight(p) * strength * COMB_DRAG_PER_S * relative,
                    }
                },
                |name| stroke.touches_group(name),
            )?;
            for i in touched {
                moved[i] = true;
            }
        }
        Ok((0..moved.len()).filter(|&i| moved[i]).collect())
    }

    /// The base parameters of engine strand `i` (its group's, or its
    /// imported strand's) and its edit, made if missing.
    fn edit_of(&mut self, i: usize) -> (StrandParams, &mut StrandEdit) {
        let StyleStrand {
            group,
            strand,
            ref base,
            ..
        } = self.strands[i];
        let base = base.clone();
        (
            base,
            edit_mut(&mut self.groom.grown.groups[group].edits, strand),
        )
    }

    /// Freezes `which` strands in their current shapes (see
    /// [`crate::brush::freeze`]), then rebuilds the engine with them at
    /// rest there.
    pub fn freeze(&mut self, which: &[usize]) -> anyhow::Result<RestCounts> {
        let start = Instant::now();
        let counts = freeze_strands(
            self.sim.engine(),
            &self.strands,
            which,
            &mut self.groom.grown,
        )
        .map_err(|e| anyhow!(e))?;
        self.rebuild(which)?;
        self.freeze_secs += start.elapsed().as_secs_f64();
        Ok(counts)
    }

    /// Cut, Grow, Curl or Stiffness painted on the `reached` strands;
    /// returns how many changed.
    fn paint(
        &mut self,
        tool: &Tool,
        reached: &[(usize, f64)],
        strength: f64,
    ) -> anyhow::Result<usize> {
        let mut changed = 0;
        for &(i, weight) in reached {
            let w = (weight * strength).clamp(0.0, 1.0);
            let model = self.engine().strand_model(i).clone();
            let (base, edit) = self.edit_of(i);
            let before = edit.clone();
            match *tool {
                Tool::Cut { length_m } if model.params.length_m > length_m => {
                    set_length(edit, &base, length_m);
                }
                Tool::Grow { length_m } if model.params.length_m < length_m => {
                    set_length(edit, &base, length_m);
                }
                Tool::Stiffness { scale } => {
                    let now = edit.stiffness_scale.unwrap_or(1.0);
                    let new = now + (scale - now) * w;
                    edit.stiffness_scale = (new != 1.0).then_some(new);
                }
                _ => {}
            }
            if *edit != before {
                changed += 1;
            }
        }
        self.groom
            .grown
            .groups
            .iter_mut()
            .for_each(|g| g.edits.retain(|e| !e.is_empty()));
        if changed > 0 {
            self.rebuild(&[])?;
        }
        Ok(changed)
    }

    /// A curl painted on the `reached` strands over `frames`: their natural
    /// strains blend from what they were to the helix's in
    /// [`CURL_RAMP_STEPS`] steps over the first half of the frames (a
    /// strand let go into a tight curl at once whips faster than a step of
    /// 1/60 s resolves, and the guard would have to step in), then the
    /// hair settles. A strand at full weight ends with exactly the helix.
    fn curl(
        &mut self,
        reached: &[(usize, f64)],
        strength: f64,
        radius_m: f64,
        step_m: f64,
        frames: usize,
    ) -> anyhow::Result<()> {
        let target = helix_strains(radius_m, step_m);
        let from: Vec<Vec<DVec3>> = reached
            .iter()
            .map(|&(i, _)| self.engine().strand_model(i).natural.clone())
            .collect();
        let steps = CURL_RAMP_STEPS.min(frames / 2).max(1);
        let frames_per_step = frames / 2 / steps;
        for step in 1..=steps {
            let share = step as f64 / steps as f64;
            for (&(i, weight), from) in reached.iter().zip(&from) {
                let w = (weight * strength).clamp(0.0, 1.0) * share;
                let (_, edit) = self.edit_of(i);
                edit.rest = None;
                edit.natural_shape = Some(if w >= 1.0 {
                    NaturalShape::Helix { radius_m, step_m }
                } else {
                    NaturalShape::PerElement(
                        from.iter().map(|k| k.lerp(target, w).to_array()).collect(),
                    )
                });
            }
            self.rebuild(&[])?;
            self.settle(frames_per_step)?;
        }
        self.settle(frames - steps * frames_per_step)?;
        Ok(())
    }

    /// The shapes of the `reached` strands relaxed toward their weighted
    /// mean (by arc-length fraction); returns how many changed.
    fn smooth(&mut self, reached: &[(usize, f64)], strength: f64) -> usize {
        const SAMPLES: usize = 64;
        let fractions: Vec<f64> = vec![1.0 / SAMPLES as f64; SAMPLES];
        let mut mean = vec![DVec3::ZERO; SAMPLES];
        let mut total = 0.0;
        for &(i, w) in reached {
            let lengths = &self.engine().strand_model(i).lengths_m;
            let q = resample_per_element(&self.engine().q(i), lengths, &fractions);
            for (m, x) in mean.iter_mut().zip(q) {
                *m += w * x;
            }
            total += w;
        }
        if reached.len() < 2 || total <= 0.0 {
            return 0;
        }
        mean.iter_mut().for_each(|m| *m /= total);
        for &(i, w) in reached {
            let lengths = self.engine().strand_model(i).lengths_m.clone();
            let target = resample_per_element(&mean, &fractions, &lengths);
            let q: Vec<DVec3> = self
                .engine()
                .q(i)
                .iter()
                .zip(target)
                .map(|(q, t)| q.lerp(t, (w * strength).clamp(0.0, 1.0)))
                .collect();
            let still = vec![DVec3::ZERO; q.len()];
            self.sim.engine_mut().set_state(i, &q, &still);
        }
        reached.len()
    }

    /// Roots within the brush of the parting line turned away from it;
    /// returns the strands turned.
    fn part(&mut self, stroke: &Stroke, angle_deg: f64) -> anyhow::Result<Vec<usize>> {
        let mut parted = Vec::new();
        for i in 0..self.strands.len() {
            let name = &self.groom.grown.groups[self.strands[i].group].name;
            if !stroke.touches_group(name) {
                continue;
            }
            let root = *self.engine().root(i);
            let origin = root.position_m;
            let Some((closest, tangent)) = nearest_on_path(&stroke.path, origin) else {
                continue;
            };
            let reach = Reach::sphere(closest, stroke.radius_m, stroke.falloff);
            let w = reach.weight(origin) * stroke.strength;
            if w <= 0.0 {
                continue;
            }
            let direction = root.head_from_root.col(0);
            let mut side = origin - closest;
            side -= tangent * tangent.dot(side);
            side -= direction * direction.dot(side);
            let Some(side) = side.try_normalize() else {
                continue;
            };
            let angle = (angle_deg * w).to_radians();
            let turned = (direction * angle.cos() + side * angle.sin()).normalize();
            let (_, edit) = self.edit_of(i);
            edit.root_direction = Some(turned);
            parted.push(i);
        }
        if !parted.is_empty() {
            self.rebuild(&[])?;
        }
        Ok(parted)
    }

    /// A new engine for the edited grown style, every strand's state
    /// carried over (by arc length where its elements changed); the strands
    /// in `at_rest` start with no velocity.
    fn rebuild(&mut self, at_rest: &[usize]) -> anyhow::Result<()> {
        let overrides = SimOverrides {
            engine: Some(EngineKind::Reference),
            ..SimOverrides::default()
        };
        let mut sim = HeadlessSim::new(&self.groom.grown, overrides)
            .context("the styled hair cannot be simulated")?;
        sim.set_head_pivot(self.sim.head_pivot_m());
        sim.engine_mut().set_collider(self.collider.clone());
        let old = self.sim.engine();
        for i in 0..old.strand_count().min(sim.engine().strand_count()) {
            let old_lengths = &old.strand_model(i).lengths_m;
            let new_lengths = sim.engine().strand_model(i).lengths_m.clone();
            let carry = |x: Vec<DVec3>| {
                if *old_lengths == new_lengths {
                    x
                } else {
                    resample_by_arc_length(&x, old_lengths, &new_lengths)
                }
            };
            let q = carry(old.q(i));
            let v = if at_rest.contains(&i) {
                vec![DVec3::ZERO; q.len()]
            } else {
                carry(old.v(i))
            };
            sim.engine_mut().set_state(i, &q, &v);
        }
        self.strands = style_strands(&self.groom.grown, |_, g| g.params.clone());
        self.sim = sim;
        Ok(())
    }
}

/// The indices of `(index, weight)` pairs.
fn indices(reached: &[(usize, f64)]) -> Vec<usize> {
    reached.iter().map(|&(i, _)| i).collect()
}

/// `edit` made to give its strand `length_m` (base parameters `base`),
/// its kept rest shape cut or grown with it by arc length.
fn set_length(edit: &mut StrandEdit, base: &StrandParams, length_m: f64) {
    let old = edit.params(base);
    let elements = elements_for_length(base, length_m);
    edit.length_m = Some(length_m);
    if let Some(rest) = &mut edit.rest {
        let new_lengths = StrandParams {
            length_m,
            elements,
            ..old.clone()
        }
        .element_lengths();
        let old_lengths = old.element_lengths();
        rest.strains = resample_by_arc_length(&rest.strains, &old_lengths, &new_lengths);
        rest.natural = resample_by_arc_length(&rest.natural, &old_lengths, &new_lengths);
    }
}

/// The point of `path` nearest to `p` and the path's direction there.
fn nearest_on_path(path: &[DVec3], p: DVec3) -> Option<(DVec3, DVec3)> {
    if let [only] = path {
        return Some((*only, DVec3::ZERO));
    }
    path.windows(2)
        .map(|pair| {
            let closest = closest_on_segment(p, pair[0], pair[1]);
            (closest, (pair[1] - pair[0]).normalize_or_zero())
        })
        .min_by(|a, b| a.0.distance(p).total_cmp(&b.0.distance(p)))
}

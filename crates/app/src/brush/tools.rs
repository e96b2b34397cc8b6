//! What each tool leaves in the style: cut and grown lengths, painted curl
//! and stiffness, smoothed and frozen shapes, parted roots, written as
//! per-strand edits ([`crate::style::strand_edit`]) on any
//! [`BrushHost`], which then rebuilds its engine from them.
//!
//! Comb and Grab act through forces while the physics runs
//! ([`crate::brush::stroke_run`]); the rest change parameters or shapes at
//! once, the hair then settling into them. Settling is the physics with a
//! drag ([`SETTLE_DRAG_PER_S`]) that brings swinging hair to rest within a
//! second or two.

use std::time::Instant;

use glam::DVec3;
use helixhair_physics::natural_shape::helix_strains;
use helixhair_physics::{NaturalShape, StrandParams};

use crate::brush::freeze::{RestCounts, freeze_strands};
use crate::brush::host::{BrushHost, step_with_forces, strands_allowed};
use crate::brush::sphere::{Reach, closest_on_segment};
use crate::brush::strokes::{Stroke, Tool};
use crate::sim::resample::{resample_by_arc_length, resample_per_element};
use crate::sim::strands::StyleStrand;
use crate::style::strand_edit::{StrandEdit, edit_mut, elements_for_length};

/// The drag that settles the hair between strokes and before the first,
/// 1/s: a swing of hanging hair at 1 Hz is then damped at 0.64 of
/// critical and a slow creep over the head (0.3 Hz) at 2, so both come to
/// rest within about two seconds instead of swinging for many, and each
/// stroke meets the hair at rest.
pub const SETTLE_DRAG_PER_S: f64 = 8.0;

/// The steps a painted curl is blended in over (see [`curl`]): ten, each
/// a sixth of the way at most through a tight curl's strain change in the
/// default half second, slow enough that no strand whips.
pub const CURL_RAMP_STEPS: usize = 10;

/// Steps `frames` frames with the settling drag; returns the guard's
/// interventions.
pub fn settle(host: &mut impl BrushHost, frames: usize) -> anyhow::Result<usize> {
    let mut events = 0;
    for _ in 0..frames {
        events += step_with_forces(host, |_, _, _, v| -SETTLE_DRAG_PER_S * v, |_| true)?.1;
    }
    Ok(events)
}

/// The strands the stroke's swept brush reaches now (of those it may
/// touch: its groups, less its masked strands), with weights.
pub fn reached(host: &impl BrushHost, stroke: &Stroke) -> Vec<(usize, f64)> {
    let reach = Reach {
        path: stroke.path.clone(),
        radius_m: stroke.radius_m,
        falloff: stroke.falloff,
    };
    let allowed = strands_allowed(host, stroke);
    crate::brush::host::reached_strands(host, &reach, |i| allowed[i])
}

/// The indices of `(index, weight)` pairs.
pub fn indices(reached: &[(usize, f64)]) -> Vec<usize> {
    reached.iter().map(|&(i, _)| i).collect()
}

/// The base parameters of engine strand `i` (its group's, or its
/// imported strand's) and its edit, made if missing.
fn edit_of(host: &mut impl BrushHost, i: usize) -> (StrandParams, &mut StrandEdit) {
    let StyleStrand {
        group,
        strand,
        ref base,
        ..
    } = host.strands()[i];
    let base = base.clone();
    (
        base,
        edit_mut(&mut host.grown_mut().groups[group].edits, strand),
    )
}

/// Freezes `which` strands in their current shapes (see
/// [`crate::brush::freeze`]), then rebuilds the engine with them at rest
/// there; returns the counts and the wall time, seconds.
pub fn freeze(host: &mut impl BrushHost, which: &[usize]) -> anyhow::Result<(RestCounts, f64)> {
    let start = Instant::now();
    if which.is_empty() {
        return Ok((RestCounts::default(), 0.0));
    }
    let strands = host.strands().to_vec();
    let mut grown = host.grown().clone();
    let counts = freeze_strands(host.engine(), &strands, which, &mut grown)
        .map_err(|e| anyhow::anyhow!(e))?;
    *host.grown_mut() = grown;
    host.rebuild(which)?;
    Ok((counts, start.elapsed().as_secs_f64()))
}

/// Cut, Grow or Stiffness painted on the `reached` strands; returns how
/// many changed.
pub fn paint(
    host: &mut impl BrushHost,
    tool: &Tool,
    reached: &[(usize, f64)],
    strength: f64,
) -> anyhow::Result<usize> {
    let mut changed = 0;
    for &(i, weight) in reached {
        let w = (weight * strength).clamp(0.0, 1.0);
        let length_now = host.engine().strand_model(i).params.length_m;
        let (base, edit) = edit_of(host, i);
        let before = edit.clone();
        match *tool {
            Tool::Cut { length_m } if length_now > length_m => set_length(edit, &base, length_m),
            Tool::Grow { length_m } if length_now < length_m => set_length(edit, &base, length_m),
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
    host.grown_mut()
        .groups
        .iter_mut()
        .for_each(|g| g.edits.retain(|e| !e.is_empty()));
    if changed > 0 {
        host.rebuild(&[])?;
    }
    Ok(changed)
}

/// A curl painted on the `reached` strands over `frames`: their natural
/// strains blend from what they were to the helix's in [`CURL_RAMP_STEPS`]
/// steps over the first half of the frames (a strand let go into a tight
/// curl at once whips faster than a step of 1/60 s resolves, and the guard
/// would have to step in), then the hair settles. A strand at full weight
/// ends with exactly the helix. Returns the guard's interventions.
pub fn curl(
    host: &mut impl BrushHost,
    reached: &[(usize, f64)],
    strength: f64,
    (radius_m, step_m): (f64, f64),
    frames: usize,
) -> anyhow::Result<usize> {
    let target = helix_strains(radius_m, step_m);
    let from: Vec<Vec<DVec3>> = reached
        .iter()
        .map(|&(i, _)| host.engine().strand_model(i).natural.clone())
        .collect();
    let steps = CURL_RAMP_STEPS.min(frames / 2).max(1);
    let frames_per_step = frames / 2 / steps;
    let mut events = 0;
    for step in 1..=steps {
        let share = step as f64 / steps as f64;
        for (&(i, weight), from) in reached.iter().zip(&from) {
            let w = (weight * strength).clamp(0.0, 1.0) * share;
            let (_, edit) = edit_of(host, i);
            edit.rest = None;
            edit.natural_shape = Some(if w >= 1.0 {
                NaturalShape::Helix { radius_m, step_m }
            } else {
                NaturalShape::PerElement(
                    from.iter().map(|k| k.lerp(target, w).to_array()).collect(),
                )
            });
        }
        host.rebuild(&[])?;
        events += settle(host, frames_per_step)?;
    }
    events += settle(host, frames.saturating_sub(steps * frames_per_step))?;
    Ok(events)
}

/// The shapes of the `reached` strands relaxed toward their weighted mean
/// (by arc-length fraction); returns how many changed.
pub fn smooth(host: &mut impl BrushHost, reached: &[(usize, f64)], strength: f64) -> usize {
    const SAMPLES: usize = 64;
    let fractions: Vec<f64> = vec![1.0 / SAMPLES as f64; SAMPLES];
    let mut mean = vec![DVec3::ZERO; SAMPLES];
    let mut total = 0.0;
    for &(i, w) in reached {
        let lengths = &host.engine().strand_model(i).lengths_m;
        let q = resample_per_element(&host.engine().q(i), lengths, &fractions);
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
        let lengths = host.engine().strand_model(i).lengths_m.clone();
        let target = resample_per_element(&mean, &fractions, &lengths);
        let q: Vec<DVec3> = host
            .engine()
            .q(i)
            .iter()
            .zip(target)
            .map(|(q, t)| q.lerp(t, (w * strength).clamp(0.0, 1.0)))
            .collect();
        let still = vec![DVec3::ZERO; q.len()];
        host.engine_mut().set_state(i, &q, &still);
    }
    reached.len()
}

/// Roots within the brush of the parting line turned away from it;
/// returns the strands turned.
pub fn part(
    host: &mut impl BrushHost,
    stroke: &Stroke,
    angle_deg: f64,
) -> anyhow::Result<Vec<usize>> {
    let mut parted = Vec::new();
    let allowed = strands_allowed(host, stroke);
    for (i, _) in allowed.iter().enumerate().filter(|(_, a)| **a) {
        let root = *host.engine().root(i);
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
        let (_, edit) = edit_of(host, i);
        edit.root_direction = Some(turned);
        parted.push(i);
    }
    if !parted.is_empty() {
        host.rebuild(&[])?;
    }
    Ok(parted)
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

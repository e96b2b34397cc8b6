//! What a brush acts on: a running simulation of a grown style, whose
//! strands take external forces, and the style's per-strand edits.
//!
//! Two hosts implement it: the headless styling session
//! ([`crate::brush::session::GroomSession`], `helixhair groom`) and the
//! window's live run ([`crate::window::live::live_sim::LiveSim`] with the
//! head held still). The strokes themselves ([`crate::brush::stroke_run`],
//! [`crate::brush::tools`]) are written once, against this trait, so a
//! stroke recorded in the window replays headless with the same code.
//!
//! The brush works in world coordinates with the head still: a point's
//! world velocity is then the hair's own.

use glam::DVec3;
use helixhair_physics::engine::Engine;
use rayon::prelude::*;

use crate::brush::sphere::Reach;
use crate::brush::strokes::Stroke;
use crate::sim::strands::StyleStrand;
use crate::style::Style;

/// A simulation the brush can drive and edit.
pub trait BrushHost {
    /// The engine (the reference engine: its strands take external forces).
    fn engine(&self) -> &Engine;
    /// The engine, to set forces and states.
    fn engine_mut(&mut self) -> &mut Engine;
    /// The style the engine was built from, scalp roots grown (strand `i`
    /// of the engine is `strands()[i]` of it), with its edits.
    fn grown(&self) -> &Style;
    /// The grown style, for the brush's edits; [`BrushHost::rebuild`]
    /// brings the engine in line with them.
    fn grown_mut(&mut self) -> &mut Style;
    /// The engine's strands: group, number, base parameters of each.
    fn strands(&self) -> &[StyleStrand];
    /// Steps one frame with the head held where it is; returns the guard's
    /// interventions in the frame (each retry, reset or pin once).
    fn step_frame(&mut self) -> usize;
    /// A new engine from the edited grown style, every strand's state
    /// carried by arc length (a cut strand keeps the rest of its shape);
    /// the strands in `at_rest` start with no velocity.
    fn rebuild(&mut self, at_rest: &[usize]) -> anyhow::Result<()>;
}

/// Strands `allowed` accepts (by engine index) reached by `reach`, each
/// with the largest weight of its points (element ends and quadrature
/// samples).
pub fn reached_strands(
    host: &impl BrushHost,
    reach: &Reach,
    allowed: impl Fn(usize) -> bool + Sync,
) -> Vec<(usize, f64)> {
    let engine = host.engine();
    // Every strand's reconstruction: independent, so in parallel.
    host.strands()
        .par_iter()
        .enumerate()
        .filter(|(i, _)| allowed(*i))
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

/// Every hair point's world position, strand by strand (boundary points,
/// root first): what a brush's pick tests against.
pub fn hair_points_world(engine: &Engine) -> Vec<Vec<DVec3>> {
    (0..engine.strand_count())
        .into_par_iter()
        .map(|i| engine.boundary_points_world(i))
        .collect()
}

/// Which of the host's strands `stroke` may touch (its groups, less its
/// masked strands), by engine index.
pub fn strands_allowed(host: &impl BrushHost, stroke: &Stroke) -> Vec<bool> {
    let masked: std::collections::HashSet<(&str, u32)> = stroke
        .masked
        .iter()
        .map(|m| (m.group.as_str(), m.strand))
        .collect();
    let groups = &host.grown().groups;
    host.strands()
        .iter()
        .map(|s| {
            let name = groups[s.group].name.as_str();
            stroke.touches_group(name) && !masked.contains(&(name, s.strand as u32))
        })
        .collect()
}

/// Steps one frame with an external force per unit mass on every
/// quadrature sample of the strands `allowed` accepts (by engine index):
/// `accel(strand, sample, position, velocity)` (world, m/s²). Returns the
/// strands that felt a force and the guard's interventions in the frame.
pub fn step_with_forces(
    host: &mut impl BrushHost,
    accel: impl Fn(usize, usize, DVec3, DVec3) -> DVec3 + Sync,
    allowed: impl Fn(usize) -> bool + Sync,
) -> anyhow::Result<(Vec<usize>, usize)> {
    // Each strand's forces from its own reconstruction: independent, so
    // in parallel over strands (a whole groom reconstructs every frame).
    let engine = host.engine();
    let forces: Vec<Vec<DVec3>> = host
        .strands()
        .par_iter()
        .enumerate()
        .map(|(i, _)| {
            if !allowed(i) {
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
    let system = host
        .engine_mut()
        .reference_mut()
        .ok_or_else(|| anyhow::anyhow!("the brush needs the reference engine"))?;
    for (strand, f) in system.strands_mut().iter_mut().zip(&forces) {
        strand.set_external_forces(f);
    }
    let events = host.step_frame();
    if let Some(system) = host.engine_mut().reference_mut() {
        for strand in system.strands_mut() {
            strand.set_external_forces(&[]);
        }
    }
    Ok((touched, events))
}

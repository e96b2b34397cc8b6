//! Study `volume`: what the hair–hair model (`helixhair_physics::volume`,
//! docs/volume.md) does to a full head, and what it costs.
//!
//! The scene is `assets/styles/groomed/full_head.ron` (3,000 guides of
//! 25 and 15 cm curls) on the default head with its collider, stepped by
//! the reference engine (volume and shake; the cost runs both engines),
//! once with the model and once without; `--style` (and `--head`) settles
//! another groom instead, an imported one say, with the engine its style
//! names:
//!
//! - **volume**: settled 5 s on a still head; mean distance of the hair's
//!   element points from the nearest root (the scalp) and the volume of
//!   the 2 cm cells the hair passes through, against the rest pose;
//! - **interpenetration**: the `shake` clip (1.33 s) and 1 s still after;
//!   per frame, pairs of element chords of different strands closer than
//!   the strand radius (35 µm) and closer than 1 mm;
//! - **stability**: the kinetic energy per frame of the same run, and the
//!   guard's events;
//! - **cost** ([`crate::bench::volume::cost`]): the model's share of a frame at
//!   3,000 and 10,000 strands, on both engines.
//!
//! Each part is its own `--study` (`volume`, `volume-shake`,
//! `volume-cost`), so a small machine can run them one at a time. Files:
//! `volume.csv`, `volume_shake.csv`, `volume_cost.csv`,
//! `volume_shake.svg`, `volume_energy.svg`, `volume_cost.svg`. Quick
//! mode: 70 strands, a few frames.

pub mod cost;
pub mod measures;

use std::sync::Arc;

use anyhow::Context as _;
use glam::DVec3;
use helixhair_physics::engine::{Engine, EngineKind};
use helixhair_render::head_generate::default_head;
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, Series, draw_line_chart};
use super::groom::GroomInput;
use super::table::write_csv;
use crate::bench::volume::measures::{close_pairs, mean_scalp_distance_m, occupied_volume_m3};
use crate::head::groom::Groom;
use crate::motion::clip::Clip;
use crate::sim::build::SimOverrides;
use crate::sim::headless::HeadlessSim;
use crate::style::Style;

const FULL_HEAD_RON: &str = include_str!("../../../../../assets/styles/groomed/full_head.ron");

/// Edge of the cells of the occupied volume, metres (the model's default
/// grid cell).
const CELL_M: f64 = 0.02;

/// Strand radius of the full head, metres (its `radius_m`).
const STRAND_RADIUS_M: f64 = 35e-6;

/// One line of `volume.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct VolumeRow {
    /// `rest`, `off` (settled without the model) or `on` (with it).
    pub case: String,
    /// Simulated seconds.
    pub time_secs: f64,
    /// Mean distance of non-root element points from the nearest root, m.
    pub mean_scalp_distance_m: f64,
    /// Volume of the 2 cm cells the hair passes through, m³.
    pub occupied_volume_m3: f64,
    /// Guard events so far.
    pub guard_events: usize,
}

/// One line of `volume_shake.csv`: a frame of the shake run.
#[derive(Clone, Debug, Serialize)]
pub struct ShakeRow {
    /// Whether the model was on.
    pub interaction: bool,
    /// Simulated seconds at the frame's end.
    pub time_secs: f64,
    /// Chord pairs of different strands closer than the strand radius.
    pub pairs_within_radius: usize,
    /// Chord pairs of different strands closer than 1 mm.
    pub pairs_within_1mm: usize,
    /// Kinetic energy of the hair, J.
    pub kinetic_j: f64,
    /// Guard events so far.
    pub guard_events: usize,
}

/// Which part of the study to run: each is its own `--study` name, so a
/// small machine can run them one at a time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// Volume after 5 s on a still head (`volume.csv`).
    Settle,
    /// Interpenetration and energy during and after a shake
    /// (`volume_shake.csv`, `volume_shake.svg`, `volume_energy.svg`).
    Shake,
}

/// The head with the model on or off on `engine`, colliding.
pub fn build(groom: &Groom, engine: EngineKind, on: bool) -> anyhow::Result<HeadlessSim> {
    let overrides = SimOverrides {
        engine: Some(engine),
        interaction: Some(on),
        ..SimOverrides::default()
    };
    let mut sim = HeadlessSim::new(&groom.grown, overrides).context("building the head")?;
    let collider = groom.collider().context("the default head's collider")?;
    sim.engine_mut().set_collider(Some(Arc::new(collider)));
    Ok(sim)
}

/// Runs `part` of the study: on the built-in full head, or, for the
/// settle, on the groom `input` names (`--style`, `--head`; an imported
/// groom, say) with the engine its style names.
pub fn run(
    ctx: &mut BenchContext<'_>,
    part: Part,
    input: Option<&GroomInput>,
) -> anyhow::Result<()> {
    let strands = if ctx.quick { 70 } else { 3000 };
    match (part, input) {
        (Part::Settle, Some(input)) => {
            let (groom, head_path) = input.load()?;
            writeln!(ctx.log, "   {}", input.describe(head_path.as_deref()))?;
            let engine = groom.grown.engine;
            settle(ctx, &groom, engine)
        }
        (Part::Settle, None) => settle(ctx, &scaled_groom(strands)?, EngineKind::Reference),
        (Part::Shake, _) => shake(ctx, &scaled_groom(strands)?),
    }
}

fn settle(ctx: &mut BenchContext<'_>, base: &Groom, engine: EngineKind) -> anyhow::Result<()> {
    let settle = if ctx.quick { 10 } else { 300 };
    let mut rows = Vec::new();
    for on in [false, true] {
        let mut sim = build(base, engine, on)?;
        if !on {
            rows.push(volume_row("rest", sim.engine()));
        }
        sim.run(settle).context("settling the head")?;
        rows.push(volume_row(if on { "on" } else { "off" }, sim.engine()));
    }
    for r in &rows {
        writeln!(
            ctx.log,
            "   {:>4} at {:.2} s: mean distance from the scalp {:.2} cm, occupied {:.0} cm³, \
             {} guard events",
            r.case,
            r.time_secs,
            100.0 * r.mean_scalp_distance_m,
            1e6 * r.occupied_volume_m3,
            r.guard_events
        )?;
    }
    write_csv(&ctx.file("volume.csv"), &rows)
}

fn shake(ctx: &mut BenchContext<'_>, base: &Groom) -> anyhow::Result<()> {
    let still = if ctx.quick { 10 } else { 60 };
    let shake_frames = (Clip::Shake.duration_secs() * 60.0).ceil() as usize + still;
    let mut shake = Vec::new();
    for on in [false, true] {
        let mut sim = build(base, EngineKind::Reference, on)?;
        sim.play(Clip::Shake);
        for _ in 0..shake_frames {
            sim.run(1).context("shaking the head")?;
            shake.push(shake_row(on, &sim));
        }
        let last = shake.last().context("no frames")?;
        let pairs: usize = shake
            .iter()
            .filter(|r| r.interaction == on)
            .map(|r| r.pairs_within_radius)
            .sum();
        let pairs_mm: usize = shake
            .iter()
            .filter(|r| r.interaction == on)
            .map(|r| r.pairs_within_1mm)
            .sum();
        writeln!(
            ctx.log,
            "   shake, model {}: {:.1} pairs within the radius and {:.1} within 1 mm per frame; \
             kinetic {:.3e} J at the end; {} guard events",
            if on { "on" } else { "off" },
            pairs as f64 / shake_frames as f64,
            pairs_mm as f64 / shake_frames as f64,
            last.kinetic_j,
            last.guard_events
        )?;
    }
    write_csv(&ctx.file("volume_shake.csv"), &shake)?;
    draw_shake(ctx, &shake)
}

/// The full head with its guides scaled to about `count` strands.
pub fn scaled_groom(count: usize) -> anyhow::Result<Groom> {
    let mut style = Style::from_ron(FULL_HEAD_RON, "full_head.ron".as_ref())
        .context("the built-in full-head style")?;
    let total: u32 = style
        .groups
        .iter()
        .filter_map(|g| g.scalp.as_ref().map(|s| s.count))
        .sum();
    for group in &mut style.groups {
        if let Some(scalp) = &mut group.scalp {
            scalp.count = (f64::from(scalp.count) * count as f64 / f64::from(total)).round() as u32;
        }
    }
    style.engine = EngineKind::Reference;
    Ok(Groom::new(style, default_head()))
}

/// Element boundary points of every strand, head coordinates.
fn head_points(engine: &Engine) -> Vec<Vec<DVec3>> {
    let head = engine.head();
    let body_from_world = head.world_from_body.transpose();
    (0..engine.strand_count())
        .map(|i| {
            let points = engine.boundary_points_world(i);
            points
                .iter()
                .map(|p| body_from_world * (*p - head.position_m))
                .collect()
        })
        .collect()
}

fn volume_row(case: &str, engine: &Engine) -> VolumeRow {
    let strands = head_points(engine);
    VolumeRow {
        case: case.to_owned(),
        time_secs: engine.time_secs(),
        mean_scalp_distance_m: mean_scalp_distance_m(&strands),
        occupied_volume_m3: occupied_volume_m3(&strands, CELL_M),
        guard_events: engine.reference().map_or(0, |r| r.guard_event_count()),
    }
}

fn shake_row(on: bool, sim: &HeadlessSim) -> ShakeRow {
    let engine = sim.engine();
    let strands = head_points(engine);
    let [pairs_within_radius, pairs_within_1mm] = close_pairs(&strands, [STRAND_RADIUS_M, 1e-3]);
    ShakeRow {
        interaction: on,
        time_secs: engine.time_secs(),
        pairs_within_radius,
        pairs_within_1mm,
        kinetic_j: engine.energies().kinetic_j,
        guard_events: engine.reference().map_or(0, |r| r.guard_event_count()),
    }
}

fn draw_shake(ctx: &BenchContext<'_>, rows: &[ShakeRow]) -> anyhow::Result<()> {
    let series = |f: &dyn Fn(&ShakeRow) -> f64| {
        [false, true]
            .into_iter()
            .enumerate()
            .map(|(colour, on)| Series {
                name: format!("model {}", if on { "on" } else { "off" }),
                points: rows
                    .iter()
                    .filter(|r| r.interaction == on)
                    .map(|r| (r.time_secs, f(r)))
                    .collect(),
                line: true,
                markers: false,
                colour,
            })
            .collect()
    };
    let time = Axis {
        label: "time, s (shake 0 to 1.33 s, then still)".to_owned(),
        log: false,
    };
    draw_line_chart(
        &ctx.file("volume_shake.svg"),
        &LineChart {
            title: "Full head, shake: chord pairs of different strands closer than 1 mm".to_owned(),
            x: time.clone(),
            y: Axis {
                label: "pairs per frame".to_owned(),
                log: false,
            },
            series: series(&|r| r.pairs_within_1mm as f64),
        },
    )?;
    draw_line_chart(
        &ctx.file("volume_energy.svg"),
        &LineChart {
            title: "Full head, shake: kinetic energy of the hair".to_owned(),
            x: time,
            y: Axis {
                label: "kinetic energy, J".to_owned(),
                log: true,
            },
            series: series(&|r| r.kinetic_j),
        },
    )
}

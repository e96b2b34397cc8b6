//! Study `stability`: where each solver fails, raw (the guards off).
//!
//! A curly strand (20 cm, 10 elements) hangs from the side of the head. For
//! each solver, every cell of a grid over time step × stiffness (Young's
//! and shear moduli scaled together) × root speed (still, a head shake,
//! a fast head shake) runs for a few seconds and is classed:
//!
//! - **blown-up**: the state went non-finite, the tip moved faster than
//!   [`SPEED_LIMIT_M_PER_S`] relative to the root, or its motion was more
//!   than [`ENERGY_GROWTH_FACTOR`] times the reference's (energy the
//!   physics never put in);
//! - **damped-out**: finite, but the tip moved less than
//!   [`DAMPED_FACTOR`] of the reference's motion (the step's numerical
//!   damping ate the motion);
//! - **stable**: otherwise.
//!
//! The reference is Dense at h = 1/960 s on the same cell. The study also
//! runs the default curly style (`assets/styles/curly.ron`, all its
//! strands, still head and head shake) at growing time steps and reports
//! the largest step at which each solver stays finite. It builds that
//! style's system with [`HeadlessSim::new`], the same style-to-engine path
//! `helixhair sim` and `helixhair render` take, so the study measures what
//! those commands run; the dependency points one way (the headless path
//! knows nothing of the bench).

use std::path::Path;

use anyhow::Context as _;
use glam::DVec3;
use helixhair_physics::engine::EngineKind;
use helixhair_physics::{Method, Oscillation, StrandParams};
use plotters::prelude::*;
use serde::Serialize;

use super::BenchContext;
use super::chart::{CHART_SIZE_PX, plot_error};
use super::cost::SOLVERS;
use super::scenes::{
    CurlClass, RunSetting, Scene, SceneMotion, Trajectory, run_scene, tip_motion_rms,
};
use super::table::write_csv;
use crate::sim::build::SimOverrides;
use crate::sim::headless::HeadlessSim;
use crate::style::Style;

/// Tip speed relative to the root above which a run counts as blown up,
/// m/s: hair tips in a fast head shake move a few m/s.
pub const SPEED_LIMIT_M_PER_S: f64 = 30.0;
/// Tip motion above this multiple of the reference's counts as blown up.
pub const ENERGY_GROWTH_FACTOR: f64 = 3.0;
/// Tip motion below this fraction of the reference's counts as damped out.
pub const DAMPED_FACTOR: f64 = 0.5;
/// Time steps of the full grid, seconds.
pub const FULL_STEPS_SECS: [f64; 6] = [
    1.0 / 30.0,
    1.0 / 60.0,
    1.0 / 120.0,
    1.0 / 240.0,
    1.0 / 480.0,
    1.0 / 960.0,
];
/// Stiffness multipliers of the full grid.
pub const FULL_STIFFNESS: [f64; 3] = [0.1, 1.0, 10.0];
/// Reference step, seconds.
pub const REFERENCE_STEP_SECS: f64 = 1.0 / 960.0;

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    /// Finite and moving like the reference.
    Stable,
    /// Finite but its motion damped away.
    DampedOut,
    /// Non-finite, too fast, or gaining energy.
    BlownUp,
}

/// Head motions of the grid: still, a shake, a fast shake.
pub fn root_speeds() -> [(&'static str, SceneMotion); 3] {
    let shake = |amplitude_rad, frequency_hz| {
        SceneMotion::Shake(Oscillation {
            axis: DVec3::Y,
            amplitude_rad,
            frequency_hz,
        })
    };
    [
        ("still", SceneMotion::Still),
        ("shake", shake(0.5, 1.5)),
        ("fast shake", shake(1.0, 3.0)),
    ]
}

/// One row of `stability.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct StabilityRow {
    /// Solver label.
    pub method: String,
    /// Step, seconds.
    pub dt_secs: f64,
    /// Multiplier on Young's and shear moduli.
    pub stiffness_scale: f64,
    /// Head motion.
    pub motion: String,
    /// The class of the run.
    pub outcome: Outcome,
    /// Tip motion RMS over the reference's.
    pub motion_ratio: f64,
    /// Fastest tip speed relative to the root, m/s.
    pub max_tip_speed_m_per_s: f64,
}

/// Classes a run against the reference's tip motion.
pub fn classify(run: &Trajectory, reference_motion_m: f64) -> (Outcome, f64) {
    let ratio = tip_motion_rms(run) / reference_motion_m.max(1e-12);
    let outcome = if !run.finite
        || run.max_relative_tip_speed_m_per_s > SPEED_LIMIT_M_PER_S
        || ratio > ENERGY_GROWTH_FACTOR
    {
        Outcome::BlownUp
    } else if ratio < DAMPED_FACTOR {
        Outcome::DampedOut
    } else {
        Outcome::Stable
    };
    (outcome, ratio)
}

/// The grid's scene: a curly strand on the side of the head.
fn scene(stiffness_scale: f64, motion: SceneMotion, duration_secs: f64, dt: f64) -> Scene {
    let mut scene = Scene::shake(duration_secs);
    let base = StrandParams::default();
    scene.name = "stability".into();
    scene.params.natural_shape = CurlClass::Curly.shape();
    scene.params.youngs_modulus_pa = base.youngs_modulus_pa * stiffness_scale;
    scene.params.shear_modulus_pa = base.shear_modulus_pa * stiffness_scale;
    scene.motion = motion;
    scene.frame_secs = dt;
    scene
}

/// Runs the study: `stability.csv`, `stability.svg`, `curly_dt.csv`.
pub fn run(ctx: &mut BenchContext<'_>) -> anyhow::Result<()> {
    let (steps, stiffness, duration): (&[f64], &[f64], f64) = if ctx.quick {
        (&[1.0 / 30.0, 1.0 / 60.0, 1.0 / 240.0], &[1.0, 10.0], 1.0)
    } else {
        (&FULL_STEPS_SECS, &FULL_STIFFNESS, 3.0)
    };
    let mut rows = Vec::new();
    for &scale in stiffness {
        for (motion_name, motion) in root_speeds() {
            let reference = run_scene(
                &scene(scale, motion, duration, REFERENCE_STEP_SECS),
                setting(Method::Dense),
            );
            let reference_motion = tip_motion_rms(&reference);
            for method in SOLVERS {
                for &dt in steps {
                    let run = run_scene(&scene(scale, motion, duration, dt), setting(method));
                    let (outcome, motion_ratio) = classify(&run, reference_motion);
                    rows.push(StabilityRow {
                        method: method.label(),
                        dt_secs: dt,
                        stiffness_scale: scale,
                        motion: motion_name.into(),
                        outcome,
                        motion_ratio,
                        max_tip_speed_m_per_s: run.max_relative_tip_speed_m_per_s,
                    });
                }
            }
        }
    }
    for method in SOLVERS {
        let label = method.label();
        let stable: Vec<&StabilityRow> = rows
            .iter()
            .filter(|r| r.method == label && r.outcome == Outcome::Stable)
            .collect();
        let blown = rows
            .iter()
            .filter(|r| r.method == label && r.outcome == Outcome::BlownUp)
            .count();
        writeln!(
            ctx.log,
            "   {label:>12}: {} stable, {blown} blown up of {} cells",
            stable.len(),
            rows.iter().filter(|r| r.method == label).count()
        )?;
    }
    write_csv(&ctx.file("stability.csv"), &rows)?;
    draw_maps(&ctx.file("stability.svg"), &rows, steps, stiffness)?;
    curly_style_steps(ctx, duration)
}

fn setting(method: Method) -> RunSetting {
    RunSetting {
        method,
        elements: 10,
        substeps: 1,
    }
}

/// One row of `curly_dt.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct CurlyStepRow {
    /// Solver label.
    pub method: String,
    /// Head motion.
    pub motion: String,
    /// Frame step, seconds (one substep).
    pub dt_secs: f64,
    /// Whether every strand stayed finite and slower than the speed limit.
    pub stable: bool,
}

/// The default curly style at growing steps, guards off: which stay finite.
fn curly_style_steps(ctx: &mut BenchContext<'_>, duration_secs: f64) -> anyhow::Result<()> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/styles/curly.ron");
    let style = Style::load(&path)?;
    let steps = [
        1.0 / 15.0,
        1.0 / 20.0,
        1.0 / 30.0,
        1.0 / 45.0,
        1.0 / 60.0,
        1.0 / 120.0,
        1.0 / 240.0,
        1.0 / 480.0,
        1.0 / 960.0,
    ];
    let mut rows = Vec::new();
    for method in SOLVERS {
        for (motion_name, motion) in root_speeds().into_iter().take(2) {
            let mut largest = None;
            for &dt in &steps {
                let mut sim = HeadlessSim::new(
                    &style,
                    SimOverrides {
                        engine: Some(EngineKind::Reference),
                        method: Some(method),
                        dt_secs: Some(dt),
                        accuracy_target: None,
                        scheme: None,
                        interaction: None,
                    },
                )?;
                let system = sim
                    .engine_mut()
                    .reference_mut()
                    .context("the stability study runs the reference engine")?;
                system.set_guard(None);
                let stable = style_run_is_stable(system, &motion, dt, duration_secs);
                if stable && largest.is_none() {
                    largest = Some(dt);
                }
                rows.push(CurlyStepRow {
                    method: method.label(),
                    motion: motion_name.into(),
                    dt_secs: dt,
                    stable,
                });
            }
            writeln!(
                ctx.log,
                "   curly style, {:>12}, {motion_name}: largest stable step {}",
                method.label(),
                largest.map_or("none of those tried".into(), |dt| format!(
                    "1/{:.0} s",
                    1.0 / dt
                ))
            )?;
        }
    }
    write_csv(&ctx.file("curly_dt.csv"), &rows)
}

/// Steps `sim` under `motion`; false at the first non-finite state or tip
/// faster than the speed limit relative to its root.
fn style_run_is_stable(
    system: &mut helixhair_physics::HairSystem,
    motion: &SceneMotion,
    dt: f64,
    duration_secs: f64,
) -> bool {
    let strands = system.strands().len();
    let relative_tips = |s: &helixhair_physics::HairSystem| -> Vec<DVec3> {
        (0..strands)
            .map(|i| {
                let p = s.boundary_points_world(i);
                p[p.len() - 1] - p[0]
            })
            .collect()
    };
    let mut previous = relative_tips(system);
    for _ in 0..(duration_secs / dt).round() as usize {
        system.step_frame(motion);
        if !system.is_finite() {
            return false;
        }
        let now = relative_tips(system);
        let fastest = now
            .iter()
            .zip(&previous)
            .map(|(a, b)| a.distance(*b) / dt)
            .fold(0.0, f64::max);
        if fastest > SPEED_LIMIT_M_PER_S {
            return false;
        }
        previous = now;
    }
    true
}

/// One panel per solver: columns are steps, rows stiffness × motion.
fn draw_maps(
    path: &Path,
    rows: &[StabilityRow],
    steps: &[f64],
    stiffness: &[f64],
) -> anyhow::Result<()> {
    let root = SVGBackend::new(path, (CHART_SIZE_PX.0, CHART_SIZE_PX.1 + 240)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_error)?;
    let (legend, maps) = root.split_vertically(40);
    for (i, (name, colour)) in outcome_colours().iter().enumerate() {
        let x = 20 + 190 * i as i32;
        legend
            .draw(&Rectangle::new([(x, 12), (x + 22, 30)], colour.filled()))
            .map_err(plot_error)?;
        legend
            .draw(&Text::new(
                name.to_string(),
                (x + 28, 14),
                ("sans-serif", 15),
            ))
            .map_err(plot_error)?;
    }
    let motions = root_speeds();
    let row_labels: Vec<String> = stiffness
        .iter()
        .flat_map(|s| motions.iter().map(move |(m, _)| format!("E×{s}, {m}")))
        .collect();
    for (panel, method) in maps.split_evenly((2, 2)).iter().zip(SOLVERS) {
        let label = method.label();
        let mut chart = ChartBuilder::on(panel)
            .caption(&label, ("sans-serif", 16))
            .margin(6)
            .x_label_area_size(30)
            .y_label_area_size(120)
            .build_cartesian_2d(0f64..steps.len() as f64, 0f64..row_labels.len() as f64)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(steps.len() * 2 + 1)
            .y_labels(row_labels.len() * 2 + 1)
            .x_label_formatter(&|v| {
                cell_label(*v, |i| steps.get(i).map(|dt| format!("1/{:.0}", 1.0 / dt)))
            })
            .y_label_formatter(&|v| cell_label(*v, |i| row_labels.get(i).cloned()))
            .x_desc("time step, s")
            .draw()
            .map_err(plot_error)?;
        let cells = rows.iter().filter(|r| r.method == label).filter_map(|r| {
            let x = steps.iter().position(|&s| s == r.dt_secs)?;
            let si = stiffness.iter().position(|&s| s == r.stiffness_scale)?;
            let mi = motions.iter().position(|(m, _)| *m == r.motion)?;
            let y = si * motions.len() + mi;
            let colour = outcome_colours()[r.outcome as usize].1;
            Some(Rectangle::new(
                [
                    (x as f64 + 0.04, y as f64 + 0.06),
                    (x as f64 + 0.96, y as f64 + 0.94),
                ],
                colour.filled(),
            ))
        });
        chart.draw_series(cells).map_err(plot_error)?;
    }
    root.present().map_err(plot_error)
}

/// The label of the cell whose centre is at `v`, or nothing between cells.
fn cell_label(v: f64, name: impl Fn(usize) -> Option<String>) -> String {
    let centre = v - 0.5;
    if v < 0.0 || (centre - centre.round()).abs() > 1e-6 {
        return String::new();
    }
    name(centre.round() as usize).unwrap_or_default()
}

/// Legend names and colours, in [`Outcome`] order.
fn outcome_colours() -> [(&'static str, RGBColor); 3] {
    [
        ("stable", RGBColor(0, 158, 115)),
        ("damped-out", RGBColor(230, 159, 0)),
        ("blown-up", RGBColor(213, 94, 0)),
    ]
}

//! Study `accuracy`: the error of every solver and setting against a fine
//! Dense reference, plotted against its cost, with the Pareto front.
//!
//! Each scene of [`super::scenes`] runs once as the reference (Dense,
//! [`REFERENCE`] elements and substeps) and once per setting in the grid of
//! solvers × element counts × substeps. The error is the tip-position RMS
//! over the run as a fraction of the length (see [`tip_rms_error`]); the
//! cost is CPU milliseconds per simulated second, single thread. The
//! bouncing runs of every curl class also make the error model the
//! automatic choice of N and solver reads (`error_model.ron`).

use helixhair_physics::Method;
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, REFERENCE_COLOUR, Series, draw_line_chart, series_per_method};
use super::error_model_build::{error_model_from_entries, save_error_model};
use super::pareto::pareto_front;
use super::scenes::{CurlClass, RunSetting, Scene, run_scene, tip_rms_error};
use super::table::write_csv;
use crate::sim::error_model::ErrorEntry;
use crate::stats::median;

/// The reference setting: Dense, 64 elements, 16 substeps (h = 1/960 s).
pub const REFERENCE: RunSetting = RunSetting {
    method: Method::Dense,
    elements: 64,
    substeps: 16,
};
/// Reference of the quick study.
pub const QUICK_REFERENCE: RunSetting = RunSetting {
    method: Method::Dense,
    elements: 16,
    substeps: 4,
};
/// Runs of each setting whose median CPU time is its cost (full, quick):
/// the machine is shared, and a single run can be slowed by a neighbour.
/// The runs are deterministic, so their trajectories are identical.
pub const REPEATS: (usize, usize) = (3, 1);
/// Simulated seconds per scene (full, quick).
pub const DURATION_SECS: (f64, f64) = (3.0, 1.0);

/// Solvers of the full grid: Iterative at several iteration counts shows
/// how fast CG wins back Block-diagonal's error.
pub const FULL_METHODS: [Method; 7] = [
    Method::Dense,
    Method::BlockDiagonal,
    Method::Exact,
    Method::Iterative { iterations: 1 },
    Method::Iterative { iterations: 2 },
    Method::Iterative { iterations: 4 },
    Method::Iterative { iterations: 8 },
];
/// Element counts of the full grid.
pub const FULL_ELEMENTS: [usize; 7] = [4, 6, 8, 12, 16, 24, 32];
/// Substeps of the full grid (h = 1/60 s and 1/240 s).
pub const FULL_SUBSTEPS: [u32; 2] = [1, 4];

/// One row of `accuracy.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct AccuracyRow {
    /// Scene name.
    pub scene: String,
    /// Solver label.
    pub method: String,
    /// Elements per strand.
    pub elements: usize,
    /// Substeps per 1/60 s frame.
    pub substeps: u32,
    /// Tip-position RMS error over the run, fraction of the length
    /// (infinite when the run blew up).
    pub error: f64,
    /// CPU milliseconds per simulated second, one thread (median of
    /// [`REPEATS`] runs).
    pub cost_ms_per_sim_sec: f64,
    /// Whether the run stayed finite.
    pub finite: bool,
    /// Whether the setting is on the scene's Pareto front.
    pub pareto: bool,
}

/// The rows of the `bounce-CLASS` scenes as the error model's entries.
pub fn error_entries(rows: &[AccuracyRow]) -> Vec<ErrorEntry> {
    rows.iter()
        .filter_map(|r| {
            let class = r.scene.strip_prefix("bounce-")?;
            Some(ErrorEntry {
                class: class.into(),
                method: Method::from_name(&r.method)?,
                elements: r.elements,
                substeps: r.substeps,
                error: r.error,
                cost_ms_per_sim_sec: r.cost_ms_per_sim_sec,
            })
        })
        .collect()
}

/// The scenes: the three the charts show, then the other curl classes.
pub fn scenes(duration_secs: f64) -> Vec<Scene> {
    let mut scenes = vec![
        Scene::swing(duration_secs),
        Scene::bounce(CurlClass::Curly, duration_secs),
        Scene::shake(duration_secs),
    ];
    scenes.extend(
        [CurlClass::Straight, CurlClass::Wavy, CurlClass::Coily]
            .into_iter()
            .map(|c| Scene::bounce(c, duration_secs)),
    );
    scenes
}

/// Runs one scene's grid against its reference.
pub fn measure_scene(
    scene: &Scene,
    reference: RunSetting,
    grid: &[RunSetting],
    repeats: usize,
) -> Vec<AccuracyRow> {
    let truth = run_scene(scene, reference);
    let mut rows: Vec<AccuracyRow> = grid
        .iter()
        .map(|&setting| {
            let mut run = run_scene(scene, setting);
            let mut secs = vec![run.step_secs];
            for _ in 1..repeats {
                secs.push(run_scene(scene, setting).step_secs);
            }
            run.step_secs = median(&secs);
            AccuracyRow {
                scene: scene.name.clone(),
                method: setting.method.label(),
                elements: setting.elements,
                substeps: setting.substeps,
                error: tip_rms_error(&run, &truth, scene.params.length_m),
                cost_ms_per_sim_sec: run.step_secs * 1e3 / scene.duration_secs,
                finite: run.finite,
                pareto: false,
            }
        })
        .collect();
    let points: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.cost_ms_per_sim_sec, r.error))
        .collect();
    for i in pareto_front(&points) {
        rows[i].pareto = true;
    }
    rows
}

/// Runs the study: `accuracy.csv`, one chart per shown scene and
/// `error_model.ron`.
pub fn run(ctx: &mut BenchContext<'_>) -> anyhow::Result<()> {
    let (methods, elements, substeps, reference, duration): (&[Method], &[usize], &[u32], _, _) =
        if ctx.quick {
            (
                &[
                    Method::Dense,
                    Method::BlockDiagonal,
                    Method::Exact,
                    Method::Iterative { iterations: 2 },
                ],
                &[4, 8],
                &[1],
                QUICK_REFERENCE,
                DURATION_SECS.1,
            )
        } else {
            (
                &FULL_METHODS,
                &FULL_ELEMENTS,
                &FULL_SUBSTEPS,
                REFERENCE,
                DURATION_SECS.0,
            )
        };
    let mut grid = Vec::new();
    for &method in methods {
        for &n in elements {
            for &s in substeps {
                grid.push(RunSetting {
                    method,
                    elements: n,
                    substeps: s,
                });
            }
        }
    }
    let mut rows = Vec::new();
    for (i, scene) in scenes(duration).iter().enumerate() {
        let repeats = if ctx.quick { REPEATS.1 } else { REPEATS.0 };
        let scene_rows = measure_scene(scene, reference, &grid, repeats);
        report_scene(ctx, scene, &scene_rows)?;
        if i < 3 {
            draw_scene_chart(ctx, scene, &scene_rows, methods)?;
        }
        rows.extend(scene_rows);
    }
    write_csv(&ctx.file("accuracy.csv"), &rows)?;
    save_error_model(
        &error_model_from_entries(error_entries(&rows), reference, duration),
        &ctx.file("error_model.ron"),
    )?;
    super::iterations::run(ctx, duration)
}

/// Prints the headline numbers of one scene: each solver's error at the
/// default 60 Hz step for the middle element count.
fn report_scene(
    ctx: &mut BenchContext<'_>,
    scene: &Scene,
    rows: &[AccuracyRow],
) -> anyhow::Result<()> {
    let front = rows.iter().filter(|r| r.pareto).count();
    writeln!(
        ctx.log,
        "   scene {}: {} settings on the Pareto front",
        scene.name, front
    )?;
    for r in rows.iter().filter(|r| r.substeps == 1) {
        writeln!(
            ctx.log,
            "     {:>12} N = {:>2}: error {:.3e}, {:.2} ms per simulated s",
            r.method, r.elements, r.error, r.cost_ms_per_sim_sec
        )?;
    }
    Ok(())
}

fn draw_scene_chart(
    ctx: &mut BenchContext<'_>,
    scene: &Scene,
    rows: &[AccuracyRow],
    methods: &[Method],
) -> anyhow::Result<()> {
    let point = |r: &AccuracyRow| (r.cost_ms_per_sim_sec, r.error);
    let mut series = series_per_method(
        methods,
        rows,
        |r| &r.method,
        |r| r.finite.then(|| point(r)),
        false,
    );
    let mut front: Vec<&AccuracyRow> = rows.iter().filter(|r| r.pareto).collect();
    front.sort_by(|a, b| a.cost_ms_per_sim_sec.total_cmp(&b.cost_ms_per_sim_sec));
    series.push(Series {
        name: "Pareto front".into(),
        points: front.into_iter().map(point).collect(),
        line: true,
        markers: false,
        colour: REFERENCE_COLOUR,
    });
    let blown = rows.iter().filter(|r| !r.finite).count();
    draw_line_chart(
        &ctx.file(&format!("accuracy_{}.svg", scene.name)),
        &LineChart {
            title: format!(
                "Scene {}: error against cost ({} of {} settings blew up)",
                scene.name,
                blown,
                rows.len()
            ),
            x: Axis {
                label: "CPU ms per simulated second (one strand, one thread)".into(),
                log: true,
            },
            y: Axis {
                label: "tip RMS error / length".into(),
                log: true,
            },
            series,
        },
    )
}

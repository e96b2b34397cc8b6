//! Study `throughput`: element-steps per second and memory per strand of
//! every path that steps many strands, against strand count and N.
//!
//! Paths: the f64 reference (`HairSystem`, one thread; up to 1,000
//! strands, it is slow), the f32 batch path (`BatchSystem`) on one thread
//! and on all threads, and the GPU on whatever adapter the environment
//! gives (Exact and Block-diagonal: the GPU engine's step, `GpuEngine`,
//! velocity-implicit as the batch rows; Dense: the velocity-explicit
//! kernel of `GpuSystem`); without one the GPU rows are skipped with the
//! reason. Methods: Block-diagonal, Exact and Dense. `BatchSystem` has no
//! Dense, so Dense's `f32-batch-1-thread` rows time
//! `batch::dense::step_dense` over the same lane batches on one thread
//! (its matrix is per-thread scratch, so its memory per strand is the
//! batch state's); on the GPU the matrix is per strand, 36N² bytes. On the development machine the only adapter is lavapipe, Mesa's
//! software Vulkan: its figures are CPU figures, not a GPU's.
//!
//! Scene: straight 20 cm default strands on roots around a still head, one
//! step per 60 Hz frame. Each figure is the median of [`BATCHES`] timed
//! batches of at least [`BATCH_SECS`]; the machine is shared, so compare
//! paths as ratios within one run. `frame_ms` is the physics time of one
//! frame at that strand count; the log names the largest strand count whose
//! frame stays under [`FRAME_BUDGET_MS`].

use glam::DVec3;
use helixhair_physics::batch::layout::{BatchModel, ElementData, RootMotion, StepEnv};
use helixhair_physics::batch::step::dense::{DenseScratch, step_dense};
use helixhair_physics::batch::vec::V3;
use helixhair_physics::batch::{BatchSystem, LANES, Lanes};
use helixhair_physics::gpu::kernels::GpuState;
use helixhair_physics::gpu::{GpuContext, GpuEngine, GpuSystem};
use helixhair_physics::{
    HairSystem, Method, RigidMotion, RootPose, SimSettings, StrandModel, StrandParams,
};
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, Series, draw_line_chart};
use super::table::write_csv;
use super::timing::secs_per_call;
use crate::stats::median;

/// Timed batches per figure (odd: the median is one batch).
pub const BATCHES: usize = 5;
/// Shortest timed batch, seconds.
pub const BATCH_SECS: f64 = 0.1;
/// The physics budget of one 60 Hz frame.
pub const FRAME_BUDGET_MS: f64 = 8.0;
/// Strand counts (full, quick).
pub const STRANDS: (&[usize], &[usize]) = (&[10, 100, 1_000, 10_000, 100_000], &[10, 100]);
/// Element counts (full, quick).
pub const ELEMENTS: (&[usize], &[usize]) = (&[10, 20], &[10]);
/// Quadrature points per element: the reference's default 4, and 2.
pub const POINTS: [usize; 2] = [2, 4];
/// Largest strand count the f64 reference is timed at.
pub const REFERENCE_MAX_STRANDS: usize = 1_000;

/// One row of `throughput.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct ThroughputRow {
    /// `f64-reference-1-thread`, `f32-batch-1-thread`,
    /// `f32-batch-all-threads` or `gpu` (see `adapter`).
    pub path: String,
    /// The adapter for GPU rows, the thread count for CPU rows.
    pub adapter: String,
    /// `block`, `exact` or `dense`.
    pub method: String,
    /// Strands stepped together.
    pub strands: usize,
    /// Elements per strand.
    pub elements: usize,
    /// Quadrature points per element.
    pub points: usize,
    /// Median element-steps per second.
    pub element_steps_per_sec: f64,
    /// Physics milliseconds of one frame (one step) at this strand count.
    pub frame_ms: f64,
    /// Memory held per strand (state, roots, scratch), bytes.
    pub bytes_per_strand: f64,
    /// Whether the state stayed finite (a blow-up would time NaN arithmetic).
    pub finite: bool,
}

fn roots(count: usize) -> Vec<RootPose> {
    (0..count)
        .map(|i| {
            // Golden-angle spiral on a 10 cm sphere, strands growing outwards.
            let t = (i as f64 + 0.5) / count as f64;
            let (polar, azimuth) = ((1.0 - t).acos() * 0.9, i as f64 * 2.399_963);
            let dir = DVec3::new(
                polar.sin() * azimuth.cos(),
                polar.cos(),
                polar.sin() * azimuth.sin(),
            );
            RootPose::from_direction(dir * 0.1, dir, DVec3::Y)
        })
        .collect()
}

/// Median element-steps per second of `step` (which does `work`
/// element-steps per call).
fn rate(step: impl FnMut(), work: f64) -> f64 {
    // BATCHES is odd, so this is the median of the batches' rates.
    work / median(&secs_per_call(step, BATCHES, BATCH_SECS))
}

/// What one timed path reports: (element-steps/s, bytes per strand, finite).
type Timed = (f64, f64, bool);

/// Dense on the f32 lanes, one thread: `step_dense` over every lane batch
/// of `roots`, as `BatchSystem` steps Block-diagonal and Exact.
fn lane_dense(
    settings: &SimSettings,
    params: &StrandParams,
    roots: &[RootPose],
    head: &RigidMotion,
    work: f64,
) -> anyhow::Result<Timed> {
    let model = BatchModel::new(&StrandModel::new(params, settings.quadrature_points)?);
    let n = model.elements();
    let env = StepEnv {
        h_secs: settings.substep_secs(),
        gravity_m_per_s2: settings.gravity_m_per_s2.to_array(),
        air_velocity_m_per_s: settings.air_velocity_m_per_s.to_array(),
    };
    let natural: Vec<V3<Lanes>> = model.natural.iter().map(|k| V3::splat(*k)).collect();
    let batches = roots.len().div_ceil(LANES);
    let mut q = natural.repeat(batches);
    let mut v = vec![V3::<Lanes>::zero(); batches * n];
    let mut scratch = vec![ElementData::zero(); n];
    let mut dense = DenseScratch::new(n);
    let r = rate(
        || {
            let states = q.chunks_mut(n).zip(v.chunks_mut(n));
            for ((q, v), roots) in states.zip(roots.chunks(LANES)) {
                let motions: [RigidMotion; LANES] =
                    std::array::from_fn(|i| head.carry(&roots[i.min(roots.len() - 1)]));
                let root = RootMotion::<Lanes>::gather(&motions);
                step_dense(&model, &env, &root, q, v, &mut scratch, &mut dense);
            }
        },
        work,
    );
    let finite = q.iter().chain(&v).all(|x| {
        [x.x, x.y, x.z]
            .iter()
            .all(|l| l.to_array().iter().all(|f| f.is_finite()))
    });
    let state_bytes = (q.len() + v.len()) * size_of::<V3<Lanes>>();
    let bytes = state_bytes as f64 / roots.len().max(1) as f64 + size_of::<RootPose>() as f64;
    Ok((r, bytes, finite))
}

/// Runs the study: `throughput.csv`, `throughput.svg`.
pub fn run(ctx: &mut BenchContext<'_>) -> anyhow::Result<()> {
    let strands = if ctx.quick { STRANDS.1 } else { STRANDS.0 };
    let elements = if ctx.quick { ELEMENTS.1 } else { ELEMENTS.0 };
    // Quick: the settings' default point count only (half the rows, half
    // the study's time; the quick run checks that the study runs, not its
    // figures).
    let default_points = [SimSettings::default().quadrature_points];
    let point_counts: &[usize] = if ctx.quick { &default_points } else { &POINTS };
    let head = RigidMotion::default();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    // One device for every GPU row: on an NVIDIA H200 a context opened per
    // row failed from the 29th on ("vulkan drivers/libraries could not be
    // loaded"), leaving no rows at N = 20.
    let gpu_context = GpuContext::new_headless();
    let gpu_note = match &gpu_context {
        Ok(c) => format!("GPU rows on `{}`", c.adapter_name),
        Err(e) => format!("GPU rows skipped: {e}"),
    };
    writeln!(ctx.log, "   {gpu_note}")?;
    let mut rows = Vec::new();
    for &n in elements {
        for &points in point_counts {
            for method in [Method::BlockDiagonal, Method::Exact, Method::Dense] {
                let settings = SimSettings {
                    method,
                    quadrature_points: points,
                    ..SimSettings::default()
                };
                let params = StrandParams {
                    elements: n,
                    ..StrandParams::default()
                };
                for &count in strands {
                    let roots = roots(count);
                    let work = (count * n) as f64;
                    let mut push = |path: &str, adapter: String, r: f64, bytes: f64, finite| {
                        rows.push(ThroughputRow {
                            path: path.into(),
                            adapter,
                            method: method.name().into(),
                            strands: count,
                            elements: n,
                            points,
                            element_steps_per_sec: r,
                            frame_ms: 1e3 * work / r,
                            bytes_per_strand: bytes,
                            finite,
                        })
                    };
                    if count <= REFERENCE_MAX_STRANDS {
                        let mut sys = HairSystem::new(settings.clone())?;
                        sys.add_group(&params, &roots)?;
                        sys.set_parallel(false);
                        let r = rate(|| sys.step_frame(&head), work);
                        let finite = sys.is_finite();
                        push("f64-reference-1-thread", "1".into(), r, f64::NAN, finite);
                    }
                    // Dense: one thread on the lanes (no BatchSystem);
                    // the others: BatchSystem, serial and parallel.
                    let batch_paths: &[bool] = if method == Method::Dense {
                        let (r, bytes, finite) =
                            lane_dense(&settings, &params, &roots, &head, work)?;
                        push("f32-batch-1-thread", "1".into(), r, bytes, finite);
                        &[]
                    } else {
                        &[false, true]
                    };
                    for &parallel in batch_paths {
                        let mut sys = BatchSystem::new(settings.clone())?;
                        sys.add_group(&params, &roots)?;
                        sys.set_parallel(parallel);
                        let r = rate(|| sys.step_frame(&head), work);
                        let memory = sys.memory_use();
                        let (path, t) = if parallel {
                            ("f32-batch-all-threads", threads)
                        } else {
                            ("f32-batch-1-thread", 1)
                        };
                        push(
                            path,
                            t.to_string(),
                            r,
                            memory.bytes_per_strand,
                            sys.is_finite(),
                        );
                    }
                    let context = gpu_context.as_ref().map_err(|e| anyhow::anyhow!("{e}"));
                    let row = context
                        .and_then(|c| gpu_row(c.clone(), &settings, &params, &roots, &head, work));
                    match row {
                        Ok((r, bytes, finite, adapter)) => push("gpu", adapter, r, bytes, finite),
                        Err(e) => writeln!(ctx.log, "   gpu, {count} strands, N = {n}: {e}")?,
                    }
                }
            }
        }
    }
    write_csv(&ctx.file("throughput.csv"), &rows)?;
    report_budget(ctx, &rows)?;
    draw(ctx, &rows, elements[0])
}

/// The GPU row of one case: (element-steps per second, bytes per strand,
/// finite, adapter). Exact and Block-diagonal run the GPU engine's step
/// (`GpuEngine`: the CPU engines' velocity-implicit step, as the batch
/// rows run it, without the guard); Dense the velocity-explicit kernel of
/// `GpuSystem`.
fn gpu_row(
    context: GpuContext,
    settings: &SimSettings,
    params: &StrandParams,
    roots: &[RootPose],
    head: &RigidMotion,
    work: f64,
) -> anyhow::Result<(f64, f64, bool, String)> {
    let finite = |(q, v): GpuState| q.iter().chain(&v).flatten().all(|x| x.is_finite());
    if matches!(settings.method, Method::Exact | Method::BlockDiagonal) {
        let model = BatchModel::new(&StrandModel::new(params, settings.quadrature_points)?);
        let models = vec![model; roots.len()];
        let mut g = GpuEngine::new(context, settings, &models, roots, None)?;
        let r = rate(
            || {
                g.step_frame(head);
                let _ = g.wait();
            },
            work,
        );
        let bytes = g.bytes_per_strand();
        Ok((
            r,
            bytes,
            finite(g.read_state()?),
            g.adapter_name().to_owned(),
        ))
    } else {
        let mut g = GpuSystem::new(context, settings, params, roots)?;
        let r = rate(
            || {
                g.step_frame(head);
                let _ = g.wait();
            },
            work,
        );
        let bytes = g.bytes_per_strand() as f64;
        Ok((
            r,
            bytes,
            finite(g.read_state()?),
            g.adapter_name().to_owned(),
        ))
    }
}

/// Logs, per path, method, N and quadrature, the best rate and the largest
/// strand count whose frame fits [`FRAME_BUDGET_MS`]: the largest measured
/// count that fits, and the estimate budget × rate / N from the rate at the
/// largest measured count.
fn report_budget(ctx: &mut BenchContext<'_>, rows: &[ThroughputRow]) -> anyhow::Result<()> {
    let mut keys: Vec<(&str, &str, usize, usize)> = Vec::new();
    for r in rows {
        let key = (r.path.as_str(), r.method.as_str(), r.elements, r.points);
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    for (path, method, n, points) in keys {
        let same: Vec<&ThroughputRow> = rows
            .iter()
            .filter(|r| r.path == path && r.method == method && r.elements == n)
            .filter(|r| r.points == points && r.finite)
            .collect();
        let fits = same
            .iter()
            .filter(|r| r.frame_ms <= FRAME_BUDGET_MS)
            .map(|r| r.strands)
            .max();
        let Some(largest) = same.iter().max_by_key(|r| r.strands) else {
            continue;
        };
        let estimate = FRAME_BUDGET_MS * 1e-3 * largest.element_steps_per_sec / n as f64;
        writeln!(
            ctx.log,
            "   {path}, {method}, N = {n}, {points} points: {:.3e} element-steps/s at {} strands; \
             a {FRAME_BUDGET_MS} ms frame fits {} measured strands, about {estimate:.0} by that rate",
            largest.element_steps_per_sec,
            largest.strands,
            fits.map_or("no".to_owned(), |c| c.to_string()),
        )?;
    }
    Ok(())
}

fn draw(ctx: &BenchContext<'_>, rows: &[ThroughputRow], n: usize) -> anyhow::Result<()> {
    let mut keys: Vec<(String, String)> = rows
        .iter()
        .filter(|r| r.elements == n && r.points == 2)
        .map(|r| (r.path.clone(), r.method.clone()))
        .collect();
    keys.sort();
    keys.dedup();
    let series = keys
        .iter()
        .enumerate()
        .map(|(i, (path, method))| Series {
            name: format!("{path}, {method}"),
            points: rows
                .iter()
                .filter(|r| {
                    &r.path == path && &r.method == method && r.elements == n && r.points == 2
                })
                .map(|r| (r.strands as f64, r.element_steps_per_sec))
                .collect(),
            line: true,
            markers: true,
            colour: if i >= 6 { i + 1 } else { i },
        })
        .collect();
    draw_line_chart(
        &ctx.file("throughput.svg"),
        &LineChart {
            title: format!("Throughput, N = {n}, 2 quadrature points, one step per frame"),
            x: Axis {
                label: "strands".into(),
                log: true,
            },
            y: Axis {
                label: "element-steps per second".into(),
                log: true,
            },
            series,
        },
    )
}

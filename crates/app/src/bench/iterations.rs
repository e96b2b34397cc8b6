//! Part of study `accuracy`: how many conjugate-gradient iterations win
//! back Block-diagonal's error (the seed paper's open question).
//!
//! On the swing scene at 60 Hz, for a few element counts, each run of
//! Iterative with k iterations is compared with Dense at the same N and
//! step (not with the fine reference: the question is how far the solve
//! is from the exact one, not how far the model is from the continuum).
//! Block-diagonal is k = 0. The answer `docs/solvers.md` quotes is the
//! first k whose difference is at most 1% of Block-diagonal's.

use helixhair_physics::Method;
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, Series, draw_line_chart};
use super::scenes::{RunSetting, Scene, run_scene, tip_rms_error};
use super::table::write_csv;

/// Iteration counts tried (0 is Block-diagonal).
pub const ITERATIONS: [u32; 10] = [0, 1, 2, 3, 4, 6, 8, 12, 16, 24];
/// Element counts tried (full, quick).
pub const ELEMENTS: (&[usize], &[usize]) = (&[8, 12, 32], &[8]);
/// Fraction of Block-diagonal's error the answer asks for.
pub const WIN_BACK: f64 = 0.01;

/// One row of `iterations.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct IterationRow {
    /// Elements per strand.
    pub elements: usize,
    /// CG iterations (0: Block-diagonal).
    pub iterations: u32,
    /// Tip RMS difference from Dense at the same N and step, fraction of
    /// length.
    pub difference_from_dense: f64,
    /// The same over Block-diagonal's.
    pub over_block: f64,
}

/// Runs the comparison: `iterations.csv`, `iterations.svg`.
pub fn run(ctx: &mut BenchContext<'_>, duration_secs: f64) -> anyhow::Result<()> {
    let scene = Scene::swing(duration_secs);
    let elements = if ctx.quick { ELEMENTS.1 } else { ELEMENTS.0 };
    let mut rows = Vec::new();
    for &n in elements {
        let setting = |method| RunSetting {
            method,
            elements: n,
            substeps: 1,
        };
        let dense = run_scene(&scene, setting(Method::Dense));
        let mut block_difference = f64::NAN;
        let mut answer = None;
        for k in ITERATIONS {
            let run = run_scene(&scene, setting(Method::Iterative { iterations: k }));
            let difference = tip_rms_error(&run, &dense, scene.params.length_m);
            if k == 0 {
                block_difference = difference;
            }
            let over_block = difference / block_difference;
            if answer.is_none() && over_block <= WIN_BACK {
                answer = Some(k);
            }
            rows.push(IterationRow {
                elements: n,
                iterations: k,
                difference_from_dense: difference,
                over_block,
            });
        }
        writeln!(
            ctx.log,
            "   swing, N = {n}: Block-diagonal differs from Dense by {block_difference:.3e} of length; \
             Iterative is within 1% of that from {}",
            answer.map_or("more than 24 iterations".into(), |k| format!(
                "{k} iterations"
            ))
        )?;
    }
    write_csv(&ctx.file("iterations.csv"), &rows)?;
    let series = elements
        .iter()
        .enumerate()
        .map(|(i, &n)| Series {
            name: format!("N = {n}"),
            points: rows
                .iter()
                .filter(|r| r.elements == n && r.iterations > 0)
                .map(|r| (f64::from(r.iterations), r.over_block))
                .collect(),
            line: true,
            markers: true,
            colour: i,
        })
        .collect();
    draw_line_chart(
        &ctx.file("iterations.svg"),
        &LineChart {
            title: "Swing at 60 Hz: Iterative's difference from Dense over Block-diagonal's".into(),
            x: Axis {
                label: "CG iterations".into(),
                log: true,
            },
            y: Axis {
                label: "difference / Block-diagonal's difference".into(),
                log: true,
            },
            series,
        },
    )
}

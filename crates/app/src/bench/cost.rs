//! Study `cost`: seconds per step against element count for every solver,
//! one straight 20 cm strand, one thread (the seed paper's Figure 2,
//! extended to 200 elements and to the Exact and Iterative solvers).
//!
//! A straight strand at h = 1/600 s keeps every solver finite, so all of
//! them time the same work; a curl costs the same per step (the series in
//! the helix coefficients have a fixed length).

use helixhair_physics::settings::DEFAULT_ITERATIONS;
use helixhair_physics::{Method, StrandParams};
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, draw_line_chart, series_per_method};
use super::scenes::horizontal_strand;
use super::table::write_csv;
use super::timing::{BATCHES, time_steps};

/// Element counts of the full study: 5 to 200, about evenly in log N.
pub const FULL_ELEMENTS: [usize; 10] = [5, 7, 10, 14, 20, 30, 50, 70, 100, 200];
/// Element counts of the quick study.
pub const QUICK_ELEMENTS: [usize; 3] = [5, 10, 20];
/// Step used for timing, seconds: small enough for every solver to stay
/// finite on a straight strand.
pub const TIMING_STEP_SECS: f64 = 1.0 / 600.0;

/// The solvers the studies compare: the four methods of `docs/physics.md` (section 5) with
/// Iterative at its default iteration count.
pub const SOLVERS: [Method; 4] = [
    Method::Dense,
    Method::BlockDiagonal,
    Method::Exact,
    Method::Iterative {
        iterations: DEFAULT_ITERATIONS,
    },
];

/// One row of `cost.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct CostRow {
    /// Solver label (`dense`, `block`, `exact`, `iterative:4`).
    pub method: String,
    /// Elements per strand.
    pub elements: usize,
    /// Median microseconds per step.
    pub median_us: f64,
    /// Fastest batch, microseconds per step.
    pub min_us: f64,
    /// Slowest batch, microseconds per step.
    pub max_us: f64,
}

/// Measures the cost of one step of `method` with `elements` elements.
pub fn measure(method: Method, elements: usize, batches: usize) -> CostRow {
    let params = StrandParams {
        elements,
        ..StrandParams::default()
    };
    let mut strand = horizontal_strand(&params, method);
    let t = time_steps(&mut strand, TIMING_STEP_SECS, batches);
    CostRow {
        method: method.label(),
        elements,
        median_us: t.median_secs * 1e6,
        min_us: t.min_secs * 1e6,
        max_us: t.max_secs * 1e6,
    }
}

/// Runs the study: `cost.csv` and `cost.svg`.
pub fn run(ctx: &mut BenchContext<'_>) -> anyhow::Result<()> {
    let (elements, batches): (&[usize], usize) = if ctx.quick {
        (&QUICK_ELEMENTS, 3)
    } else {
        (&FULL_ELEMENTS, BATCHES)
    };
    let mut rows = Vec::new();
    for &n in elements {
        for method in SOLVERS {
            let row = measure(method, n, batches);
            writeln!(
                ctx.log,
                "   {:>12} N = {n:>3}: {:>9.2} µs/step",
                row.method, row.median_us
            )?;
            rows.push(row);
        }
    }
    write_csv(&ctx.file("cost.csv"), &rows)?;
    let series = series_per_method(
        &SOLVERS,
        &rows,
        |r| &r.method,
        |r| Some((r.elements as f64, r.median_us)),
        true,
    );
    draw_line_chart(
        &ctx.file("cost.svg"),
        &LineChart {
            title: "Cost per step, one strand, one thread (median of batches)".into(),
            x: Axis {
                label: "elements per strand N".into(),
                log: true,
            },
            y: Axis {
                label: "µs per step".into(),
                log: true,
            },
            series,
        },
    )
}

//! Study `modes`: the first bending mode's frequency and damping against
//! element count, for every solver, against the continuum's analytic value.
//!
//! A straight cantilever (20 cm, default parameters, root horizontal, no
//! gravity) is released from a small uniform bend, which is close to the
//! first mode, and the tip's in-plane displacement is recorded.
//!
//! - **Frequency**: the mean half-period between zero crossings (linearly
//!   interpolated) gives the damped frequency ω_d.
//! - **Damping**: the ratio of successive extrema gives the logarithmic
//!   decrement δ per half cycle, ζ = δ / √(π² + δ²), and ω = ω_d / √(1 − ζ²).
//!
//! The analytic first mode of the continuum cantilever is ω₁ = 3.5160
//! √(EI / ρS L⁴). Internal friction (γ ℓ q̇) is γ/EI times the stiffness and
//! air drag (ν per unit length) is ν/ρS times the mass, so the damping is of
//! Rayleigh form and every continuum mode keeps its shape with
//! ζ₁ = ν / (2 ρS ω₁) + γ ω₁ / (2 EI).
//!
//! The step is a thousandth of the analytic period: the linearly implicit
//! step's own damping, about π/1000 per period there, stays below 1% of
//! the physical ζ.

use glam::DVec3;
use helixhair_physics::{Method, RigidMotion, Strand, StrandParams};
use serde::Serialize;

use super::BenchContext;
use super::chart::{Axis, LineChart, REFERENCE_COLOUR, Series, draw_line_chart, series_per_method};
use super::cost::SOLVERS;
use super::scenes::horizontal_strand;
use super::table::write_csv;

/// First cantilever eigenvalue ω₁ √(ρS L⁴ / EI).
pub const CANTILEVER_FIRST: f64 = 3.5160;
/// Element counts of the full study.
pub const FULL_ELEMENTS: [usize; 9] = [2, 3, 5, 7, 10, 14, 20, 30, 50];
/// Element counts of the quick study.
pub const QUICK_ELEMENTS: [usize; 3] = [2, 5, 10];
/// Steps per analytic period.
pub const STEPS_PER_PERIOD: f64 = 1000.0;
/// Initial bend, 1/m: a tip deflection of 0.4 mm on 20 cm, in the linear range.
pub const INITIAL_CURVATURE_PER_M: f64 = 0.02;
/// Half cycles measured after the first zero crossing.
pub const HALF_CYCLES: usize = 4;

/// The continuum's first mode for `p`: (ω₁ in rad/s, ζ₁).
pub fn analytic_first_mode(p: &StrandParams) -> (f64, f64) {
    let ei = p.stiffness()[2];
    let rho_s = p.mass_per_length();
    let omega = CANTILEVER_FIRST * (ei / (rho_s * p.length_m.powi(4))).sqrt();
    let zeta = p.air_drag / (2.0 * rho_s * omega) + p.internal_friction * omega / (2.0 * ei);
    (omega, zeta)
}

/// One row of `modes.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct ModeRow {
    /// Solver label.
    pub method: String,
    /// Elements per strand.
    pub elements: usize,
    /// Measured undamped first-mode frequency, Hz.
    pub frequency_hz: f64,
    /// Measured damping ratio ζ.
    pub damping_ratio: f64,
    /// Analytic frequency of the continuum, Hz.
    pub analytic_frequency_hz: f64,
    /// Analytic damping ratio of the continuum.
    pub analytic_damping_ratio: f64,
}

/// Zero crossings and the extremum between each pair, of a sampled signal.
pub fn crossings_and_extrema(samples: &[f64], h: f64) -> (Vec<f64>, Vec<f64>) {
    let (mut crossings, mut extrema) = (Vec::new(), Vec::new());
    let mut peak = 0.0f64;
    for (i, pair) in samples.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        if b.abs() > peak.abs() {
            peak = b;
        }
        if (a <= 0.0 && b > 0.0) || (a >= 0.0 && b < 0.0) {
            crossings.push(h * (i as f64 + a / (a - b)));
            extrema.push(peak);
            peak = 0.0;
        }
    }
    (crossings, extrema)
}

/// Frequency (rad/s, undamped) and ζ from crossings and the extrema
/// between them; the extremum before the first crossing is left out.
pub fn frequency_and_damping(crossings: &[f64], extrema: &[f64]) -> Option<(f64, f64)> {
    if crossings.len() < HALF_CYCLES + 1 {
        return None;
    }
    let half = (crossings[HALF_CYCLES] - crossings[0]) / HALF_CYCLES as f64;
    let peaks = &extrema[1..=HALF_CYCLES];
    let decrements: Vec<f64> = peaks
        .windows(2)
        .map(|p| (p[0].abs() / p[1].abs()).ln())
        .collect();
    let delta = decrements.iter().sum::<f64>() / decrements.len() as f64;
    let zeta = delta / (std::f64::consts::PI.powi(2) + delta * delta).sqrt();
    let omega_d = std::f64::consts::PI / half;
    Some((omega_d / (1.0 - zeta * zeta).sqrt(), zeta))
}

/// Measures the first mode of `method` with `elements` elements.
pub fn measure(method: Method, elements: usize) -> ModeRow {
    let params = StrandParams {
        elements,
        ..StrandParams::default()
    };
    let (omega, zeta) = analytic_first_mode(&params);
    let mut strand = horizontal_strand(&params, method);
    let bend = vec![DVec3::new(0.0, 0.0, INITIAL_CURVATURE_PER_M); elements];
    strand.set_state(&bend, &vec![DVec3::ZERO; elements]);
    let root = RigidMotion::default();
    let period = std::f64::consts::TAU / omega;
    let h = period / STEPS_PER_PERIOD;
    // Block-diagonal swings up to ~3× faster; 4 analytic periods cover it.
    let steps = (4.0 * STEPS_PER_PERIOD) as usize;
    let mut tip = Vec::with_capacity(steps + 1);
    let tip_y = |s: &Strand| {
        s.boundary_points_world(&root)
            .last()
            .map_or(f64::NAN, |p| p.y)
    };
    tip.push(tip_y(&strand));
    for _ in 0..steps {
        strand.step(&root, DVec3::ZERO, DVec3::ZERO, h);
        tip.push(tip_y(&strand));
    }
    let (crossings, extrema) = crossings_and_extrema(&tip, h);
    let (measured_omega, measured_zeta) =
        frequency_and_damping(&crossings, &extrema).unwrap_or((f64::NAN, f64::NAN));
    ModeRow {
        method: method.label(),
        elements,
        frequency_hz: measured_omega / std::f64::consts::TAU,
        damping_ratio: measured_zeta,
        analytic_frequency_hz: omega / std::f64::consts::TAU,
        analytic_damping_ratio: zeta,
    }
}

/// Runs the study: `modes.csv`, `modes_frequency.svg`, `modes_damping.svg`.
pub fn run(ctx: &mut BenchContext<'_>) -> anyhow::Result<()> {
    let elements: &[usize] = if ctx.quick {
        &QUICK_ELEMENTS
    } else {
        &FULL_ELEMENTS
    };
    let mut rows = Vec::new();
    for &n in elements {
        for method in SOLVERS {
            let row = measure(method, n);
            writeln!(
                ctx.log,
                "   {:>12} N = {n:>2}: f = {:.4} Hz (analytic {:.4}), ζ = {:.4} (analytic {:.4})",
                row.method,
                row.frequency_hz,
                row.analytic_frequency_hz,
                row.damping_ratio,
                row.analytic_damping_ratio
            )?;
            rows.push(row);
        }
    }
    write_csv(&ctx.file("modes.csv"), &rows)?;
    for (file, title, label, value) in [
        (
            "modes_frequency.svg",
            "First-mode frequency over the continuum's, 20 cm cantilever",
            "f₁ / f₁ analytic",
            (|r: &ModeRow| r.frequency_hz / r.analytic_frequency_hz) as fn(&ModeRow) -> f64,
        ),
        (
            "modes_damping.svg",
            "First-mode damping ratio over the continuum's",
            "ζ₁ / ζ₁ analytic",
            |r: &ModeRow| r.damping_ratio / r.analytic_damping_ratio,
        ),
    ] {
        let mut series = series_per_method(
            &SOLVERS,
            &rows,
            |r| &r.method,
            |r| Some((r.elements as f64, value(r))),
            true,
        );
        series.push(Series {
            name: "analytic (continuum)".into(),
            points: elements.iter().map(|&n| (n as f64, 1.0)).collect(),
            line: true,
            markers: false,
            colour: REFERENCE_COLOUR,
        });
        let chart = LineChart {
            title: title.into(),
            x: Axis {
                label: "elements per strand N".into(),
                log: true,
            },
            y: Axis {
                label: label.into(),
                log: false,
            },
            series,
        };
        draw_line_chart(&ctx.file(file), &chart)?;
    }
    Ok(())
}

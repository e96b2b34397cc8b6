//! Charts as SVG files, drawn with plotters: line and scatter charts on
//! linear or logarithmic axes, and the stability grids.
//!
//! SVG keeps text as text (no font files are needed to draw it, and the
//! charts stay sharp when docs/benchmarks.md is zoomed); plotters' SVG backend lays
//! text out with an estimate of glyph widths, which is enough for labels.

use std::ops::Range;
use std::path::Path;

use anyhow::anyhow;
use helixhair_physics::Method;
use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::prelude::*;

/// Chart size in pixels: wide enough for a legend beside the data.
pub const CHART_SIZE_PX: (u32, u32) = (900, 560);

/// Colours of successive series, picked to stay apart for common colour
/// blindness (the Okabe–Ito palette, with purple for its yellow, which is
/// hard to see on white). Index [`REFERENCE_COLOUR`] (black) is kept for
/// reference lines: the Pareto front, the analytic value.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(117, 77, 156),
];

/// Palette index of reference lines; [`series_per_method`] skips it.
pub const REFERENCE_COLOUR: usize = 6;

/// One axis: its label and whether it is logarithmic.
#[derive(Clone, Debug)]
pub struct Axis {
    /// Label, with units.
    pub label: String,
    /// Logarithmic scale (all values must then be positive).
    pub log: bool,
}

/// One series of points.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// (x, y) points; non-finite points (and non-positive ones on a log
    /// axis) are left out.
    pub points: Vec<(f64, f64)>,
    /// Join the points with a line.
    pub line: bool,
    /// Mark each point.
    pub markers: bool,
    /// Index into [`PALETTE`] (wraps).
    pub colour: usize,
}

/// One series per solver: the rows whose `method` label matches, as
/// points, markers on, joined when `line`; colours follow `methods`' order.
pub fn series_per_method<R>(
    methods: &[Method],
    rows: &[R],
    method_of: impl Fn(&R) -> &str,
    point: impl Fn(&R) -> Option<(f64, f64)>,
    line: bool,
) -> Vec<Series> {
    methods
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let label = m.label();
            let colour = if i >= REFERENCE_COLOUR { i + 1 } else { i };
            Series {
                points: rows
                    .iter()
                    .filter(|r| method_of(r) == label)
                    .filter_map(&point)
                    .collect(),
                name: label,
                line,
                markers: true,
                colour,
            }
        })
        .collect()
}

/// A chart of several series against shared axes.
#[derive(Clone, Debug)]
pub struct LineChart {
    /// Caption above the plot.
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// The data.
    pub series: Vec<Series>,
}

/// Writes `chart` as an SVG file at `path`.
pub fn draw_line_chart(path: &Path, chart: &LineChart) -> anyhow::Result<()> {
    let root = SVGBackend::new(path, CHART_SIZE_PX).into_drawing_area();
    root.fill(&WHITE).map_err(plot_error)?;
    draw_line_chart_on(&root, chart)?;
    root.present().map_err(plot_error)
}

/// Draws `chart` into one drawing area (a whole file or one panel).
///
/// A logarithmic axis is drawn as a linear axis over log₁₀ of the values,
/// labelled with the values themselves: plotters' own log axis drops its
/// tick labels below 1 (0.3.7), and decades are what the reader needs.
pub fn draw_line_chart_on(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    chart: &LineChart,
) -> anyhow::Result<()> {
    let to_axis = |axis: &Axis, v: f64| -> Option<f64> {
        match (v.is_finite(), axis.log) {
            (true, false) => Some(v),
            (true, true) if v > 0.0 => Some(v.log10()),
            _ => None,
        }
    };
    let plotted: Vec<Vec<(f64, f64)>> = chart
        .series
        .iter()
        .map(|s| {
            s.points
                .iter()
                .filter_map(|&(x, y)| Some((to_axis(&chart.x, x)?, to_axis(&chart.y, y)?)))
                .collect()
        })
        .collect();
    let all = || plotted.iter().flatten();
    let x_range = padded_range(all().map(|p| p.0));
    let y_range = padded_range(all().map(|p| p.1));
    let x_spec = TickedAxis {
        ticks: ticks(&x_range, chart.x.log),
        range: x_range,
    };
    let y_spec = TickedAxis {
        ticks: ticks(&y_range, chart.y.log),
        range: y_range,
    };
    let label = |axis: &Axis, v: f64| short_number(if axis.log { 10f64.powf(v) } else { v });
    let x_label = |v: &f64| label(&chart.x, *v);
    let y_label = |v: &f64| label(&chart.y, *v);
    let mut ctx = ChartBuilder::on(area)
        .caption(&chart.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d(x_spec, y_spec)
        .map_err(plot_error)?;
    ctx.configure_mesh()
        .x_desc(axis_title(&chart.x))
        .y_desc(axis_title(&chart.y))
        .x_label_formatter(&x_label)
        .y_label_formatter(&y_label)
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(plot_error)?;
    for (series, points) in chart.series.iter().zip(plotted) {
        let colour = PALETTE[series.colour % PALETTE.len()];
        let style = ShapeStyle::from(&colour).stroke_width(2);
        if series.line {
            ctx.draw_series(LineSeries::new(points.clone(), style))
                .map_err(plot_error)?
                .label(&series.name)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
        }
        if series.markers {
            let drawn = ctx
                .draw_series(points.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                .map_err(plot_error)?;
            if !series.line {
                drawn
                    .label(&series.name)
                    .legend(move |(x, y)| Circle::new((x + 9, y), 4, colour.filled()));
            }
        }
    }
    ctx.configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .draw()
        .map_err(plot_error)?;
    Ok(())
}

/// An axis title, saying when the scale is logarithmic.
fn axis_title(axis: &Axis) -> String {
    if axis.log {
        format!("{} (log scale)", axis.label)
    } else {
        axis.label.clone()
    }
}

/// The data's range widened by a fraction, so that no point sits on the
/// frame; a unit range if there is no data.
pub fn padded_range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if !lo.is_finite() {
        return 0.0..1.0;
    }
    let pad = ((hi - lo) * 0.06)
        .max(hi.abs().max(lo.abs()) * 1e-3)
        .max(1e-9);
    lo - pad..hi + pad
}

/// A linear axis with tick marks where [`ticks`] puts them (plotters' own
/// linear axis picks round values of the log, not of the value).
#[derive(Clone, Debug)]
struct TickedAxis {
    range: Range<f64>,
    ticks: Vec<f64>,
}

impl Ranged for TickedAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let t = (value - self.range.start) / (self.range.end - self.range.start);
        limit.0 + (t * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, _hint: Hint) -> Vec<f64> {
        self.ticks.clone()
    }

    fn range(&self) -> Range<f64> {
        self.range.clone()
    }
}

/// Tick positions over `range` (log₁₀ values on a log axis): 1, 2, 5 times
/// powers of ten on a log axis (every integer multiple when that gives
/// fewer than three), and a 1-2-5 step giving at most eight on a linear one.
pub fn ticks(range: &Range<f64>, log: bool) -> Vec<f64> {
    let (lo, hi) = (range.start, range.end);
    if log {
        let decades = lo.floor() as i32..=hi.ceil() as i32;
        let pick = |mantissas: &[f64]| -> Vec<f64> {
            decades
                .clone()
                .flat_map(|k| mantissas.iter().map(move |m| (m * 10f64.powi(k)).log10()))
                .filter(|v| (lo..=hi).contains(v))
                .collect()
        };
        let coarse = pick(&[1.0, 2.0, 5.0]);
        if coarse.len() >= 3 {
            coarse
        } else {
            pick(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0])
        }
    } else {
        let span = (hi - lo).max(1e-12);
        let base = 10f64.powf((span / 8.0).log10().floor());
        let step = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|m| m * base)
            .find(|s| span / s <= 8.0)
            .unwrap_or(10.0 * base);
        let first = (lo / step).ceil() as i64;
        let last = (hi / step).floor() as i64;
        (first..=last).map(|i| i as f64 * step).collect()
    }
}

/// A tick label: plain for ordinary magnitudes, scientific otherwise.
pub fn short_number(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".into()
    } else if (1e-2..1e4).contains(&a) {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.0e}")
    }
}

/// plotters' errors carry the backend's error type; the caller wants text.
pub fn plot_error<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("drawing a chart: {e}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ticks_fall_on_one_two_five() {
        let values: Vec<f64> = ticks(&(0.0..2.5), true)
            .iter()
            .map(|v| (10f64.powf(*v) * 1e6).round() / 1e6)
            .collect();
        assert_eq!(values, vec![1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0]);
        assert_eq!(ticks(&(0.0..1.0), false).len(), 6);
    }

    #[test]
    fn ranges_pad_by_a_fraction() {
        let r = padded_range([0.0, 10.0].into_iter());
        assert!((r.start + 0.6).abs() < 1e-12 && (r.end - 10.6).abs() < 1e-12);
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(short_number(5.0), "5");
        assert_eq!(short_number(0.25), "0.25");
        assert_eq!(short_number(1e-5), "1e-5");
    }
}

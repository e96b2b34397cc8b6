//! Degenerate strands repaired or skipped one by one, never the groom.
//!
//! Every reader hands the strands it decoded to `repair`, which looks at
//! each strand alone, in this order:
//!
//! 1. fewer than two points: **skipped** ([`RepairReason::TooFewPoints`]);
//! 2. a NaN or infinite coordinate, in any frame: **skipped**
//!    ([`RepairReason::NonFinitePoint`]);
//! 3. total length at most [`DUPLICATE_DISTANCE_M`] (all points on one
//!    spot): **skipped** ([`RepairReason::ZeroLength`]);
//! 4. a point within [`DUPLICATE_DISTANCE_M`] of the last kept point
//!    (repeated points, zero-length segments): the point is **dropped**,
//!    with its width and colour, in every frame
//!    ([`RepairReason::RepeatedPoints`], counted once per strand); if fewer
//!    than two points remain the strand is **skipped**
//!    ([`RepairReason::TooFewDistinctPoints`]);
//! 5. a NaN, infinite or negative width, or a per-point width list of the
//!    wrong length: the strand keeps its points and **loses its width**
//!    ([`RepairReason::InvalidWidth`]); the same for a non-finite colour
//!    ([`RepairReason::InvalidColour`]).
//!
//! Decisions are taken on the first frame (the rest pose) except the
//! finiteness check, which looks at every frame, so all frames keep the
//! same topology. Bends sharp enough to trouble a Super-Helix fit are the
//! fitter's business, not this crate's.
//!
//! The [`RepairSummary`] counts strands read and kept and, per reason, the
//! strands it touched; [`RepairReason::name`] gives stable snake_case names
//! for JSON keys.

use std::fmt;

use glam::Vec3;

use crate::animation::Frame;
use crate::curve_set::{Curve, StrandValue};

/// Consecutive points closer than this (metres) are one point: 1 µm, about
/// ten `f32` steps at a metre from the origin and a hundredth of a hair's
/// diameter.
pub const DUPLICATE_DISTANCE_M: f32 = 1e-6;

/// Why a strand was repaired or skipped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum RepairReason {
    /// Skipped: fewer than two points in the file.
    TooFewPoints,
    /// Skipped: a NaN or infinite coordinate.
    NonFinitePoint,
    /// Skipped: every point on one spot.
    ZeroLength,
    /// Repaired: repeated points (zero-length segments) dropped.
    RepeatedPoints,
    /// Skipped: fewer than two points left once repeats were dropped.
    TooFewDistinctPoints,
    /// Repaired: a NaN, infinite or negative width (or a per-point list of
    /// the wrong length) removed.
    InvalidWidth,
    /// Repaired: a NaN or infinite colour removed.
    InvalidColour,
}

impl RepairReason {
    /// Every reason, in a fixed order.
    pub const ALL: [RepairReason; 7] = [
        RepairReason::TooFewPoints,
        RepairReason::NonFinitePoint,
        RepairReason::ZeroLength,
        RepairReason::RepeatedPoints,
        RepairReason::TooFewDistinctPoints,
        RepairReason::InvalidWidth,
        RepairReason::InvalidColour,
    ];

    /// The stable snake_case name, for JSON keys and reports.
    pub fn name(self) -> &'static str {
        match self {
            RepairReason::TooFewPoints => "too_few_points",
            RepairReason::NonFinitePoint => "non_finite_point",
            RepairReason::ZeroLength => "zero_length",
            RepairReason::RepeatedPoints => "repeated_points",
            RepairReason::TooFewDistinctPoints => "too_few_distinct_points",
            RepairReason::InvalidWidth => "invalid_width",
            RepairReason::InvalidColour => "invalid_colour",
        }
    }

    /// Whether strands with this reason were dropped (or kept, repaired).
    pub fn skips_strand(self) -> bool {
        matches!(
            self,
            RepairReason::TooFewPoints
                | RepairReason::NonFinitePoint
                | RepairReason::ZeroLength
                | RepairReason::TooFewDistinctPoints
        )
    }

    fn index(self) -> usize {
        self as usize
    }
}

impl fmt::Display for RepairReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What repair did to a file's strands.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RepairSummary {
    /// Strands decoded from the file.
    pub strands_read: usize,
    /// Strands kept (repaired or untouched).
    pub strands_kept: usize,
    /// Points dropped from kept strands as repeats.
    pub points_dropped: usize,
    counts: [usize; RepairReason::ALL.len()],
}

impl RepairSummary {
    /// How many strands this reason touched.
    pub fn count(&self, reason: RepairReason) -> usize {
        self.counts[reason.index()]
    }

    /// Strands skipped, all reasons together.
    pub fn strands_skipped(&self) -> usize {
        self.strands_read - self.strands_kept
    }

    /// The reasons that touched at least one strand, with their counts.
    pub fn nonzero(&self) -> impl Iterator<Item = (RepairReason, usize)> + '_ {
        RepairReason::ALL
            .into_iter()
            .map(|reason| (reason, self.count(reason)))
            .filter(|&(_, count)| count > 0)
    }

    fn add(&mut self, reason: RepairReason) {
        self.counts[reason.index()] += 1;
    }
}

impl fmt::Display for RepairSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} strands read, {} kept",
            self.strands_read, self.strands_kept
        )?;
        for (reason, count) in self.nonzero() {
            write!(f, ", {reason}: {count}")?;
        }
        Ok(())
    }
}

/// Strands and frames after repair.
pub(crate) struct Repaired {
    pub curves: Vec<Curve>,
    pub frames: Vec<Frame>,
    pub summary: RepairSummary,
}

/// Repairs or skips each strand (see the module docs). `frames` hold the
/// strands' points flattened in order; each must be as long as all the
/// strands' points together (the readers guarantee it).
pub(crate) fn repair(curves: Vec<Curve>, frames: Vec<Frame>) -> Repaired {
    let mut summary = RepairSummary {
        strands_read: curves.len(),
        ..RepairSummary::default()
    };
    let mut kept_curves = Vec::with_capacity(curves.len());
    let mut kept_frames: Vec<Frame> = frames
        .iter()
        .map(|frame| Frame {
            time_code: frame.time_code,
            points_m: Vec::with_capacity(frame.points_m.len()),
        })
        .collect();
    let mut offset = 0;
    for mut curve in curves {
        let range = offset..offset + curve.points_m.len();
        offset = range.end;
        let keep = match plan(&curve, &frames, range.clone()) {
            Ok(keep) => keep,
            Err(reason) => {
                summary.add(reason);
                continue;
            }
        };
        if keep.len() < curve.points_m.len() {
            summary.add(RepairReason::RepeatedPoints);
            summary.points_dropped += curve.points_m.len() - keep.len();
            curve.points_m = select(&curve.points_m, &keep);
            if let Some(StrandValue::PerPoint(widths)) = &mut curve.width_m {
                *widths = select_if_long_enough(widths, &keep);
            }
            if let Some(StrandValue::PerPoint(colours)) = &mut curve.colour {
                *colours = select_if_long_enough(colours, &keep);
            }
        }
        if !width_is_valid(curve.width_m.as_ref(), curve.points_m.len()) {
            summary.add(RepairReason::InvalidWidth);
            curve.width_m = None;
        }
        if !colour_is_valid(curve.colour.as_ref(), curve.points_m.len()) {
            summary.add(RepairReason::InvalidColour);
            curve.colour = None;
        }
        for (frame, kept) in frames.iter().zip(&mut kept_frames) {
            let points = &frame.points_m[range.clone()];
            kept.points_m
                .extend(keep.iter().map(|&index| points[index]));
        }
        kept_curves.push(curve);
    }
    summary.strands_kept = kept_curves.len();
    Repaired {
        curves: kept_curves,
        frames: kept_frames,
        summary,
    }
}

/// The indices of the points to keep, or why the strand goes.
fn plan(
    curve: &Curve,
    frames: &[Frame],
    range: std::ops::Range<usize>,
) -> Result<Vec<usize>, RepairReason> {
    let points = &curve.points_m;
    if points.len() < 2 {
        return Err(RepairReason::TooFewPoints);
    }
    let finite = |points: &[Vec3]| points.iter().all(|point| point.is_finite());
    if !finite(points)
        || !frames
            .iter()
            .all(|frame| finite(&frame.points_m[range.clone()]))
    {
        return Err(RepairReason::NonFinitePoint);
    }
    if curve.length_m() <= f64::from(DUPLICATE_DISTANCE_M) {
        return Err(RepairReason::ZeroLength);
    }
    let mut keep = vec![0];
    let mut last = points[0];
    for (index, &point) in points.iter().enumerate().skip(1) {
        if point.distance(last) > DUPLICATE_DISTANCE_M {
            keep.push(index);
            last = point;
        }
    }
    if keep.len() < 2 {
        return Err(RepairReason::TooFewDistinctPoints);
    }
    Ok(keep)
}

fn select<T: Copy>(values: &[T], keep: &[usize]) -> Vec<T> {
    keep.iter().map(|&index| values[index]).collect()
}

/// A per-point list of the wrong length is left as it is (and then found
/// invalid), rather than indexed out of bounds.
fn select_if_long_enough<T: Copy>(values: &[T], keep: &[usize]) -> Vec<T> {
    match keep.last() {
        Some(&last) if last < values.len() => select(values, keep),
        _ => values.to_vec(),
    }
}

fn width_is_valid(width: Option<&StrandValue<f32>>, point_count: usize) -> bool {
    let ok = |w: &f32| w.is_finite() && *w >= 0.0;
    match width {
        None => true,
        Some(StrandValue::PerStrand(w)) => ok(w),
        Some(StrandValue::PerPoint(widths)) => widths.len() == point_count && widths.iter().all(ok),
    }
}

fn colour_is_valid(colour: Option<&StrandValue<[f32; 3]>>, point_count: usize) -> bool {
    let ok = |c: &[f32; 3]| c.iter().all(|v| v.is_finite());
    match colour {
        None => true,
        Some(StrandValue::PerStrand(c)) => ok(c),
        Some(StrandValue::PerPoint(colours)) => {
            colours.len() == point_count && colours.iter().all(ok)
        }
    }
}

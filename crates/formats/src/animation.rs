//! Moving curves: frames of points over a fixed topology.
//!
//! An [`Animation`] belongs to a [`crate::CurveSet`]: every frame holds the
//! points of all its curves, in curve order and flattened (curve 0's points,
//! then curve 1's, …), so a frame is as long as
//! [`crate::CurveSet::point_count`]. Widths and colours do not move. Only
//! USD and Alembic store time samples; the other writers take one frame
//! (write a numbered sequence for them).

use glam::Vec3;

use crate::curve_set::CurveSet;

/// Frames of a groom's points over time.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    /// Time codes per second (USD's `timeCodesPerSecond`; 24 when the file
    /// does not say).
    pub time_codes_per_second: f64,
    /// The frames, in increasing time.
    pub frames: Vec<Frame>,
}

/// The points of every curve at one time.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The time code (a frame number in USD's convention).
    pub time_code: f64,
    /// Every curve's points, in metres, flattened in curve order.
    pub points_m: Vec<Vec3>,
}

impl Frame {
    /// A frame holding a curve set's current points.
    pub fn from_curves(time_code: f64, curves: &CurveSet) -> Frame {
        Frame {
            time_code,
            points_m: curves
                .curves
                .iter()
                .flat_map(|curve| curve.points_m.iter().copied())
                .collect(),
        }
    }
}

//! What every reader returns: the repaired groom ([`Imported`]), and the
//! two steps every reader shares to get there: the file's numbers made
//! metres, Y up ([`Units`], the caller's options over what the file
//! declares over the format's defaults), and the decoded strands repaired
//! into the result ([`finish`]).
//!
//! The readers (`tfx`, `hair`, `obj`, `usda`, `usdc`, `abc`) build on this module and
//! [`crate::read`] dispatches to them, so neither depends on the other.

use glam::Vec3;

use crate::animation::{Animation, Frame};
use crate::curve_set::{Curve, CurveSet, Metadata, UpAxis};
use crate::error::{Location, ReadError, ReadErrorKind};
use crate::format::Format;
use crate::options::ReadOptions;
use crate::repair::{RepairSummary, repair};

/// A groom read from a file.
#[derive(Clone, Debug, PartialEq)]
pub struct Imported {
    /// The curves, repaired, in metres, Y up. Animated files give the first
    /// frame here.
    pub curves: CurveSet,
    /// The frames, when the file holds time samples (USD and Alembic); their points
    /// follow `curves` (same strands, same repairs).
    pub animation: Option<Animation>,
    /// What repair did, strand by strand.
    pub summary: RepairSummary,
    /// What was read approximately or ignored (e.g. cubic USD curves read as
    /// their control polylines, transforms not applied).
    pub warnings: Vec<String>,
}

impl Imported {
    /// The points held, in the curves and in every frame: never more than
    /// the file has bytes (the fuzz targets and mutation tests check it).
    pub fn points_held(&self) -> usize {
        let frames: usize = self
            .animation
            .iter()
            .flat_map(|animation| &animation.frames)
            .map(|frame| frame.points_m.len())
            .sum();
        self.curves.point_count() + frames
    }
}

/// How a file's numbers become metres, Y up.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Units {
    pub metres_per_unit: f64,
    pub up_axis: UpAxis,
    pub declared_by_file: bool,
}

impl Units {
    /// The caller's options over what the file declared (if it declares
    /// anything) over the format's defaults (metres, Y up).
    pub fn resolve(
        format: Format,
        options: &ReadOptions,
        declared: Option<(f64, UpAxis)>,
    ) -> Result<Units, ReadError> {
        let (file_metres, file_up) = declared.unwrap_or((1.0, UpAxis::Y));
        let metres_per_unit = options.metres_per_unit.unwrap_or(file_metres);
        if !(metres_per_unit.is_finite() && metres_per_unit > 0.0) {
            return Err(ReadError::new(
                format,
                Location::File,
                ReadErrorKind::BadValue,
                format!("metres per unit must be finite and positive, not {metres_per_unit}"),
            ));
        }
        Ok(Units {
            metres_per_unit,
            up_axis: options.up_axis.unwrap_or(file_up),
            declared_by_file: declared.is_some()
                && options.metres_per_unit.is_none()
                && options.up_axis.is_none(),
        })
    }

    /// A point in file units and axes, in metres and Y up.
    pub fn point(&self, x: f64, y: f64, z: f64) -> Vec3 {
        let scale = self.metres_per_unit;
        let point = Vec3::new((x * scale) as f32, (y * scale) as f32, (z * scale) as f32);
        self.up_axis.to_y_up(point)
    }

    /// A length in file units, in metres.
    pub fn length(&self, value: f64) -> f32 {
        (value * self.metres_per_unit) as f32
    }

    pub fn metadata(&self, format: Format) -> Metadata {
        Metadata {
            source_format: Some(format),
            file_up_axis: self.up_axis,
            file_metres_per_unit: self.metres_per_unit,
            declared_by_file: self.declared_by_file,
        }
    }
}

/// Repairs decoded strands and frames into the result every reader returns.
pub(crate) fn finish(
    format: Format,
    units: &Units,
    curves: Vec<Curve>,
    animation: Option<(f64, Vec<Frame>)>,
    warnings: Vec<String>,
) -> Imported {
    let (time_codes_per_second, frames) = animation.unwrap_or((0.0, Vec::new()));
    let animated = !frames.is_empty();
    let repaired = repair(curves, frames);
    Imported {
        curves: CurveSet {
            curves: repaired.curves,
            metadata: units.metadata(format),
        },
        animation: animated.then_some(Animation {
            time_codes_per_second,
            frames: repaired.frames,
        }),
        summary: repaired.summary,
        warnings,
    }
}

//! The format-neutral groom: curves as polylines in metres, Y up.
//!
//! Every reader converts what it reads into a [`CurveSet`], and every writer
//! writes one, so a groom goes from any format to any other through this one
//! type. Conventions, whatever the file said:
//!
//! - **Points are `f32` metres** ([`glam::Vec3`]). All the binary formats
//!   store `f32`, so nothing is lost there; text formats are parsed in `f64`,
//!   scaled to metres and rounded once to `f32`. Writers print the shortest
//!   decimal that reads back as the same `f32`, so a write–read round trip
//!   is exact to the bit in every format.
//! - **Y is up.** A file declared (or said by the caller to be) Z-up is
//!   turned by −90° about X on reading: `(x, y, z)` becomes `(x, z, −y)`.
//!   [`Metadata`] keeps what the file said.
//! - **Root first**: a curve's first point is its root.
//! - **Widths are diameters in metres** (USD's `widths`, the `.hair`
//!   thickness), per strand or per point ([`StrandValue`]); colours are
//!   linear RGB in 0..1 as the file gives them.

use glam::Vec3;

use crate::format::Format;

/// A groom: curves and what is known about where they came from.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CurveSet {
    /// The strands, root first.
    pub curves: Vec<Curve>,
    /// Where they came from and how the file measured them.
    pub metadata: Metadata,
}

/// One strand: a polyline, root first, with optional width and colour.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Curve {
    /// The points in metres, Y up, root first.
    pub points_m: Vec<Vec3>,
    /// The strand's diameter in metres, for the whole strand or per point.
    pub width_m: Option<StrandValue<f32>>,
    /// The strand's linear RGB colour, for the whole strand or per point.
    pub colour: Option<StrandValue<[f32; 3]>>,
}

/// A value given once for a strand or once per point of it.
#[derive(Clone, Debug, PartialEq)]
pub enum StrandValue<T> {
    /// One value for the whole strand (USD's `uniform`).
    PerStrand(T),
    /// One value per point (USD's `vertex`); as long as the points.
    PerPoint(Vec<T>),
}

impl<T: Copy> StrandValue<T> {
    /// The value at point `index` of a strand.
    pub fn at(&self, index: usize) -> Option<T> {
        match self {
            StrandValue::PerStrand(value) => Some(*value),
            StrandValue::PerPoint(values) => values.get(index).copied(),
        }
    }
}

/// The axis a file calls up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum UpAxis {
    /// +Y up (TressFX, OBJ, USD's fallback, this crate's convention).
    #[default]
    Y,
    /// +Z up (Cem Yuksel's hair models, many DCC scenes).
    Z,
}

impl UpAxis {
    /// A point in this up-axis convention, turned to Y up.
    pub fn to_y_up(self, point: Vec3) -> Vec3 {
        match self {
            UpAxis::Y => point,
            UpAxis::Z => Vec3::new(point.x, point.z, -point.y),
        }
    }
}

/// Where a groom came from and how its file measured it.
#[derive(Clone, Debug, PartialEq)]
pub struct Metadata {
    /// The format it was read from; `None` for curves made in memory.
    pub source_format: Option<Format>,
    /// The up axis of the file (the points are Y up regardless).
    pub file_up_axis: UpAxis,
    /// The file's length unit in metres (the points are metres regardless).
    pub file_metres_per_unit: f64,
    /// Whether the file declared its unit and up axis (USD does), or they
    /// were the caller's choice or the format's default.
    pub declared_by_file: bool,
}

impl Default for Metadata {
    fn default() -> Metadata {
        Metadata {
            source_format: None,
            file_up_axis: UpAxis::Y,
            file_metres_per_unit: 1.0,
            declared_by_file: false,
        }
    }
}

impl CurveSet {
    /// Curves made in memory, with default metadata.
    pub fn new(curves: Vec<Curve>) -> CurveSet {
        CurveSet {
            curves,
            metadata: Metadata::default(),
        }
    }

    /// The number of points over all curves.
    pub fn point_count(&self) -> usize {
        self.curves.iter().map(|curve| curve.points_m.len()).sum()
    }

    /// The smallest box (min, max corners, metres) holding every point, or
    /// `None` without points.
    pub fn bounds_m(&self) -> Option<(Vec3, Vec3)> {
        bounds_of(self.curves.iter().flat_map(|curve| curve.points_m.iter()))
    }
}

/// The smallest box holding the points, or `None` without points.
pub(crate) fn bounds_of<'a>(points: impl Iterator<Item = &'a Vec3>) -> Option<(Vec3, Vec3)> {
    points.fold(None, |bounds, &point| match bounds {
        None => Some((point, point)),
        Some((min, max)) => Some((min.min(point), max.max(point))),
    })
}

impl Curve {
    /// A bare polyline, without width or colour.
    pub fn new(points_m: Vec<Vec3>) -> Curve {
        Curve {
            points_m,
            width_m: None,
            colour: None,
        }
    }

    /// The polyline's length in metres (in `f64`).
    pub fn length_m(&self) -> f64 {
        self.points_m
            .windows(2)
            .map(|pair| f64::from(pair[0].distance(pair[1])))
            .sum()
    }
}

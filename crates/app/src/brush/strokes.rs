//! Stroke files: a styling session's brush strokes in RON, so strokes made
//! in the window can be replayed headless (`helixhair groom --strokes`),
//! tested in CI and scripted (format: `docs/stroke-format.md`).
//!
//! ```ron
//! (
//!     version: 1,
//!     strokes: [
//!         (tool: Comb, path: [(-0.17, -0.10, -0.10), (-0.17, -0.10, 0.15)], radius_m: 0.08, seconds: 1.0),
//!         (tool: Cut(length_m: 0.15), path: [(0.0, -0.20, -0.20)], radius_m: 0.08),
//!         (tool: Curl(radius_m: 0.01, step_m: 0.03), path: [(0.17, -0.15, 0.0)], radius_m: 0.08),
//!         (tool: Freeze, path: [(0.0, 0.0, 0.0)], radius_m: 1.0),
//!     ],
//! )
//! ```
//!
//! The brush is a sphere of `radius_m` (head coordinates, metres) moved
//! along `path` at constant speed over `seconds` of simulated time, the
//! physics running. A strand is under the brush when one of its points
//! (element ends and quadrature samples) lies inside the sphere; each
//! point's weight falls from 1 at the centre's side of the sphere to 0 at
//! its rim as `falloff` says ([`crate::brush::sphere`]). What each tool
//! does: [`Tool`].

use glam::DVec3;
use helixhair_physics::natural_shape::MAX_NATURAL_STRAIN_PER_M;
use serde::{Deserialize, Serialize};

use crate::style::checks::MAX_ROOT_COORDINATE_M;
use crate::style::field_path::FieldPath;
use crate::style::ron_file::RonFile;
use crate::style::strand_edit::{MIN_ELEMENT_LENGTH_M, STIFFNESS_SCALE_RANGE};

/// The stroke format version this build reads and writes.
pub const STROKES_VERSION: u32 = 1;

/// Most strokes one file may hold.
pub const MAX_STROKES: usize = 10_000;

/// Most points one stroke's path may hold.
pub const MAX_PATH_POINTS: usize = 100_000;

/// Longest stroke, seconds of simulated time.
pub const MAX_STROKE_SECS: f64 = 60.0;

/// Largest brush, metres (a radius of 1 m takes a whole head).
pub const MAX_RADIUS_M: f64 = 2.0;

/// A styling session's strokes, applied in order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrokeFile {
    /// Format version; must be [`STROKES_VERSION`].
    pub version: u32,
    /// The strokes, in the order they were made.
    pub strokes: Vec<Stroke>,
}

/// One brush stroke.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stroke {
    /// What the brush does.
    pub tool: Tool,
    /// The brush centre's path, head coordinates, metres: one point for a
    /// dab, more for a drag (moved through at constant speed).
    pub path: Vec<DVec3>,
    /// The brush's radius, metres.
    pub radius_m: f64,
    /// Simulated time the stroke takes, seconds: the brush moves along its
    /// path over it (Comb, Grab, Part), or the hair settles for it after a
    /// dab (Cut, Grow, Curl, Stiffness, Smooth, Freeze). Default 1 s.
    #[serde(default = "default_seconds")]
    pub seconds: f64,
    /// How strongly the tool acts, 0 to 1. Default 1.
    #[serde(default = "one")]
    pub strength: f64,
    /// Which part of the radius fades out, 0 (a hard brush: full weight
    /// inside the sphere) to 1 (falls smoothly from the centre to the
    /// rim). Default 0.
    #[serde(default)]
    pub falloff: f64,
    /// Whether the strands the stroke moved keep their new shape as their
    /// rest shape at its end (Comb, Grab, Part, Smooth). Default true.
    #[serde(default = "yes")]
    pub freeze: bool,
    /// The strand groups the stroke may touch, by name; empty: all.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub groups: Vec<String>,
    /// Strands the stroke may not touch (the window's scalp mask); empty:
    /// none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub masked: Vec<StrandRef>,
}

/// One strand of a style: its group's name and its number in the group
/// (as a style's `edits` number them: listed roots, then grown or
/// imported ones).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrandRef {
    /// The group's name.
    pub group: String,
    /// The strand's number in it.
    pub strand: u32,
}

/// What a brush does to the strands under it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Tool {
    /// Drags the points under the brush along with it as it moves (a
    /// velocity-matching drag), then freezes the strands it moved.
    Comb,
    /// Takes the points under the brush at the path's start and pulls them
    /// along the path on soft springs; released at the end, then frozen.
    Grab,
    /// Shortens every strand under the brush to at most `length_m`.
    Cut {
        /// The longest a cut strand may be, metres.
        length_m: f64,
    },
    /// Lengthens every strand under the brush to at least `length_m`, its
    /// tip's curl continued.
    Grow {
        /// The shortest a grown strand may be, metres.
        length_m: f64,
    },
    /// Gives every strand under the brush this natural curl.
    Curl {
        /// Curl radius, metres.
        radius_m: f64,
        /// Rise per turn along the curl's axis, metres (its sign the
        /// handedness, 0 a flat circle).
        step_m: f64,
    },
    /// Scales the moduli of every strand under the brush to `scale` times
    /// its group's.
    Stiffness {
        /// Factor on the group's Young's and shear moduli.
        scale: f64,
    },
    /// Relaxes the shape of the strands under the brush toward their mean
    /// (the shapes by arc-length fraction), then freezes them.
    Smooth,
    /// Draws a parting line along the path on the scalp: roots within the
    /// radius turn away from it, up to `angle_deg` at the line; the hair
    /// then settles for the stroke's time and is frozen.
    Part {
        /// The largest turn of a root's growth direction, degrees.
        angle_deg: f64,
    },
    /// Makes the current shape of every strand under the brush its rest
    /// shape (sag-free, resting on the head).
    Freeze,
}

fn default_seconds() -> f64 {
    1.0
}

fn one() -> f64 {
    1.0
}

fn yes() -> bool {
    true
}

impl Tool {
    /// The tool's name as a file spells it.
    pub fn name(&self) -> &'static str {
        match self {
            Tool::Comb => "Comb",
            Tool::Grab => "Grab",
            Tool::Cut { .. } => "Cut",
            Tool::Grow { .. } => "Grow",
            Tool::Curl { .. } => "Curl",
            Tool::Stiffness { .. } => "Stiffness",
            Tool::Smooth => "Smooth",
            Tool::Part { .. } => "Part",
            Tool::Freeze => "Freeze",
        }
    }

    /// The first problem of the tool's values, as a field under `at` and a
    /// message.
    fn check(&self, at: &FieldPath) -> Result<(), (FieldPath, String)> {
        let in_range = |name: &str, value: f64, low: f64, high: f64| {
            if value.is_finite() && (low..=high).contains(&value) {
                Ok(())
            } else {
                Err((
                    at.field(name),
                    format!("must lie in [{low}, {high}]; found {value}"),
                ))
            }
        };
        match *self {
            Tool::Cut { length_m } | Tool::Grow { length_m } => {
                in_range("length_m", length_m, MIN_ELEMENT_LENGTH_M, 2.0)
            }
            Tool::Curl { radius_m, step_m } => {
                // The tightest curl the format holds: curvature R/(R²+c²)
                // under the strain limit.
                in_range("radius_m", radius_m, 1.0 / MAX_NATURAL_STRAIN_PER_M, 1.0)?;
                in_range("step_m", step_m, -1.0, 1.0)
            }
            Tool::Stiffness { scale } => in_range(
                "scale",
                scale,
                STIFFNESS_SCALE_RANGE.0,
                STIFFNESS_SCALE_RANGE.1,
            ),
            Tool::Part { angle_deg } => in_range("angle_deg", angle_deg, 0.0, 90.0),
            Tool::Comb | Tool::Grab | Tool::Smooth | Tool::Freeze => Ok(()),
        }
    }
}

impl Stroke {
    /// The first problem of the stroke, as a field under `at`.
    fn check(&self, at: &FieldPath) -> Result<(), (FieldPath, String)> {
        self.tool.check(&at.field("tool"))?;
        let path = at.field("path");
        if self.path.is_empty() || self.path.len() > MAX_PATH_POINTS {
            return Err((
                path,
                format!(
                    "must hold 1 to {MAX_PATH_POINTS} points; found {}",
                    self.path.len()
                ),
            ));
        }
        for (i, p) in self.path.iter().enumerate() {
            for (k, x) in p.to_array().into_iter().enumerate() {
                if !(x.is_finite() && x.abs() <= MAX_ROOT_COORDINATE_M) {
                    return Err((
                        path.index(i).index(k),
                        format!(
                            "must be a finite number in [-{MAX_ROOT_COORDINATE_M}, {MAX_ROOT_COORDINATE_M}] metres; found {x}"
                        ),
                    ));
                }
            }
        }
        let ranges = [
            ("radius_m", self.radius_m, 1e-4, MAX_RADIUS_M),
            ("seconds", self.seconds, 0.0, MAX_STROKE_SECS),
            ("strength", self.strength, 0.0, 1.0),
            ("falloff", self.falloff, 0.0, 1.0),
        ];
        for (name, value, low, high) in ranges {
            if !(value.is_finite() && (low..=high).contains(&value)) {
                return Err((
                    at.field(name),
                    format!("must lie in [{low}, {high}]; found {value}"),
                ));
            }
        }
        if let Some(i) = self.groups.iter().position(|g| g.trim().is_empty()) {
            return Err((at.field("groups").index(i), "must name a group".to_owned()));
        }
        if let Some(i) = self.masked.iter().position(|m| m.group.trim().is_empty()) {
            return Err((
                at.field("masked").index(i).field("group"),
                "must name a group".to_owned(),
            ));
        }
        Ok(())
    }

    /// The brush centre at fraction `t` of the stroke (0 to 1), moving
    /// along the path at constant speed.
    pub fn centre_at(&self, t: f64) -> DVec3 {
        match self.segment_at(t) {
            Some((a, b, fraction)) => a.lerp(b, fraction),
            None => *self.path.last().unwrap_or(&DVec3::ZERO),
        }
    }

    /// The brush centre's velocity at fraction `t`, m/s (zero for a dab or
    /// an instant stroke).
    pub fn velocity_at(&self, t: f64) -> DVec3 {
        if self.seconds <= 0.0 {
            return DVec3::ZERO;
        }
        let speed = self.path_length_m() / self.seconds;
        self.segment_at(t)
            .map_or(DVec3::ZERO, |(a, b, _)| (b - a).normalize_or_zero() * speed)
    }

    /// The path segment the centre is on at fraction `t` of the path's
    /// length, and the fraction of that segment; `None` for a dab.
    fn segment_at(&self, t: f64) -> Option<(DVec3, DVec3, f64)> {
        let mut left = t.clamp(0.0, 1.0) * self.path_length_m();
        let mut last = None;
        for pair in self.path.windows(2) {
            let length = pair[0].distance(pair[1]);
            if length <= 0.0 {
                continue;
            }
            last = Some((pair[0], pair[1], 1.0));
            if left <= length {
                return Some((pair[0], pair[1], left / length));
            }
            left -= length;
        }
        last
    }

    /// The path's length, metres.
    pub fn path_length_m(&self) -> f64 {
        self.path.windows(2).map(|p| p[0].distance(p[1])).sum()
    }

    /// Whether the stroke may touch the group named `name`.
    pub fn touches_group(&self, name: &str) -> bool {
        self.groups.is_empty() || self.groups.iter().any(|g| g == name)
    }
}

impl RonFile for StrokeFile {
    const WHAT: &'static str = "stroke file";

    fn check(&self) -> Result<(), (FieldPath, String)> {
        let root = FieldPath::root();
        if self.version != STROKES_VERSION {
            return Err((
                root.field("version"),
                format!(
                    "version {} is not supported: this build reads version {STROKES_VERSION}",
                    self.version
                ),
            ));
        }
        if self.strokes.len() > MAX_STROKES {
            return Err((
                root.field("strokes"),
                format!("{} strokes; at most {MAX_STROKES}", self.strokes.len()),
            ));
        }
        for (i, stroke) in self.strokes.iter().enumerate() {
            stroke.check(&root.field("strokes").index(i))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    #[test]
    fn the_bundled_stroke_file_loads() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/strokes/comb_cut_curl.ron");
        let file = StrokeFile::load(&path).expect("loads");
        assert_eq!(file.strokes.len(), 4);
        assert_eq!(file.strokes[1].tool, Tool::Cut { length_m: 0.15 });
        // Defaults: a second, full strength, a hard brush, frozen.
        let cut = &file.strokes[1];
        assert_eq!(
            (cut.seconds, cut.strength, cut.falloff, cut.freeze),
            (1.0, 1.0, 0.0, true)
        );
    }

    #[test]
    fn a_bad_value_names_the_file_line_and_field() {
        let src = "(\n    version: 1,\n    strokes: [\n        (tool: Comb, path: [(0.0, 0.0, 0.0)], radius_m: -0.1),\n    ],\n)\n";
        let error = StrokeFile::from_ron(src, Path::new("bad.ron")).expect_err("refused");
        let text = error.to_string();
        assert!(
            text.starts_with("bad.ron:4:") && text.contains("field `strokes[0].radius_m`"),
            "{text}"
        );
        let src = "(version: 1, strokes: [(tool: Curl(radius_m: 0.01), path: [(0.0, 0.0, 0.0)], radius_m: 0.1)])";
        let error = StrokeFile::from_ron(src, Path::new("s.ron")).expect_err("refused");
        assert!(error.to_string().contains("step_m"), "{error}");
    }

    #[test]
    fn the_brush_moves_along_its_path_at_constant_speed() {
        let stroke = Stroke {
            tool: Tool::Comb,
            path: vec![
                DVec3::ZERO,
                DVec3::new(0.1, 0.0, 0.0),
                DVec3::new(0.1, 0.3, 0.0),
            ],
            radius_m: 0.05,
            seconds: 2.0,
            strength: 1.0,
            falloff: 0.0,
            freeze: true,
            groups: Vec::new(),
            masked: Vec::new(),
        };
        // 0.4 m in 2 s: a quarter of the way is 0.1 m along, the corner.
        assert!((stroke.centre_at(0.25) - DVec3::new(0.1, 0.0, 0.0)).length() < 1e-12);
        assert!((stroke.centre_at(0.5) - DVec3::new(0.1, 0.1, 0.0)).length() < 1e-12);
        assert!((stroke.velocity_at(0.1) - DVec3::new(0.2, 0.0, 0.0)).length() < 1e-12);
        assert!((stroke.velocity_at(0.9) - DVec3::new(0.0, 0.2, 0.0)).length() < 1e-12);
        assert_eq!(stroke.centre_at(1.0), DVec3::new(0.1, 0.3, 0.0));
    }
}

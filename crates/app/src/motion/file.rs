//! Motion files: a head's rotation and position as keyframes in RON, so a
//! shot plays the same in the window, in `helixhair sim --play FILE` and
//! in a batch job (format: `docs/motion-format.md`).
//!
//! ```ron
//! (
//!     version: 1,
//!     name: "look left",
//!     keys: [
//!         (time_secs: 0.0),
//!         (time_secs: 0.5, turn_deg: 40.0, tilt_deg: 10.0),
//!         (time_secs: 1.2, offset_m: (0.0, 0.02, 0.0)),
//!     ],
//! )
//! ```
//!
//! # How it works
//!
//! Each key gives the head's pose at a time: turn (about +Y, degrees, to
//! the head's left), tilt (about +X, positive looks down), roll (about +Z)
//! and an offset in metres; fields left out are 0. The rotation is
//! Ry(turn) · Rx(tilt) · Rz(roll), the window's manual pose with roll
//! added. Between keys every channel follows a cubic Hermite curve with
//! Catmull–Rom slopes (the chord over the two neighbouring keys; zero at
//! the first and last key), so the head moves smoothly through the keys,
//! with continuous velocity, and starts and stops at rest; before the
//! first key and after the last it holds still. The physics takes
//! velocities and accelerations as central differences of this pose
//! ([`crate::motion::clip::motion_from_pose`]), as for the built-in clips.
//!
//! Errors name the file, the line and the field, as style errors do
//! (`shot.ron:7:20: field `keys\[2\].time_secs`: …`).

use std::path::Path;

use glam::{DMat3, DVec3};
use helixhair_physics::{HeadTrajectory, RigidMotion};
use serde::{Deserialize, Serialize};

use crate::motion::clip::motion_from_pose;
use crate::style::field_path::FieldPath;
use crate::style::ron_file::{RonFile, RonFileError};

/// The motion format version this build reads and writes.
pub const MOTION_VERSION: u32 = 1;

/// Most keys a motion file may hold (an hour of keys at 60 Hz).
pub const MAX_KEYS: usize = 216_000;

/// Largest offset a key may give, metres: a head moved further is a typo
/// (centimetres written as metres), not a shot.
pub const MAX_OFFSET_M: f64 = 10.0;

/// A head motion: keyframes in time order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Motion {
    /// Format version; must be [`MOTION_VERSION`].
    pub version: u32,
    /// A name for menus and reports.
    #[serde(default)]
    pub name: String,
    /// The keys, times strictly increasing.
    pub keys: Vec<MotionKey>,
}

/// The head's pose at one time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionKey {
    /// Time of the key, seconds from the start of the shot (≥ 0).
    pub time_secs: f64,
    /// Turn about +Y (yaw), degrees; positive turns to the head's left.
    #[serde(default)]
    pub turn_deg: f64,
    /// Tilt about +X (pitch), degrees; positive looks down.
    #[serde(default)]
    pub tilt_deg: f64,
    /// Roll about +Z, degrees.
    #[serde(default)]
    pub roll_deg: f64,
    /// Position of the head, metres (the head's origin at rest is 0).
    #[serde(default)]
    pub offset_m: DVec3,
}

/// Why a motion file could not be read or written (errors name the file,
/// the line and the field).
pub type MotionError = RonFileError;

impl RonFile for Motion {
    const WHAT: &'static str = "motion file";

    fn check(&self) -> Result<(), (FieldPath, String)> {
        self.validate()
    }
}

/// The header comment a saved motion file starts with.
fn motion_header() -> String {
    format!("HelixHair head motion, format version {MOTION_VERSION}: see docs/motion-format.md.")
}

impl MotionKey {
    /// The pose channels: turn, tilt, roll (radians), offset (metres).
    fn channels(&self) -> [f64; 6] {
        [
            self.turn_deg.to_radians(),
            self.tilt_deg.to_radians(),
            self.roll_deg.to_radians(),
            self.offset_m.x,
            self.offset_m.y,
            self.offset_m.z,
        ]
    }
}

/// The rotation of pose channels (turn, tilt, roll in radians).
fn rotation(turn_rad: f64, tilt_rad: f64, roll_rad: f64) -> DMat3 {
    DMat3::from_rotation_y(turn_rad)
        * DMat3::from_rotation_x(tilt_rad)
        * DMat3::from_rotation_z(roll_rad)
}

impl Motion {
    /// Reads and checks a motion file.
    pub fn load(path: &Path) -> Result<Motion, MotionError> {
        <Motion as RonFile>::load(path)
    }

    /// Parses and checks motion RON text; `path` only names the file in
    /// errors.
    pub fn from_ron(src: &str, path: &Path) -> Result<Motion, MotionError> {
        <Motion as RonFile>::from_ron(src, path)
    }

    /// The first problem of the motion: the field and what is wrong.
    pub fn validate(&self) -> Result<(), (FieldPath, String)> {
        let root = FieldPath::root();
        if self.version != MOTION_VERSION {
            return Err((
                root.field("version"),
                format!(
                    "version {} is not supported: this build reads version {MOTION_VERSION}",
                    self.version
                ),
            ));
        }
        if self.keys.is_empty() {
            return Err((root.field("keys"), "a motion needs at least one key".into()));
        }
        if self.keys.len() > MAX_KEYS {
            return Err((
                root.field("keys"),
                format!("{} keys; at most {MAX_KEYS}", self.keys.len()),
            ));
        }
        for (i, key) in self.keys.iter().enumerate() {
            let at = root.field("keys").index(i);
            let angles = [
                ("time_secs", key.time_secs),
                ("turn_deg", key.turn_deg),
                ("tilt_deg", key.tilt_deg),
                ("roll_deg", key.roll_deg),
            ];
            for (name, value) in angles {
                if !value.is_finite() {
                    return Err((
                        at.field(name),
                        format!("must be a finite number, not {value}"),
                    ));
                }
            }
            if !key.offset_m.is_finite() || key.offset_m.abs().max_element() > MAX_OFFSET_M {
                return Err((
                    at.field("offset_m"),
                    format!(
                        "each coordinate must be finite and within ±{MAX_OFFSET_M} m, not {}",
                        key.offset_m
                    ),
                ));
            }
            if key.time_secs < 0.0 {
                return Err((
                    at.field("time_secs"),
                    format!("must be 0 or more, not {}", key.time_secs),
                ));
            }
            if i > 0 && key.time_secs <= self.keys[i - 1].time_secs {
                return Err((
                    at.field("time_secs"),
                    format!(
                        "{} s does not come after the previous key's {} s: times must increase",
                        key.time_secs,
                        self.keys[i - 1].time_secs
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The motion as pretty RON text, with a header naming the format.
    pub fn to_ron(&self) -> Result<String, MotionError> {
        RonFile::to_ron(self, &motion_header())
    }

    /// Writes the motion to `path` atomically.
    pub fn save(&self, path: &Path) -> Result<(), MotionError> {
        RonFile::save(self, path, &motion_header())
    }

    /// The time of the last key, seconds.
    pub fn duration_secs(&self) -> f64 {
        self.keys.last().map_or(0.0, |k| k.time_secs)
    }

    /// (rotation, offset) of the head at `t_secs`: the keys' Hermite
    /// curves between them, held before the first and after the last.
    pub fn pose_at(&self, t_secs: f64) -> (DMat3, DVec3) {
        let c = self.channels_at(t_secs);
        (rotation(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5]))
    }

    /// The pose channels at `t_secs` (see [`MotionKey`]).
    fn channels_at(&self, t_secs: f64) -> [f64; 6] {
        let keys = &self.keys;
        let Some(first) = keys.first() else {
            return [0.0; 6];
        };
        let last = keys[keys.len() - 1];
        if t_secs <= first.time_secs || keys.len() == 1 {
            return first.channels();
        }
        if t_secs >= last.time_secs {
            return last.channels();
        }
        // The segment [keys[i], keys[i + 1]] holding t.
        let i = keys.partition_point(|k| k.time_secs <= t_secs) - 1;
        let (a, b) = (keys[i], keys[i + 1]);
        let h = b.time_secs - a.time_secs;
        let s = (t_secs - a.time_secs) / h;
        let slope = |j: usize| -> [f64; 6] {
            if j == 0 || j + 1 == keys.len() {
                return [0.0; 6];
            }
            let (before, after) = (keys[j - 1], keys[j + 1]);
            let span = after.time_secs - before.time_secs;
            let (p, q) = (before.channels(), after.channels());
            std::array::from_fn(|c| (q[c] - p[c]) / span)
        };
        let (ma, mb) = (slope(i), slope(i + 1));
        let (pa, pb) = (a.channels(), b.channels());
        // Cubic Hermite basis.
        let s2 = s * s;
        let s3 = s2 * s;
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h10 = s3 - 2.0 * s2 + s;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h11 = s3 - s2;
        std::array::from_fn(|c| h00 * pa[c] + h10 * h * ma[c] + h01 * pb[c] + h11 * h * mb[c])
    }
}

/// A motion played from time zero: what `sim --play FILE` steps the hair
/// on.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionTrajectory(pub Motion);

impl HeadTrajectory for MotionTrajectory {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        motion_from_pose(|t| self.0.pose_at(t), t_secs)
    }
}

#[cfg(test)]
#[path = "file_tests.rs"]
mod tests;

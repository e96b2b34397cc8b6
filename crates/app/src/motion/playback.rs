//! What `--play` names: a built-in clip (nod, shake, turn, jerk) or a
//! motion file ([`crate::motion::file`]), and the head trajectory either
//! becomes, so `helixhair sim` and `helixhair export` play both alike.

use std::path::PathBuf;

use glam::{DMat3, DVec3};
use helixhair_physics::{HeadTrajectory, RigidMotion};

use crate::motion::clip::{Clip, ClipTrajectory, about_pivot, motion_from_pose};
use crate::motion::file::{Motion, MotionError, MotionTrajectory};

/// A head motion as the command line names it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Playback {
    /// A built-in clip.
    Clip(Clip),
    /// A motion file (RON, docs/motion-format.md).
    File(PathBuf),
}

/// Parses `--play`: a clip's name, or a path to a motion file (anything
/// with a `.ron` extension or a path separator).
pub fn parse_play(text: &str) -> Result<Playback, String> {
    if let Some(clip) = Clip::from_name(text) {
        return Ok(Playback::Clip(clip));
    }
    let path = PathBuf::from(text);
    let is_ron = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ron"));
    if is_ron || text.contains(std::path::MAIN_SEPARATOR) || text.contains('/') {
        return Ok(Playback::File(path));
    }
    let names: Vec<&str> = Clip::ALL.iter().map(|c| c.name()).collect();
    Err(format!(
        "unknown clip `{text}`; expected one of {}, or a motion file (FILE.ron, see \
         docs/motion-format.md)",
        names.join(", ")
    ))
}

impl Playback {
    /// The head trajectory to step on: the clip, or the motion file read
    /// and checked (its errors name the file, line and field).
    pub fn load(&self) -> Result<HeadPlayback, MotionError> {
        match self {
            Playback::Clip(clip) => Ok(HeadPlayback::Clip(ClipTrajectory(*clip))),
            Playback::File(path) => Ok(HeadPlayback::Motion(MotionTrajectory(Motion::load(path)?))),
        }
    }
}

/// A head motion played from time zero, then a still head.
#[derive(Clone, Debug, PartialEq)]
pub enum HeadPlayback {
    /// A built-in clip.
    Clip(ClipTrajectory),
    /// A motion file's keys.
    Motion(MotionTrajectory),
}

impl HeadPlayback {
    /// (rotation, offset) of the head at `t_secs` from the start: what the
    /// window composes with the user's own pose.
    pub fn pose_at(&self, t_secs: f64) -> (DMat3, DVec3) {
        match self {
            HeadPlayback::Clip(clip) => clip.0.pose_at(t_secs),
            HeadPlayback::Motion(motion) => motion.0.pose_at(t_secs),
        }
    }

    /// How long it moves, seconds (after that the head holds still).
    pub fn duration_secs(&self) -> f64 {
        match self {
            HeadPlayback::Clip(clip) => clip.0.duration_secs(),
            HeadPlayback::Motion(motion) => motion.0.duration_secs(),
        }
    }
}

impl HeadTrajectory for HeadPlayback {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        match self {
            HeadPlayback::Clip(clip) => clip.motion_at(t_secs),
            HeadPlayback::Motion(motion) => motion.motion_at(t_secs),
        }
    }
}

/// A playback turning the head about `pivot_m` ([`about_pivot`]).
pub struct PivotedPlayback<'a> {
    /// The playback.
    pub playback: &'a HeadPlayback,
    /// The pivot, world coordinates at rest, metres.
    pub pivot_m: DVec3,
}

impl HeadTrajectory for PivotedPlayback<'_> {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        if self.pivot_m == DVec3::ZERO {
            return self.playback.motion_at(t_secs);
        }
        motion_from_pose(
            |t| about_pivot(self.playback.pose_at(t), self.pivot_m),
            t_secs,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_names_and_file_paths_parse_and_anything_else_is_refused() {
        assert_eq!(parse_play("shake"), Ok(Playback::Clip(Clip::Shake)));
        assert_eq!(
            parse_play("shots/look.ron"),
            Ok(Playback::File(PathBuf::from("shots/look.ron")))
        );
        assert_eq!(
            parse_play("look.RON"),
            Ok(Playback::File(PathBuf::from("look.RON")))
        );
        let error = parse_play("shaek").expect_err("a typo");
        assert!(
            error.starts_with("unknown clip `shaek`; expected one of nod, shake, turn, jerk"),
            "{error}"
        );
    }
}

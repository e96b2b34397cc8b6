//! How the head moves: the built-in clips, motion files of keyframes, and
//! what `--play` names.
//!
//! The physics takes a [`helixhair_physics::HeadTrajectory`]: the head's
//! rigid pose, velocity and acceleration at any time. [`clip`] gives the
//! four built-in clips (nod, shake, turn, jerk) as closed-form
//! trajectories; [`file`](mod@file) reads and writes motion files (keyframes
//! interpolated smoothly, `docs/motion-format.md`); [`playback`] turns
//! what `--play` names, a clip or a file, into one trajectory, so `sim`,
//! `render`, `export` and the window play both alike.

pub mod clip;
pub mod file;
pub mod playback;

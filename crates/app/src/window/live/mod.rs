//! The live scene behind the 3D view: the simulation following the
//! artist's edits, the head's motion and the hair drawn from it.
//!
//! [`live_sim`] keeps an [`helixhair_physics::engine::Engine`] running
//! while a style is edited, without a reset (shapes kept by
//! [`crate::sim::carry`] when element counts change), against the head collider of
//! [`collision`]; [`head_motion`] is the user's head pose and the built-in
//! motions, with the velocities and accelerations the physics needs, and
//! [`motion_recorder`] records a head drag as a motion file; [`drawn`]
//! draws styles with `render` sections as `helixhair render` does, and
//! [`device_plan`] an imported groom of guides from the GPU engine's own
//! buffers;
//! [`still_head`] is the run as a brush's host, the head held still.

pub mod collision;
pub mod device_plan;
pub mod drawn;
pub mod head_motion;
pub mod live_sim;
pub mod motion_recorder;
pub mod still_head;

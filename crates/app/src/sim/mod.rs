//! The simulation core's face: a style built into a running
//! [`helixhair_physics::engine::Engine`], stepped frame by frame, and
//! reported.
//!
//! [`build`] is the one builder from a style to an engine (its engine and
//! solver, or the command line's overrides, or the cheapest solver that
//! meets an accuracy target: [`auto_choice`] over the measured
//! [`error_model`]); the window's live run builds through it too.
//! [`headless::HeadlessSim`] steps what it built on a still or moving head:
//! `sim`, `render`, `export` and the bench all step through it, one frame
//! at a time ([`frame_stepper`], which the window's own run also implements),
//! and [`report`] gathers timings, energies and shapes for the summary and
//! the JSON file ([`tip_trajectories`] for the tips' paths).

pub mod auto_choice;
pub mod build;
pub mod carry;
pub mod engine_arg;
pub mod error_model;
pub mod frame_stepper;
pub mod grown;
pub mod headless;
pub mod report;
pub mod resample;
pub mod settle;
pub mod strands;
pub mod tip_trajectories;

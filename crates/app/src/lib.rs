//! HelixHair the application: hair styles in RON files, the headless
//! simulation, and the `helixhair` command line.
//!
//! The binary (`src/main.rs`) is a thin shell over [`cli::run`], so tests
//! drive everything through this library.
//!
//! # From a style file to a report
//!
//! 1. [`Style::load`] reads a style ([`style`]); every error names the file,
//!    the line and the field ([`StyleError`], located with
//!    [`source_map::SourceMap`]).
//! 2. [`HeadlessSim::new`] builds a [`helixhair_physics::HairSystem`] from it
//!    ([`headless`]), with the command line's overrides.
//! 3. [`HeadlessSim::run`] steps it on a still head, timing each frame and
//!    checking the state stays finite.
//! 4. [`SimReport`] ([`sim_report`]) gathers timings, energies and strand
//!    shapes, for a summary and the JSON file of `docs/sim-json.md`.

#![warn(missing_docs)]

pub mod atomic_write;
pub mod auto_choice;
pub mod bench;
pub mod cli;
pub mod error_model;
pub mod field_path;
pub mod headless;
pub mod sim_report;
pub mod source_map;
pub mod style;
pub mod style_error;
pub mod style_validate;

pub use field_path::FieldPath;
pub use headless::{HeadlessSim, SimError, SimOverrides};
pub use sim_report::SimReport;
pub use style::{Root, STYLE_VERSION, StrandGroup, Style};
pub use style_error::{StyleError, StyleErrorKind, StyleIssue};

#[cfg(test)]
mod style_tests;

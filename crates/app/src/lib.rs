//! HelixHair the application: hair styles in RON files, the headless
//! simulation, and the `helixhair` command line.
//!
//! The binary (`src/main.rs`) is a thin shell over [`cli::run`], so tests
//! drive everything through this library. Without a command it opens the
//! styling window (module `window`, cargo feature `window`); `helixhair
//! bench` is module `bench` (feature `bench`). Both features are on by
//! default; without them the style format and the headless `sim` and
//! `render` commands build alone.
//!
//! Every face (`sim`, `render`, the window, the bench) steps the physics
//! through one core, [`helixhair_physics::engine::Engine`] (the f64
//! reference `HairSystem` or the f32 `BatchSystem`). `sim`, `render` and
//! the bench's stability study build it from a style with
//! [`HeadlessSim`]; the window builds its own (`window::live_sim`). The
//! module graph has no cycles, and nothing below the faces depends on the
//! window or the bench.
//!
//! # From a style file to a report
//!
//! 1. [`Style::load`] reads a style ([`style`]); every error names the file,
//!    the line and the field ([`StyleError`], located with
//!    [`source_map::SourceMap`]).
//! 2. [`HeadlessSim::new`] builds an [`helixhair_physics::engine::Engine`]
//!    from it ([`headless`]) on the style's engine or `--engine`, with the
//!    command line's other overrides (and, with an accuracy target, the
//!    solver and element counts of [`auto_choice`]).
//! 3. [`HeadlessSim::run`] steps it on a still head, timing each frame and
//!    checking the state stays finite.
//! 4. [`SimReport`] ([`sim_report`]) gathers timings, energies and strand
//!    shapes, for a summary and the JSON file of `docs/sim-json.md`.
//!
//! # From a style file to a picture (`helixhair render`)
//!
//! 1. [`groom::Groom`] grows the style's scalp placements ([`style_groom`])
//!    into roots on the head (the default head or an OBJ).
//! 2. [`HeadlessSim`] simulates the grown style for the asked frames.
//! 3. [`drawn_layout`] places the drawn strands and picks the guides each
//!    follows; [`drawn_hair`] rebuilds them every frame from the guides'
//!    strains ([`strain_blend`]), colours them and drapes them over the
//!    head. The window draws through the same two functions.
//! 4. [`helixhair_render::OffscreenRenderer`] draws the picture, and
//!    [`render_cmd`] writes it as PNG ([`render_cmd::run_render`]).

#![warn(missing_docs)]

pub mod atomic_write;
pub mod auto_choice;
#[cfg(feature = "bench")]
pub mod bench;
pub mod camera_arg;
pub mod cli;
pub mod drawn_hair;
pub mod drawn_layout;
pub mod engine_arg;
pub mod error_model;
pub mod export;
pub mod export_cmd;
pub mod field_path;
pub mod frame_stepper;
pub mod groom;
pub mod guide_curves;
pub mod head_clip;
pub mod head_playback;
pub mod headless;
pub mod import_cmd;
pub mod import_fit;
pub mod import_report;
pub mod import_roots;
pub mod json_report;
pub mod motion_file;
pub mod render_cmd;
pub mod sim_report;
pub mod source_map;
pub mod stats;
pub mod strain_blend;
pub mod strand_colours;
pub mod strand_sampling;
pub mod style;
pub mod style_checks;
pub mod style_error;
pub mod style_groom;
pub mod style_groom_validate;
pub mod style_head;
pub mod style_imported;
pub mod style_imported_validate;
pub mod style_root;
pub mod style_validate;
pub mod tip_trajectories;
#[cfg(feature = "window")]
pub mod window;
pub mod work_progress;

pub use field_path::FieldPath;
pub use groom::Groom;
pub use headless::{HeadlessSim, SimError, SimOverrides};
pub use sim_report::SimReport;
pub use style::{Root, STYLE_VERSION, StrandGroup, Style};
pub use style_error::{StyleError, StyleErrorKind, StyleIssue};

#[cfg(test)]
mod drawn_layout_tests;
#[cfg(test)]
mod groom_tests;
#[cfg(test)]
mod style_groom_tests;
#[cfg(test)]
mod style_tests;

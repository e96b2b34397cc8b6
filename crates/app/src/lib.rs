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
//! # Rooms
//!
//! One folder a concern, each leaning only on the ones listed before it
//! (`tests/app_modules.rs` checks that the folders form no cycle):
//!
//! | module | what is inside |
//! | --- | --- |
//! | [`style`] | the RON style format: its types, checks and errors naming file, line and field |
//! | [`motion`] | head clips, motion files, what `--play` names |
//! | [`head`] | the head: roots grown from scalp placements, the collider, a style's own head |
//! | [`sim`] | a style built into a running engine ([`sim::grown`]), stepped and reported |
//! | [`hair`] | drawn and exported strands rebuilt from the simulated guides |
//! | [`import`] | grooms from other tools made into styles |
//! | [`export`] | the hair and its head out to curve files |
//! | [`brush`] | styling by hand: stroke files, the tools, `helixhair groom` |
//! | [`cli`] | the `helixhair` command line and `render` |
//! | `window` | the styling window (feature `window`) |
//! | `bench` | `helixhair bench` (feature `bench`) |
//!
//! and three small helpers at the top: [`atomic_write`], [`json_report`],
//! [`stats`] and [`work_progress`].
//!
//! Every face (`sim`, `render`, the window, the bench) steps the physics
//! through one core, [`helixhair_physics::engine::Engine`] (the f64
//! reference `HairSystem` or the f32 `BatchSystem`).
//!
//! # From a style file to a report
//!
//! 1. [`Style::load`] reads a style ([`style`]); every error names the file,
//!    the line and the field ([`StyleError`], located with
//!    [`style::source_map::SourceMap`]).
//! 2. [`HeadlessSim::new`] builds an [`helixhair_physics::engine::Engine`]
//!    from it through the one builder, [`sim::build`] (which the window's
//!    live run uses too), on the style's engine or `--engine`, with the
//!    command line's other overrides (and, with an accuracy target, the
//!    solver and element counts of [`sim::auto_choice`]).
//! 3. [`HeadlessSim::run`] steps it, timing each frame and checking the
//!    state stays finite.
//! 4. [`SimReport`] ([`sim::report`]) gathers timings, energies and strand
//!    shapes, for a summary and the JSON file of `docs/sim-json.md`.
//!
//! # From a style file to a picture (`helixhair render`)
//!
//! 1. [`sim::grown::grown_sim`] grows the style's scalp placements
//!    ([`head::groom::Groom`]) into roots on the head (the default head or
//!    an OBJ) and builds the simulation colliding with it.
//! 2. [`HeadlessSim`] simulates the grown style for the asked frames.
//! 3. [`hair::layout`] places the drawn strands and picks the guides each
//!    follows; [`hair::drawn`] rebuilds them every frame from the guides'
//!    strains ([`hair::strain_blend`]), colours them and drapes them over
//!    the head. The window draws through the same two functions.
//! 4. [`helixhair_render::OffscreenRenderer`] draws the picture, and
//!    [`cli::render`] writes it as PNG ([`cli::render::run_render`]).

#![warn(missing_docs)]

pub mod atomic_write;
#[cfg(feature = "bench")]
pub mod bench;
pub mod brush;
pub mod cli;
pub mod export;
pub mod hair;
pub mod head;
pub mod import;
pub mod json_report;
pub mod motion;
pub mod sim;
pub mod stats;
pub mod style;
#[cfg(feature = "window")]
pub mod window;
pub mod work_progress;

pub use head::groom::Groom;
pub use sim::build::{SimError, SimOverrides};
pub use sim::headless::HeadlessSim;
pub use sim::report::SimReport;
pub use style::error::{StyleError, StyleErrorKind, StyleIssue};
pub use style::field_path::FieldPath;
pub use style::{Root, STYLE_VERSION, StrandGroup, Style};

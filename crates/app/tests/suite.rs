//! Every integration test of the app crate, one module per file, in one
//! binary: one link of the app and its dependencies (wgpu, egui, winit)
//! instead of one per file. Run one file's tests with
//! `cargo test --release -p helixhair-app --test suite save_kill::`.

mod support;

#[cfg(feature = "bench")]
mod auto_choice;
mod cli;
mod example_styles;
mod export_cli;
mod export_kill;
mod export_round_trip;
mod groom_strokes;
mod import_cli;
mod import_sintel;
mod save_kill;
mod scalp_cover;
mod style_format_doc;
mod tip_trajectories;
mod window_brush;
#[cfg(feature = "window")]
mod window_screenshot;
mod window_sintel;

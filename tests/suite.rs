//! Every end-to-end test in one binary, one module per file. Run one
//! file's tests with `cargo test --release -p helixhair-e2e --test suite <file>::`.

/// The app's top-level modules lean on each other without a cycle (read
/// from the sources).
mod app_modules;
/// The documents hold together: links resolve, every picture is shown,
/// README.md is short and gives CI's test command, no history outside
/// CHANGELOG.md (reads files only).
mod doc_links;
/// No two files of different concerns import each other, in any crate (read
/// from the sources).
mod file_circles;
/// The layers (physics, render, the app's features) checked on `cargo
/// metadata`; runs no binary.
mod layers;
/// The GPU engine and the renderer on a device destroyed under them: an
/// error naming the loss, never a panic.
mod lost_device;
/// Render and the GPU engine with the adapter hidden: a message or a
/// fallback, never a panic.
mod no_adapter;
mod render_cli;
mod sim_cli;
mod style_errors;
/// The hair–hair model end to end: `sim --interaction`, the volume study.
mod volume_cli;

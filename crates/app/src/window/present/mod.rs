//! Putting a frame on screen: the 3D view, egui's paint and screenshots.
//!
//! [`viewport`] says what the renderer is asked to draw and how the mouse
//! moves the camera; [`window_gpu`] owns the surface and the 3D renderers;
//! [`egui_paint`] paints egui's frame, with the panels cached as a layer
//! where they do not change ([`panel_layer`]); [`preview`] chooses the
//! interactive preview's resolution on a software adapter;
//! [`screenshot`] writes `--screenshot`; [`frame_profile`] says where a
//! frame's time goes (`--frames K --profile`).

pub mod egui_paint;
pub mod frame_profile;
pub mod panel_layer;
pub mod pick;
pub mod preview;
pub mod screenshot;
pub mod viewport;
pub mod window_gpu;

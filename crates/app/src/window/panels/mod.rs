//! The egui panels: what the artist reads and touches.
//!
//! [`ui`] lays out the window (a [`tool_bar`] on top with the
//! [`files::file_menu`], the [`style_panel`] on the left with its
//! [`contact_panel`], [`interaction_panel`] and [`imported_summary`], the [`readout_panel`]
//! and [`density_view`] on the right); [`files`] holds its
//! dialogs, and [`value_slider`] the slider an
//! artist can trust (showing a value never changes it).

pub mod brush_input;
pub mod brush_panel;
pub mod contact_panel;
pub mod density_view;
pub mod files;
pub mod imported_summary;
pub mod interaction_panel;
pub mod readout_panel;
pub mod style_panel;
pub mod tool_bar;
pub mod ui;
pub mod value_slider;
pub mod view_state;

//! What the window shows and edits, with no window: tested without a
//! display.
//!
//! [`app_state::AppState`] is the whole of it, stepped once per frame: the
//! [`document`] (the style, its file, unsaved marker and [`undo`]
//! history), the head a style names ([`head_of_style`]), the guard's story
//! told in words ([`guard_status`]), live numbers ([`readouts`]),
//! [`presets`], the style the window opens with ([`default_style`]),
//! the brush tools and their strokes ([`brush_state`], [`brushing`]),
//! "set current shape as rest" ([`set_rest`]) and the unsaved-changes
//! guard on closing or opening ([`unsaved`]).

pub mod app_state;
pub mod brush_state;
pub mod brushing;
pub mod default_style;
pub mod document;
pub mod guard_status;
pub mod head_of_style;
pub mod presets;
pub mod readouts;
pub mod requests;
pub mod set_rest;
pub mod undo;
pub mod unsaved;

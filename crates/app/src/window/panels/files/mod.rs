//! The File menu ([`file_menu`]) and the dialogs it opens: the
//! [`file_picker`] for every open and save, the [`import_dialog`] that asks
//! for a groom's head, and the [`export_dialog`].

pub mod export_dialog;
pub mod file_menu;
pub mod file_picker;
pub mod import_dialog;

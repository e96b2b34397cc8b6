//! Long file work off the window's thread, with a progress bar and Cancel.
//!
//! [`job`] runs one piece of work on a worker thread and reports its
//! progress; [`export_job`] is File → Export frame… and Record animation…
//! (through `sim --export`'s code), [`import_job`] is File → Import groom…
//! and a groom dropped on the window (through `import`'s code).

pub mod export_job;
pub mod import_job;
pub mod job;

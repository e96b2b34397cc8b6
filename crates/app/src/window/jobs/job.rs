//! Long file work off the window's thread: recording an animation,
//! importing a groom. The window stays responsive (it keeps drawing and
//! simulating), shows a progress bar and offers Cancel.
//!
//! # How it works
//!
//! [`Job::spawn`] runs a closure on a worker thread and hands it a
//! [`Progress`]: two atomics the worker writes (work done) and reads
//! (cancel asked) and the window reads and writes, so neither waits for
//! the other. Each frame the window calls [`Job::poll`], which returns the
//! worker's result once the thread has finished. Cancelling is the
//! worker's business: it checks [`WorkProgress::cancelled`] between frames or
//! strands and stops, leaving no file under its final name (writes are
//! atomic, see [`crate::atomic_write`]).

use std::path::PathBuf;
use std::sync::Arc;
use std::thread::JoinHandle;

use crate::export::command::ExportOutcome;
use crate::work_progress::WorkProgress;

/// What a finished file job leaves.
#[derive(Debug)]
pub enum JobDone {
    /// Curve files written.
    Exported(ExportOutcome),
    /// A groom imported into this style file, to be opened, and the
    /// reader's warnings (a unit assumed, curves skipped) to show.
    Imported(PathBuf, Vec<String>),
}

/// What a worker reports to and reads from the window.
pub type Progress = Arc<WorkProgress>;

/// A worker thread producing a `T`, with its progress.
#[derive(Debug)]
pub struct Job<T> {
    /// What the job does, for the progress window ("Recording 120 frames").
    pub label: String,
    /// Shared with the worker.
    pub progress: Progress,
    handle: Option<JoinHandle<anyhow::Result<T>>>,
}

impl<T: Send + 'static> Job<T> {
    /// Starts `work` on a worker thread (fails only if the system cannot
    /// start one).
    pub fn spawn(
        label: String,
        work: impl FnOnce(&Progress) -> anyhow::Result<T> + Send + 'static,
    ) -> anyhow::Result<Self> {
        let progress = Progress::default();
        let theirs = progress.clone();
        let handle = std::thread::Builder::new()
            .name("helixhair-file-job".into())
            .spawn(move || work(&theirs))
            .map_err(|e| anyhow::anyhow!("cannot start a worker thread: {e}"))?;
        Ok(Job {
            label,
            progress,
            handle: Some(handle),
        })
    }

    /// Asks the worker to stop.
    pub fn cancel(&self) {
        self.progress.cancel();
    }

    /// The worker's result once it has finished (once); `None` while it runs.
    pub fn poll(&mut self) -> Option<anyhow::Result<T>> {
        if !self.handle.as_ref()?.is_finished() {
            return None;
        }
        let handle = self.handle.take()?;
        Some(
            handle.join().unwrap_or_else(|_| {
                Err(anyhow::anyhow!("the worker stopped on an internal error"))
            }),
        )
    }

    /// Waits for the worker (tests).
    pub fn wait(mut self) -> anyhow::Result<T> {
        match self.handle.take() {
            Some(h) => h.join().unwrap_or_else(|_| {
                Err(anyhow::anyhow!("the worker stopped on an internal error"))
            }),
            None => Err(anyhow::anyhow!("the job's result was already taken")),
        }
    }
}

/// The progress window: label, bar and Cancel. Returns true when Cancel
/// was clicked this frame.
pub fn progress_ui(ctx: &egui::Context, label: &str, progress: &Progress) -> bool {
    let mut cancel = false;
    egui::Window::new("Working")
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_BOTTOM, egui::vec2(0.0, -60.0))
        .show(ctx, |ui| {
            ui.label(label);
            let (done, total) = progress.counts();
            ui.add(
                egui::ProgressBar::new(progress.fraction())
                    .desired_width(320.0)
                    .text(format!("{done} / {total}")),
            );
            if ui.button("Cancel").clicked() {
                cancel = true;
            }
        });
    cancel
}

//! Progress of long work (an import's fit, an export's frames) that
//! another thread watches and may cancel: counters behind atomics, so the
//! worker never waits for the watcher (the window's progress bar,
//! `window::job`) nor the other way round.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Work done out of a total, and whether the watcher asked to stop.
#[derive(Debug, Default)]
pub struct WorkProgress {
    done: AtomicUsize,
    total: AtomicUsize,
    cancel: AtomicBool,
}

impl WorkProgress {
    /// Sets the work done so far, out of `total` units.
    pub fn set(&self, done: usize, total: usize) {
        self.total.store(total, Ordering::Relaxed);
        self.done.store(done, Ordering::Relaxed);
    }

    /// Sets the total and starts counting from zero.
    pub fn start(&self, total: usize) {
        self.set(0, total);
    }

    /// Counts `units` more done (from any thread).
    pub fn add(&self, units: usize) {
        self.done.fetch_add(units, Ordering::Relaxed);
    }

    /// Asks the worker to stop.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// Whether the watcher asked to stop.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// Work done and total.
    pub fn counts(&self) -> (usize, usize) {
        (
            self.done.load(Ordering::Relaxed),
            self.total.load(Ordering::Relaxed),
        )
    }

    /// The fraction done, 0 to 1 (0 while the total is not known).
    pub fn fraction(&self) -> f32 {
        match self.counts() {
            (_, 0) => 0.0,
            (done, total) => (done as f32 / total as f32).min(1.0),
        }
    }
}

//! Timing one strand's steps: medians of repeated batches.
//!
//! The machine is shared and noisy, so a single timing means little: each
//! measurement runs a warm-up, then batches sized to take at least a given
//! time ([`secs_per_call`]; [`BATCH_SECS`] for one strand's steps), and
//! reports the median batch with the fastest and slowest. Methods are compared as ratios of medians from one run.

use std::time::Instant;

use glam::DVec3;
use helixhair_physics::{RigidMotion, Strand};
use serde::Serialize;

use crate::stats::median;

/// Batches per measurement (odd, so the median is one batch).
pub const BATCHES: usize = 15;
/// Target length of one batch in seconds: long against the clock's
/// resolution, short enough that 15 batches of every case fit in a minute.
pub const BATCH_SECS: f64 = 4e-3;

/// Seconds per step: median, fastest and slowest batch.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct StepTiming {
    /// Median over batches, seconds per step.
    pub median_secs: f64,
    /// Fastest batch, seconds per step.
    pub min_secs: f64,
    /// Slowest batch, seconds per step.
    pub max_secs: f64,
}

/// Seconds per call of `call`, one figure per batch: after a warm-up call,
/// the calls per batch double until a batch lasts `batch_secs`, then
/// `batches` batches of that many calls are timed.
pub fn secs_per_call(mut call: impl FnMut(), batches: usize, batch_secs: f64) -> Vec<f64> {
    let mut timed = |count: usize| {
        let start = Instant::now();
        for _ in 0..count {
            call();
        }
        start.elapsed().as_secs_f64()
    };
    timed(1);
    let mut per_batch = 1usize;
    while timed(per_batch) < batch_secs && per_batch < MAX_CALLS_PER_BATCH {
        per_batch *= 2;
    }
    (0..batches.max(1))
        .map(|_| timed(per_batch) / per_batch as f64)
        .collect()
}

/// Most calls one batch may hold (a call too fast to time on its own).
pub const MAX_CALLS_PER_BATCH: usize = 1 << 20;

/// Times `strand.step` under a still root and gravity with step `h_secs`.
pub fn time_steps(strand: &mut Strand, h_secs: f64, batches: usize) -> StepTiming {
    let root = RigidMotion::default();
    let gravity = DVec3::new(0.0, -9.81, 0.0);
    let secs = secs_per_call(
        || {
            strand.step(&root, gravity, DVec3::ZERO, h_secs);
        },
        batches,
        BATCH_SECS,
    );
    StepTiming {
        median_secs: median(&secs),
        min_secs: secs.iter().copied().fold(f64::INFINITY, f64::min),
        max_secs: secs.iter().copied().fold(0.0, f64::max),
    }
}

//! Live numbers for the readout panel: frame and physics times, throughput,
//! energies over time, the compare view's difference and the guard's log.
//!
//! Histories are fixed-length rings ([`HISTORY_FRAMES`]), so a long session
//! uses constant memory; times are smoothed over the ring for display.

use std::collections::VecDeque;

use helixhair_physics::{Energies, GuardEvent, StageTimes};

/// Frames of history kept for plots and averages (10 s at 60 Hz).
pub const HISTORY_FRAMES: usize = 600;

/// Guard messages kept.
pub const GUARD_LOG_LINES: usize = 50;

/// One frame's physics record.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhysicsSample {
    /// Simulated time at the end of the frame, seconds.
    pub time_secs: f64,
    /// Wall time of the step, seconds.
    pub wall_secs: f64,
    /// Stage times, summed over strands (CPU seconds over all threads);
    /// `None` on the batch engine, which does not time stages apart.
    pub stages: Option<StageTimes>,
    /// Elements × substeps stepped.
    pub element_steps: usize,
    /// Energies at the end of the frame; `None` on the batch engine (too
    /// costly to reconstruct every frame).
    pub energies: Option<Energies>,
    /// Compare view: RMS tip distance between the two runs, metres.
    pub difference_m: Option<(f64, f64)>,
}

/// The readouts' memory.
#[derive(Clone, Debug, Default)]
pub struct Readouts {
    frames_secs: VecDeque<f64>,
    physics: VecDeque<PhysicsSample>,
    guard_log: VecDeque<String>,
    guard_total: usize,
    /// How the last frame's hair was drawn: from the GPU engine's own
    /// buffers (`Some(strands)`) or rebuilt on the CPU (`None`).
    drawn_on_device: Option<usize>,
}

fn push_capped<T>(ring: &mut VecDeque<T>, value: T, cap: usize) {
    if ring.len() == cap {
        ring.pop_front();
    }
    ring.push_back(value);
}

impl Readouts {
    /// Records the wall time between two displayed frames.
    pub fn record_frame(&mut self, secs: f64) {
        push_capped(&mut self.frames_secs, secs, HISTORY_FRAMES);
    }

    /// Records how the frame's hair was drawn: from the GPU engine's
    /// buffers, that many strands, or (`None`) rebuilt on the CPU.
    pub fn record_drawing(&mut self, on_device: Option<usize>) {
        self.drawn_on_device = on_device;
    }

    /// Strands the last frame drew from the GPU engine's buffers, if it
    /// drew from them.
    pub fn drawn_on_device(&self) -> Option<usize> {
        self.drawn_on_device
    }

    /// Records one physics frame and its guard events (`label` says which
    /// run they come from).
    pub fn record_physics(&mut self, sample: PhysicsSample, events: &[GuardEvent], label: &str) {
        push_capped(&mut self.physics, sample, HISTORY_FRAMES);
        self.record_physics_events(events, label);
    }

    /// Records guard events of a run without a physics sample (the
    /// compare view's second run).
    pub fn record_physics_events(&mut self, events: &[GuardEvent], label: &str) {
        for e in events {
            self.guard_total += 1;
            push_capped(
                &mut self.guard_log,
                format!("{label} t = {:.2} s: {e}", e.time_secs),
                GUARD_LOG_LINES,
            );
        }
    }

    /// Mean frame time over the last `n` frames, seconds.
    pub fn mean_frame_secs(&self, n: usize) -> Option<f64> {
        mean(self.frames_secs.iter().rev().take(n).copied())
    }

    /// Median frame time over the last `n` frames, seconds (a frame the
    /// system stalled moves the mean, not the median).
    pub fn median_frame_secs(&self, n: usize) -> Option<f64> {
        let recent: Vec<f64> = self.frames_secs.iter().rev().take(n).copied().collect();
        (!recent.is_empty()).then(|| crate::stats::median(&recent))
    }

    /// Mean physics wall time per frame over the last `n` frames, seconds.
    pub fn mean_physics_secs(&self, n: usize) -> Option<f64> {
        mean(self.physics.iter().rev().take(n).map(|s| s.wall_secs))
    }

    /// Median physics wall time per frame over the last `n` frames,
    /// seconds.
    pub fn median_physics_secs(&self, n: usize) -> Option<f64> {
        let recent: Vec<f64> = self
            .physics
            .iter()
            .rev()
            .take(n)
            .map(|s| s.wall_secs)
            .collect();
        (!recent.is_empty()).then(|| crate::stats::median(&recent))
    }

    /// Element steps per wall second over the last `n` frames.
    pub fn element_steps_per_sec(&self, n: usize) -> Option<f64> {
        let recent = || self.physics.iter().rev().take(n);
        let wall: f64 = recent().map(|s| s.wall_secs).sum();
        let steps: usize = recent().map(|s| s.element_steps).sum();
        (wall > 0.0).then(|| steps as f64 / wall)
    }

    /// The last physics frame.
    pub fn last(&self) -> Option<&PhysicsSample> {
        self.physics.back()
    }

    /// The physics history, oldest first.
    pub fn history(&self) -> impl Iterator<Item = &PhysicsSample> {
        self.physics.iter()
    }

    /// Guard messages, oldest first, and how many there were in all.
    pub fn guard_log(&self) -> (impl Iterator<Item = &String>, usize) {
        (self.guard_log.iter(), self.guard_total)
    }
}

fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn means_and_throughput_over_the_recent_frames() {
        let mut r = Readouts::default();
        assert_eq!(r.mean_frame_secs(10), None);
        for k in 0..HISTORY_FRAMES + 10 {
            r.record_frame(if k % 2 == 0 { 0.01 } else { 0.03 });
            let sample = PhysicsSample {
                wall_secs: 0.005,
                element_steps: 1000,
                ..Default::default()
            };
            r.record_physics(sample, &[], "");
        }
        assert!((r.mean_frame_secs(100).unwrap() - 0.02).abs() < 1e-12);
        assert!((r.element_steps_per_sec(50).unwrap() - 200_000.0).abs() < 1e-6);
        assert_eq!(r.history().count(), HISTORY_FRAMES);
    }
}

//! Where a displayed frame's time goes, for `helixhair --frames K
//! --profile`: the time between two frames (winit's event loop and the
//! window system), physics, strand geometry (drawn strands interpolated and
//! draped on the CPU), the 3D picture (recorded and, with `--profile`,
//! waited for, so the GPU's or lavapipe's time lands here instead of in a
//! later stage), egui's layout, egui's tessellation (shapes to triangles,
//! on the CPU), painting the panels and pictures into the window's image
//! (waited for), and presenting it. Medians over the second half of the
//! run are printed with the summary, with the panel pixels repainted per
//! frame ([`super::panel_layer`]; 0 when the panels are not cached).

use std::time::Instant;

use crate::stats::median;

/// The stages of a frame, in order.
pub const STAGES: [&str; 8] = [
    "between frames",
    "physics",
    "strands",
    "picture",
    "egui layout",
    "tessellate",
    "paint",
    "present",
];

/// Per-stage seconds of every frame.
#[derive(Clone, Debug, Default)]
pub struct FrameProfile {
    frames: Vec<[f64; 8]>,
    current: [f64; 8],
    mark: Option<Instant>,
    repainted_px: Vec<f64>,
    /// When the last frame ended.
    finished: Option<Instant>,
}

impl FrameProfile {
    /// Starts timing a frame's first stage; the time since the last
    /// frame ended (the event loop, the window system) is stage 0.
    pub fn start(&mut self) {
        let now = Instant::now();
        self.current = [0.0; 8];
        if let Some(finished) = self.finished {
            self.current[0] = now.duration_since(finished).as_secs_f64();
        }
        self.mark = Some(now);
    }

    /// Ends stage `stage` (an index into [`STAGES`]) and starts the next.
    pub fn lap(&mut self, stage: usize) {
        let now = Instant::now();
        if let Some(mark) = self.mark.replace(now) {
            self.current[stage] += now.duration_since(mark).as_secs_f64();
        }
    }

    /// Ends the frame, in which `repainted_px` panel pixels were painted.
    pub fn finish(&mut self, repainted_px: u64) {
        self.finished = Some(Instant::now());
        self.frames.push(self.current);
        self.repainted_px.push(repainted_px as f64);
    }

    /// Median milliseconds of each stage over the last `n` frames.
    pub fn median_ms(&self, n: usize) -> [f64; 8] {
        let last = &self.frames[self.frames.len().saturating_sub(n)..];
        std::array::from_fn(|s| {
            let v: Vec<f64> = last.iter().map(|f| 1e3 * f[s]).collect();
            median(&v)
        })
    }

    /// One line: each stage's median milliseconds.
    pub fn line(&self, n: usize) -> String {
        let ms = self.median_ms(n);
        let parts: Vec<String> = STAGES
            .iter()
            .zip(ms)
            .map(|(name, ms)| format!("{name} {ms:.1}"))
            .collect();
        let repainted = &self.repainted_px[self.repainted_px.len().saturating_sub(n)..];
        format!(
            "median ms per frame by stage: {}; panel pixels repainted per frame (median): {:.0}",
            parts.join(", "),
            median(repainted)
        )
    }
}

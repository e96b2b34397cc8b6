//! The result of a headless run, as `helixhair sim --json` writes it and as
//! its summary prints it.
//!
//! The JSON format `helixhair-sim`, version [`SIM_REPORT_VERSION`], is
//! documented field by field in `docs/sim-json.md`; a change to these
//! structs that renames, removes or re-means a field must bump the version.

use std::fmt::Write as _;

use helixhair_physics::{Energies, StageTimes};
use serde::Serialize;

use crate::sim::auto_choice::Choice;

use crate::sim::headless::HeadlessSim;
use crate::sim::tip_trajectories::TipTrajectories;
use crate::stats::median;

/// Value of the `format` field.
pub const SIM_REPORT_FORMAT: &str = "helixhair-sim";

/// Value of the `version` field.
pub const SIM_REPORT_VERSION: u32 = 1;

/// Everything a headless run reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SimReport {
    /// Always [`SIM_REPORT_FORMAT`].
    pub format: &'static str,
    /// Always [`SIM_REPORT_VERSION`].
    pub version: u32,
    /// The style file, as given on the command line.
    pub style_path: String,
    /// The style's `name`.
    pub style_name: String,
    /// The engine that ran ([`helixhair_physics::engine::EngineKind::label`]):
    /// `reference`, `batch` or `gpu`.
    pub engine: &'static str,
    /// With the GPU engine, what stepped the frames, in words ("physics
    /// on the GPU (adapter)", or why the CPU batch engine stepped them);
    /// `None` (JSON `null`) on the other engines.
    pub gpu: Option<String>,
    /// Solver, as `--method` spells it ([`helixhair_physics::Method::label`]:
    /// `exact`, `iterative:4`, …).
    pub method: String,
    /// Frame time step, seconds.
    pub dt_secs: f64,
    /// Substeps per frame.
    pub substeps: u32,
    /// Frames simulated.
    pub steps: usize,
    /// Simulated time at the end, seconds.
    pub time_secs: f64,
    /// Number of strands.
    pub strand_count: usize,
    /// Number of Super-Helix elements over all strands.
    pub element_count: usize,
    /// Energies of the final state (the batch engine's reconstructed in
    /// f64 from its f32 state).
    pub energies: EnergiesReport,
    /// Wall-clock time of the frames.
    pub wall_time: WallTimeReport,
    /// Stage times of the last frame, summed over strands and substeps;
    /// `None` (JSON `null`) on the batch engine, which fuses the stages.
    pub last_step_stages: Option<StageTimesReport>,
    /// Final shape of every strand, in the order of the style's roots.
    pub strands: Vec<StrandReport>,
    /// The automatic choice per group (empty without an accuracy target).
    pub choices: Vec<ChoiceReport>,
    /// What the physics guard did during the run (on the batch engine: its
    /// resets of failing strands to rest).
    pub guard: Option<GuardReport>,
    /// Every strand's tip at the start and after each frame, when asked
    /// (`--tip-trajectories`); left out of the JSON otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tip_trajectories: Option<TipTrajectories>,
}

/// The solver and element count chosen for one group.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ChoiceReport {
    /// The group's name.
    pub group: String,
    /// The choice.
    #[serde(flatten)]
    pub choice: Choice,
}

/// The guard's interventions over a run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GuardReport {
    /// How many times it stepped in.
    pub event_count: usize,
    /// The first events (at most `MAX_KEPT_GUARD_EVENTS`), as sentences.
    pub events: Vec<String>,
    /// On a Block-diagonal run, how many strand-frames Block-diagonal
    /// could not hold and the guard stepped with Exact instead.
    pub block_handed_to_exact: usize,
}

/// Energies in joules, summed over strands.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EnergiesReport {
    /// Kinetic energy, J.
    pub kinetic_j: f64,
    /// Elastic (bending and twisting) energy, J.
    pub elastic_j: f64,
    /// Gravitational potential energy, J (zero at height 0).
    pub gravity_j: f64,
    /// Sum of the three, J.
    pub total_j: f64,
}

/// Wall-clock time per frame.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WallTimeReport {
    /// Each frame's time, seconds, in order.
    pub per_step_secs: Vec<f64>,
    /// Median of `per_step_secs`, seconds.
    pub median_secs: f64,
    /// Mean of `per_step_secs`, seconds.
    pub mean_secs: f64,
    /// Sum of `per_step_secs`, seconds.
    pub total_secs: f64,
}

/// Time per pipeline stage, seconds, summed over strands and substeps (so
/// with parallel stepping the sum can exceed the frame's wall time).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StageTimesReport {
    /// Stage "reconstruct".
    pub reconstruct_secs: f64,
    /// Stage "forces".
    pub forces_secs: f64,
    /// Stage "mass".
    pub mass_secs: f64,
    /// Stage "solve".
    pub solve_secs: f64,
    /// Stage "integrate".
    pub integrate_secs: f64,
    /// Sum of the five.
    pub total_secs: f64,
}

/// The final state of one strand.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StrandReport {
    /// The name of the strand's group.
    pub group: String,
    /// The N + 1 element boundary points, root first, metres, world frame.
    pub points_m: Vec<[f64; 3]>,
    /// Strains (τ, κ₁, κ₂) of each of the N elements, root first, m⁻¹.
    pub q_per_m: Vec<[f64; 3]>,
}

impl From<Energies> for EnergiesReport {
    fn from(e: Energies) -> Self {
        Self {
            kinetic_j: e.kinetic_j,
            elastic_j: e.elastic_j,
            gravity_j: e.gravity_j,
            total_j: e.total_j(),
        }
    }
}

impl From<StageTimes> for StageTimesReport {
    fn from(t: StageTimes) -> Self {
        Self {
            reconstruct_secs: t.reconstruct_secs,
            forces_secs: t.forces_secs,
            mass_secs: t.mass_secs,
            solve_secs: t.solve_secs,
            integrate_secs: t.integrate_secs,
            total_secs: t.total_secs(),
        }
    }
}

impl WallTimeReport {
    /// Statistics of per-frame times (all zero for no frames).
    pub fn new(per_step_secs: Vec<f64>) -> Self {
        let total_secs: f64 = per_step_secs.iter().sum();
        let mean_secs = if per_step_secs.is_empty() {
            0.0
        } else {
            total_secs / per_step_secs.len() as f64
        };
        Self {
            median_secs: median(&per_step_secs),
            mean_secs,
            total_secs,
            per_step_secs,
        }
    }
}

impl SimReport {
    /// The report of `sim` after a run whose frames took `per_step_secs`.
    pub fn new(
        style_path: &str,
        style_name: &str,
        sim: &HeadlessSim,
        per_step_secs: Vec<f64>,
    ) -> Self {
        let engine = sim.engine();
        let settings = engine.settings();
        let strands = (0..engine.strand_count())
            .map(|i| StrandReport {
                group: sim.group_name(i).to_owned(),
                points_m: engine
                    .boundary_points_world(i)
                    .iter()
                    .map(|p| p.to_array())
                    .collect(),
                q_per_m: engine.q(i).iter().map(|q| q.to_array()).collect(),
            })
            .collect();
        let reference = engine.reference();
        Self {
            format: SIM_REPORT_FORMAT,
            version: SIM_REPORT_VERSION,
            style_path: style_path.to_owned(),
            style_name: style_name.to_owned(),
            engine: engine.kind().label(),
            gpu: engine.gpu_note().map(str::to_owned),
            method: settings.method.label(),
            dt_secs: settings.dt_secs,
            substeps: settings.substeps,
            steps: per_step_secs.len(),
            time_secs: engine.time_secs(),
            strand_count: engine.strand_count(),
            element_count: engine.element_count(),
            energies: engine.energies().into(),
            wall_time: WallTimeReport::new(per_step_secs),
            last_step_stages: reference.map(|r| r.last_stage_times().into()),
            strands,
            choices: sim
                .choices()
                .iter()
                .enumerate()
                .map(|(i, choice)| ChoiceReport {
                    group: sim.group_names().get(i).cloned().unwrap_or_default(),
                    choice: choice.clone(),
                })
                .collect(),
            tip_trajectories: None,
            guard: Some(GuardReport {
                block_handed_to_exact: sim.handed_to_exact(),
                event_count: sim.engine().guard_event_count(),
                events: sim
                    .guard_events()
                    .iter()
                    .map(|e| format!("{e} (group {})", sim.group_name(e.strand)))
                    .collect(),
            }),
        }
    }

    /// A few lines for a person: what ran, how fast, where it ended.
    pub fn summary(&self) -> String {
        let mut out = String::new();
        let w = &self.wall_time;
        let e = &self.energies;
        // Writing to a String cannot fail.
        let _ = writeln!(out, "style `{}` ({})", self.style_name, self.style_path);
        let _ = writeln!(
            out,
            "  {} strands, {} elements; {} engine, method {}, dt {} s x {} substep(s)",
            self.strand_count,
            self.element_count,
            self.engine,
            self.method,
            self.dt_secs,
            self.substeps
        );
        if let Some(gpu) = &self.gpu {
            let _ = writeln!(out, "  {gpu}");
        }
        let _ = writeln!(
            out,
            "  {} step{} = {:.4} s simulated in {:.4} s wall (per step: median {:.3} ms, mean {:.3} ms)",
            self.steps,
            if self.steps == 1 { "" } else { "s" },
            self.time_secs,
            w.total_secs,
            w.median_secs * 1e3,
            w.mean_secs * 1e3
        );
        let _ = writeln!(
            out,
            "  final energies: kinetic {:.4e} J, elastic {:.4e} J, gravity {:.4e} J, total {:.4e} J",
            e.kinetic_j, e.elastic_j, e.gravity_j, e.total_j
        );
        for c in &self.choices {
            let ch = &c.choice;
            let _ = writeln!(
                out,
                "  group `{}`: chose {} with {} elements, {} substep(s) (measured error {:.2e} of length on the {} scene{})",
                c.group,
                ch.method.label(),
                ch.elements,
                ch.substeps,
                ch.predicted_error,
                ch.class,
                if ch.target_met {
                    ""
                } else {
                    "; the target is out of reach, this is the most accurate"
                }
            );
        }
        if let Some(guard) = &self.guard
            && guard.event_count > 0
        {
            let _ = writeln!(
                out,
                "  warning: the stability guard stepped in {} time(s); first: {}",
                guard.event_count,
                guard.events.first().map_or("", String::as_str)
            );
        }
        if let Some(guard) = self.guard.as_ref().filter(|g| g.block_handed_to_exact > 0) {
            let _ = writeln!(
                out,
                "  Block-diagonal could not hold this style at a {:.1} ms frame in {} substep(s): \
                 the guard stepped {} strand-frame(s) with Exact instead, and that is what they \
                 show (more substeps may let Block-diagonal hold it)",
                self.dt_secs * 1e3,
                self.substeps,
                guard.block_handed_to_exact
            );
        }
        out
    }
}

/// An error when the guard reset or pinned strands `lost` times, unless the
/// user accepts it (`--accept-resets`).
pub fn refuse_lost_strands(lost: usize, accept: bool) -> anyhow::Result<()> {
    if lost > 0 && !accept {
        anyhow::bail!(
            "the guard reset or pinned strands {lost} times (see the summary): this is not the \
             simulation the style asks for; try more substeps or the Exact solver, or pass \
             --accept-resets to accept the result"
        );
    }
    Ok(())
}

/// "N frames in S s" for a summary line; "at rest, no frame simulated"
/// for none (it read "0 frames in -0.00 s").
pub fn frames_simulated(frames: usize, wall_secs: f64) -> String {
    match frames {
        0 => "at rest, no frame simulated".to_owned(),
        1 => format!("1 frame in {:.2} s", wall_secs.max(0.0)),
        n => format!("{n} frames in {:.2} s", wall_secs.max(0.0)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wall_time_statistics() {
        let w = WallTimeReport::new(vec![1.0, 2.0, 6.0]);
        assert_eq!((w.median_secs, w.mean_secs, w.total_secs), (2.0, 3.0, 9.0));
    }
}

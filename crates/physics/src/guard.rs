//! Failing safe: detect a strand whose step has gone wrong, recover it, and
//! say so.
//!
//! The stability study (`helixhair bench --study stability`,
//! `docs/RESULTS.md`) finds settings a user can reach where a solver blows
//! up: Block-diagonal on a hanging curl at 60 Hz, any solver on a long
//! tilted curl with little friction. A blow-up grows over a few steps, so
//! it is caught at the end of the frame by two cheap O(N) bounds on the
//! state:
//!
//! - **finite**: every strain and strain rate is a number;
//! - **speed**: Σ_Q ℓ_Q |q̇_Q| (L − s_Q) bounds the speed of any point
//!   relative to the root frame (element Q's strain rate turns everything
//!   beyond its start, at most L − s_Q away, at ℓ_Q |q̇_Q| rad/s). A frame
//!   fails when the bound ends above [`Guard::speed_limit_m_per_s`] (not
//!   hair's motion), or above [`Guard::growth_factor`] times its value at
//!   the start of the frame once past [`Guard::speed_floor_m_per_s`]. The
//!   growth test matters: an instability grows by a large factor per
//!   frame, and by the time it passes any absolute limit the state it
//!   would restart from is already ruined (measured: Block-diagonal on a
//!   hanging curl goes 11, 15, 36, 281 m/s in four frames, while healthy
//!   runs of the same strand stay between 1 and 5 m/s).
//!
//! Recovery: the strand goes back to its state at the start of the frame
//! and the frame is stepped again. An approximate solver (Block-diagonal,
//! Iterative) is first replaced by Exact at the same substeps: measured,
//! Block-diagonal's failure on an excited curl is not cured by a smaller
//! step (it went from 36 m/s to 1e108 m/s within one frame of 16
//! substeps), because it comes from the truncated inertia, not from h.
//! Then the substeps double, up to [`Guard::max_substeps`]. A retry is
//! judged by the absolute bounds only (finite, under the speed limit):
//! growth is what flags a suspect frame, but a full-matrix solve at a finer
//! step is trusted to grow when the physics does (a strand falling from
//! rest doubles its speed in a frame). The strand
//! keeps what worked for [`Guard::hold_frames`] frames, then tries its own
//! solver and substeps again, so a strand at the edge of stability does not
//! fail every other frame. If no retry
//! passes, the strand is reset to the start-of-frame shape at rest
//! relative to its root. Either way the system records a [`GuardEvent`]
//! that the app shows the user.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::model::StrandModel;
use crate::settings::Method;

/// Bounds and the recovery budget.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Guard {
    /// Largest speed bound relative to the root, m/s. Default 50: tips of
    /// hair in a fast head shake move a few m/s relative to the head, and
    /// the bound over-estimates the true speed by at most a few times.
    pub speed_limit_m_per_s: f64,
    /// Speed bound below which a frame never fails, m/s. Default 5: the
    /// bound of healthy 20 cm strands falling and swinging.
    pub speed_floor_m_per_s: f64,
    /// Largest growth of the speed bound over one frame. Default 2: healthy
    /// frames grow it by at most 1.8 (a strand released from rest), an
    /// instability by 2.4 and then 8 per frame.
    pub growth_factor: f64,
    /// Most substeps per frame a retry may use. Default 32: at 60 Hz that
    /// is h ≈ 0.5 ms, where the stability study finds every solver stable.
    pub max_substeps: u32,
    /// Frames a strand keeps the substeps of a successful retry. Default 60
    /// (one second at 60 Hz).
    pub hold_frames: u32,
}

impl Default for Guard {
    fn default() -> Self {
        Self {
            speed_limit_m_per_s: 50.0,
            speed_floor_m_per_s: 5.0,
            growth_factor: 2.0,
            max_substeps: 32,
            hold_frames: 60,
        }
    }
}

/// What tripped the guard.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GuardCause {
    /// A strain or rate was NaN or infinite.
    NotFinite,
    /// The speed bound exceeded the limit.
    TooFast {
        /// The bound, m/s.
        speed_m_per_s: f64,
    },
}

/// What the guard did about it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GuardAction {
    /// The frame was stepped again, and passed; the strand keeps this
    /// solver and these substeps for [`Guard::hold_frames`] frames.
    Retried {
        /// Solver of the successful retry.
        method: Method,
        /// Substeps of the successful retry.
        substeps: u32,
    },
    /// No retry passed: the strand was put back at its start-of-frame
    /// shape, at rest relative to its root.
    Reset,
}

/// One intervention of the guard.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GuardEvent {
    /// Index of the strand in its system.
    pub strand: usize,
    /// Simulated time at the start of the frame, seconds.
    pub time_secs: f64,
    /// What tripped it.
    pub cause: GuardCause,
    /// What was done.
    pub action: GuardAction,
}

impl std::fmt::Display for GuardEvent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let cause = match self.cause {
            GuardCause::NotFinite => "its state was not finite".to_string(),
            GuardCause::TooFast { speed_m_per_s } => {
                format!("it moved at up to {speed_m_per_s:.3e} m/s")
            }
        };
        let action = match self.action {
            GuardAction::Retried { method, substeps } => format!(
                "re-stepped the frame with {} and {substeps} substeps, kept for a while",
                method.label()
            ),
            GuardAction::Reset => "reset it to its last good shape, at rest".to_string(),
        };
        write!(
            f,
            "strand {} at t = {:.3} s: {cause}; {action}",
            self.strand, self.time_secs
        )
    }
}

/// The bound Σ_Q ℓ_Q |q̇_Q| (L − s_Q) on any point's speed relative to the
/// root frame, m/s.
pub fn speed_bound_m_per_s(model: &StrandModel, v: &[DVec3]) -> f64 {
    let mut beyond_m: f64 = model.lengths_m.iter().sum();
    let mut bound = 0.0;
    for (l, rate) in model.lengths_m.iter().zip(v) {
        bound += l * rate.length() * beyond_m;
        beyond_m -= l;
    }
    bound
}

impl Guard {
    /// What is wrong with the state (`q`, `v`) a strand of `model` ended a
    /// frame in, given the speed bound it started the frame with.
    pub fn check(
        &self,
        model: &StrandModel,
        q: &[DVec3],
        v: &[DVec3],
        start_speed_m_per_s: f64,
    ) -> Option<GuardCause> {
        if !q.iter().chain(v).all(|x| x.is_finite()) {
            return Some(GuardCause::NotFinite);
        }
        let speed = speed_bound_m_per_s(model, v);
        let grown = self.growth_factor * start_speed_m_per_s.max(self.speed_floor_m_per_s);
        (speed > self.speed_limit_m_per_s || speed > grown).then_some(GuardCause::TooFast {
            speed_m_per_s: speed,
        })
    }
}

/// A strand's standing with the guard: the substeps a retry needed, kept
/// for a while.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GuardState {
    /// Substeps per frame the strand uses at least (0: the system's own).
    pub substeps: u32,
    /// Frames left before it tries the system's substeps again.
    pub hold_frames: u32,
    /// The strand's own solver while the guard has it on Exact.
    pub own_method: Option<Method>,
}

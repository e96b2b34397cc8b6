//! Failing safe: detect a strand whose step has gone wrong, recover it, and
//! say so.
//!
//! A step can fail in settings a user reaches (the stability maps of
//! `docs/benchmarks.md`): it blows up (energy doubling frame after frame), or, with a
//! solver that is not passive (Block-diagonal's truncated inertia), it keeps
//! a strand moving with a still head. Both show as energy that no force put
//! in, so the guard **measures** each frame at its end, from a
//! reconstruction of the state (one measure for both engines,
//! [`crate::batch::measure`]; the balance, [`crate::frame_balance`]):
//!
//! - **finite**: every strain and strain rate is a number;
//! - **energy**: the energy the frame gained beyond the work of the root
//!   and of the external forces (drag, the hair–hair model, a brush;
//!   summed by the step's own rule, [`crate::frame_balance`]) must stay below
//!   [`Guard::energy_tolerance`] times the frame's kinetic energy (start
//!   plus end), plus round-off. Frames in which any sample touches the
//!   head are not judged by energy: contact starts and stops within a
//!   frame, and its work is not known at the frame's resolution. With a
//!   still head and no wind this is
//!   "energy must not grow"; with head motion, "not faster than the root's
//!   work allows", give or take what the frame-level rule can miss where
//!   the root's acceleration changes within the frame
//!   ([`crate::frame_balance::root_sampling_uncertainty_j`]). Measured on healthy frames (Exact and Dense, a 30 cm
//!   strand under a head shake at 1/60 s): at most 2% of the kinetic
//!   energy, the estimate's error on the root's work;
//! - **speed**: the true speed of every quadrature sample relative to the
//!   root's rigid motion must stay below [`Guard::speed_limit_m_per_s`]. Not
//!   a bound: the old bound Σ ℓ|q̇|(L − s) read 50 m/s on coiled strands
//!   whose fastest point moved at 1 m/s, and reset healthy hair.
//!
//! Recovery, one policy for both engines ([`retry_frame`]): the strand
//! goes back to its state at the start of the frame and the frame is
//! stepped again. An approximate solver (Block-diagonal,
//! Iterative) is first replaced by Exact at the same substeps: its failure
//! comes from the truncated inertia, not from h. Then the substeps double,
//! up to [`Guard::max_substeps`]. A retry is judged by the same measures.
//! The strand keeps what worked for [`Guard::hold_frames`] frames, then
//! tries its own solver and substeps again. If no retry passes, the strand
//! is reset to the start-of-frame shape at rest relative to its root; a
//! strand reset [`Guard::resets_before_pinning`] times within
//! [`Guard::hold_frames`] frames, or [`Guard::long_resets_before_pinning`]
//! times each within [`Guard::long_window_frames`] of the previous (a
//! strand failing every time a head motion repeats), is **pinned**: held at rest in its
//! rest pose ([`crate::Strand::rest_pose`]: its natural shape unless told), carried by the head, and no longer stepped, with one
//! event that says so, instead of a reset every frame. Each intervention is
//! a [`GuardEvent`] that the app shows the user.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::frame_balance::{
    SteppedFrame, StrandMeasure, root_sampling_uncertainty_j, unexplained_energy_j,
};
use crate::model::StrandModel;
use crate::settings::Method;

/// Limits and the recovery budget.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Guard {
    /// Largest true speed of any point relative to the root's rigid
    /// motion, m/s. Default 50: the fastest healthy hair measured (30 cm
    /// strands whipping under a head shake) moves at 2–5 m/s.
    pub speed_limit_m_per_s: f64,
    /// Largest unexplained energy gain of a frame, as a fraction of its
    /// kinetic energy (start plus end). Default 0.25: healthy frames
    /// measure at most 0.02 (the rule's error on the root's
    /// work), a blow-up more than 1, and Block-diagonal's gain on a
    /// released strand up to 12.
    pub energy_tolerance: f64,
    /// Most substeps per frame a retry may use. Default 32: at 60 Hz that
    /// is h ≈ 0.5 ms, where the stability study finds every solver stable.
    pub max_substeps: u32,
    /// Frames a strand keeps the substeps of a successful retry, and the
    /// window in which resets are counted. Default 60 (one second at 60 Hz).
    pub hold_frames: u32,
    /// Resets within [`Guard::hold_frames`] after which a strand is pinned
    /// at rest. Default 3: a strand that no retry can step three times in a
    /// second will not be stepped in the next one either.
    pub resets_before_pinning: u32,
    /// The long memory's window, frames: a reset within this many frames
    /// of the strand's previous one adds to its long count. Default 1800
    /// (30 s at 60 Hz): a strand that fails once every few seconds, each
    /// time a head motion repeats, is failing for good.
    pub long_window_frames: u32,
    /// Resets in a row, each within [`Guard::long_window_frames`] of the
    /// previous, after which a strand is pinned. Default 5.
    pub long_resets_before_pinning: u32,
}

impl Default for Guard {
    fn default() -> Self {
        Self {
            speed_limit_m_per_s: 50.0,
            energy_tolerance: 0.25,
            max_substeps: 32,
            hold_frames: 60,
            resets_before_pinning: 3,
            long_window_frames: 1800,
            long_resets_before_pinning: 5,
        }
    }
}

/// Relative round-off allowed on the energy balance (of the sizes of the
/// energies summed): f64 sums of a few hundred terms that cancel.
pub const ENERGY_ROUND_OFF: f64 = 1e-9;

/// What tripped the guard.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GuardCause {
    /// A strain or rate was NaN or infinite.
    NotFinite,
    /// A point moved faster than the limit relative to the root.
    TooFast {
        /// The true speed of the fastest point, m/s.
        speed_m_per_s: f64,
    },
    /// The frame gained energy that no force put in.
    EnergyGain {
        /// Energy gained beyond the work done on the strand, joules.
        gained_j: f64,
        /// What the tolerance allowed, joules.
        allowed_j: f64,
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
    /// The strand kept failing ([`Guard::resets_before_pinning`] resets in
    /// [`Guard::hold_frames`] frames): it is held at rest in its natural
    /// shape, carried by the head, and no longer stepped.
    Pinned,
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

impl std::fmt::Display for GuardCause {
    /// What failed and by how much, as a clause ("a point moved at …").
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            GuardCause::NotFinite => write!(f, "its state was not finite"),
            GuardCause::TooFast { speed_m_per_s } => {
                write!(
                    f,
                    "a point moved at {speed_m_per_s:.3e} m/s relative to its root"
                )
            }
            GuardCause::EnergyGain {
                gained_j,
                allowed_j,
            } => write!(
                f,
                "it gained {gained_j:.3e} J that no force put in (allowed {allowed_j:.3e} J)"
            ),
        }
    }
}

impl std::fmt::Display for GuardEvent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let cause = self.cause;
        let action = match self.action {
            GuardAction::Retried { method, substeps } => format!(
                "re-stepped the frame with {} and {substeps} substeps, kept for a while",
                method.label()
            ),
            GuardAction::Reset => "reset it to its last good shape, at rest".to_string(),
            GuardAction::Pinned => "it kept failing, so it is pinned at rest in its rest \
                                    shape and no longer simulated; change its settings (fewer \
                                    elements, more substeps, the Exact solver) to free it"
                .to_string(),
        };
        write!(
            f,
            "strand {} at t = {:.3} s: {cause}; {action}",
            self.strand, self.time_secs
        )
    }
}

/// The bound Σ_Q ℓ_Q |q̇_Q| (L − s_Q) on any point's speed relative to the
/// root frame, m/s. An upper bound only (50 times the true speed on a
/// coiled strand): the guard measures true speeds instead; tests use it to
/// bound motion from above.
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
    /// What is wrong with a frame `frame` that took a strand with
    /// strains `q` and rates `v` from the measure `start` to `end`.
    pub fn check(
        &self,
        q: &[DVec3],
        v: &[DVec3],
        start: &StrandMeasure,
        end: &StrandMeasure,
        frame: SteppedFrame,
    ) -> Option<GuardCause> {
        self.check_with_round_off(q, v, start, end, frame, ENERGY_ROUND_OFF)
    }

    /// [`Guard::check`] with a relative round-off allowance on the energy
    /// balance (f64 sums: [`ENERGY_ROUND_OFF`]; the f32 batch path allows
    /// more).
    pub fn check_with_round_off(
        &self,
        q: &[DVec3],
        v: &[DVec3],
        start: &StrandMeasure,
        end: &StrandMeasure,
        frame: SteppedFrame,
        round_off: f64,
    ) -> Option<GuardCause> {
        if !q.iter().chain(v).all(|x| x.is_finite()) || !end.energy_j.is_finite() {
            return Some(GuardCause::NotFinite);
        }
        if end.fastest_relative_m_per_s > self.speed_limit_m_per_s {
            return Some(GuardCause::TooFast {
                speed_m_per_s: end.fastest_relative_m_per_s,
            });
        }
        if start.in_contact || end.in_contact {
            // Contact starts, stiffens and ends within a frame: its work is
            // not known at the frame's resolution (measured: strands landing
            // on a sphere were flagged at impact with every solver and every
            // contact stiffness tried). Such frames are judged by
            // finiteness and true speed only.
            return None;
        }
        let gained_j = unexplained_energy_j(start, end, frame);
        let allowed_j = self.energy_tolerance * (start.kinetic_j + end.kinetic_j)
            + round_off * (start.size_j + end.size_j);
        // The uncertainty below is never negative: a gain within the
        // allowance so far passes whatever it adds (the same verdict, and
        // most strands in most frames skip its cost).
        if gained_j <= allowed_j {
            return None;
        }
        let allowed_j = allowed_j + root_sampling_uncertainty_j(start, end, frame);
        (gained_j > allowed_j).then_some(GuardCause::EnergyGain {
            gained_j,
            allowed_j,
        })
    }
}

/// A strand's memory of its resets, which decides when it is pinned: a
/// short window ([`Guard::resets_before_pinning`] resets, each within
/// [`Guard::hold_frames`] of the previous) and a long one
/// ([`Guard::long_resets_before_pinning`] within
/// [`Guard::long_window_frames`]). Shared by both engines' guards.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ResetMemory {
    short_count: u32,
    short_frames_left: u32,
    long_count: u32,
    long_frames_left: u32,
}

impl ResetMemory {
    /// One frame has passed: windows that run out forget their count.
    pub fn tick(&mut self) {
        for (count, left) in [
            (&mut self.short_count, &mut self.short_frames_left),
            (&mut self.long_count, &mut self.long_frames_left),
        ] {
            if *left > 0 {
                *left -= 1;
                if *left == 0 {
                    *count = 0;
                }
            }
        }
    }

    /// Records that no retry could step the strand: it is pinned
    /// ([`GuardAction::Pinned`]) if its resets now repeat too often, else
    /// reset ([`GuardAction::Reset`]).
    pub fn give_up(&mut self, guard: &Guard) -> GuardAction {
        self.short_count += 1;
        self.short_frames_left = guard.hold_frames;
        self.long_count += 1;
        self.long_frames_left = guard.long_window_frames;
        if self.short_count >= guard.resets_before_pinning
            || self.long_count >= guard.long_resets_before_pinning
        {
            GuardAction::Pinned
        } else {
            GuardAction::Reset
        }
    }
}

/// The guard's one recovery of a failed frame, which both engines follow
/// (the f64 reference strand by strand, the batch engine a batch's lanes
/// at once, [`crate::batch`]): the frame, stepped in `own` substeps, is
/// stepped again from its start with Exact, at the same substeps if the
/// frame was stepped with an approximate solver (`approximate`:
/// Block-diagonal, Iterative; its failure comes from the truncated
/// inertia, not from h), then with twice the substeps, and twice again, up
/// to [`Guard::max_substeps`] (or `own`, if more).
/// `step_again(substeps, pending)` steps the strands still failing
/// (`pending[i]`) with Exact in `substeps`, judges them by the same
/// measures against the same start, and clears those that passed. A
/// strand still pending at the end is given up
/// ([`ResetMemory::give_up`]).
pub fn retry_frame(
    guard: &Guard,
    own: u32,
    approximate: bool,
    pending: &mut [bool],
    mut step_again: impl FnMut(u32, &mut [bool]),
) {
    let mut substeps = if approximate {
        own
    } else {
        own.saturating_mul(2)
    };
    while substeps <= guard.max_substeps.max(own) && pending.contains(&true) {
        step_again(substeps, pending);
        substeps = substeps.saturating_mul(2);
    }
}

/// A strand's standing with the guard: the substeps a retry needed, kept
/// for a while, and its recent resets.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GuardState {
    /// Substeps per frame the strand uses at least (0: the system's own).
    pub substeps: u32,
    /// Frames left before it tries the system's substeps again.
    pub hold_frames: u32,
    /// The strand's own solver while the guard has it on Exact.
    pub own_method: Option<Method>,
    /// Its recent resets, which decide when it is pinned.
    pub resets: ResetMemory,
    /// Whether the strand is pinned at rest ([`GuardAction::Pinned`]).
    pub pinned: bool,
}

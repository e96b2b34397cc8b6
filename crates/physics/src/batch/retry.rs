//! The batch guard's recovery: the guard's one policy
//! ([`crate::guard::retry_frame`]), batched.
//!
//! # How it works
//!
//! A strand whose frame fails the guard's check is stepped again from the
//! frame's start: with Exact at the frame's substeps if the frame was
//! Block-diagonal (its failure comes from the truncated inertia, not from
//! h), then with twice the substeps, and twice again, up to
//! [`Guard::max_substeps`]. A retry is judged by the same measures, against
//! the same start. If none passes, the strand goes back to its
//! start-of-frame shape at rest; resets that repeat pin it
//! ([`crate::guard::ResetMemory::give_up`]), held at rest in its rest pose.
//!
//! Lanes share their batch's arithmetic, so a retry steps the whole batch
//! (eight strands) from its checkpoint ([`Group::save_checkpoint`]) and
//! keeps the result only for the lanes that failed; the others keep the
//! frame they passed. Only batches with a failing lane are re-stepped,
//! so a healthy frame costs one copy of the state and nothing else. After
//! a retry passes, the batch steps with Exact for
//! [`Guard::hold_frames`] frames ([`BatchStanding::hold_frames`]) before
//! it tries its own solver again, as the f64 guard holds a strand; the
//! extra substeps are not held (the whole system's substep loop is
//! shared), so a held frame that fails again is retried with more.

use std::sync::Arc;

use super::contact::NearCells;
use super::contact::SkinTest;
use super::group::{BatchStanding, Group, StepKinds, step_one_batch};
use super::guard::{F32_ENERGY_ROUND_OFF, finite_state, measure_lanes, set_at_rest};
use super::lane_model::LaneModel;
use super::lanes::{LANES, Lanes};
use super::layout::{RootMotion, StepEnv};
use super::step::Scratch;
use super::vec::{V3, lane_of, set_lane};
use super::volume::{BatchVolume, carried};
use crate::collision::{ContactSettings, SignedDistanceField};
use crate::frame_balance::{KineticEnergy, SteppedFrame, StrandMeasure};
use crate::guard::{Guard, GuardAction, retry_frame};
use crate::motion::{HeadTrajectory, RootPose};
use crate::settings::Method;

/// What a retry needs besides the batch: the frame, the head and the
/// forces as the frame's own step had them.
pub(super) struct RetryInputs<'a> {
    pub(super) guard: &'a Guard,
    pub(super) head: &'a dyn HeadTrajectory,
    pub(super) start_secs: f64,
    /// The frame's length and its own substeps.
    pub(super) frame: SteppedFrame,
    /// The frame's environment (its substep length is replaced).
    pub(super) env: StepEnv,
    pub(super) kinds: StepKinds,
    /// The energy the system's own step is judged by, which the retry's
    /// end measure must also carry for the next frame.
    pub(super) measured: KineticEnergy,
    pub(super) collider: &'a Option<(Arc<SignedDistanceField>, NearCells)>,
    pub(super) contact: ContactSettings,
    pub(super) pulls: Option<(&'a BatchVolume, usize)>,
}

impl Group {
    /// Re-steps every batch with a lane the frame's check failed, as the
    /// module docs say, and notes in each failing lane's standing what the
    /// guard did ([`Group::record_check`] reports it).
    pub(super) fn retry_failed(&mut self, inputs: &RetryInputs<'_>) {
        let n = self.n;
        Scratch::with_thread_scratch(n, inputs.kinds.iterations(), |scratch| {
            for (b, standing) in self.standing.iter_mut().enumerate() {
                if standing.failed.iter().all(Option::is_none) {
                    continue;
                }
                let range = b * n..(b + 1) * n;
                let batch = RetryBatch {
                    index: b,
                    model: &self.models[b],
                    roots: &self.roots[b * LANES..((b + 1) * LANES).min(self.roots.len())],
                    rest_q: &self.rest_q[range.clone()],
                    start: (
                        &self.checkpoint.0[range.clone()],
                        &self.checkpoint.1[range.clone()],
                    ),
                    q: &mut self.q[range.clone()],
                    v: &mut self.v[range],
                    measures: &mut self.measures[b],
                };
                retry_batch(inputs, batch, standing, scratch);
            }
        });
    }
}

/// One batch with a failing lane, as its retry takes it.
struct RetryBatch<'a> {
    index: usize,
    model: &'a LaneModel,
    roots: &'a [RootPose],
    rest_q: &'a [V3<Lanes>],
    /// q and q̇ at the frame's start.
    start: (&'a [V3<Lanes>], &'a [V3<Lanes>]),
    q: &'a mut [V3<Lanes>],
    v: &'a mut [V3<Lanes>],
    measures: &'a mut [StrandMeasure; LANES],
}

fn retry_batch(
    inputs: &RetryInputs<'_>,
    batch: RetryBatch<'_>,
    standing: &mut BatchStanding,
    scratch: &mut Scratch,
) {
    let RetryBatch {
        index,
        model,
        roots,
        rest_q,
        start,
        q,
        v,
        measures,
    } = batch;
    let guard = inputs.guard;
    let frame = inputs.frame;
    let pull = inputs
        .pulls
        .and_then(|(volume, group)| volume.pull(group, index));
    // What the frame left, which the lanes that passed keep.
    let (mut kept_q, mut kept_v) = (q.to_vec(), v.to_vec());
    let approximate = standing.stepped_own && inputs.kinds.own.is_block_diagonal();
    let end_secs = inputs.start_secs + frame.dt_secs;
    let end_motion = inputs.head.motion_at(end_secs);
    let frame_h_secs = frame.dt_secs / f64::from(frame.substeps.max(1));
    let mut retried = false;
    let mut pending: [bool; LANES] = std::array::from_fn(|lane| standing.failed[lane].is_some());
    retry_frame(
        guard,
        frame.substeps,
        approximate,
        &mut pending,
        |substeps, pending| {
            q.copy_from_slice(start.0);
            v.copy_from_slice(start.1);
            let h_secs = frame.dt_secs / f64::from(substeps);
            let env = StepEnv {
                h_secs,
                ..inputs.env
            };
            for i in 0..substeps {
                let motion = inputs
                    .head
                    .step_motion_at(inputs.start_secs + f64::from(i) * h_secs, h_secs);
                let contact = SkinTest::of_head(inputs.collider, inputs.contact, &motion, h_secs);
                let kind = inputs.kinds.retry;
                step_one_batch(
                    model, &env, &motion, roots, kind, contact, pull, q, v, scratch,
                );
            }
            for (lane, _) in standing.lanes.iter().enumerate().filter(|(_, s)| s.pinned) {
                set_at_rest(q, v, lane, lane_of(rest_q, lane));
            }
            let motions = carried(&end_motion, roots);
            let root = RootMotion::<Lanes>::gather(&motions);
            let contact =
                SkinTest::of_head(inputs.collider, inputs.contact, &end_motion, frame_h_secs);
            let end = measure_lanes(
                model,
                &env,
                &root,
                &motions,
                q,
                v,
                contact.as_ref(),
                pull.as_ref(),
                None,
                inputs.measured,
            );
            let finite = finite_state(q, v);
            let stepped = SteppedFrame {
                dt_secs: frame.dt_secs,
                substeps,
            };
            for lane in 0..LANES {
                if !pending[lane] {
                    continue;
                }
                let to = end.strand(lane);
                let from = &standing.retry_from[lane];
                let passed = finite[lane]
                    && guard
                        .check_with_round_off(&[], &[], from, &to, stepped, F32_ENERGY_ROUND_OFF)
                        .is_none();
                if passed {
                    set_lane(&mut kept_q, lane, lane_of(q, lane));
                    set_lane(&mut kept_v, lane, lane_of(v, lane));
                    measures[lane] = to;
                    set_action(
                        standing,
                        lane,
                        GuardAction::Retried {
                            method: Method::Exact,
                            substeps,
                        },
                    );
                    pending[lane] = false;
                    retried = true;
                }
            }
        },
    );
    for lane in (0..LANES).filter(|&lane| pending[lane]) {
        let memory = &mut standing.lanes[lane];
        let action = memory.resets.give_up(guard);
        memory.pinned = action == GuardAction::Pinned;
        let shape = if memory.pinned { rest_q } else { start.0 };
        set_at_rest(&mut kept_q, &mut kept_v, lane, lane_of(shape, lane));
        set_action(standing, lane, action);
    }
    q.copy_from_slice(&kept_q);
    v.copy_from_slice(&kept_v);
    if retried {
        standing.hold_frames = guard.hold_frames;
    }
}

fn set_action(standing: &mut BatchStanding, lane: usize, action: GuardAction) {
    if let Some((_, slot)) = &mut standing.failed[lane] {
        *slot = Some(action);
    }
}

//! [`Group`]: the strands of one element count, in batches of [`LANES`],
//! with their state, roots, constants and standing with the guard; how a
//! group steps, and how the guard measures and judges it.

use std::sync::Arc;

use rayon::prelude::*;

use super::batch_step::{BatchStep, Scratch, step_pulled};
use super::contact::{LaneContact, NoContact, SkinTest};
use super::guard::{check_and_reset, measure_lanes, set_natural_at_rest};
use super::lane_model::LaneModel;
use super::lanes::{LANES, Lanes};
use super::layout::{BatchModel, RootMotion, StepEnv};
use super::vec::V3;
use super::volume::{BatchVolume, GroupView};
use crate::frame_balance::StrandMeasure;
use crate::guard::{Guard, GuardAction, GuardCause, GuardEvent, ResetMemory};
use crate::motion::{RigidMotion, RootPose};

/// Strands of one element count, in batches of [`LANES`] (see the module
/// docs' "Packing").
#[derive(Clone, Debug)]
pub(super) struct Group {
    /// Elements per strand, N.
    pub(super) n: usize,
    /// Per batch: its lanes' constants.
    pub(super) models: Vec<Arc<LaneModel>>,
    /// Per slot (batch · LANES + lane; padding has none): the strand's root.
    pub(super) roots: Vec<RootPose>,
    /// Per slot: the strand's index in the system.
    pub(super) strands: Vec<usize>,
    /// Batch-major: batch b's element e is entry b·N + e.
    pub(super) q: Vec<V3<Lanes>>,
    pub(super) v: Vec<V3<Lanes>>,
    /// The guard's per-lane measures at the end of the last frame, while
    /// the state has not changed since.
    pub(super) measures: Option<Vec<[StrandMeasure; LANES]>>,
    /// Per strand (batch-major, padding included): its recent resets and
    /// whether the guard pinned it.
    guard_standing: Vec<LaneStanding>,
}

/// One strand's standing with the batch guard.
#[derive(Clone, Copy, Debug, Default)]
struct LaneStanding {
    resets: ResetMemory,
    pinned: bool,
}

/// One batch's state, roots and constants, read only, as the guard's
/// measure takes them.
type BatchView<'a> = (
    ((&'a [V3<Lanes>], &'a [V3<Lanes>]), &'a [RootPose]),
    &'a Arc<LaneModel>,
);

/// One batch's state, roots and constants, as the step's iterators hand
/// them out.
type BatchRef<'a> = (
    ((&'a mut [V3<Lanes>], &'a mut [V3<Lanes>]), &'a [RootPose]),
    &'a Arc<LaneModel>,
);

/// One batch's state and constants with its lanes' measures at the start
/// and end of a frame, as the guard's check takes them.
type BatchCheck<'a> = (
    (
        (&'a mut [V3<Lanes>], &'a mut [V3<Lanes>]),
        &'a Arc<LaneModel>,
    ),
    (&'a [StrandMeasure; LANES], &'a [StrandMeasure; LANES]),
);

impl Group {
    /// No strands yet, of `n` elements each.
    pub(super) fn new(n: usize) -> Self {
        Self {
            n,
            models: Vec::new(),
            roots: Vec::new(),
            strands: Vec::new(),
            q: Vec::new(),
            v: Vec::new(),
            measures: None,
            guard_standing: Vec::new(),
        }
    }

    /// Places strand `strand` (constants `model`, `uniform` in every lane)
    /// in the next free slot, at its natural shape and at rest, and
    /// returns the slot: lane 0 of a new batch (all of whose lanes copy
    /// it), or the next lane of the last batch (whose lanes after it, the
    /// padding, then copy it).
    pub(super) fn push(
        &mut self,
        model: &BatchModel,
        uniform: &Arc<LaneModel>,
        root: RootPose,
        strand: usize,
    ) -> usize {
        let n = self.n;
        let slot = self.roots.len();
        let (batch, lane) = (slot / LANES, slot % LANES);
        if lane == 0 {
            self.models.push(uniform.clone());
            self.q.extend_from_slice(&uniform.natural);
            self.v.extend(std::iter::repeat_n(V3::zero(), n));
            self.guard_standing.extend([LaneStanding::default(); LANES]);
        } else {
            // Batches of one call already hold `model` in every lane.
            if !Arc::ptr_eq(&self.models[batch], uniform) {
                Arc::make_mut(&mut self.models[batch]).set_lanes_from(lane, model);
            }
            let range = batch * n..(batch + 1) * n;
            for l in lane..LANES {
                let (q, v) = (&mut self.q[range.clone()], &mut self.v[range.clone()]);
                set_natural_at_rest(&self.models[batch], q, v, l);
                self.guard_standing[batch * LANES + l] = LaneStanding::default();
            }
        }
        self.roots.push(root);
        self.strands.push(strand);
        self.measures = None;
        slot
    }

    /// Per batch, the guard's measures of every lane for the head moving
    /// as `motion` (see [`super::guard`]).
    pub(super) fn measure(
        &self,
        motion: &RigidMotion,
        env: &StepEnv,
        contact: Option<&SkinTest<'_>>,
        pulls: Option<(&BatchVolume, usize)>,
        parallel: bool,
    ) -> Vec<[StrandMeasure; LANES]> {
        let n = self.n;
        let one = |(b, (((q, v), roots), model)): (usize, BatchView<'_>)| {
            let motions: [RigidMotion; LANES] =
                std::array::from_fn(|i| motion.carry(&roots[i.min(roots.len() - 1)]));
            let root = RootMotion::<Lanes>::gather(&motions);
            let pull = pulls.and_then(|(volume, group)| volume.pull(group, b));
            measure_lanes(&**model, env, &root, &motions, q, v, contact, pull.as_ref())
        };
        if parallel {
            self.q
                .par_chunks(n)
                .zip(self.v.par_chunks(n))
                .zip(self.roots.par_chunks(LANES))
                .zip(self.models.par_iter())
                .enumerate()
                .map(one)
                .collect()
        } else {
            self.q
                .chunks(n)
                .zip(self.v.chunks(n))
                .zip(self.roots.chunks(LANES))
                .zip(self.models.iter())
                .enumerate()
                .map(one)
                .collect()
        }
    }

    /// The group as the hair–hair model's gather reads it.
    pub(super) fn view(&self) -> GroupView<'_> {
        GroupView {
            n: self.n,
            models: &self.models,
            roots: &self.roots,
            q: &self.q,
            v: &self.v,
        }
    }

    /// The guard's end-of-frame check of the frame that started at
    /// `start_secs`; appends an event per reset or pinned strand.
    #[expect(
        clippy::too_many_arguments,
        reason = "the frame's measures and times, where events go, and how to run"
    )]
    pub(super) fn guard(
        &mut self,
        guard: &Guard,
        start: &[[StrandMeasure; LANES]],
        end: &[[StrandMeasure; LANES]],
        dt_secs: f64,
        start_secs: f64,
        events: &mut Vec<GuardEvent>,
        parallel: bool,
    ) {
        let n = self.n;
        for standing in &mut self.guard_standing {
            standing.resets.tick();
        }
        // Each batch's f64 checks (and resets) are its own: in parallel.
        let check = |(((q, v), model), (start, end)): BatchCheck<'_>| {
            check_and_reset(guard, model, q, v, start, end, dt_secs)
        };
        let failures: Vec<[Option<GuardCause>; LANES]> = if parallel {
            self.q
                .par_chunks_mut(n)
                .zip(self.v.par_chunks_mut(n))
                .zip(self.models.par_iter())
                .zip(start.par_iter().zip(end))
                .map(check)
                .collect()
        } else {
            self.q
                .chunks_mut(n)
                .zip(self.v.chunks_mut(n))
                .zip(self.models.iter())
                .zip(start.iter().zip(end))
                .map(check)
                .collect()
        };
        for (batch, failed) in failures.into_iter().enumerate() {
            for (lane, cause) in failed.into_iter().enumerate() {
                let standing = &mut self.guard_standing[batch * LANES + lane];
                // A pinned strand is held, not judged.
                let Some(cause) = cause.filter(|_| !standing.pinned) else {
                    continue;
                };
                standing.pinned = standing.resets.record_reset(guard);
                let local = batch * LANES + lane;
                // Padding lanes are reset too, but name no strand.
                if let Some(&strand) = self.strands.get(local) {
                    events.push(GuardEvent {
                        strand,
                        time_secs: start_secs,
                        cause,
                        action: if standing.pinned {
                            GuardAction::Pinned
                        } else {
                            GuardAction::Reset
                        },
                    });
                }
            }
        }
    }

    /// Puts every pinned strand back at its natural shape, at rest.
    pub(super) fn hold_pinned(&mut self) {
        let n = self.n;
        for (i, standing) in self.guard_standing.iter().enumerate() {
            if !standing.pinned {
                continue;
            }
            let (batch, lane) = (i / LANES, i % LANES);
            let range = batch * n..(batch + 1) * n;
            set_natural_at_rest(
                &self.models[batch],
                &mut self.q[range.clone()],
                &mut self.v[range],
                lane,
            );
        }
    }

    pub(super) fn step(
        &mut self,
        motion: &RigidMotion,
        env: &StepEnv,
        step_kind: BatchStep,
        contact: Option<SkinTest<'_>>,
        pulls: Option<(&BatchVolume, usize)>,
        parallel: bool,
    ) {
        let n = self.n;
        let step_batch =
            |scratch: &mut Scratch, (b, (((q, v), roots), model)): (usize, BatchRef<'_>)| {
                let motions: [RigidMotion; LANES] =
                    std::array::from_fn(|i| motion.carry(&roots[i.min(roots.len() - 1)]));
                let root = RootMotion::<Lanes>::gather(&motions);
                let pull = pulls.and_then(|(volume, group)| volume.pull(group, b));
                // One branch per batch: without a collider, the sweep has no
                // contact stage at all.
                match contact {
                    Some(test) => {
                        let positions = std::array::from_fn(|i| motions[i].position_m);
                        let implicit = step_kind != BatchStep::BlockDiagonal;
                        let end_force = LaneContact::new(test, model, positions, implicit);
                        step_pulled(model, env, &root, step_kind, q, v, scratch, end_force, pull);
                    }
                    None => {
                        step_pulled(model, env, &root, step_kind, q, v, scratch, NoContact, pull)
                    }
                }
            };
        if parallel {
            self.q
                .par_chunks_mut(n)
                .zip(self.v.par_chunks_mut(n))
                .zip(self.roots.par_chunks(LANES))
                .zip(self.models.par_iter())
                .enumerate()
                .for_each(|batch| {
                    Scratch::with_thread_scratch(n, step_kind.iterations(), |scratch| {
                        step_batch(scratch, batch)
                    })
                });
        } else {
            Scratch::with_thread_scratch(n, step_kind.iterations(), |scratch| {
                self.q
                    .chunks_mut(n)
                    .zip(self.v.chunks_mut(n))
                    .zip(self.roots.chunks(LANES))
                    .zip(self.models.iter())
                    .enumerate()
                    .for_each(|batch| step_batch(scratch, batch))
            });
        }
    }
}

//! [`Group`]: the strands of one element count, in batches of [`LANES`],
//! with their state, roots, constants and standing with the guard; how a
//! group steps, and how the guard measures and judges it.

use std::sync::Arc;

use rayon::prelude::*;

use super::contact::{LaneContact, NearCells, SkinTest};
use super::forward::NoContact;
use super::guard::{check_lanes, finite_state, measure_lanes, set_at_rest};
use super::lane_model::LaneModel;
use super::lanes::{LANES, Lanes};
use super::layout::{BatchModel, RootMotion, StepEnv};
use super::vec::{V3, lane_of, set_lane};
use super::volume::{BatchVolume, GroupView, KeptSamples, carried};
use crate::batch::step::{BatchStep, Scratch, step_pulled};
use crate::batch::volume::pull::SamplePull;
use crate::collision::SignedDistanceField;
use crate::frame_balance::{KineticEnergy, SteppedFrame, StrandMeasure};
use crate::guard::{Guard, GuardAction, GuardCause, GuardEvent, ResetMemory};
use crate::motion::{RigidMotion, RootPose};
use crate::settings::SimSettings;

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
    /// Batch-major as `q`: the strains each lane rests in, which the
    /// hair–hair model's rest density is built from (its natural strains
    /// unless told: [`crate::Strand::rest_pose`]).
    pub(super) rest_q: Vec<V3<Lanes>>,
    /// Per batch: the guard's measures of its lanes, at the start of the
    /// frame while it steps, at its end once the frame is judged.
    pub(super) measures: Vec<[StrandMeasure; LANES]>,
    /// Whether `measures` describe the state as it is (false after a
    /// reset, a new strand or a state set from outside).
    pub(super) measured: bool,
    /// Per batch: its lanes' standing with the guard.
    pub(super) standing: Vec<BatchStanding>,
    /// `q` and `v` at the start of the frame, where a retry starts from
    /// ([`super::retry`]); stale with the guard off.
    pub(super) checkpoint: (Vec<V3<Lanes>>, Vec<V3<Lanes>>),
    /// Per batch: its quadrature samples (position relative to the root,
    /// world velocity; N × nodes) as the guard's end-of-frame measure
    /// found them, kept for the hair–hair model's next gather; empty where
    /// the measure ran without the model.
    kept_samples: Vec<Vec<[V3<Lanes>; 2]>>,
    /// The head's motion `kept_samples` were taken at, if the last frame's
    /// judgement kept them.
    kept_at: Option<RigidMotion>,
}

/// One batch's lanes' end-of-frame measures and whether each lane's state
/// is finite, as the device that stepped them found them (`None`: a
/// padding lane, not judged).
pub(crate) type LaneEnds = [Option<(StrandMeasure, bool)>; LANES];

/// Which batches a [`Group::step`] steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Advance {
    /// Every batch (the batch engine's own frame).
    All,
    /// Only batches that hold a retry's step: the rest were stepped
    /// elsewhere with the settings' own step (the GPU engine's frame).
    Held,
}

impl Advance {
    /// Whether a batch standing as `standing` steps.
    fn steps(self, standing: &BatchStanding) -> bool {
        match self {
            Advance::All => true,
            Advance::Held => standing.hold_frames > 0,
        }
    }
}

/// One batch's standing with the guard.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct BatchStanding {
    /// Per lane: what the last check found (`None`: passed, or not judged)
    /// and, once the retry has run, what the guard did about it.
    pub(super) failed: [Option<(GuardCause, Option<GuardAction>)>; LANES],
    /// Per lane: the measure its failed frame started from, which a retry
    /// is judged against (set only where the lane failed).
    pub(super) retry_from: [StrandMeasure; LANES],
    /// Per lane: its recent resets and whether the guard pinned it.
    pub(super) lanes: [LaneStanding; LANES],
    /// Frames the batch still steps with the retry's solver after a
    /// retry passed (the f64 guard's [`Guard::hold_frames`], per batch:
    /// its lanes share one step).
    pub(super) hold_frames: u32,
    /// Whether the last frame stepped with the settings' own solver (not
    /// held on the retry's).
    pub(super) stepped_own: bool,
}

/// One strand's standing with the batch guard.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct LaneStanding {
    pub(super) resets: ResetMemory,
    pub(super) pinned: bool,
}

/// The steps a frame takes: the settings' own, and the retry's, which a
/// batch also takes while it holds a retry ([`BatchStanding::hold_frames`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct StepKinds {
    pub(super) own: BatchStep,
    pub(super) retry: BatchStep,
}

impl StepKinds {
    /// GMRES iterations the scratch must hold for either step.
    pub(super) fn iterations(self) -> usize {
        self.own.iterations().max(self.retry.iterations())
    }

    /// The step a batch takes with `standing`.
    fn of(self, standing: &BatchStanding) -> BatchStep {
        if standing.hold_frames > 0 {
            self.retry
        } else {
            self.own
        }
    }
}

/// What the guard needs to judge a frame at its end, batch by batch, in
/// the same pass as the frame's last substep: each batch is measured and
/// checked right after it stepped, while its state and constants are
/// still in cache (a separate pass over the whole group found them gone:
/// the measure's loads missed, a third of its time).
#[derive(Clone, Copy, Debug)]
pub(super) struct FrameCheck<'a> {
    pub(super) guard: &'a Guard,
    /// The head at the end of the frame.
    pub(super) motion: &'a RigidMotion,
    /// The contact test with the head there, if a collider is set.
    pub(super) contact: Option<SkinTest<'a>>,
    /// The frame's length and substeps.
    pub(super) frame: SteppedFrame,
    /// The energy the frame's step conserves, which it is judged by.
    pub(super) kinetic: KineticEnergy,
}

impl<'a> FrameCheck<'a> {
    /// The check of a frame of `settings` (its step, substeps and contact)
    /// ending with the head as `motion`, judged by `kinetic`.
    pub(super) fn new(
        guard: &'a Guard,
        motion: &'a RigidMotion,
        collider: &'a Option<(Arc<SignedDistanceField>, NearCells)>,
        settings: &SimSettings,
        kinetic: KineticEnergy,
    ) -> Self {
        let h = settings.substep_secs();
        Self {
            guard,
            motion,
            contact: SkinTest::of_head(collider, settings.contact, motion, h),
            frame: SteppedFrame {
                dt_secs: settings.dt_secs,
                substeps: settings.substeps,
            },
            kinetic,
        }
    }
}

/// One batch's state, roots and constants, read only, with where its
/// measures go, as the guard's start-of-frame measure takes them.
type BatchView<'a> = (
    (
        ((&'a [V3<Lanes>], &'a [V3<Lanes>]), &'a [RootPose]),
        &'a Arc<LaneModel>,
    ),
    &'a mut [StrandMeasure; LANES],
);

/// One batch's state, roots, constants, measures and standing, as the
/// step's iterators hand them out.
type BatchRef<'a> = (
    (
        (
            (
                ((&'a mut [V3<Lanes>], &'a mut [V3<Lanes>]), &'a [RootPose]),
                &'a Arc<LaneModel>,
            ),
            &'a mut [StrandMeasure; LANES],
        ),
        &'a mut BatchStanding,
    ),
    &'a mut Vec<[V3<Lanes>; 2]>,
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
            rest_q: Vec::new(),
            measures: Vec::new(),
            measured: false,
            standing: Vec::new(),
            checkpoint: (Vec::new(), Vec::new()),
            kept_samples: Vec::new(),
            kept_at: None,
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
            self.rest_q.extend_from_slice(&uniform.natural);
            self.v.extend(std::iter::repeat_n(V3::zero(), n));
            self.measures.push(Default::default());
            self.standing.push(BatchStanding::default());
            self.kept_samples.push(Vec::new());
        } else {
            // Batches of one call already hold `model` in every lane.
            if !Arc::ptr_eq(&self.models[batch], uniform) {
                Arc::make_mut(&mut self.models[batch]).set_lanes_from(lane, model);
            }
            let range = batch * n..(batch + 1) * n;
            for l in lane..LANES {
                let rest_q = &mut self.rest_q[range.clone()];
                set_lane(rest_q, l, self.models[batch].natural_of_lane(l));
                let (q, v) = (&mut self.q[range.clone()], &mut self.v[range.clone()]);
                set_at_rest(q, v, l, lane_of(rest_q, l));
                self.standing[batch].lanes[l] = LaneStanding::default();
            }
        }
        self.roots.push(root);
        self.strands.push(strand);
        self.measured = false;
        slot
    }

    /// Measures every lane for the head moving as `motion` (see
    /// [`super::guard`]) into `measures`: the start of a frame, where the
    /// last frame's end measures do not describe the state.
    pub(super) fn measure(
        &mut self,
        motion: &RigidMotion,
        env: &StepEnv,
        contact: Option<&SkinTest<'_>>,
        pulls: Option<(&BatchVolume, usize)>,
        kinetic: KineticEnergy,
        parallel: bool,
    ) {
        let n = self.n;
        let one = |(b, ((((q, v), roots), model), out)): (usize, BatchView<'_>)| {
            let motions = carried(motion, roots);
            let root = RootMotion::<Lanes>::gather(&motions);
            let pull = pulls.and_then(|(volume, group)| volume.pull(group, b));
            let measured = measure_lanes(
                &**model,
                env,
                &root,
                &motions,
                q,
                v,
                contact,
                pull.as_ref(),
                None,
                kinetic,
            );
            for (lane, out) in out.iter_mut().enumerate() {
                *out = measured.strand(lane);
            }
        };
        if parallel {
            self.q
                .par_chunks(n)
                .zip(self.v.par_chunks(n))
                .zip(self.roots.par_chunks(LANES))
                .zip(self.models.par_iter())
                .zip(self.measures.par_iter_mut())
                .enumerate()
                .for_each(one);
        } else {
            self.q
                .chunks(n)
                .zip(self.v.chunks(n))
                .zip(self.roots.chunks(LANES))
                .zip(self.models.iter())
                .zip(self.measures.iter_mut())
                .enumerate()
                .for_each(one);
        }
        self.measured = true;
    }

    /// Whether a batch holds a retry's step ([`BatchStanding::hold_frames`]).
    pub(super) fn any_held(&self) -> bool {
        self.standing.iter().any(|s| s.hold_frames > 0)
    }

    /// Whether the last check found a lane failing.
    pub(super) fn any_failed(&self) -> bool {
        self.standing
            .iter()
            .any(|s| s.failed.iter().any(Option::is_some))
    }

    /// Whether a lane is pinned in its rest pose.
    pub(super) fn any_pinned(&self) -> bool {
        self.standing
            .iter()
            .any(|s| s.lanes.iter().any(|lane| lane.pinned))
    }

    /// Puts every batch that holds a retry's step back at the frame's
    /// start ([`Self::save_checkpoint`]): a state stepped elsewhere with
    /// the settings' own step is not what such a batch steps.
    pub(super) fn restore_held(&mut self) {
        let n = self.n;
        for (b, standing) in self.standing.iter().enumerate() {
            if standing.hold_frames > 0 {
                let range = b * n..(b + 1) * n;
                self.q[range.clone()].copy_from_slice(&self.checkpoint.0[range.clone()]);
                self.v[range.clone()].copy_from_slice(&self.checkpoint.1[range]);
            }
        }
    }

    /// Keeps the state as the start of the frame, where a retry starts
    /// from: one copy of the state per frame, with the guard on.
    pub(super) fn save_checkpoint(&mut self) {
        let (q, v) = &mut self.checkpoint;
        q.clone_from(&self.q);
        v.clone_from(&self.v);
    }

    /// The group as the hair–hair model's gather reads it: with the
    /// samples the last judgement kept, while they describe the state.
    pub(super) fn view(&self) -> GroupView<'_> {
        let kept = self
            .kept_at
            .filter(|_| self.measured)
            .map(|at| KeptSamples {
                at,
                batches: &self.kept_samples,
            });
        GroupView {
            n: self.n,
            models: &self.models,
            roots: &self.roots,
            q: &self.q,
            v: &self.v,
            rest_q: &self.rest_q,
            kept,
        }
    }

    /// Turns the last check's findings ([`FrameCheck`], made in the
    /// frame's last substep) and what the retry did about them
    /// ([`super::retry`]) into the guard's record for the frame that
    /// started at `start_secs`: appends an event per strand the guard
    /// re-stepped, reset or pinned. The measures stay the start of the
    /// next frame unless the guard stepped in.
    pub(super) fn record_check(&mut self, start_secs: f64, events: &mut Vec<GuardEvent>) {
        let before = events.len();
        for (batch, standing) in self.standing.iter_mut().enumerate() {
            let failed = std::mem::take(&mut standing.failed);
            for (lane, found) in failed.into_iter().enumerate() {
                let Some((cause, Some(action))) = found else {
                    continue;
                };
                // Padding lanes are stepped and judged too, but name no strand.
                if let Some(&strand) = self.strands.get(batch * LANES + lane) {
                    events.push(GuardEvent {
                        strand,
                        time_secs: start_secs,
                        cause,
                        action,
                    });
                }
            }
        }
        self.measured = events.len() == before;
    }

    /// One substep of every batch, the head moving as `motion`; with
    /// `check` (the frame's last substep, guard on), each batch is then
    /// measured and judged at once ([`judge_batch`]) and
    /// [`Self::record_check`] records what failed. `advance` says which
    /// batches step here ([`Advance`]); the others' state as it stands
    /// (stepped elsewhere: [`super::BatchSystem::step_frame_offloaded`])
    /// is only judged.
    #[expect(
        clippy::too_many_arguments,
        reason = "the substep's head, forces and kind, the frame's check, and how to run"
    )]
    pub(super) fn step(
        &mut self,
        motion: &RigidMotion,
        env: &StepEnv,
        kinds: StepKinds,
        contact: Option<SkinTest<'_>>,
        pulls: Option<(&BatchVolume, usize)>,
        check: Option<&FrameCheck<'_>>,
        parallel: bool,
        advance: Advance,
        measured: Option<&[LaneEnds]>,
    ) {
        let n = self.n;
        // Kept samples from the last frame describe the state no more.
        self.kept_at = None;
        let rest_q = &self.rest_q;
        let step_batch = |scratch: &mut Scratch,
                          (b, ((((((q, v), roots), model), measures), standing), kept)): (
            usize,
            BatchRef<'_>,
        )| {
            let kind = kinds.of(standing);
            let pull = pulls.and_then(|(volume, group)| volume.pull(group, b));
            let steps_here = advance.steps(standing);
            if steps_here {
                step_one_batch(
                    model, env, motion, roots, kind, contact, pull, q, v, scratch,
                );
            }
            // Measured where it was stepped, if there.
            let given = measured.filter(|_| !steps_here).map(|ends| &ends[b]);
            if let Some(check) = check {
                let rest_q = &rest_q[b * n..(b + 1) * n];
                let batch = BatchState {
                    model,
                    roots,
                    rest_q,
                    q,
                    v,
                };
                judge_batch(
                    check, env, batch, measures, standing, kind, pull, kept, given,
                );
            }
        };
        if parallel {
            self.q
                .par_chunks_mut(n)
                .zip(self.v.par_chunks_mut(n))
                .zip(self.roots.par_chunks(LANES))
                .zip(self.models.par_iter())
                .zip(self.measures.par_iter_mut())
                .zip(self.standing.par_iter_mut())
                .zip(self.kept_samples.par_iter_mut())
                .enumerate()
                .for_each(|batch| {
                    Scratch::with_thread_scratch(n, kinds.iterations(), |scratch| {
                        step_batch(scratch, batch)
                    })
                });
        } else {
            Scratch::with_thread_scratch(n, kinds.iterations(), |scratch| {
                self.q
                    .chunks_mut(n)
                    .zip(self.v.chunks_mut(n))
                    .zip(self.roots.chunks(LANES))
                    .zip(self.models.iter())
                    .zip(self.measures.iter_mut())
                    .zip(self.standing.iter_mut())
                    .zip(self.kept_samples.iter_mut())
                    .enumerate()
                    .for_each(|batch| step_batch(scratch, batch))
            });
        }
        if let Some(check) = check.filter(|_| pulls.is_some()) {
            self.kept_at = Some(*check.motion);
        }
    }
}

/// One step of `kind` of one batch (constants `model`, roots `roots`
/// carried by the head moving as `motion`) with the head's `contact` and
/// the hair–hair model's `pull`, where on.
#[expect(
    clippy::too_many_arguments,
    reason = "the step's inputs and buffers, passed through"
)]
#[inline(always)]
pub(super) fn step_one_batch(
    model: &LaneModel,
    env: &StepEnv,
    motion: &RigidMotion,
    roots: &[RootPose],
    kind: BatchStep,
    contact: Option<SkinTest<'_>>,
    pull: Option<SamplePull<'_>>,
    q: &mut [V3<Lanes>],
    v: &mut [V3<Lanes>],
    scratch: &mut Scratch,
) {
    let motions = carried(motion, roots);
    let root = RootMotion::<Lanes>::gather(&motions);
    // One branch per batch: without a collider, the sweep has no contact
    // stage at all.
    match contact {
        Some(test) => {
            let positions = std::array::from_fn(|i| motions[i].position_m);
            let hook = LaneContact::new(test, model.mass_per_length, positions);
            step_pulled(model, env, &root, kind, q, v, scratch, hook, pull);
        }
        None => step_pulled(model, env, &root, kind, q, v, scratch, NoContact, pull),
    }
}

/// One batch as the guard's end-of-frame judgement takes it.
struct BatchState<'a> {
    model: &'a LaneModel,
    roots: &'a [RootPose],
    /// The lanes' rest poses, where the guard resets and holds them.
    rest_q: &'a [V3<Lanes>],
    q: &'a mut [V3<Lanes>],
    v: &'a mut [V3<Lanes>],
}

/// The guard's end of a frame for one batch that has just stepped with
/// `kind`: holds its pinned lanes at rest, measures every lane at the end
/// of the frame, checks each against its start `measures` (which then
/// become the end's) by the energy `kind` conserves, and notes in
/// `standing` what failed and the measure it started from, for the retry
/// ([`super::retry`]). With the hair–hair model on (`pull`), the
/// measure's samples are kept in `kept` for the model's next gather
/// (emptied if a lane failed: the retry changes it, and the gather sweeps
/// that batch itself). With `given`, the lanes' end measures and
/// finiteness come from where the batch was stepped (the GPU engine's
/// device, [`super::BatchSystem::step_frame_offloaded`]) instead of a
/// sweep here. Not inlined: folded into the step's closure it made
/// the whole step twice as slow (one function too large for the compiler
/// to keep the step's lanes in registers), guard on or off.
#[expect(
    clippy::too_many_arguments,
    reason = "the batch, its standing, the step it took, the model's samples and the given ends"
)]
#[inline(never)]
fn judge_batch(
    check: &FrameCheck<'_>,
    env: &StepEnv,
    batch: BatchState<'_>,
    measures: &mut [StrandMeasure; LANES],
    standing: &mut BatchStanding,
    kind: BatchStep,
    pull: Option<SamplePull<'_>>,
    kept: &mut Vec<[V3<Lanes>; 2]>,
    given: Option<&LaneEnds>,
) {
    let BatchState {
        model,
        roots,
        rest_q,
        q,
        v,
    } = batch;
    standing.stepped_own = standing.hold_frames == 0;
    standing.hold_frames = standing.hold_frames.saturating_sub(1);
    for lane in &mut standing.lanes {
        lane.resets.tick();
    }
    for (lane, _) in standing.lanes.iter().enumerate().filter(|(_, s)| s.pinned) {
        set_at_rest(q, v, lane, lane_of(rest_q, lane));
    }
    let judged_by = if kind.is_block_diagonal() {
        check.kinetic
    } else {
        KineticEnergy::True
    };
    // The lanes' end measures and finiteness: given, or swept here.
    let (finite, ends): ([bool; LANES], [Option<StrandMeasure>; LANES]) = match given {
        Some(given) => (
            std::array::from_fn(|lane| given[lane].is_none_or(|(_, finite)| finite)),
            (*given).map(|end| end.map(|(measure, _)| measure)),
        ),
        None => {
            let motions = carried(check.motion, roots);
            let root = RootMotion::<Lanes>::gather(&motions);
            let contact = check.contact.as_ref();
            let samples = pull.is_some().then(|| {
                kept.resize(q.len() * model.nodes.len(), [V3::zero(); 2]);
                kept.as_mut_slice()
            });
            let end = measure_lanes(
                model,
                env,
                &root,
                &motions,
                q,
                v,
                contact,
                pull.as_ref(),
                samples,
                check.kinetic,
            );
            (
                finite_state(q, v),
                std::array::from_fn(|lane| Some(end.strand(lane))),
            )
        }
    };
    let failed = check_lanes(
        check.guard,
        finite,
        measures,
        &mut standing.retry_from,
        |lane| ends[lane],
        check.frame,
        judged_by,
    );
    for (lane, cause) in failed.into_iter().enumerate() {
        // A pinned strand is held, not judged.
        let cause = cause.filter(|_| !standing.lanes[lane].pinned);
        standing.failed[lane] = cause.map(|cause| (cause, None));
    }
    if pull.is_none() || standing.failed.iter().any(Option::is_some) {
        kept.clear();
    }
}

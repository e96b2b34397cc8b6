//! The hair–hair model ([`crate::volume`]) on the batch engine: once per
//! frame, before the strands step, gather every lane's quadrature samples
//! into its points, one per pair of nodes
//! ([`crate::volume::pair_points`]), splat them on the rest grid with the
//! shared f64 arithmetic
//! ([`crate::volume::field`]), and hand each batch its pull
//! ([`crate::batch::volume::pull::SamplePull`]) for the frame's steps.
//!
//! # One arithmetic with the reference
//!
//! Only the gather is the batch engine's own: a root-to-tip sweep in f32
//! lanes, as the guard's measure sweeps ([`super::guard`]), gives each
//! sample's position relative to its root and its world velocity; they are
//! widened to f64, averaged over each pair of nodes with the quadrature
//! weights and carried into head coordinates exactly as the reference's
//! [`crate::volume::pair_points::pair_points`] does, with mass
//! ρS·ℓ·(w_a + w_b) (four lanes at a time in f64x4, each lane's
//! operations those of the reference's DVec3 arithmetic, in the same
//! order). The splat, the
//! density excess and what each point reads back (grid velocity, pressure
//! push) are the same functions the reference calls. The reading becomes
//! the point's known force k = ρS (μ u_rel + a) (world axes; u_rel the
//! grid velocity relative to the head, [`crate::volume::friction`]),
//! rounded to f32 once.
//!
//! # The guard's samples
//!
//! The sweep the gather needs is the one the guard's end-of-frame measure
//! made ([`super::guard::measure_lanes`]) at the state and head the next
//! frame starts from. With the model on, that measure keeps each sample's
//! position relative to its root and its velocity, and the gather takes
//! them ([`KeptSamples`]) instead of sweeping the batch again, where they
//! still describe it: not after a reset or any change from outside (the
//! group's measures are stale then too), and not when the head is not
//! where the last frame ended. The same sweep on the same state, so the
//! same bits; at 3,000 strands it halved the gather's instructions (12.6
//! to 5.3 M a frame) and took about 7% off the model's pass in paired runs.
//! With the guard off nothing
//! is kept and every frame sweeps.
//!
//! # Rest density
//!
//! Built on first use, as on the reference, from the rest pose: every
//! strand in the strains it rests in (its natural strains unless told,
//! [`crate::Strand::rest_pose`]), at rest, the head at the origin, on a
//! grid fitted to those samples with half the longest strand to spare. It
//! is gathered by the same f32 sweep the frames use, so a batch at rest in
//! its rest pose on a still head splats exactly the rest density and
//! feels no pressure.
//!
//! # Padding
//!
//! A short last batch pads with copies of its last strand
//! ([`super::layout`]); their points splat with zero mass (a strand is
//! counted once) and read the field like any other, so the padding steps
//! as its strand does.

pub mod pull;
pub mod read;

use std::sync::Arc;
use std::time::Instant;

use rayon::prelude::*;
use wide::f64x4;

use super::forward::sweep_samples;
use super::lane_model::{Constants, LaneModel};
use super::lanes::{LANES, Lanes, Real};
use super::layout::RootMotion;
use super::vec::V3;
use crate::batch::volume::pull::{RootVelocity, SamplePull, friction_rate};
use crate::batch::volume::read::{BatchRates, Exchange, ReadInputs, read_batch};
use crate::frame_balance::StrandMeasure;
use crate::motion::{RigidMotion, RootPose};
use crate::volume::balance::PullWork;
use crate::volume::cell::CellLanes;
use crate::volume::friction::HeadVelocity;
use crate::volume::pair_points::{NODES_PER_POINT, PairWeights, pair_weights, points_per_element};
use crate::volume::splat_lanes::PointLanes;
use crate::volume::{InteractionSettings, ModelState, RestDensity};

/// One group of strands as the gather reads it: its batches' constants,
/// roots and batch-major state (batch b's element e at b·N + e).
#[derive(Clone, Copy, Debug)]
pub struct GroupView<'a> {
    /// Elements per strand N.
    pub n: usize,
    /// Each batch's f32 constants, lane by lane.
    pub models: &'a [Arc<LaneModel>],
    /// One root per strand.
    pub roots: &'a [RootPose],
    /// Strains, batch-major.
    pub q: &'a [V3<Lanes>],
    /// Strain rates, batch-major.
    pub v: &'a [V3<Lanes>],
    /// The strains each lane rests in, batch-major
    /// ([`crate::Strand::rest_pose`]): the rest density's pose.
    pub rest_q: &'a [V3<Lanes>],
    /// The samples the guard's measure kept at the end of the last frame,
    /// if they still describe the state ([`KeptSamples`]).
    pub kept: Option<KeptSamples<'a>>,
}

/// Each batch's quadrature samples (position relative to the root, world
/// velocity: what the gather's sweep finds) as the guard's end-of-frame
/// measure found them, with the head's motion then. The frame that follows
/// starts from that state, so where the head is where it was and a batch's
/// samples are all there (none where a lane was reset), the gather takes
/// them instead of sweeping the batch again: the same sweep on the same
/// state, so the same bits.
#[derive(Clone, Copy, Debug)]
pub struct KeptSamples<'a> {
    /// The head's motion the samples were taken at.
    pub at: RigidMotion,
    /// Per batch, its N × nodes samples, or none.
    pub batches: &'a [Vec<[V3<Lanes>; 2]>],
}

impl<'a> KeptSamples<'a> {
    /// Batch `batch`'s samples if they were kept with the head at `head`
    /// and are all there (`samples` of them).
    fn batch(
        &self,
        batch: usize,
        head: &RigidMotion,
        samples: usize,
    ) -> Option<&'a [[V3<Lanes>; 2]]> {
        let kept = self.batches.get(batch)?;
        (self.at == *head && kept.len() == samples).then_some(kept.as_slice())
    }
}

/// One batch's outputs of the gather: its points, its samples
/// (where it swept them itself), and whether it took the kept samples
/// instead.
type BatchOut<'a> = (
    (&'a mut [PointLanes], &'a mut [[V3<Lanes>; 2]]),
    &'a mut bool,
);

/// One batch's read-back: its c, points and their cells, motion and work
/// exchange.
type BatchRead<'a> = (
    (
        (&'a mut [V3<Lanes>], (&'a [PointLanes], &'a [CellLanes])),
        (&'a [[V3<Lanes>; 2]], &'a bool),
    ),
    &'a mut [Exchange; LANES],
);

/// One group's samples and pulls of the current frame.
#[derive(Clone, Debug, Default)]
struct GroupPulls {
    /// Batch b's point p, lanes 4h..4h + 4 at (b·P + p)·2 + h.
    points: Vec<PointLanes>,
    /// Batch b's sample i's position relative to its root and velocity
    /// (world, f32 lanes) at b·S + i, where the gather swept batch b.
    motion: Vec<[V3<Lanes>; 2]>,
    /// Per batch, whether the gather took its kept samples
    /// ([`KeptSamples`]) rather than sweeping it into `motion`.
    from_kept: Vec<bool>,
    /// Batch b's point p's known force k at b·P + p, N/m.
    known: Vec<V3<Lanes>>,
    /// Per batch, μρS lane by lane, kg/(m·s).
    rate: Vec<Lanes>,
    /// Per batch and lane, the old and the new pull's work at the frame's
    /// start ([`crate::batch::volume::read`]).
    exchange: Vec<[Exchange; LANES]>,
    /// Points per strand P ([`crate::volume::pair_points`]).
    points_per_strand: usize,
    /// Samples per strand S = N × nodes.
    samples: usize,
    /// Quadrature nodes per element.
    nodes: usize,
}

/// The model's state on a batch engine.
#[derive(Clone, Debug)]
pub struct BatchVolume {
    state: ModelState,
    groups: Vec<GroupPulls>,
}

impl BatchVolume {
    /// The model with `settings`; the rest density waits for the first frame.
    pub fn new(settings: InteractionSettings) -> Self {
        Self {
            state: ModelState::new(settings),
            groups: Vec::new(),
        }
    }

    /// Settings, rest density, last field and the last pass's time.
    pub fn state(&self) -> &ModelState {
        &self.state
    }

    /// The state, to retune the model or forget its rest density.
    pub fn state_mut(&mut self) -> &mut ModelState {
        &mut self.state
    }

    /// Batch `batch` of group `group`'s pull for the frame prepared last,
    /// if [`Self::prepare`] has run on it.
    pub fn pull(&self, group: usize, batch: usize) -> Option<SamplePull<'_>> {
        let g = self.groups.get(group)?;
        let p = g.points_per_strand;
        let known = g.known.get(batch * p..(batch + 1) * p)?;
        Some(SamplePull {
            friction_per_s: self.state.settings().friction_per_s as f32,
            rate: *g.rate.get(batch)?,
            known,
            nodes: g.nodes,
        })
    }

    /// Of the batches the last frame's gather read, how many took the
    /// samples the guard's measure kept ([`KeptSamples`]) and how many
    /// there were: (kept, all).
    pub fn gathered_from_kept(&self) -> (usize, usize) {
        self.groups.iter().fold((0, 0), |(kept, all), g| {
            let from_kept = g.from_kept.iter().filter(|k| **k).count();
            (kept + from_kept, all + g.from_kept.len())
        })
    }

    /// Group `group`'s start measures (per batch, per lane), reused from
    /// the last frame's end, which counted the old pull's work: the new
    /// pull's counted instead ([`crate::batch::volume::read`]). Without an old pull
    /// (the first frame with the model) the old work is zero, as it was.
    pub fn exchange_start_work(&self, group: usize, measures: &mut [[StrandMeasure; LANES]]) {
        let Some(g) = self.groups.get(group) else {
            return;
        };
        for (batch, exchange) in measures.iter_mut().zip(&g.exchange) {
            for (m, (old, new)) in batch.iter_mut().zip(exchange) {
                PullWork::exchange(m, old, new);
            }
        }
    }

    /// Gathers every group's samples with the head at `head`, splats them
    /// and sets every batch's pull for the coming frame.
    pub fn prepare(&mut self, groups: &[GroupView<'_>], head: &RigidMotion, parallel: bool) {
        let start = Instant::now();
        if !self
            .state
            .ensure_rest(|settings| rest_density(groups, settings))
        {
            self.groups.clear();
            return;
        }
        self.groups.resize_with(groups.len(), GroupPulls::default);
        for (view, pulls) in groups.iter().zip(&mut self.groups) {
            gather_group(view, head, parallel, pulls);
        }
        let parts: Vec<&[PointLanes]> = self.groups.iter().map(|g| g.points.as_slice()).collect();
        let Some((_, field, settings)) =
            self.state
                .update_lanes(&parts, &HeadVelocity::of(head), parallel)
        else {
            return;
        };
        let mut cells = field.cell_lanes();
        let mu = settings.friction_per_s as f32;
        for (view, pulls) in groups.iter().zip(&mut self.groups) {
            if pulls.points.is_empty() {
                // A group without strands (added with no roots): nothing
                // to read, and no chunks to cut.
                pulls.known.clear();
                pulls.rate.clear();
                pulls.exchange.clear();
                continue;
            }
            let (per_strand, lanes) = (pulls.points_per_strand, pulls.points_per_strand * HALVES);
            let batches = pulls.points.len() / lanes;
            // An old pull exists when the last frame read this very layout.
            let had_old = pulls.known.len() == batches * per_strand && pulls.rate.len() == batches;
            let rates: Vec<Lanes> = view.models.iter().map(|m| friction_rate(mu, m)).collect();
            let old_rates = std::mem::replace(&mut pulls.rate, rates);
            let inputs = ReadInputs {
                field,
                settings,
                head,
            };
            pulls.known.resize(batches * per_strand, V3::zero());
            let none = (PullWork::default(), PullWork::default());
            pulls.exchange.resize(batches, [none; LANES]);
            let (group_cells, after) = cells.split_at(pulls.points.len());
            cells = after;
            let read =
                |(b, (((known, points), (swept, from_kept)), exchange)): (usize, BatchRead<'_>)| {
                    let rates = BatchRates {
                        model: &view.models[b],
                        old: had_old.then(|| old_rates[b]),
                        new: pulls.rate[b],
                    };
                    let kept = view.kept.as_ref().filter(|_| *from_kept);
                    let motion = kept.map_or(swept, |k| k.batches[b].as_slice());
                    let roots = &view.roots[b * LANES..((b + 1) * LANES).min(view.roots.len())];
                    let root = RootVelocity::carried_by(head, roots);
                    read_batch(&inputs, &rates, points, (motion, &root), known, exchange);
                };
            if parallel {
                let known = pulls.known.par_chunks_mut(per_strand);
                known
                    .zip(
                        pulls
                            .points
                            .par_chunks(lanes)
                            .zip(group_cells.par_chunks(lanes)),
                    )
                    .zip(
                        pulls
                            .motion
                            .par_chunks(pulls.samples)
                            .zip(pulls.from_kept.par_iter()),
                    )
                    .zip(pulls.exchange.par_iter_mut())
                    .enumerate()
                    .for_each(read);
            } else {
                let known = pulls.known.chunks_mut(per_strand);
                known
                    .zip(pulls.points.chunks(lanes).zip(group_cells.chunks(lanes)))
                    .zip(pulls.motion.chunks(pulls.samples).zip(&pulls.from_kept))
                    .zip(pulls.exchange.iter_mut())
                    .enumerate()
                    .for_each(read);
            }
        }
        self.state.set_last_secs(start.elapsed().as_secs_f64());
    }
}

/// Every batch of `view` gathered into `out.points` (parallel over
/// batches when `parallel`): from the kept samples where they serve
/// ([`KeptSamples`]), else swept.
fn gather_group(view: &GroupView<'_>, head: &RigidMotion, parallel: bool, out: &mut GroupPulls) {
    let n = view.n;
    out.nodes = view.models.first().map_or(0, |m| m.nodes.len());
    out.points_per_strand = n * points_per_element(out.nodes);
    out.samples = n * out.nodes;
    let batches = view.models.len();
    if batches == 0 || out.samples == 0 {
        // A group without strands, or of strands without samples: no
        // points (and no chunks of zero to cut).
        out.points.clear();
        out.motion.clear();
        out.from_kept.clear();
        return;
    }
    let lanes = out.points_per_strand * HALVES;
    out.points.resize(batches * lanes, PointLanes::default());
    out.motion.resize(batches * out.samples, [V3::zero(); 2]);
    out.from_kept.resize(batches, false);
    let samples = out.samples;
    let pairs = view
        .models
        .first()
        .map(|m| lane_pair_weights(m))
        .unwrap_or_default();
    let one = |(b, (((out, (q, v)), roots), model)): (
        usize,
        (((BatchOut<'_>, _), _), &Arc<LaneModel>),
    )| {
        let ((points, motion), from_kept) = out;
        let kept = view.kept.and_then(|k| k.batch(b, head, samples));
        *from_kept = kept.is_some();
        gather_batch(model, roots, head, (q, v), (kept, &pairs), (points, motion));
    };
    if parallel {
        let state = view.q.par_chunks(n).zip(view.v.par_chunks(n));
        out.points
            .par_chunks_mut(lanes)
            .zip(out.motion.par_chunks_mut(samples))
            .zip(out.from_kept.par_iter_mut())
            .zip(state)
            .zip(view.roots.par_chunks(LANES))
            .zip(view.models.par_iter())
            .enumerate()
            .for_each(one);
    } else {
        let state = view.q.chunks(n).zip(view.v.chunks(n));
        out.points
            .chunks_mut(lanes)
            .zip(out.motion.chunks_mut(samples))
            .zip(out.from_kept.iter_mut())
            .zip(state)
            .zip(view.roots.chunks(LANES))
            .zip(view.models.iter())
            .enumerate()
            .for_each(one);
    }
}

/// One quadrature sample of a batch, lane by lane: its position relative
/// to the root and its world velocity.
pub type SampleLanes = [V3<Lanes>; 2];

/// A batch's lanes in groups of four ([`PointLanes`]): two per sample.
pub(super) const HALVES: usize = LANES / 4;

/// One batch's points (state `q`, `v`; its ≤ [`LANES`] `roots`; the head
/// at `head`), one per pair of quadrature nodes, in head coordinates,
/// written to `out` (point p, lanes 4h..4h + 4 at p·2 + h; padding lanes
/// get zero mass), with `pairs` the pairs' weights of `model`'s
/// quadrature ([`lane_pair_weights`], the same for every batch). The
/// samples' f32 lanes of position relative to the root and world velocity
/// are `kept` if given (the guard's measure found them at this state),
/// else swept root to tip here and written to `motion` (sample i at i).
pub fn gather_batch(
    model: &LaneModel,
    roots: &[RootPose],
    head: &RigidMotion,
    (q, v): (&[V3<Lanes>], &[V3<Lanes>]),
    (kept, pairs): (Option<&[SampleLanes]>, &[PairWeights]),
    (out, motion): (&mut [PointLanes], &mut [SampleLanes]),
) {
    let motions = carried(head, roots);
    let place = Placement::new(model, roots, &motions, head);
    let samples = match kept {
        Some(kept) => kept,
        None => {
            let root = RootMotion::<Lanes>::gather(&motions);
            let nodes = model.nodes.len();
            let sample = |e: usize, j: usize, r: V3<Lanes>, vel: V3<Lanes>| {
                motion[e * nodes + j] = [r, vel];
            };
            sweep_samples(model, &root, q, v, sample, |_, _| {});
            &*motion
        }
    };
    let mut out = out.chunks_exact_mut(HALVES);
    for (e, nodes) in samples.chunks_exact(model.nodes.len().max(1)).enumerate() {
        let points = nodes.chunks(NODES_PER_POINT).zip(pairs);
        for ((nodes, pair), out) in points.zip(&mut out) {
            place.write(nodes, pair, model.length_m(e), out);
        }
    }
}

/// The pairs' weights ([`pair_weights`]) of `model`'s quadrature, widened
/// to f64: the same for every batch of a system, so found once per group.
pub fn lane_pair_weights(model: &LaneModel) -> Vec<PairWeights> {
    let weights: Vec<f64> = model.weights.iter().map(|w| f64::from(*w)).collect();
    pair_weights(&weights)
}

/// Each lane's root motion for the head moving as `head` (padding lanes
/// copy the batch's last root).
pub(super) fn carried(head: &RigidMotion, roots: &[RootPose]) -> [RigidMotion; LANES] {
    std::array::from_fn(|i| head.carry(&roots[i.min(roots.len() - 1)]))
}

/// What turns a batch's samples (f32 lanes: position relative to the
/// root, world velocity) into its points in head coordinates, four lanes
/// at a time in f64x4, each lane's arithmetic that of a DVec3 as the
/// reference's [`crate::volume::pair_points::pair_points`] does: the
/// pair's mean x̄ = share_a x_a + share_b x_b ([`PairWeights`]), then
/// `root + x̄ − head` and glam's `body_from_world * d`,
/// ((X d_x) + (Y d_y)) + (Z d_z) per component.
struct Placement {
    columns: [[f64x4; 3]; 3],
    head_at: [f64x4; 3],
    root_at: [[f64x4; 3]; HALVES],
    rho_s: Lanes,
    /// Padding lanes (past the batch's strands) weigh nothing: a mask of
    /// the real lanes.
    real: [f64x4; HALVES],
}

impl Placement {
    fn new(
        model: &LaneModel,
        roots: &[RootPose],
        motions: &[RigidMotion; LANES],
        head: &RigidMotion,
    ) -> Self {
        let turn = head.world_from_body.transpose();
        let columns =
            [turn.x_axis, turn.y_axis, turn.z_axis].map(|c| c.to_array().map(f64x4::splat));
        Self {
            columns,
            head_at: head.position_m.to_array().map(f64x4::splat),
            root_at: std::array::from_fn(|h| {
                std::array::from_fn(|a| {
                    f64x4::new(std::array::from_fn(|k| motions[4 * h + k].position_m[a]))
                })
            }),
            rho_s: model.mass_per_length(),
            real: std::array::from_fn(|h| {
                let lane = f64x4::new(std::array::from_fn(|k| (4 * h + k) as f64));
                lane.simd_lt(f64x4::splat(roots.len() as f64))
            }),
        }
    }

    /// The point of a pair of quadrature `nodes` (position relative to the
    /// root, velocity; or one node) weighing `pair` on an element
    /// `length_m` long, into its [`HALVES`] groups of four lanes.
    #[inline(always)]
    fn write(
        &self,
        nodes: &[[V3<Lanes>; 2]],
        pair: &PairWeights,
        length_m: Lanes,
        out: &mut [PointLanes],
    ) {
        for (h, (root_h, out)) in self.root_at.iter().zip(out).enumerate() {
            let (mean_r, mean_v) = pair_mean(nodes, &pair.share, h);
            let d: [f64x4; 3] = std::array::from_fn(|a| root_h[a] + mean_r[a] - self.head_at[a]);
            let columns = &self.columns;
            *out = PointLanes {
                position_m: std::array::from_fn(|c| {
                    columns[0][c] * d[0] + columns[1][c] * d[1] + columns[2][c] * d[2]
                }),
                velocity_m_per_s: mean_v,
                mass_kg: (widen(self.rho_s, h) * widen(length_m, h) * f64x4::splat(pair.sum))
                    & self.real[h],
            };
        }
    }
}

/// Lanes `4h..4h + 4` of the mean position and velocity of a pair of
/// `nodes` (or one node) with their `share`s of the pair's weight
/// ([`PairWeights`]), in f64, in node order.
#[inline(always)]
fn pair_mean(
    nodes: &[[V3<Lanes>; 2]],
    share: &[f64; NODES_PER_POINT],
    h: usize,
) -> ([f64x4; 3], [f64x4; 3]) {
    let mut terms = nodes.iter().zip(share).map(|([r, v], w)| {
        let w = f64x4::splat(*w);
        let axes = |x: &V3<Lanes>| [x.x, x.y, x.z].map(|a| w * widen(a, h));
        (axes(r), axes(v))
    });
    let first = terms.next().unwrap_or(([f64x4::ZERO; 3], [f64x4::ZERO; 3]));
    terms.fold(first, |(r, v), (dr, dv)| {
        (
            std::array::from_fn(|a| r[a] + dr[a]),
            std::array::from_fn(|a| v[a] + dv[a]),
        )
    })
}

/// Lanes `4h..4h + 4` of `x` in f64 (exact).
#[inline(always)]
fn widen(x: Lanes, h: usize) -> f64x4 {
    let a = x.to_array();
    f64x4::new(std::array::from_fn(|k| f64::from(a[4 * h + k])))
}

/// The rest density of the groups' rest pose (each lane's rest strains,
/// at rest, head at the origin), gathered as the frames are; `None`
/// without strands.
pub fn rest_density(
    groups: &[GroupView<'_>],
    settings: &InteractionSettings,
) -> Option<RestDensity> {
    let head = RigidMotion::default();
    let mut points = Vec::new();
    let mut longest_m: f64 = 0.0;
    for view in groups {
        let rest = view.rest_q.chunks(view.n.max(1));
        for ((model, roots), q) in view.models.iter().zip(view.roots.chunks(LANES)).zip(rest) {
            let v = vec![V3::zero(); q.len()];
            let samples = q.len() * model.nodes.len();
            let count = q.len() * points_per_element(model.nodes.len());
            let mut batch = vec![PointLanes::default(); count * HALVES];
            let mut motion = vec![[V3::zero(); 2]; samples];
            let pairs = lane_pair_weights(model);
            let kept = (None, pairs.as_slice());
            gather_batch(
                model,
                roots,
                &head,
                (q, &v),
                kept,
                (&mut batch, &mut motion),
            );
            let lanes = batch.iter().flat_map(|p| (0..4).map(|k| p.lane(k)));
            points.extend(lanes.filter(|p| p.mass_kg > 0.0));
            let length_m = (0..view.n).fold(Lanes::splat(0.0), |sum, e| sum + model.length_m(e));
            for l in 0..roots.len() {
                longest_m = longest_m.max(f64::from(length_m.lane(l)));
            }
        }
    }
    RestDensity::new(&points, settings.cell_m, 0.5 * longest_m)
}

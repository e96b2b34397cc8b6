//! Reading the field back into a batch's pull ([`crate::batch::volume`]), and
//! the pull's work for the guard's reused start measure.
//!
//! Each point ([`crate::volume::pair_points`]) of each lane reads the field
//! (grid velocity u, pressure push a: [`crate::volume::VolumeField::read_in`],
//! the reference's [`crate::volume::VolumeField::read`] in the cell the splat
//! found for the point, [`crate::volume::VolumeField::cells`]) and keeps k = ρS
//! (μ u_rel + a) in f32, u_rel = u − c the grid velocity relative to the head's
//! rigid motion at the point ([`crate::volume::friction`]). While it is at it,
//! it sums, per lane, the old pull's work and the new one's at the state just
//! gathered ([`crate::volume::balance::PullWork`]): the guard's start measure
//! is the last frame's end measure, which counted the old pull, and exchanging
//! the two is what lets it be reused instead of measured again (a sweep over
//! every batch). The work is summed in f32 lanes exactly as the
//! guard's measure sums it ([`super::pull::add_pull_work`]), at the
//! positions and velocities the gather's sweep found (the same sweep as
//! the measure's, on the same state).

use std::cell::RefCell;

use glam::DVec3;
use wide::f64x4;

use super::pull::{RootVelocity, SamplePull, add_pull_work};
use crate::batch::lane_model::{Constants, LaneModel};
use crate::batch::lanes::{LANES, Lanes, Real};
use crate::batch::vec::V3;
use crate::batch::volume::HALVES;
use crate::motion::RigidMotion;
use crate::volume::balance::PullWork;
use crate::volume::cell::CellLanes;
use crate::volume::splat_lanes::PointLanes;
use crate::volume::{InteractionSettings, VolumeField};

/// What every batch of a group reads with.
#[derive(Clone, Copy, Debug)]
pub struct ReadInputs<'a> {
    /// This frame's field.
    pub field: &'a VolumeField,
    /// The model's settings.
    pub settings: &'a InteractionSettings,
    /// The head at the frame's start.
    pub head: &'a RigidMotion,
}

/// One batch's constants and its pull's μρS, old and new, lane by lane.
#[derive(Clone, Copy, Debug)]
pub struct BatchRates<'a> {
    /// The batch's constants.
    pub model: &'a LaneModel,
    /// The old pull's μρS, or `None` when there was no old pull.
    pub old: Option<Lanes>,
    /// The new pull's μρS.
    pub new: Lanes,
}

/// A lane's old and new pull work at the frame's start.
pub type Exchange = (PullWork, PullWork);

/// Reads batch `points` (point p, lanes 4h..4h + 4 at 2p + h; in
/// `cells`, the field's [`VolumeField::cell_lanes`] of these points) into
/// `known` (per point, its old k on entry, the new k on return)
/// and sums each lane's old and
/// new pull work into `exchange`, at the samples' positions relative to
/// their roots and velocities `motion` (f32 lanes, from the gather: the
/// numbers the guard's measure sweeps), the roots' rigid velocity `root`.
pub fn read_batch(
    inputs: &ReadInputs<'_>,
    rates: &BatchRates<'_>,
    (points, cells): (&[PointLanes], &[CellLanes]),
    (motion, root): (&[[V3<Lanes>; 2]], &RootVelocity),
    known: &mut [V3<Lanes>],
    exchange: &mut [Exchange; LANES],
) {
    // The new k go to the thread's buffer first: the old k are still
    // needed for the old work, and one pass then sums both.
    let mut fresh = FRESH.with(|kept| std::mem::take(&mut *kept.borrow_mut()));
    fresh.clear();
    fresh.resize(known.len(), V3::zero());
    read_into(inputs, rates.model, (points, cells), &mut fresh);
    *exchange = works(inputs.settings, rates, motion, root, (known, &fresh));
    known.copy_from_slice(&fresh);
    FRESH.with(|kept| *kept.borrow_mut() = fresh);
}

thread_local! {
    /// The thread's buffer of new k, kept: a batch's read allocates
    /// nothing.
    static FRESH: RefCell<Vec<V3<Lanes>>> = const { RefCell::new(Vec::new()) };
}

/// Each lane's old pull's work (`old` k with the rate `rates.old`, zero
/// without an old pull) and new pull's (`new` k, `rates.new`) at the
/// samples `motion`: one pass, each sample's velocity relative to its
/// root's rigid motion found once for both, each sum in the order the
/// guard's measure takes it ([`super::pull::add_pull_work`]).
fn works(
    settings: &InteractionSettings,
    rates: &BatchRates<'_>,
    motion: &[[V3<Lanes>; 2]],
    root: &RootVelocity,
    (old, new): (&[V3<Lanes>], &[V3<Lanes>]),
) -> [Exchange; LANES] {
    let model = rates.model;
    let nodes = model.nodes.len();
    let friction_per_s = settings.friction_per_s as f32;
    let old_pull = rates.old.map(|rate| SamplePull {
        friction_per_s,
        rate,
        known: old,
        nodes,
    });
    let new_pull = SamplePull {
        friction_per_s,
        rate: rates.new,
        known: new,
        nodes,
    };
    let zero = || (V3::zero(), V3::zero(), Lanes::splat(0.0));
    let (mut old_sums, mut new_sums) = (zero(), zero());
    for (i, [r, v]) in motion.iter().enumerate() {
        let (e, j) = (i / nodes, i % nodes);
        let w_len = Lanes::splat(model.weights[j]) * model.length_m(e);
        let relative = *v - root.at(*r);
        if let Some(old_pull) = &old_pull {
            let (force, torque, power) = &mut old_sums;
            add_pull_work(
                old_pull,
                e,
                j,
                *r,
                (*v, relative),
                w_len,
                (force, torque, power),
            );
        }
        let (force, torque, power) = &mut new_sums;
        add_pull_work(
            &new_pull,
            e,
            j,
            *r,
            (*v, relative),
            w_len,
            (force, torque, power),
        );
    }
    let x = |t: Lanes, l: usize| f64::from(t.lane(l));
    let x3 = |t: V3<Lanes>, l: usize| DVec3::new(x(t.x, l), x(t.y, l), x(t.z, l));
    let work = |(force, torque, power): &(V3<Lanes>, V3<Lanes>, Lanes), l: usize| PullWork {
        force_n: x3(*force, l),
        torque_n_m: x3(*torque, l),
        power_w: x(*power, l),
    };
    std::array::from_fn(|l| {
        let old = if old_pull.is_some() {
            work(&old_sums, l)
        } else {
            PullWork::default()
        };
        (old, work(&new_sums, l))
    })
}

/// Reads the batch's `points` (in `cells`) into their new k, `out`.
fn read_into(
    inputs: &ReadInputs<'_>,
    model: &LaneModel,
    (points, cells): (&[PointLanes], &[CellLanes]),
    out: &mut [V3<Lanes>],
) {
    let ReadInputs {
        field,
        settings,
        head,
    } = *inputs;
    let mu = f64x4::splat(settings.friction_per_s);
    let rho_s = model.mass_per_length().to_array().map(f64::from);
    // Point by point, the eight lanes in turn: the eight strands of a
    // batch lie side by side, so the nodes one point reads are mostly
    // those the last read, still in cache. Each point's reading is its
    // own: the order changes no number.
    // Most points feel no push, +0 on every axis (bit for bit, not −0:
    // the turn of −0 may differ in the sign of a zero); its turn to world
    // axes is the same for all of them.
    let no_push = head.world_from_body * DVec3::ZERO;
    let no_push = f64x4::new([no_push.x, no_push.y, no_push.z, 0.0]);
    let is_no_push = |a: DVec3| a.to_array().iter().all(|x| x.to_bits() == 0);
    let groups = points.chunks_exact(HALVES).zip(cells.chunks_exact(HALVES));
    for (c, (points, cells)) in out.iter_mut().zip(groups) {
        let mut value = [[0.0_f32; 3]; LANES];
        for (h, (point, cells)) in points.iter().zip(cells).enumerate() {
            let read = |k: usize, relative: f64x4, push: Option<DVec3>| {
                let l = 4 * h + k;
                let push = match push {
                    Some(a) if !is_no_push(a) => {
                        let a = head.world_from_body * a;
                        f64x4::new([a.x, a.y, a.z, 0.0])
                    }
                    _ => no_push,
                };
                // ρS (μ u_rel + a), axis by axis as in DVec3 arithmetic.
                let [x, y, z, _] = (f64x4::splat(rho_s[l]) * (mu * relative + push)).to_array();
                value[l] = [x as f32, y as f32, z as f32];
            };
            field.read_lanes(settings, cells, point, read);
        }
        *c = V3::new(
            Lanes::from_array(value.map(|v| v[0])),
            Lanes::from_array(value.map(|v| v[1])),
            Lanes::from_array(value.map(|v| v[2])),
        );
    }
}

//! Failing safe on the fast path: the guard's measure and check
//! ([`crate::guard`]), lane by lane.
//!
//! # How it works
//!
//! After each frame, every strand (every lane of every batch) is measured
//! by the measure both engines share ([`super::measure`]), in f32 lanes:
//! the hair–hair model's pull is the extra force it counts
//! ([`crate::batch::volume::pull`]), and the head's contact is tested with
//! the step's own test ([`LaneContact::touching`]) on the samples the
//! sweep kept. [`check_lanes`] judges each lane's frame from the measures
//! at its start and end with [`Guard::check_with_round_off`], allowing for
//! f32 round-off ([`F32_ENERGY_ROUND_OFF`]). The start of a frame is the
//! end of the previous one, so a frame costs one sweep more than its
//! steps.
//!
//! A failing lane is recovered by the guard's one policy, batched
//! ([`super::retry`]): re-stepped with Exact and more substeps, else reset
//! to its start-of-frame shape at rest, else pinned in its rest pose
//! ([`set_at_rest`]), each intervention reported as a
//! [`crate::guard::GuardEvent`] ([`super::BatchSystem::last_guard_events`]).
//!
//! A strand that passes is not touched, so a healthy run is bit-identical
//! with and without the guard.

use std::cell::RefCell;

use super::forward::NoContact;
use super::lane_model::Constants;
use super::lanes::{LANES, Lanes, Real};
use super::layout::{RootMotion, StepEnv};
use super::measure::{LaneMeasures, MeasureInputs, MeasureScratch, Touching, measure_state};
use super::vec::{V3, set_lane};
use crate::batch::contact::LaneContact;
use crate::batch::contact::near_cells::SkinTest;
use crate::batch::volume::pull::{RootVelocity, SamplePull, WithPull};
use crate::frame_balance::{KineticEnergy, SteppedFrame, StrandMeasure};
use crate::guard::{Guard, GuardCause};
use crate::motion::RigidMotion;

/// Per lane of a batch (`v`: its N rate triples), the speed bound
/// Σ_Q ℓ_Q |q̇_Q| (L − s_Q), m/s.
pub fn speed_bound_m_per_s(model: &impl Constants<Lanes>, v: &[V3<Lanes>]) -> Lanes {
    let n = model.element_count();
    let mut beyond_m = (0..n).fold(Lanes::splat(0.0), |sum, e| sum + model.length_m(e));
    let mut bound = Lanes::splat(0.0);
    for (e, rate) in v.iter().enumerate().take(n) {
        let l = model.length_m(e);
        bound += rate.dot(*rate).sqrt() * (l * beyond_m);
        beyond_m -= l;
    }
    bound
}

/// Per lane, whether every value of `values` is finite.
fn finite_lanes(values: &[V3<Lanes>]) -> [bool; LANES] {
    let zero = Lanes::splat(0.0);
    let mut nan_if_not = zero;
    for x in values {
        nan_if_not += x.x * zero + x.y * zero + x.z * zero;
    }
    std::array::from_fn(|i| nan_if_not.lane(i) == 0.0)
}

/// Per lane of a batch, whether every strain and rate is finite.
pub(super) fn finite_state(q: &[V3<Lanes>], v: &[V3<Lanes>]) -> [bool; LANES] {
    let (finite_q, finite_v) = (finite_lanes(q), finite_lanes(v));
    std::array::from_fn(|lane| finite_q[lane] && finite_v[lane])
}

/// Relative round-off allowed on an f32 lane's energy balance (of the
/// sizes of the energies summed): f32 sums of a few hundred terms.
pub const F32_ENERGY_ROUND_OFF: f64 = 1e-4;

thread_local! {
    /// Each thread's buffers for [`measure_lanes`].
    static KEPT: RefCell<MeasureScratch<Lanes>> = RefCell::new(MeasureScratch::default());
}

/// Per lane, the guard's measure ([`super::measure::measure_state`]) of a
/// batch in state (`q`, `v`), its roots moving as `root` (lanes) and
/// `motions` (each lane's), under `env`'s gravity and air, with the head's
/// `contact` if any and the hair–hair model's `pull` if on
/// ([`crate::batch::volume::pull`]). With `samples` (N × nodes entries),
/// each quadrature sample's position relative to its root and world
/// velocity is kept there, for the hair–hair model's next gather.
#[expect(
    clippy::too_many_arguments,
    reason = "the batch's state, every force the balance counts, and where its samples go"
)]
pub fn measure_lanes<'a>(
    model: &impl Constants<Lanes>,
    env: &StepEnv,
    root: &RootMotion<Lanes>,
    motions: &'a [RigidMotion; LANES],
    q: &[V3<Lanes>],
    v: &[V3<Lanes>],
    contact: Option<&SkinTest<'_>>,
    pull: Option<&SamplePull<'_>>,
    samples: Option<&mut [[V3<Lanes>; 2]]>,
    judged_by: KineticEnergy,
) -> LaneMeasures<'a, Lanes> {
    let rho_s = model.mass_per_length();
    let touching = contact.map(|test| {
        let contact = LaneContact::new(*test, rho_s, motions.map(|m| m.position_m));
        move |points: &[(V3<Lanes>, V3<Lanes>)]| lanes_in_contact(&contact, points)
    });
    let touching = touching.as_ref().map(|t| t as Touching<'_, Lanes>);
    let mut scratch = KEPT.with(|kept| std::mem::take(&mut *kept.borrow_mut()));
    let inputs = MeasureInputs {
        env,
        root,
        motions,
        touching,
        judged_by,
    };
    let measured = match pull {
        Some(pull) => {
            let forces = WithPull {
                inner: NoContact,
                pull: *pull,
                root: RootVelocity::of(root),
            };
            measure_state(model, q, v, &inputs, &forces, samples, &mut scratch)
        }
        None => measure_state(model, q, v, &inputs, &NoContact, samples, &mut scratch),
    };
    KEPT.with(|kept| *kept.borrow_mut() = scratch);
    measured
}

/// Per lane (bit `lane` of the mask), whether the head's `contact` acts
/// at any of a batch's samples (relative to each lane's root) moving as
/// `points` say: the step's own test ([`LaneContact::touching`]).
///
/// Only "is there contact" is found, not the force: a frame that starts or
/// ends in contact is judged by finiteness and true speed alone
/// ([`Guard::check_with_round_off`]), so the contact's work never enters a
/// verdict. A lane stops being tested at its first point in contact, and
/// the sweep at the point where every lane is.
fn lanes_in_contact(contact: &LaneContact<'_>, points: &[(V3<Lanes>, V3<Lanes>)]) -> u32 {
    const ALL: u32 = (1 << LANES) - 1;
    let mut found = 0;
    for (point_m, velocity_m_per_s) in points {
        found |= contact.touching(*point_m, *velocity_m_per_s, ALL & !found, |_, _| {});
        if found == ALL {
            break;
        }
    }
    found
}

/// Checks one batch whose lanes started the frame measured as `measures`
/// and ended it as `end` says (`None`: a lane not judged, a padding lane
/// of a batch measured elsewhere), its state finite where `finite` says
/// ([`finite_state`]), by the energy of the dynamics `judged_by`, and
/// leaves the end's measures in `measures`; a failing lane's start measure
/// goes to `retry_from`, which its retry is judged against
/// ([`super::retry`]). Returns, per lane, what failed (`None`: the lane
/// passed), as the f64 guard names it.
pub fn check_lanes(
    guard: &Guard,
    finite: [bool; LANES],
    measures: &mut [StrandMeasure; LANES],
    retry_from: &mut [StrandMeasure; LANES],
    end: impl Fn(usize) -> Option<StrandMeasure>,
    frame: SteppedFrame,
    judged_by: KineticEnergy,
) -> [Option<GuardCause>; LANES] {
    let mut failed = [None; LANES];
    for (lane, (start, failed)) in measures.iter_mut().zip(&mut failed).enumerate() {
        let Some(end) = end(lane) else { continue };
        *failed = if finite[lane] {
            let (from, to) = (start.judged_by(judged_by), end.judged_by(judged_by));
            guard.check_with_round_off(&[], &[], &from, &to, frame, F32_ENERGY_ROUND_OFF)
        } else {
            Some(GuardCause::NotFinite)
        };
        if failed.is_some() {
            retry_from[lane] = *start;
        }
        *start = end;
    }
    failed
}

/// Puts lane `lane` of a batch (`q`, `v`: N triples each) in `shape` (N
/// triples), at rest: where the guard resets and holds a strand (its rest
/// pose: an imported sag-free strand's is its groomed shape, which gravity
/// holds, not its natural strains, from which it would swing back into
/// its shape) and where a new lane starts.
pub fn set_at_rest(
    q: &mut [V3<Lanes>],
    v: &mut [V3<Lanes>],
    lane: usize,
    shape: impl IntoIterator<Item = [f32; 3]>,
) {
    set_lane(q, lane, shape);
    set_lane(v, lane, std::iter::repeat([0.0; 3]));
}

//! Failing safe on the fast path: the measures of [`crate::guard`], lane by
//! lane, and a reset.
//!
//! # How it works
//!
//! After each frame, every strand (every lane of every batch) is measured
//! as the f64 [`crate::HairSystem`] measures it ([`crate::frame_balance`]):
//! [`measure_lanes`] sweeps the batch root to tip in f32 lanes, summing
//! over the quadrature samples each lane's kinetic, elastic and
//! gravitational energy, momentum, angular momentum about the root, the
//! external forces with their torque and power (gravity, drag and the
//! hair–hair model's pull, [`crate::batch::volume::pull`]), whether the head's contact
//! acts at any quadrature sample, as the step applies it (a frame in
//! contact is judged by finiteness and speed alone, so the contact's force
//! itself is not summed), and the fastest point relative to the root's
//! rigid motion. Each lane's sums go
//! into a [`StrandMeasure`], and [`Guard::check`] judges the frame from
//! the measures at its start and end: finite, true speed under the limit,
//! no energy that no force put in (with an allowance for f32 round-off,
//! [`F32_ENERGY_ROUND_OFF`]). The start of a frame is the end of the
//! previous one, so a frame costs one sweep more than its steps.
//!
//! **Recovery is a reset**: a failing strand goes back to its rest pose at
//! rest (q = its rest strains, qⁿ unless told otherwise, as an imported
//! sag-free strand is told its groomed shape; q̇ = 0), and reported with the check that failed and
//! by how much ([`super::BatchSystem::last_guard_events`], the f64
//! guard's [`crate::guard::GuardEvent`]). This path does not retry the
//! frame with Exact and more substeps as the f64 guard does: it is the
//! interactive path, where a frame's cost must stay predictable (a retry
//! of a whole batch at 32 substeps would stall the frame it happens in), and
//! lanes share their batch's arithmetic, so one strand cannot be re-stepped
//! on its own without stepping its seven neighbours again. The f64
//! `HairSystem` is the careful path; use it where a recovered trajectory
//! matters more than the frame rate.
//!
//! A strand that passes is not touched, so a healthy run is bit-identical
//! with and without the guard.

use std::cell::RefCell;

use glam::DVec3;

use super::block_kinetic::{BlockKinetic, BlockKineticBuffer};
use super::forward::{FrameState, sweep_samples};
use super::lane_model::Constants;
use super::lanes::{LANES, Lanes, Real};
use super::layout::{RootMotion, StepEnv};
use super::vec::{V3, set_lane};
use crate::batch::contact::LaneContact;
use crate::batch::contact::near_cells::SkinTest;
use crate::batch::volume::pull::{RootVelocity, SamplePull, add_pull_work};
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
pub(super) fn finite_lanes(values: &[V3<Lanes>]) -> [bool; LANES] {
    let zero = Lanes::splat(0.0);
    let mut nan_if_not = zero;
    for x in values {
        nan_if_not += x.x * zero + x.y * zero + x.z * zero;
    }
    std::array::from_fn(|i| nan_if_not.lane(i) == 0.0)
}

/// Relative round-off allowed on an f32 lane's energy balance (of the
/// sizes of the energies summed): f32 sums of a few hundred terms.
pub const F32_ENERGY_ROUND_OFF: f64 = 1e-4;

thread_local! {
    /// Each thread's buffer of quadrature samples for [`measure_lanes`].
    static KEPT_POINTS: RefCell<Vec<(V3<Lanes>, V3<Lanes>)>> = const { RefCell::new(Vec::new()) };
    /// Each thread's buffer for Block-diagonal's kinetic energy.
    static KEPT_BLOCK: RefCell<BlockKineticBuffer<Lanes>> = RefCell::new(BlockKineticBuffer::default());
}

/// Per lane, the guard's measure of a batch in state (`q`, `v`), its roots
/// moving as `root` (lanes) with root points at `root_positions_m`
/// (world), under `env`'s gravity and air, with the head's `contact` if any
/// and the hair–hair model's `pull` if on ([`crate::batch::volume::pull`]). With
/// `samples` (N × nodes entries), each quadrature sample's position
/// relative to its root and world velocity is kept there as the sweep
/// finds it: the hair–hair model's gather of the next frame starts from
/// the state this measure ends, and takes them instead of sweeping again
/// ([`super::volume`]).
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
    mut samples: Option<&mut [[V3<Lanes>; 2]]>,
    judged_by: KineticEnergy,
) -> LaneMeasures<'a> {
    let rho_s = model.mass_per_length();
    let nu = model.air_drag();
    let g = V3::splat_f64(env.gravity_m_per_s2);
    let air = V3::splat_f64(env.air_velocity_m_per_s);
    let zero = Lanes::splat(0.0);
    let (mut kinetic, mut elastic, mut power, mut fastest_squared) = (zero, zero, zero, zero);
    let mut strain_kinetic = zero;
    let (mut momentum, mut angular, mut force, mut torque, mut first_moment) =
        (V3::zero(), V3::zero(), V3::zero(), V3::zero(), V3::zero());
    let (mut mass, mut second_moment) = (zero, zero);
    let nodes = model.node_count();
    // Quadrature samples (relative to the root) and their velocities, for
    // the contact's test after the sweep: kept out of the SIMD loop, whose
    // state would otherwise be spilled for the per-lane lookups.
    // The thread's buffer, kept: a batch's measure allocates nothing.
    let mut points = KEPT_POINTS.with(|kept| std::mem::take(&mut *kept.borrow_mut()));
    points.clear();
    let carried = RootVelocity::of(root);
    // Block-diagonal's own kinetic energy, only where a frame is judged by it.
    let block = (judged_by == KineticEnergy::BlockDiagonal).then(|| {
        let buffer = KEPT_BLOCK.with(|kept| std::mem::take(&mut *kept.borrow_mut()));
        RefCell::new(BlockKinetic::new(FrameState::at_root(root), buffer))
    });
    let sample = |e: usize, j: usize, r: V3<Lanes>, vel: V3<Lanes>| {
        if let Some(kept) = samples.as_deref_mut() {
            kept[e * nodes + j] = [r, vel];
        }
        let w_len = model.weight(j) * model.length_m(e);
        let w_mass = w_len * rho_s;
        if let Some(block) = &block {
            block.borrow_mut().sample(w_mass, r, vel);
        }
        kinetic = (vel.dot(vel) * w_mass).mul_add(Lanes::splat(0.5), kinetic);
        momentum = vel.scale_add(w_mass, momentum);
        angular = r.cross(vel).scale_add(w_mass, angular);
        first_moment = r.scale_add(w_mass, first_moment);
        mass += w_mass;
        second_moment = r.dot(r).mul_add(w_mass, second_moment);
        if contact.is_some() {
            points.push((r, vel));
        }
        let rel = vel - carried.at(r);
        strain_kinetic = (rel.dot(rel) * w_mass).mul_add(Lanes::splat(0.5), strain_kinetic);
        if let Some(pull) = pull {
            let sums = (&mut force, &mut torque, &mut power);
            add_pull_work(pull, e, j, r, (vel, rel), w_len, sums);
        }
        // Squares here, one root at the end: the root is monotone and
        // correctly rounded, so the same bits (NaN stays NaN).
        fastest_squared = fastest_squared.max(rel.dot(rel));
    };
    let element_end = |e: usize, s: &FrameState<Lanes>| {
        let d = q[e] - model.natural(e);
        let k = model.stiffness(e);
        elastic += (d.x * d.x * k.x + d.y * d.y * k.y + d.z * d.z * k.z) * Lanes::splat(0.5);
        if let Some(block) = &block {
            block.borrow_mut().element_end(s);
        }
    };
    sweep_samples(model, root, q, v, sample, element_end);
    let block_kinetic = block.map_or(zero, |block| {
        let (t, buffer) = block.into_inner().finish();
        KEPT_BLOCK.with(|kept| *kept.borrow_mut() = buffer);
        t
    });
    // Gravity and drag, summed from the sums above: the drag per unit
    // length is ν (ṙ − v_air) = (ν/ρS) ρS (ṙ − v_air), so its force,
    // torque and power over the samples are (ν/ρS) times those of the
    // momentum sums (exact; in f32 the same up to round-off, which the
    // balance allows, [`F32_ENERGY_ROUND_OFF`]).
    let drag_per_mass = nu / rho_s;
    force += g.scale(mass) - (momentum - air.scale(mass)).scale(drag_per_mass);
    torque += first_moment.cross(g) - (angular - first_moment.cross(air)).scale(drag_per_mass);
    power -= (kinetic + kinetic - air.dot(momentum)) * drag_per_mass;
    let in_contact = match contact {
        Some(contact) => lanes_in_contact(model, contact, motions, &points),
        None => 0,
    };
    KEPT_POINTS.with(|kept| *kept.borrow_mut() = points);
    LaneMeasures {
        kinetic,
        strain_kinetic,
        block_kinetic,
        elastic,
        power,
        mass,
        second_moment,
        momentum,
        angular,
        force,
        torque,
        first_moment,
        in_contact,
        motions,
        fastest: fastest_squared.sqrt(),
        // The gravity the f32 step felt, rounded as it was.
        gravity_m_per_s2: DVec3::from_array(
            env.gravity_m_per_s2
                .map(|g| Lanes::splat_f64(g).lane_f64(0)),
        ),
    }
}

/// A batch's measure as [`measure_lanes`] sums it, in lanes; each strand's
/// [`StrandMeasure`] is read from it lane by lane ([`Self::strand`]), where
/// it is needed, instead of all eight built and copied at once.
#[derive(Clone, Copy, Debug)]
pub struct LaneMeasures<'a> {
    kinetic: Lanes,
    strain_kinetic: Lanes,
    block_kinetic: Lanes,
    elastic: Lanes,
    power: Lanes,
    fastest: Lanes,
    mass: Lanes,
    second_moment: Lanes,
    momentum: V3<Lanes>,
    angular: V3<Lanes>,
    force: V3<Lanes>,
    torque: V3<Lanes>,
    first_moment: V3<Lanes>,
    /// Bit `lane`: whether the head's contact acts on that lane.
    in_contact: u32,
    motions: &'a [RigidMotion; LANES],
    gravity_m_per_s2: DVec3,
}

impl LaneMeasures<'_> {
    /// Lane `lane`'s measure, in f64.
    pub fn strand(&self, lane: usize) -> StrandMeasure {
        let x = |t: Lanes| f64::from(t.lane(lane));
        let x3 = |t: V3<Lanes>| DVec3::new(x(t.x), x(t.y), x(t.z));
        let motion = &self.motions[lane];
        let gravity = self.gravity_m_per_s2;
        let relative_gravity_j = -gravity.dot(x3(self.first_moment));
        let gravity_j = relative_gravity_j - x(self.mass) * gravity.dot(motion.position_m);
        let (kinetic, elastic) = (x(self.kinetic), x(self.elastic));
        StrandMeasure {
            kinetic_j: kinetic,
            strain_kinetic_j: x(self.strain_kinetic),
            block_kinetic_j: x(self.block_kinetic),
            energy_j: kinetic + elastic + gravity_j,
            size_j: kinetic + elastic + relative_gravity_j.abs(),
            momentum: x3(self.momentum),
            angular_momentum: x3(self.angular),
            external_force_n: x3(self.force),
            external_torque_n_m: x3(self.torque),
            external_power_w: x(self.power),
            contact_power_w: 0.0,
            contact_j: 0.0,
            in_contact: self.in_contact & (1 << lane) != 0,
            root_velocity_m_per_s: motion.velocity_m_per_s,
            root_angular_velocity_rad_per_s: motion.angular_velocity_rad_per_s,
            root_acceleration_m_per_s2: motion.acceleration_m_per_s2,
            root_angular_acceleration_rad_per_s2: motion.angular_acceleration_rad_per_s2,
            mass_kg: x(self.mass),
            second_moment_kg_m2: x(self.second_moment),
            fastest_relative_m_per_s: x(self.fastest),
        }
    }
}

/// Per lane (bit `lane` of the mask), whether the head's contact acts at
/// any quadrature sample of a batch whose samples (relative to each lane's
/// root) and velocities are `points`: the step's own test
/// ([`LaneContact::touching`]).
///
/// Only "is there contact" is found, not the force: a frame that starts or
/// ends in contact is judged by finiteness and true speed alone
/// ([`Guard::check_with_round_off`]), so the contact's work never enters a
/// verdict. A lane stops being tested at its first point in contact, and
/// the sweep at the point where every lane is.
fn lanes_in_contact(
    model: &impl Constants<Lanes>,
    test: &SkinTest<'_>,
    motions: &[RigidMotion; LANES],
    points: &[(V3<Lanes>, V3<Lanes>)],
) -> u32 {
    const ALL: u32 = (1 << LANES) - 1;
    let contact = LaneContact::new(
        *test,
        model.mass_per_length(),
        motions.map(|m| m.position_m),
    );
    let mut found = 0;
    for (point_m, velocity_m_per_s) in points {
        found |= contact.touching(*point_m, *velocity_m_per_s, ALL & !found, |_, _| {});
        if found == ALL {
            break;
        }
    }
    found
}

/// Checks one batch (`q`, `v`: N triples each) whose lanes started the
/// frame measured as `measures` and ended it as `end`, by the energy of
/// the dynamics `judged_by`, and leaves the end's measures in `measures`;
/// a failing lane's start measure goes to `retry_from`, which its retry
/// is judged against ([`super::retry`]). Returns, per lane, what failed
/// (`None`: the lane passed), as the f64 guard names it.
#[expect(
    clippy::too_many_arguments,
    reason = "the batch, both ends' measures, the frame and its dynamics"
)]
pub fn check_lanes(
    guard: &Guard,
    q: &[V3<Lanes>],
    v: &[V3<Lanes>],
    measures: &mut [StrandMeasure; LANES],
    retry_from: &mut [StrandMeasure; LANES],
    end: &LaneMeasures<'_>,
    frame: SteppedFrame,
    judged_by: KineticEnergy,
) -> [Option<GuardCause>; LANES] {
    let finite_q = finite_lanes(q);
    let finite_v = finite_lanes(v);
    let mut failed = [None; LANES];
    for (lane, (start, failed)) in measures.iter_mut().zip(&mut failed).enumerate() {
        let end = end.strand(lane);
        *failed = if finite_q[lane] && finite_v[lane] {
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

//! The guard's measure of a state, written once for both engines: the f64
//! reference measures one strand with it (`T = f64`), the batch engine
//! eight in f32 lanes (`T = Lanes`).
//!
//! # How it works
//!
//! [`measure_state`] sweeps the strands root to tip with the step's own
//! reconstruction ([`super::forward::sweep_samples`]) and sums over the
//! quadrature samples each lane's kinetic, elastic and gravitational
//! energy, momentum, angular momentum about the root point, the external
//! forces with their torque and power (gravity, drag, and whatever the
//! step's sample hook adds: the hair–hair model's pull, a brush's force,
//! [`super::forward::SampleHook::sample_force`], the very force the step
//! applies at that state), the fastest point relative to the root's rigid
//! motion, and, where the frame is judged by it, Block-diagonal's own
//! kinetic energy ([`super::block_kinetic`]). Whether the head's contact
//! acts is asked after the sweep, of the samples kept
//! ([`MeasureInputs::touching`]): a frame in contact is judged by
//! finiteness and speed alone ([`crate::guard`]), so the contact's force
//! itself is never summed.
//!
//! Gravity and drag are summed from the momentum sums: the drag per unit
//! length is ν (ṙ − v_air) = (ν/ρS) ρS (ṙ − v_air), so its force, torque
//! and power over the samples are (ν/ρS) times those of the sums (exact;
//! in f32 the same up to round-off, which the balance allows).
//!
//! Each lane's sums become a [`StrandMeasure`] where it is needed
//! ([`LaneMeasures::strand`]), and [`crate::guard::Guard::check`] judges
//! a frame from its start and end measures ([`crate::frame_balance`]).

use std::cell::RefCell;

use glam::DVec3;

use super::block_kinetic::{BlockKinetic, BlockKineticBuffer};
use super::forward::{FrameState, SampleHook, sweep_samples};
use super::lane_model::Constants;
use super::lanes::Real;
use super::layout::{RootMotion, StepEnv};
use super::vec::V3;
use crate::frame_balance::{KineticEnergy, StrandMeasure};
use crate::motion::RigidMotion;

/// Per lane (bit `lane`), whether the head's contact acts at any of a
/// batch's samples, given as (position relative to the root point,
/// world velocity).
pub type Touching<'a, T> = &'a dyn Fn(&[(V3<T>, V3<T>)]) -> u32;

/// What the measure needs besides the strands' state (`'m`: the roots'
/// motions, which the measure's result keeps).
pub struct MeasureInputs<'a, 'm, T> {
    /// Gravity and air (its `h_secs` is not read).
    pub env: &'a StepEnv,
    /// The roots' motion, gathered into lanes.
    pub root: &'a RootMotion<T>,
    /// Each lane's root motion (as many as lanes; the reference's one).
    pub motions: &'m [RigidMotion],
    /// The head's contact test, if there is a collider.
    pub touching: Option<Touching<'a, T>>,
    /// The energy the frame is judged by: Block-diagonal's own kinetic
    /// energy is summed only where it is.
    pub judged_by: KineticEnergy,
}

/// The measure's buffers, kept between measures: it allocates nothing
/// once they have grown.
#[derive(Debug, Default)]
pub struct MeasureScratch<T> {
    points: Vec<(V3<T>, V3<T>)>,
    block: BlockKineticBuffer<T>,
}

/// Per lane, the guard's measure of strands in state (`q`, `v`) under
/// `inputs`, counting the extra force of the step's sample hook `forces`. With `samples` (N × nodes entries), each quadrature sample's
/// position relative to its root and world velocity is kept there as the
/// sweep finds it: the hair–hair model's gather of the next frame starts
/// from the state this measure ends, and takes them instead of sweeping
/// again ([`super::volume`]).
pub fn measure_state<'m, T: Real + Default, H: SampleHook<T>>(
    model: &impl Constants<T>,
    q: &[V3<T>],
    v: &[V3<T>],
    inputs: &MeasureInputs<'_, 'm, T>,
    forces: &H,
    mut samples: Option<&mut [[V3<T>; 2]]>,
    scratch: &mut MeasureScratch<T>,
) -> LaneMeasures<'m, T> {
    let rho_s = model.mass_per_length();
    let nu = model.air_drag();
    let (env, root) = (inputs.env, inputs.root);
    let g = V3::splat_f64(env.gravity_m_per_s2);
    let air = V3::splat_f64(env.air_velocity_m_per_s);
    let zero = T::splat(0.0);
    let (mut kinetic, mut elastic, mut power, mut fastest_squared) = (zero, zero, zero, zero);
    let mut strain_kinetic = zero;
    let (mut momentum, mut angular, mut force, mut torque, mut first_moment) =
        (V3::zero(), V3::zero(), V3::zero(), V3::zero(), V3::zero());
    let (mut mass, mut second_moment) = (zero, zero);
    let nodes = model.node_count();
    // Samples for the contact's test after the sweep: kept out of the SIMD
    // loop, whose state would otherwise be spilled for per-lane lookups.
    let points = &mut scratch.points;
    points.clear();
    let keep_points = inputs.touching.is_some();
    let carried = |r: V3<T>| root.velocity_m_per_s + root.angular_velocity_rad_per_s.cross(r);
    // Both closures below add to it, in the sweep's order.
    let block = (inputs.judged_by == KineticEnergy::BlockDiagonal).then(|| {
        let buffer = std::mem::take(&mut scratch.block);
        RefCell::new(BlockKinetic::new(FrameState::at_root(root), buffer))
    });
    let sample = |e: usize, j: usize, r: V3<T>, vel: V3<T>| {
        if let Some(kept) = samples.as_deref_mut() {
            kept[e * nodes + j] = [r, vel];
        }
        let w_len = model.weight(j) * model.length_m(e);
        let w_mass = w_len * rho_s;
        if let Some(block) = &block {
            block.borrow_mut().sample(w_mass, r, vel);
        }
        kinetic = (vel.dot(vel) * w_mass).mul_add(T::splat(0.5), kinetic);
        momentum = vel.scale_add(w_mass, momentum);
        angular = r.cross(vel).scale_add(w_mass, angular);
        first_moment = r.scale_add(w_mass, first_moment);
        mass += w_mass;
        second_moment = r.dot(r).mul_add(w_mass, second_moment);
        if keep_points {
            points.push((r, vel));
        }
        let rel = vel - carried(r);
        strain_kinetic = (rel.dot(rel) * w_mass).mul_add(T::splat(0.5), strain_kinetic);
        if H::SAMPLE_FORCES {
            let f = forces.sample_force(e, j, r, vel).scale(w_len);
            force += f;
            torque += r.cross(f);
            power += f.dot(vel);
        }
        // Squares here, one root at the end: the root is monotone and
        // correctly rounded, so the same bits (NaN stays NaN).
        fastest_squared = fastest_squared.max(rel.dot(rel));
    };
    let element_end = |e: usize, s: &FrameState<T>| {
        let d = q[e] - model.natural(e);
        let k = model.stiffness(e);
        elastic += (d.x * d.x * k.x + d.y * d.y * k.y + d.z * d.z * k.z) * T::splat(0.5);
        if let Some(block) = &block {
            block.borrow_mut().element_end(s);
        }
    };
    sweep_samples(model, root, q, v, sample, element_end);
    let block_kinetic = block.map_or(zero, |block| {
        let (t, buffer) = block.into_inner().finish();
        scratch.block = buffer;
        t
    });
    // Gravity and drag from the momentum sums (module docs).
    let drag_per_mass = nu / rho_s;
    force += g.scale(mass) - (momentum - air.scale(mass)).scale(drag_per_mass);
    torque += first_moment.cross(g) - (angular - first_moment.cross(air)).scale(drag_per_mass);
    power -= (kinetic + kinetic - air.dot(momentum)) * drag_per_mass;
    let in_contact = inputs
        .touching
        .map_or(0, |touching| touching(&scratch.points));
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
        motions: inputs.motions,
        fastest: fastest_squared.sqrt(),
        // The gravity the step felt, rounded as it was.
        gravity_m_per_s2: DVec3::from_array(
            env.gravity_m_per_s2.map(|g| T::splat_f64(g).lane_f64(0)),
        ),
    }
}

/// Strands' measure as [`measure_state`] sums it, in lanes; each strand's
/// [`StrandMeasure`] is read from it lane by lane ([`Self::strand`]), where
/// it is needed, instead of all built and copied at once. The GPU
/// engine's measure (`gpu::measure`) fills one strand's from the
/// device's sums.
#[derive(Clone, Copy, Debug)]
pub struct LaneMeasures<'a, T> {
    pub(crate) kinetic: T,
    pub(crate) strain_kinetic: T,
    pub(crate) block_kinetic: T,
    pub(crate) elastic: T,
    pub(crate) power: T,
    pub(crate) fastest: T,
    pub(crate) mass: T,
    pub(crate) second_moment: T,
    pub(crate) momentum: V3<T>,
    pub(crate) angular: V3<T>,
    pub(crate) force: V3<T>,
    pub(crate) torque: V3<T>,
    pub(crate) first_moment: V3<T>,
    /// Bit `lane`: whether the head's contact acts on that lane.
    pub(crate) in_contact: u32,
    pub(crate) motions: &'a [RigidMotion],
    pub(crate) gravity_m_per_s2: DVec3,
}

impl<T: Real> LaneMeasures<'_, T> {
    /// Lane `lane`'s measure, in f64.
    pub fn strand(&self, lane: usize) -> StrandMeasure {
        let x = |t: T| t.lane_f64(lane);
        let x3 = |t: V3<T>| DVec3::new(x(t.x), x(t.y), x(t.z));
        let motion = &self.motions[lane.min(self.motions.len() - 1)];
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

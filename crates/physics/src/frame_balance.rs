//! Measuring a frame: the energy a strand gained, against the work done on
//! it from outside.
//!
//! # Why
//!
//! A failing step shows as energy the physics never put in: a blow-up
//! doubles a strand's energy in a frame or two, and a solver that is not
//! passive (Block-diagonal with its truncated inertia) keeps a strand
//! moving forever with a still head. A bound on speed sees neither in
//! time: the old guard's bound Σ ℓ|q̇|(L − s) read 50 m/s on coiled strands
//! whose fastest point moved at 1 m/s, and reset healthy hair. So the guard
//! measures the state itself: each sample's true velocity and the
//! strand's energy, from the same reconstruction the step runs.
//!
//! # How
//!
//! At the end of a frame, the measure both engines share
//! ([`crate::batch::measure`]) sums over the quadrature samples: the
//! energy E = T + U_elastic + U_gravity, the momentum P and the angular
//! momentum L about the root point, the external forces (gravity, air
//! drag, the hair–hair model's pull, the external hook a brush drives)
//! with their torque and their power, the fastest point relative to the
//! root's rigid motion, and whether the head's contact acts. A frame that
//! starts or ends in contact is judged by finiteness and speed alone
//! ([`crate::guard`]): contact starts and stops within a frame, and its
//! work is not known at the frame's resolution, so it is not summed.
//!
//! The root holds the strand with a force F and a torque τ. Newton's laws
//! about the moving root point O give them from what was measured,
//! F = Ṗ − F_ext and τ = L̇ + v_O × P − τ_ext, and their work over the
//! frame is W_root = ∫ F·v_O + τ·ω dt. [`unexplained_energy_j`] takes these
//! integrals over the frame (ΔP over the frame, the root's velocities
//! averaged) and returns ΔE − W_root − W_ext, the energy no force put in.
//!
//! # The external forces' rule: the step's own
//!
//! The external forces' impulse ∫ F_ext dt and work ∫ P_ext dt are taken
//! as the step takes them, not by the trapezoid rule. The
//! velocity-implicit step moves positions by h times the *end* velocity
//! and applies each force at the step's end: drag and the hair–hair
//! model's friction implicitly at the end velocity, the model's frozen
//! push as it is. So a step of h does work h F₁·ṙ₁ and gives the impulse
//! h F₁ (for a free particle exactly: ΔT = h F₁·(ṙ₀ + ṙ₁)/2 = h F₁·ṙ₁
//! − ½m|Δṙ|², the step's own dissipation). Over a frame of n substeps,
//! with the power changing steadily from P₀ to P₁, the substeps' end
//! powers sum to dt ((n − 1) P₀ + (n + 1) P₁)/(2n)
//! ([`SteppedFrame::end_weight`]): the end alone for one substep, the
//! trapezoid rule for many. The trapezoid rule on a frame of one step
//! missed by ½ dt (P₁ − P₀), which for strong, frozen forces is more than
//! the frame's kinetic energy (measured: the small head shaken with the
//! model's friction at 200/s, 44 strands flagged in 120 frames; its
//! pressure at 10 m²/s², 7; with the step's rule, none).
//! Internal friction only removes energy, so for a correct step it is
//! negative or at the estimate's error, which is small next to the
//! frame's kinetic energy; a blow-up makes it a large positive number.
//! With a still head and no wind every work term is zero and the test is
//! simply: energy must not grow.
//!
//! Cost: one sum over the samples of a reconstruction, O(N). The start of a
//! frame is the end of the previous one, so a frame needs one more
//! reconstruction than its steps.

use glam::DVec3;

use crate::collision::ContactInputs;
use crate::settings::{Method, StepScheme};

/// What a strand's state is, measured from its reconstruction
/// ([`crate::batch::measure`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StrandMeasure {
    /// Kinetic energy T = ½ ∫ ρS |ṙ|² ds, joules (world frame).
    pub kinetic_j: f64,
    /// Its strain-strain part ½ q̇ᵀ M q̇ = ½ ∫ ρS |J q̇|² ds, joules: the
    /// motion relative to the root's rigid motion.
    pub strain_kinetic_j: f64,
    /// What Block-diagonal's truncated inertia puts in its place,
    /// ½ Σ_Q q̇_Qᵀ M_QQ q̇_Q, joules ([`KineticEnergy::BlockDiagonal`]);
    /// zero where not measured (the batch engine on Exact).
    pub block_kinetic_j: f64,
    /// T + elastic + gravitational energy, joules.
    pub energy_j: f64,
    /// T + elastic + |gravitational energy relative to the root point|,
    /// joules: the size of the terms summed, for the round-off allowance
    /// (the root point's own height cancels between frames exactly).
    pub size_j: f64,
    /// Momentum ∫ ρS ṙ ds, kg·m/s.
    pub momentum: DVec3,
    /// Angular momentum about the root point, ∫ ρS (r − O) × ṙ ds, kg·m²/s.
    pub angular_momentum: DVec3,
    /// Gravity, drag, the hair–hair model's pull and the external hook
    /// summed, N.
    pub external_force_n: DVec3,
    /// Their torque about the root point, N·m.
    pub external_torque_n_m: DVec3,
    /// Their power but gravity's, ∫ f · ṙ ds, W (gravity's is inside E).
    pub external_power_w: f64,
    /// Whether any sample touches the head (pushed by contact).
    pub in_contact: bool,
    /// The root point's velocity, m/s.
    pub root_velocity_m_per_s: DVec3,
    /// The root frame's angular velocity, rad/s.
    pub root_angular_velocity_rad_per_s: DVec3,
    /// The root point's acceleration, m/s² (what the step holds over a
    /// step, see [`root_sampling_uncertainty_j`]).
    pub root_acceleration_m_per_s2: DVec3,
    /// The root frame's angular acceleration, rad/s².
    pub root_angular_acceleration_rad_per_s2: DVec3,
    /// The strand's mass ∫ ρS ds, kg.
    pub mass_kg: f64,
    /// Its second moment about the root point ∫ ρS |r − O|² ds, kg·m².
    pub second_moment_kg_m2: f64,
    /// Fastest sample relative to the root's rigid motion
    /// |ṙ − (v_O + ω × (r − O))|, m/s: the true speed, not a bound.
    pub fastest_relative_m_per_s: f64,
}

/// The kinetic energy a step's dynamics conserves with a still head,
/// which is the one its frames are judged by.
///
/// Exact, Dense and Iterative step the true system, whose energy is
/// T + V. Block-diagonal with its own velocity terms
/// ([`crate::batch::block_terms`]) steps a different mechanical
/// system: the same potential, and the true kinetic energy with its
/// strain-strain part ½ q̇ᵀ M q̇ replaced by ½ Σ_Q q̇_Qᵀ M_QQ q̇_Q. That system
/// conserves its own energy, not the true one, so judging it by T + V
/// flagged healthy frames (every strand of the example styles at the
/// first frames of a head shake); judged by its own, a real blow-up of
/// Block-diagonal (with the whole system's velocity terms, which belong
/// to no Lagrangian of M_bd) is still caught. Its momentum and angular
/// momentum are the true system's (the truncated part does not depend on
/// the root's motion), so the root's work is measured alike.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum KineticEnergy {
    /// The true T = ½ ∫ ρS |ṙ|² ds.
    #[default]
    True,
    /// Block-diagonal's own, T − ½ q̇ᵀ M q̇ + ½ Σ_Q q̇_Qᵀ M_QQ q̇_Q.
    BlockDiagonal,
}

impl KineticEnergy {
    /// The energy a step of `method` under `scheme` conserves: Block's own
    /// where it steps with its own velocity terms (Block-diagonal,
    /// velocity-implicit scheme), the true one otherwise.
    pub fn of(method: Method, scheme: StepScheme) -> Self {
        let own_terms =
            matches!(scheme, StepScheme::VelocityImplicit { corrections } if corrections > 0);
        if own_terms && method == Method::BlockDiagonal {
            Self::BlockDiagonal
        } else {
            Self::True
        }
    }
}

impl StrandMeasure {
    /// This measure with the energy of the dynamics `kinetic` in
    /// `energy_j`: what a frame stepped with that dynamics is judged by.
    /// `kinetic_j` stays the true kinetic energy, the scale of the
    /// allowance: Block-diagonal's own is no norm (with a moving root its
    /// cross term can make it negative), and `size_j` (the round-off's
    /// scale) adds its truncated part.
    pub fn judged_by(&self, kinetic: KineticEnergy) -> Self {
        match kinetic {
            KineticEnergy::True => *self,
            KineticEnergy::BlockDiagonal => Self {
                energy_j: self.energy_j + self.block_kinetic_j - self.strain_kinetic_j,
                size_j: self.size_j + self.block_kinetic_j,
                ..*self
            },
        }
    }
}

/// The environment the reference's measure of a strand needs besides
/// the strand ([`crate::Strand::measure`]).
#[derive(Clone, Copy, Debug)]
pub struct MeasureInputs<'a> {
    /// Gravity, m/s².
    pub gravity_m_per_s2: DVec3,
    /// Air velocity, m/s.
    pub air_velocity_m_per_s: DVec3,
    /// The head's collider, if any: a sample is in contact where the
    /// implicit push the reference steps with acts
    /// ([`ContactInputs::implicit_force`]).
    pub contact: Option<ContactInputs<'a>>,
}

/// A frame as the step took it: its length and the substeps it was
/// stepped in, which set how the external forces' impulse and work are
/// summed (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteppedFrame {
    /// The frame's length, seconds.
    pub dt_secs: f64,
    /// Substeps it was stepped in (at least 1).
    pub substeps: u32,
}

impl SteppedFrame {
    /// The weight of the frame's end in the external forces' rule,
    /// (n + 1)/(2n) for n substeps: 1 for one step, toward ½ (the
    /// trapezoid rule) for many. The start's is 1 minus it.
    pub fn end_weight(&self) -> f64 {
        let n = f64::from(self.substeps.max(1));
        (n + 1.0) / (2.0 * n)
    }

    /// ∫ x dt over the frame by the step's rule, for x `start` at its
    /// start and `end` at its end.
    fn integral<T: std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>>(
        &self,
        start: T,
        end: T,
    ) -> T {
        let w = self.end_weight();
        (start * (1.0 - w) + end * w) * self.dt_secs
    }
}

/// The energy a frame `frame` from `start` to `end` gained that no force
/// put in: ΔE − W_root − W_external, joules (see the module docs).
pub fn unexplained_energy_j(
    start: &StrandMeasure,
    end: &StrandMeasure,
    frame: SteppedFrame,
) -> f64 {
    let mean = |a: DVec3, b: DVec3| (a + b) * 0.5;
    let (root_impulse, root_angular_impulse) = root_impulses(start, end, frame);
    let root_work = root_impulse.dot(mean(start.root_velocity_m_per_s, end.root_velocity_m_per_s))
        + root_angular_impulse.dot(mean(
            start.root_angular_velocity_rad_per_s,
            end.root_angular_velocity_rad_per_s,
        ));
    let external_work = frame.integral(start.external_power_w, end.external_power_w);
    (end.energy_j - start.energy_j) - root_work - external_work
}

/// The root's impulse ∫ F dt and angular impulse ∫ τ dt over a frame
/// (Newton's laws about the moving root point, the external forces by the
/// step's rule; see the module docs).
fn root_impulses(
    start: &StrandMeasure,
    end: &StrandMeasure,
    frame: SteppedFrame,
) -> (DVec3, DVec3) {
    let mean = |a: DVec3, b: DVec3| (a + b) * 0.5;
    let dt_secs = frame.dt_secs;
    let root_impulse = end.momentum
        - start.momentum
        - frame.integral(start.external_force_n, end.external_force_n);
    let p_cross = mean(
        start.root_velocity_m_per_s.cross(start.momentum),
        end.root_velocity_m_per_s.cross(end.momentum),
    );
    let root_angular_impulse = end.angular_momentum - start.angular_momentum + p_cross * dt_secs
        - frame.integral(start.external_torque_n_m, end.external_torque_n_m);
    (root_impulse, root_angular_impulse)
}

/// How much energy the step's sampling of the root's motion can put into
/// a frame `frame` from `start` to `end` beyond what the balance
/// sees, joules.
///
/// A step that took the root's acceleration at the start of each substep
/// and held it over the substep would get the root's velocity at the
/// frame's end wrong; the step takes the acceleration averaged over each
/// substep instead ([`crate::HeadTrajectory::step_motion_at`]), which
/// removes that error at each substep's end, and this allowance, derived
/// for the held acceleration, is kept as a bound on what the frame-level
/// rule can miss where the acceleration changes within the frame. The
/// hair's rates are relative to the root. If
/// the true root velocity at the frame's end differs from the one a held
/// acceleration gives, δv = v_end − (v_start + a_start·dt) and δω likewise, every
/// sample's world velocity is off by δu = δv + δω × r, and so is the
/// kinetic energy, by up to |δv·P| + |δω·L| + ½ ∫ ρS |δu|² ds ≤ |δv·P| +
/// |δω·L| + m|δv|² + |δω|² ∫ ρS |r|² ds. The same δ is what the trapezoid
/// rule's mean root velocity can miss of the true mean (at most |δω| when
/// the velocity's departure from the held acceleration grows steadily
/// through the frame), so the root's work is unsure by up to
/// |δv|·|∫F dt| + |δω|·|∫τ dt|. For a smooth motion δ is O(dt²) and all
/// this is small; where the acceleration jumps within the frame (a clip
/// whose acceleration stops at its end) δ is O(Δa·dt), and a slowly
/// moving, healthy strand gains more than a quarter of its kinetic energy
/// from it (measured on the soak's nod before this allowance: 4.9e-10 J
/// against 3.9e-10 J allowed, on strands whose fastest point moved at a
/// few cm/s).
pub fn root_sampling_uncertainty_j(
    start: &StrandMeasure,
    end: &StrandMeasure,
    frame: SteppedFrame,
) -> f64 {
    let dt_secs = frame.dt_secs;
    let dv = end.root_velocity_m_per_s
        - start.root_velocity_m_per_s
        - start.root_acceleration_m_per_s2 * dt_secs;
    let dw = end.root_angular_velocity_rad_per_s
        - start.root_angular_velocity_rad_per_s
        - start.root_angular_acceleration_rad_per_s2 * dt_secs;
    let first = dv.dot(end.momentum).abs() + dw.dot(end.angular_momentum).abs();
    let second = end.mass_kg * dv.length_squared() + end.second_moment_kg_m2 * dw.length_squared();
    let (impulse, angular_impulse) = root_impulses(start, end, frame);
    let work = dv.length() * impulse.length() + dw.length() * angular_impulse.length();
    first + second + work
}

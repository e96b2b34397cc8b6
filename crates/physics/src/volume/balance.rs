//! The model's forces in the guard's energy balance
//! ([`crate::frame_balance`]).
//!
//! The guard flags a frame whose energy grew by more than the known
//! forces put in. Friction toward the grid velocity moves momentum between
//! strands: it can speed one strand up (the hair around it drags it
//! along) while slowing the others, and the pressure pushes. Left out of
//! the balance, that work reads as energy from nowhere (measured: a curl
//! of the window's curly style, 1.3e-9 J against 6.1e-10 J allowed, reset
//! at t = 0.4 s). So the measure counts the model's force like drag's:
//! its sum, its torque about the root point and its power ∫ f · ṙ ds, with
//! the frame's frozen grid velocity (relative to the head) and push: the
//! very force the step applies at that state
//! ([`VolumePull::force_n_per_m`]), through the step's sample hook
//! ([`crate::batch::measure`]). This module keeps a reused measure true
//! when the pull changes ([`PullWork`]).

use glam::DVec3;

use crate::frame_balance::StrandMeasure;
use crate::motion::RigidMotion;

use super::friction::VolumePull;
use super::pair_points::SampleMotion;

/// A pull's force (N), torque about the root point (N·m) and power (W)
/// on one strand at one state: its part of the measure's external terms.
///
/// # Why apart
///
/// The guard's measure at a frame's start is the previous frame's end
/// measure, reused, unless the state changed since. The pull changes every
/// frame, so the reused measure counts the old pull's work; rather than
/// measure the strand again (a reconstruction per strand and frame: the
/// whole frame was 36% dearer with the model, its own pass 17%), the
/// model's gather, which reconstructs the same state anyway, gives the old
/// and the new pull's work there, and [`PullWork::exchange`] swaps one
/// for the other in the reused measure.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PullWork {
    /// Σ f w, N.
    pub force_n: DVec3,
    /// Σ r × f w about the root point, N·m.
    pub torque_n_m: DVec3,
    /// Σ f · ṙ w, W.
    pub power_w: f64,
}

impl PullWork {
    /// Adds a sample at `r_m` (relative to the root point, world) moving at
    /// `velocity` (m/s) that feels `force_n` (its force per length times
    /// its quadrature length).
    pub fn add(&mut self, r_m: DVec3, velocity: DVec3, force_n: DVec3) {
        self.force_n += force_n;
        self.torque_n_m += r_m.cross(force_n);
        self.power_w += force_n.dot(velocity);
    }

    /// `measure`, which counted the work `old`, as if it had counted `new`.
    pub fn exchange(measure: &mut StrandMeasure, old: &PullWork, new: &PullWork) {
        measure.external_force_n += new.force_n - old.force_n;
        measure.external_torque_n_m += new.torque_n_m - old.torque_n_m;
        measure.external_power_w += new.power_w - old.power_w;
    }
}

/// `pull`'s work on a strand of ρS `mass_per_length` whose quadrature
/// samples are `samples`, its root moving as `root`.
pub fn pull_work(
    samples: &[SampleMotion],
    root: &RigidMotion,
    pull: &VolumePull,
    mass_per_length: f64,
) -> PullWork {
    let mut work = PullWork::default();
    for (i, s) in samples.iter().enumerate() {
        let (r, v) = (s.position_m, s.velocity_m_per_s);
        let carried = root.velocity_at(r);
        let f = pull.force_n_per_m(i, v, carried, mass_per_length) * s.weight_m;
        work.add(r, v, f);
    }
    work
}

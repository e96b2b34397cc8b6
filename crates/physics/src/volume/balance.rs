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
//! the frame's frozen grid velocity and push.

use crate::frame_balance::StrandMeasure;
use crate::model::StrandModel;
use crate::reconstruct::Kinematics;

use super::friction::VolumePull;

/// Adds `pull`'s force, torque and power at the state of `kin` to `out`.
pub fn add_pull(out: &mut StrandMeasure, model: &StrandModel, kin: &Kinematics, pull: &VolumePull) {
    for (i, s) in kin.samples.iter().enumerate() {
        let v = s.velocity_m_per_s;
        // The whole force at this state: its known part plus −μρS J q̇,
        // i.e. μρS (u − ṙ) + ρS a with ṙ the sample's own velocity.
        let f = pull.force_n_per_m(i, v, model.mass_per_length) * s.weight_m;
        out.external_force_n += f;
        out.external_torque_n_m += s.position_m.cross(f);
        out.external_power_w += f.dot(v);
    }
}

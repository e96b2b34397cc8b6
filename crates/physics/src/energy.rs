//! Energies of a strand, by the same quadrature the dynamics uses.

use glam::DVec3;

use crate::model::StrandModel;
use crate::step::reconstruct::Kinematics;

/// Energies in joules.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Energies {
    /// T = ½ ∫ ρS |ṙ|² ds (root motion included).
    pub kinetic_j: f64,
    /// U = ½ (q − qⁿ)ᵀ K (q − qⁿ).
    pub elastic_j: f64,
    /// U_g = −∫ ρS g · r ds, world positions.
    pub gravity_j: f64,
}

impl Energies {
    /// T + U + U_g.
    pub fn total_j(&self) -> f64 {
        self.kinetic_j + self.elastic_j + self.gravity_j
    }

    /// Adds another strand's energies.
    pub fn accumulate(&mut self, o: &Energies) {
        self.kinetic_j += o.kinetic_j;
        self.elastic_j += o.elastic_j;
        self.gravity_j += o.gravity_j;
    }
}

/// Energies of a reconstructed strand whose root point is at `root_m`.
pub fn energies(
    model: &StrandModel,
    q: &[DVec3],
    kin: &Kinematics,
    root_m: DVec3,
    gravity_m_per_s2: DVec3,
) -> Energies {
    let rho_s = model.mass_per_length;
    let mut out = Energies::default();
    for s in &kin.samples {
        let w = s.weight_m * rho_s;
        out.kinetic_j += 0.5 * w * s.velocity_m_per_s.length_squared();
        out.gravity_j -= w * gravity_m_per_s2.dot(s.position_m + root_m);
    }
    for ((q, natural), k) in q.iter().zip(&model.natural).zip(&model.stiffness) {
        let d = *q - *natural;
        out.elastic_j += 0.5 * (*k * d).dot(d);
    }
    out
}

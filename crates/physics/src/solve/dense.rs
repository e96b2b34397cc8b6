//! Dense solver (Bertails 2006): the full 3N×3N mass matrix, assembled from
//! the O(N) mass data in O(N²) and Cholesky-factored in O(N³) by nalgebra.
//! The reference every other method is measured against.

use glam::DVec3;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};

use super::StepSolver;
use crate::mass::{MassData, dense_mass};
use crate::reconstruct::Kinematics;

/// Dense Cholesky solver state.
#[derive(Clone, Debug, Default)]
pub struct DenseSolver {
    mass: DMatrix<f64>,
    factor: Option<Cholesky<f64, Dyn>>,
}

impl DenseSolver {
    /// The mass matrix of the last `prepare`.
    pub fn mass_matrix(&self) -> &DMatrix<f64> {
        &self.mass
    }
}

impl StepSolver for DenseSolver {
    fn prepare(&mut self, kin: &Kinematics, mass: &MassData, mass_scale: f64, diagonal: &[DVec3]) {
        self.mass = dense_mass(kin, mass);
        let mut step = &self.mass * mass_scale;
        for (e, d) in diagonal.iter().enumerate() {
            for i in 0..3 {
                step[(3 * e + i, 3 * e + i)] += d[i];
            }
        }
        // The step matrix is symmetric positive definite (D > 0); a failed
        // factorisation means non-finite input, which the caller's guards see
        // as a non-finite result.
        self.factor = Cholesky::new(step);
    }

    fn solve(&mut self, _kin: &Kinematics, _mass: &MassData, rhs: &[DVec3], out: &mut [DVec3]) {
        match &self.factor {
            Some(factor) => from_vector(&factor.solve(&to_vector(rhs)), out),
            None => out.fill(DVec3::NAN),
        }
    }
}

fn to_vector(x: &[DVec3]) -> DVector<f64> {
    DVector::from_iterator(3 * x.len(), x.iter().flat_map(|v| v.to_array()))
}

fn from_vector(y: &DVector<f64>, out: &mut [DVec3]) {
    for (e, o) in out.iter_mut().enumerate() {
        *o = DVec3::new(y[3 * e], y[3 * e + 1], y[3 * e + 2]);
    }
}

//! Dense solver (Bertails 2006): the full 3N×3N mass matrix, assembled from
//! the O(N) mass data in O(N²) and Cholesky-factored in O(N³) by nalgebra.
//! The reference every other method is measured against.

use glam::DVec3;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn, LU};

use super::StepSolver;
use crate::step::mass::{MassData, dense_mass};
use crate::step::reconstruct::Kinematics;

/// Dense Cholesky solver state.
#[derive(Clone, Debug, Default)]
pub struct DenseSolver {
    mass: DMatrix<f64>,
    factor: Option<Factor>,
}

/// The step matrix's factors: Cholesky while it is symmetric, LU once the
/// velocity terms make it non-symmetric.
#[derive(Clone, Debug)]
enum Factor {
    Cholesky(Cholesky<f64, Dyn>),
    Lu(LU<f64, Dyn, Dyn>),
}

impl DenseSolver {
    /// The mass matrix of the last `prepare`.
    pub fn mass_matrix(&self) -> &DMatrix<f64> {
        &self.mass
    }

    /// Builds and factors s M + D + `extra` (Cholesky without `extra`, LU
    /// with it: the velocity terms' h G is not symmetric).
    pub fn prepare_with(
        &mut self,
        kin: &Kinematics,
        mass: &MassData,
        mass_scale: f64,
        diagonal: &[DVec3],
        extra: Option<DMatrix<f64>>,
    ) {
        self.mass = dense_mass(kin, mass);
        let mut step = &self.mass * mass_scale;
        for (e, d) in diagonal.iter().enumerate() {
            for i in 0..3 {
                step[(3 * e + i, 3 * e + i)] += d[i];
            }
        }
        // Without `extra` the step matrix is symmetric positive definite
        // (D > 0); a failed factorisation means non-finite input, which the
        // caller's guards see as a non-finite result.
        self.factor = match extra {
            None => Cholesky::new(step).map(Factor::Cholesky),
            Some(extra) => {
                let lu = (step + extra).lu();
                lu.is_invertible().then_some(Factor::Lu(lu))
            }
        };
    }
}

impl StepSolver for DenseSolver {
    fn prepare(&mut self, kin: &Kinematics, mass: &MassData, mass_scale: f64, diagonal: &[DVec3]) {
        self.prepare_with(kin, mass, mass_scale, diagonal, None);
    }

    fn solve(&mut self, _kin: &Kinematics, _mass: &MassData, rhs: &[DVec3], out: &mut [DVec3]) {
        match &self.factor {
            Some(Factor::Cholesky(factor)) => from_vector(&factor.solve(&to_vector(rhs)), out),
            Some(Factor::Lu(factor)) => match factor.solve(&to_vector(rhs)) {
                Some(y) => from_vector(&y, out),
                None => out.fill(DVec3::NAN),
            },
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

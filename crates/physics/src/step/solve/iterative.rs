//! Iterative solver (the seed paper's future work): k steps of conjugate
//! gradients on the true step matrix, preconditioned by its diagonal 3×3
//! blocks, started from the Block-diagonal answer.
//!
//! How it works. The product S x = s M x + D x needs no matrix: M x is one
//! suffix and one prefix sweep over the mass data ([`crate::step::mass::mass_times`]),
//! so an iteration costs O(N) and k iterations O(kN). The preconditioner
//! is exactly the Block-diagonal solver, so k = 0 returns Block-diagonal's
//! Δv, and as k grows the answer converges to Dense's (CG on an SPD matrix
//! is exact after 3N iterations in exact arithmetic).

use glam::DVec3;

use super::StepSolver;
use super::block_diagonal::{BlockDiagonalSolver, BlockVariant};
use crate::step::mass::{MassData, mass_times};
use crate::step::reconstruct::Kinematics;

/// Preconditioned conjugate gradients with a fixed iteration count.
#[derive(Clone, Debug)]
pub struct IterativeSolver {
    iterations: u32,
    preconditioner: BlockDiagonalSolver,
    mass_scale: f64,
    diagonal: Vec<DVec3>,
    residual: Vec<DVec3>,
    direction: Vec<DVec3>,
    preconditioned: Vec<DVec3>,
    product: Vec<DVec3>,
}

impl IterativeSolver {
    /// A solver running `iterations` CG iterations per step.
    pub fn new(iterations: u32) -> Self {
        Self {
            iterations,
            preconditioner: BlockDiagonalSolver::new(BlockVariant::Subtree),
            mass_scale: 1.0,
            diagonal: Vec::new(),
            residual: Vec::new(),
            direction: Vec::new(),
            preconditioned: Vec::new(),
            product: Vec::new(),
        }
    }

    /// Iterations per step.
    pub fn iterations(&self) -> u32 {
        self.iterations
    }
}

/// out = (s M + D) x, with M applied matrix-free.
fn step_matrix_times(
    kin: &Kinematics,
    mass: &MassData,
    mass_scale: f64,
    diagonal: &[DVec3],
    x: &[DVec3],
    out: &mut Vec<DVec3>,
) {
    out.resize(x.len(), DVec3::ZERO);
    mass_times(kin, mass, x, out);
    for ((o, d), x) in out.iter_mut().zip(diagonal).zip(x) {
        *o = *o * mass_scale + *d * *x;
    }
}

fn dot(a: &[DVec3], b: &[DVec3]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x.dot(*y)).sum()
}

impl StepSolver for IterativeSolver {
    fn prepare(&mut self, kin: &Kinematics, mass: &MassData, mass_scale: f64, diagonal: &[DVec3]) {
        self.preconditioner.prepare(kin, mass, mass_scale, diagonal);
        self.mass_scale = mass_scale;
        self.diagonal.clear();
        self.diagonal.extend_from_slice(diagonal);
    }

    fn solve(&mut self, kin: &Kinematics, mass: &MassData, rhs: &[DVec3], out: &mut [DVec3]) {
        let n = rhs.len();
        self.preconditioner.solve(kin, mass, rhs, out);
        if self.iterations == 0 {
            return;
        }
        step_matrix_times(
            kin,
            mass,
            self.mass_scale,
            &self.diagonal,
            out,
            &mut self.product,
        );
        self.residual.clear();
        self.residual
            .extend(rhs.iter().zip(&self.product).map(|(b, ax)| *b - *ax));
        self.preconditioned.resize(n, DVec3::ZERO);
        self.preconditioner
            .solve(kin, mass, &self.residual, &mut self.preconditioned);
        self.direction.clear();
        self.direction.extend_from_slice(&self.preconditioned);
        let mut rz = dot(&self.residual, &self.preconditioned);
        for _ in 0..self.iterations {
            if rz <= 0.0 || !rz.is_finite() {
                break; // converged to round-off (or non-finite input)
            }
            step_matrix_times(
                kin,
                mass,
                self.mass_scale,
                &self.diagonal,
                &self.direction,
                &mut self.product,
            );
            let alpha = rz / dot(&self.direction, &self.product);
            for (x, d) in out.iter_mut().zip(&self.direction) {
                *x += alpha * *d;
            }
            for (r, p) in self.residual.iter_mut().zip(&self.product) {
                *r -= alpha * *p;
            }
            self.preconditioner
                .solve(kin, mass, &self.residual, &mut self.preconditioned);
            let rz_next = dot(&self.residual, &self.preconditioned);
            let beta = rz_next / rz;
            for (d, z) in self.direction.iter_mut().zip(&self.preconditioned) {
                *d = *z + beta * *d;
            }
            rz = rz_next;
        }
    }
}

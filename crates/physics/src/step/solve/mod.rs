//! Stage "solve" of the assembled arrangement: the linearly implicit step
//! solved on the mass data of [`crate::step::mass`], for the methods the
//! generic step ([`crate::step::generic`]) does not run.
//!
//! Every method sees the same right-hand side (the exact forces, with the
//! drag on the current velocity from the exact M q̇) and differs only in the
//! step matrix it solves: Δv from (s M̃ + D) Δv = rhs, with s = 1 + hν/ρS,
//! the per-element diagonal D = hγℓ + h²K and M̃ the method's mass matrix.
//!
//! [`dense::DenseSolver`] uses the true M (Cholesky, O(N³)).
//! [`block_diagonal::BlockDiagonalSolver`] keeps the N diagonal 3×3 blocks
//! (either reading of the seed paper): O(N), elements independent; it
//! steps the own-element reading, and with subtree blocks it is the
//! independent check of the generic Block-diagonal step and Iterative's
//! preconditioner. Exact's O(N) tip-to-root recursion is the generic
//! step's ([`crate::batch::step::exact`]). [`iterative::IterativeSolver`] runs k steps of
//! block-preconditioned conjugate gradients from the Block-diagonal answer.
//! h²K > 0 keeps every step matrix definite even where a straight strand's
//! twist rows of M vanish.

pub mod block_diagonal;
pub mod dense;
pub mod iterative;

use glam::DVec3;

use crate::settings::Method;
use crate::step::mass::MassData;
use crate::step::reconstruct::Kinematics;

/// One way to solve the step matrix.
pub trait StepSolver {
    /// Builds (and factors) s M̃ + D for this step.
    fn prepare(&mut self, kin: &Kinematics, mass: &MassData, mass_scale: f64, diagonal: &[DVec3]);
    /// out = (s M̃ + D)⁻¹ rhs.
    fn solve(&mut self, kin: &Kinematics, mass: &MassData, rhs: &[DVec3], out: &mut [DVec3]);
}

/// A solver of any [`Method`], reused from step to step.
#[derive(Clone, Debug)]
pub enum Solver {
    /// See [`dense::DenseSolver`].
    Dense(dense::DenseSolver),
    /// See [`block_diagonal::BlockDiagonalSolver`].
    BlockDiagonal(block_diagonal::BlockDiagonalSolver),
    /// See [`iterative::IterativeSolver`].
    Iterative(iterative::IterativeSolver),
}

impl Solver {
    /// A fresh solver for `method`; `None` for Exact, which only the
    /// generic step runs ([`crate::step::generic`]).
    pub fn new(method: Method) -> Option<Self> {
        use block_diagonal::{BlockDiagonalSolver, BlockVariant};
        Some(match method {
            Method::Dense => Solver::Dense(dense::DenseSolver::default()),
            Method::BlockDiagonal => {
                Solver::BlockDiagonal(BlockDiagonalSolver::new(BlockVariant::Subtree))
            }
            Method::BlockDiagonalOwnElement => {
                Solver::BlockDiagonal(BlockDiagonalSolver::new(BlockVariant::OwnElement))
            }
            Method::Exact => return None,
            Method::Iterative { iterations } => {
                Solver::Iterative(iterative::IterativeSolver::new(iterations))
            }
        })
    }

    /// The method this solver implements.
    pub fn method(&self) -> Method {
        match self {
            Solver::Dense(_) => Method::Dense,
            Solver::BlockDiagonal(b) => match b.variant() {
                block_diagonal::BlockVariant::Subtree => Method::BlockDiagonal,
                block_diagonal::BlockVariant::OwnElement => Method::BlockDiagonalOwnElement,
            },
            Solver::Iterative(i) => Method::Iterative {
                iterations: i.iterations(),
            },
        }
    }

    fn inner(&mut self) -> &mut dyn StepSolver {
        match self {
            Solver::Dense(s) => s,
            Solver::BlockDiagonal(s) => s,
            Solver::Iterative(s) => s,
        }
    }
}

impl StepSolver for Solver {
    fn prepare(&mut self, kin: &Kinematics, mass: &MassData, mass_scale: f64, diagonal: &[DVec3]) {
        self.inner().prepare(kin, mass, mass_scale, diagonal);
    }
    fn solve(&mut self, kin: &Kinematics, mass: &MassData, rhs: &[DVec3], out: &mut [DVec3]) {
        self.inner().solve(kin, mass, rhs, out);
    }
}

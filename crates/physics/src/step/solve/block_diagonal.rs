//! Block-diagonal solver (the seed paper's method): keep only the N
//! diagonal 3×3 blocks of the mass matrix and solve each element alone.
//! O(N), and every element is independent, so it parallelises over elements
//! as well as strands.
//!
//! The seed drops the parents' accelerations from each element's equation;
//! its text reads two ways, both kept as named variants:
//! - [`BlockVariant::Subtree`]: the block is ∫ ρS J_Qᵀ J_Q over everything
//!   element Q moves, the diagonal block of the true M (the default).
//! - [`BlockVariant::OwnElement`]: the block integrates element Q's own
//!   mass only.
//!
//! Dropping the off-diagonal inertia makes the strand lighter than it is
//! against its own stiffness: swings come out too fast, more so as N grows,
//! and the implicit step then damps them harder. Static equilibria are
//! unchanged (the mass matrix drops out at rest). The tests measure both.

use glam::{DMat3, DVec3};

use super::StepSolver;
use crate::step::mass::MassData;
use crate::step::reconstruct::Kinematics;

/// Which inertia each diagonal block holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockVariant {
    /// Everything the element moves: the true diagonal blocks.
    Subtree,
    /// The element's own mass only.
    OwnElement,
}

/// Block-diagonal solver state.
#[derive(Clone, Debug)]
pub struct BlockDiagonalSolver {
    variant: BlockVariant,
    inverses: Vec<DMat3>,
}

impl BlockDiagonalSolver {
    /// A solver of the given variant.
    pub fn new(variant: BlockVariant) -> Self {
        Self {
            variant,
            inverses: Vec::new(),
        }
    }

    /// The variant.
    pub fn variant(&self) -> BlockVariant {
        self.variant
    }
}

impl StepSolver for BlockDiagonalSolver {
    fn prepare(&mut self, _kin: &Kinematics, mass: &MassData, mass_scale: f64, diagonal: &[DVec3]) {
        let source = match self.variant {
            BlockVariant::Subtree => &mass.diagonal,
            BlockVariant::OwnElement => &mass.own,
        };
        self.inverses.clear();
        self.inverses.extend(
            source
                .iter()
                .zip(diagonal)
                .map(|(m, d)| (*m * mass_scale + DMat3::from_diagonal(*d)).inverse()),
        );
    }

    fn solve(&mut self, _kin: &Kinematics, _mass: &MassData, rhs: &[DVec3], out: &mut [DVec3]) {
        for ((o, inv), r) in out.iter_mut().zip(&self.inverses).zip(rhs) {
            *o = *inv * *r;
        }
    }
}

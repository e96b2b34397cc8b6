//! Exact linear-time solver (after Bertails 2009): the true step matrix in
//! O(N), by a Featherstone-style recursion.
//!
//! How it works. The mass data gives every off-diagonal block of the step
//! matrix S = sM + D as S_PQ = U_PᵀW_Q (P < Q), with U_P = (A_P; B_P) and
//! W_Q = s(X_Q; Y_Q) stacked 6×3 (see [`crate::step::mass`]); S is semiseparable.
//! Eliminating unknowns from the tip towards the root keeps that form:
//! eliminating element Q changes the blocks of the elements before it only
//! through a 6×6 matrix H, an articulated inertia passed tip to root,
//!
//!   W̃_Q = W_Q − H U_Q,  S̃_Q = S_QQ − U_QᵀH U_Q,  H ← H + W̃_Q S̃_Q⁻¹ W̃_Qᵀ,
//!
//! and the right-hand side through a 6-vector passed the same way. A second
//! sweep, root to tip, then yields the unknowns (the accelerations) from
//! x_Q = S̃_Q⁻¹(r̃_Q − W̃_Qᵀ Σ_{P<Q} U_P x_P). No approximation is made: it
//! agrees with Dense to round-off (a test pins it for N up to 100).

use glam::{DMat3, DVec3};

use super::StepSolver;
use crate::step::mass::MassData;
use crate::step::reconstruct::Kinematics;

/// A 6×3 matrix as two stacked 3×3 blocks.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Stack {
    top: DMat3,
    bottom: DMat3,
}

impl Stack {
    const ZERO: Stack = Stack {
        top: DMat3::ZERO,
        bottom: DMat3::ZERO,
    };
}

/// A symmetric 6×6 matrix as 2×2 blocks. (No `Default`: glam's default
/// matrix is the identity, and this must start at zero.)
#[derive(Clone, Copy, Debug, PartialEq)]
struct Inertia6 {
    aa: DMat3,
    ab: DMat3,
    ba: DMat3,
    bb: DMat3,
}

impl Inertia6 {
    const ZERO: Inertia6 = Inertia6 {
        aa: DMat3::ZERO,
        ab: DMat3::ZERO,
        ba: DMat3::ZERO,
        bb: DMat3::ZERO,
    };

    fn times(&self, u: &Stack) -> Stack {
        Stack {
            top: self.aa * u.top + self.ab * u.bottom,
            bottom: self.ba * u.top + self.bb * u.bottom,
        }
    }
}

/// Exact O(N) solver state: the tip-to-root factorisation of the last step.
#[derive(Clone, Debug, Default)]
pub struct ExactSolver {
    w_tilde: Vec<Stack>,
    s_tilde_inv: Vec<DMat3>,
    r_tilde: Vec<DVec3>,
}

fn stack_u(kin: &Kinematics, q: usize) -> Stack {
    Stack {
        top: kin.elements[q].a,
        bottom: kin.elements[q].b,
    }
}

impl StepSolver for ExactSolver {
    fn prepare(&mut self, kin: &Kinematics, mass: &MassData, mass_scale: f64, diagonal: &[DVec3]) {
        let n = mass.diagonal.len();
        self.w_tilde.resize(n, Stack::ZERO);
        self.s_tilde_inv.resize(n, DMat3::ZERO);
        let mut h = Inertia6::ZERO;
        for q in (0..n).rev() {
            let u = stack_u(kin, q);
            let hu = h.times(&u);
            let w = Stack {
                top: mass.x[q] * mass_scale - hu.top,
                bottom: mass.y[q] * mass_scale - hu.bottom,
            };
            let s = mass.diagonal[q] * mass_scale + DMat3::from_diagonal(diagonal[q])
                - (u.top.transpose() * hu.top + u.bottom.transpose() * hu.bottom);
            let s_inv = s.inverse();
            let p_top = w.top * s_inv;
            let p_bottom = w.bottom * s_inv;
            h.aa += p_top * w.top.transpose();
            h.ab += p_top * w.bottom.transpose();
            h.ba += p_bottom * w.top.transpose();
            h.bb += p_bottom * w.bottom.transpose();
            self.w_tilde[q] = w;
            self.s_tilde_inv[q] = s_inv;
        }
    }

    fn solve(&mut self, kin: &Kinematics, _mass: &MassData, rhs: &[DVec3], out: &mut [DVec3]) {
        let n = rhs.len();
        self.r_tilde.resize(n, DVec3::ZERO);
        // Tip to root: fold each eliminated element's load into its parents.
        let (mut carried_a, mut carried_b) = (DVec3::ZERO, DVec3::ZERO);
        for q in (0..n).rev() {
            let u = stack_u(kin, q);
            let r = rhs[q] - (u.top.transpose() * carried_a + u.bottom.transpose() * carried_b);
            let y = self.s_tilde_inv[q] * r;
            carried_a += self.w_tilde[q].top * y;
            carried_b += self.w_tilde[q].bottom * y;
            self.r_tilde[q] = r;
        }
        // Root to tip: each element's unknown from its parents' motion.
        let (mut moved_a, mut moved_b) = (DVec3::ZERO, DVec3::ZERO);
        for (q, x) in out.iter_mut().enumerate().take(n) {
            let w = &self.w_tilde[q];
            *x = self.s_tilde_inv[q]
                * (self.r_tilde[q]
                    - (w.top.transpose() * moved_a + w.bottom.transpose() * moved_b));
            let u = stack_u(kin, q);
            moved_a += u.top * *x;
            moved_b += u.bottom * *x;
        }
    }
}

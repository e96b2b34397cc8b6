//! A Super-Helix evaluated at arbitrary arc lengths, with the derivatives a
//! least-squares fit needs.
//!
//! The step's reconstruction ([`crate::reconstruct`]) samples each element
//! at fixed quadrature nodes; a fit instead compares the strand with the
//! imported polyline at the arc lengths where its points lie, which move as
//! the fit proceeds. The algebra is the same (`docs/physics.md` sections 2
//! and 4): element Q starts at p_Q with frame R_Q, a point at arc length σ
//! inside it is p_Q + R_Q h(σ, q_Q), and moving q_Q moves every later point
//! rigidly, ∂r/∂q_Q = A_Q − [r]× B_Q with A_Q = a_Q + [p_{Q+1}]× b_Q,
//! a_Q = R_Q ∂h(ℓ)/∂k and b_Q = ℓ R_Q J_l(ℓ q_Q).

use glam::{DMat3, DVec3};

use crate::helix::{centreline_and_jacobian, left_jacobian, rotation, skew};

/// A strand of equal elements, positions relative to its root point.
#[derive(Clone, Debug, PartialEq)]
pub struct UniformHelixChain {
    /// Root frame, columns (n₀, n₁, n₂) in world (or head) coordinates.
    pub root_frame: DMat3,
    /// Length ℓ of every element, metres.
    pub element_length_m: f64,
    /// Strains (τ, κ₁, κ₂) per element, m⁻¹, root first.
    pub strains_per_m: Vec<DVec3>,
}

/// Element starts and the "beyond" Jacobian factors, from one sweep.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChainSweep {
    /// Frame R_Q at each element's start (N).
    pub frames: Vec<DMat3>,
    /// Point p_Q at each element's start, relative to the root (N + 1).
    pub points_m: Vec<DVec3>,
    /// A_Q (metres²) per element.
    pub a: Vec<DMat3>,
    /// B_Q (metres) per element.
    pub b: Vec<DMat3>,
}

/// One point of the chain at a given arc length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainPoint {
    /// Position relative to the root, metres.
    pub position_m: DVec3,
    /// Unit tangent n₀ there.
    pub tangent: DVec3,
    /// Element the point lies in.
    pub element: usize,
    /// ∂r/∂q of the point's own element, metres².
    pub own_jacobian: DMat3,
}

impl UniformHelixChain {
    /// Number of elements N.
    pub fn elements(&self) -> usize {
        self.strains_per_m.len()
    }

    /// Total length Nℓ, metres.
    pub fn length_m(&self) -> f64 {
        self.element_length_m * self.elements() as f64
    }

    /// One root-to-tip sweep: element frames, points and Jacobian factors.
    pub fn sweep(&self) -> ChainSweep {
        let l = self.element_length_m;
        let mut out = ChainSweep::default();
        let mut frame = self.root_frame;
        let mut point = DVec3::ZERO;
        out.points_m.push(point);
        for k in &self.strains_per_m {
            let (h, dh) = centreline_and_jacobian(l, *k);
            let next = point + frame * h;
            let a = frame * dh;
            let b = frame * left_jacobian(*k * l) * l;
            out.frames.push(frame);
            out.a.push(a + skew(next) * b);
            out.b.push(b);
            frame *= rotation(*k * l);
            point = next;
            out.points_m.push(point);
        }
        out
    }

    /// The point at arc length `s_m` (clamped to the strand), from a sweep.
    pub fn point(&self, sweep: &ChainSweep, s_m: f64) -> ChainPoint {
        let n = self.elements();
        let l = self.element_length_m;
        let e = ((s_m / l).floor().max(0.0) as usize).min(n - 1);
        let sigma = (s_m - e as f64 * l).clamp(0.0, l);
        let k = self.strains_per_m[e];
        let frame = sweep.frames[e];
        let (h, dh) = centreline_and_jacobian(sigma, k);
        ChainPoint {
            position_m: sweep.points_m[e] + frame * h,
            tangent: frame * rotation(k * sigma).col(0),
            element: e,
            own_jacobian: frame * dh,
        }
    }

    /// Positions (relative to the root) at the given arc lengths.
    pub fn positions(&self, arc_lengths_m: &[f64]) -> Vec<DVec3> {
        let sweep = self.sweep();
        arc_lengths_m
            .iter()
            .map(|&s| self.point(&sweep, s).position_m)
            .collect()
    }
}

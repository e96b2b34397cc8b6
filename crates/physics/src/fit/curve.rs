//! A Super-Helix evaluated at arbitrary arc lengths, with the derivatives a
//! least-squares fit needs.
//!
//! The step's reconstruction ([`crate::step::reconstruct`]) samples each element
//! at fixed quadrature nodes; a fit instead compares the strand with the
//! imported polyline at the arc lengths where its points lie, which move as
//! the fit proceeds. The algebra is the same (`docs/physics.md` sections 2
//! and 4): element Q starts at p_Q with frame R_Q, a point at arc length σ
//! inside it is p_Q + R_Q h(σ, q_Q), and moving q_Q moves every later point
//! rigidly, ∂r/∂q_Q = A_Q − \[r\]× B_Q with A_Q = a_Q + [p_{Q+1}]× b_Q,
//! a_Q = R_Q ∂h(ℓ)/∂k and b_Q = ℓ R_Q J_l(ℓ q_Q).

use glam::{DMat3, DVec3};

use super::coefficients::FitCoefficients;
use crate::geometry::helix::{outer, skew};

/// Centreline h(σ, k), its Jacobian (when asked) and the frame's turn
/// exp(σ[k]×), from one evaluation of the coefficients A, B, C (the fit
/// evaluates the chain thousands of times per strand: this sharing halves
/// its cost, and [`FitCoefficients`] sums only the series terms σ|k|
/// needs).
fn element_at(sigma: f64, k: DVec3, jacobian: bool) -> (DVec3, DMat3, DMat3, FitCoefficients) {
    let phi = k * sigma;
    let co = FitCoefficients::at(phi.length_squared());
    let e0 = DVec3::X;
    let phi_x_e0 = phi.cross(e0);
    let phi_x_phi_x_e0 = phi.cross(phi_x_e0);
    let h = sigma * (e0 + co.b * phi_x_e0 + co.c * phi_x_phi_x_e0);
    let s = skew(phi);
    let turn = DMat3::IDENTITY + s * co.a + s * s * co.b;
    let dh = if jacobian {
        // ∂h/∂k = σ² ∂f/∂φ with f(φ) = J_l(φ) e₀ (`geometry::helix`).
        let df = skew(e0) * (-co.b)
            + (outer(phi, e0) + DMat3::from_diagonal(DVec3::splat(phi.x)) - outer(e0, phi) * 2.0)
                * co.c
            + outer(phi_x_e0, phi) * (2.0 * co.b1)
            + outer(phi_x_phi_x_e0, phi) * (2.0 * co.c1);
        df * (sigma * sigma)
    } else {
        DMat3::ZERO
    };
    (h, dh, turn, co)
}

/// J_l(φ) = I + B[φ]× + C[φ]×², the left Jacobian of SO(3).
fn left_jacobian(phi: DVec3, co: &FitCoefficients) -> DMat3 {
    let s = skew(phi);
    DMat3::IDENTITY + s * co.b + s * s * co.c
}

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

    /// One root-to-tip sweep: element frames, points and, with
    /// `jacobians`, the Jacobian factors.
    pub fn sweep_with(&self, jacobians: bool) -> ChainSweep {
        let l = self.element_length_m;
        let mut out = ChainSweep::default();
        let mut frame = self.root_frame;
        let mut point = DVec3::ZERO;
        out.points_m.push(point);
        for k in &self.strains_per_m {
            let (h, dh, turn, co) = element_at(l, *k, jacobians);
            let next = point + frame * h;
            out.frames.push(frame);
            if jacobians {
                let a = frame * dh;
                let b = frame * left_jacobian(*k * l, &co) * l;
                out.a.push(a + skew(next) * b);
                out.b.push(b);
            }
            frame *= turn;
            point = next;
            out.points_m.push(point);
        }
        out
    }

    /// One root-to-tip sweep: element frames, points and Jacobian factors.
    pub fn sweep(&self) -> ChainSweep {
        self.sweep_with(true)
    }

    /// The point at arc length `s_m` (clamped to the strand), from a sweep;
    /// `own_jacobian` is zero unless `jacobian`.
    pub fn point_with(&self, sweep: &ChainSweep, s_m: f64, jacobian: bool) -> ChainPoint {
        let n = self.elements();
        let l = self.element_length_m;
        let e = ((s_m / l).floor().max(0.0) as usize).min(n - 1);
        let sigma = (s_m - e as f64 * l).clamp(0.0, l);
        let frame = sweep.frames[e];
        let (h, dh, turn, _) = element_at(sigma, self.strains_per_m[e], jacobian);
        ChainPoint {
            position_m: sweep.points_m[e] + frame * h,
            tangent: frame * turn.col(0),
            element: e,
            own_jacobian: frame * dh,
        }
    }

    /// The point at arc length `s_m` (clamped to the strand), from a sweep.
    pub fn point(&self, sweep: &ChainSweep, s_m: f64) -> ChainPoint {
        self.point_with(sweep, s_m, true)
    }

    /// Positions (relative to the root) at the given arc lengths.
    pub fn positions(&self, arc_lengths_m: &[f64]) -> Vec<DVec3> {
        let sweep = self.sweep_with(false);
        arc_lengths_m
            .iter()
            .map(|&s| self.point_with(&sweep, s, false).position_m)
            .collect()
    }
}

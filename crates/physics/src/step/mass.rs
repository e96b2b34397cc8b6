//! Stage "mass": the mass matrix M_ab = ∫ ρS J_a · J_b ds, as O(N) data.
//!
//! With J = A_Q − \[r\]×B_Q beyond element Q (see [`crate::step::reconstruct`]), an
//! integral over everything beyond Q needs only the suffix mass moments
//! m = Σ wρS, c = Σ wρS r and the inertia tensor I = Σ wρS(|r|²𝟙 − rrᵀ).
//! Every off-diagonal block then factors as
//!
//! M_PQ = A_Pᵀ X_Q + B_Pᵀ Y_Q   (P < Q),
//!
//! X_Q = U_Q + m A_Q − \[c\]× B_Q,  Y_Q = V_Q + \[c\]× A_Q + I B_Q (moments of
//! the samples past Q), U_Q = Σ_own wρS G, V_Q = Σ_own wρS \[r\]× G, and the
//! diagonal block is M_QQ = D_Q + A_Qᵀ(X_Q − U_Q) + B_Qᵀ(Y_Q − V_Q) with
//! D_Q = Σ_own wρS GᵀG, G the sample's own-element Jacobian.
//!
//! So one tip-to-root sweep yields the diagonal blocks (all Block-diagonal
//! needs), and the dense matrix costs O(1) per block.

use glam::{DMat3, DVec3};
use nalgebra::DMatrix;

use crate::geometry::helix::skew;
use crate::model::StrandModel;
use crate::step::reconstruct::Kinematics;

/// Mass-matrix data of one strand.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MassData {
    /// Diagonal blocks M_QQ of the true mass matrix ("subtree"), kg·m³.
    pub diagonal: Vec<DMat3>,
    /// Blocks of the element's own mass only, D_Q ("own element"), kg·m³.
    pub own: Vec<DMat3>,
    /// X_Q (column factor of the off-diagonal blocks), kg·m².
    pub x: Vec<DMat3>,
    /// Y_Q (column factor of the off-diagonal blocks), kg·m³.
    pub y: Vec<DMat3>,
}

/// Fills `out` from the reconstruction.
pub fn mass_blocks(model: &StrandModel, kin: &Kinematics, out: &mut MassData) {
    let n = model.elements();
    let points = model.quadrature.len();
    let rho_s = model.mass_per_length;
    for v in [&mut out.diagonal, &mut out.own, &mut out.x, &mut out.y] {
        v.clear();
        v.resize(n, DMat3::ZERO);
    }
    let mut mass = 0.0;
    let mut first_moment = DVec3::ZERO;
    let mut inertia = DMat3::ZERO;
    for e in (0..n).rev() {
        let jac = &kin.elements[e];
        let c = skew(first_moment);
        let x_beyond = jac.a * mass - c * jac.b;
        let y_beyond = c * jac.a + inertia * jac.b;
        let (mut u, mut v, mut d) = (DMat3::ZERO, DMat3::ZERO, DMat3::ZERO);
        for s in &kin.samples[e * points..(e + 1) * points] {
            let w = s.weight_m * rho_s;
            u += s.jacobian * w;
            v += skew(s.position_m) * s.jacobian * w;
            d += s.jacobian.transpose() * s.jacobian * w;
            let r = s.position_m;
            mass += w;
            first_moment += r * w;
            inertia += (DMat3::from_diagonal(DVec3::splat(r.length_squared()))
                - crate::geometry::helix::outer(r, r))
                * w;
        }
        out.diagonal[e] = d + jac.a.transpose() * x_beyond + jac.b.transpose() * y_beyond;
        out.own[e] = d;
        out.x[e] = u + x_beyond;
        out.y[e] = v + y_beyond;
    }
}

/// out = M x without forming M, in O(N): with U_P = (A_P; B_P) and
/// W_Q = (X_Q; Y_Q) (6×3 each), M_PQ = U_PᵀW_Q above the diagonal and
/// W_PᵀU_Q below it, so a suffix sum of W_Q x_Q and a prefix sum of
/// U_Q x_Q give every row.
pub fn mass_times(kin: &Kinematics, mass: &MassData, x: &[DVec3], out: &mut [DVec3]) {
    let n = mass.diagonal.len();
    // Suffix sums Σ_{Q>P} (X_Q x_Q, Y_Q x_Q), applied by U_Pᵀ.
    let (mut sx, mut sy) = (DVec3::ZERO, DVec3::ZERO);
    for p in (0..n).rev() {
        let jac = &kin.elements[p];
        out[p] = mass.diagonal[p] * x[p] + jac.a.transpose() * sx + jac.b.transpose() * sy;
        sx += mass.x[p] * x[p];
        sy += mass.y[p] * x[p];
    }
    // Prefix sums Σ_{Q<P} (A_Q x_Q, B_Q x_Q), applied by W_Pᵀ.
    let (mut pa, mut pb) = (DVec3::ZERO, DVec3::ZERO);
    for p in 0..n {
        out[p] += mass.x[p].transpose() * pa + mass.y[p].transpose() * pb;
        let jac = &kin.elements[p];
        pa += jac.a * x[p];
        pb += jac.b * x[p];
    }
}

/// Assembles the full 3N×3N mass matrix (O(N²)).
pub fn dense_mass(kin: &Kinematics, mass: &MassData) -> DMatrix<f64> {
    let n = mass.diagonal.len();
    let mut m = DMatrix::zeros(3 * n, 3 * n);
    for col in 0..n {
        put_block(&mut m, col, col, &mass.diagonal[col]);
        for row in 0..col {
            let jac = &kin.elements[row];
            let block = jac.a.transpose() * mass.x[col] + jac.b.transpose() * mass.y[col];
            put_block(&mut m, row, col, &block);
            put_block(&mut m, col, row, &block.transpose());
        }
    }
    m
}

fn put_block(m: &mut DMatrix<f64>, row: usize, col: usize, block: &DMat3) {
    for j in 0..3 {
        for i in 0..3 {
            m[(3 * row + i, 3 * col + j)] = block.col(j)[i];
        }
    }
}

/// Adds a mass-like term Σ_s Jᵀ(s) W_s J(s) to `out` (the mass data of a
/// step matrix), for per-sample 3×3 symmetric weights `weights` given as
/// (sample index, W) in increasing sample order: what implicit contact puts
/// in the step matrix (W = w h (h k + c) n nᵀ).
///
/// With anisotropic weights the suffix moments become matrices,
/// M₀ = Σ W, M₁ = Σ W\[r\]×, N₂ = Σ \[r\]× W \[r\]×, and beyond element Q
/// X_Q += M₀ A_Q − M₁ B_Q, Y_Q += −M₁ᵀ A_Q − N₂ B_Q (with W = ρS w 𝟙 these
/// are the isotropic moments of [`mass_blocks`]); the element's own
/// samples add D_Q += Gᵀ W G, U_Q += W G, V_Q += \[r\]× W G.
pub fn add_sample_weights(
    model: &StrandModel,
    kin: &Kinematics,
    weights: &[(usize, DMat3)],
    out: &mut MassData,
) {
    if weights.is_empty() {
        return;
    }
    let points = model.quadrature.len();
    let (mut m0, mut m1, mut n2) = (DMat3::ZERO, DMat3::ZERO, DMat3::ZERO);
    let mut next = weights.len();
    for e in (0..model.elements()).rev() {
        let jac = &kin.elements[e];
        let x_beyond = m0 * jac.a - m1 * jac.b;
        let y_beyond = -m1.transpose() * jac.a - n2 * jac.b;
        let (mut u, mut v, mut d) = (DMat3::ZERO, DMat3::ZERO, DMat3::ZERO);
        while next > 0 && weights[next - 1].0 >= e * points {
            next -= 1;
            let (i, w) = weights[next];
            let s = &kin.samples[i];
            let r = skew(s.position_m);
            let wg = w * s.jacobian;
            u += wg;
            v += r * wg;
            d += s.jacobian.transpose() * wg;
            m0 += w;
            m1 += w * r;
            n2 += r * w * r;
        }
        out.diagonal[e] += d + jac.a.transpose() * x_beyond + jac.b.transpose() * y_beyond;
        out.own[e] += d;
        out.x[e] += u + x_beyond;
        out.y[e] += v + y_beyond;
    }
}

/// `out` = s × `mass` (every block), reusing `out`'s buffers.
pub fn scaled(mass: &MassData, s: f64, out: &mut MassData) {
    for (dst, src) in [
        (&mut out.diagonal, &mass.diagonal),
        (&mut out.own, &mass.own),
        (&mut out.x, &mass.x),
        (&mut out.y, &mass.y),
    ] {
        dst.clear();
        dst.extend(src.iter().map(|m| *m * s));
    }
}

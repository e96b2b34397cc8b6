//! Dense step in f32 (Bertails 2006): assemble the whole 3N×3N step matrix
//! from the O(N) mass data, factor it by Cholesky and solve. The f32 twin
//! of [`crate::step::solve::dense`], and the arithmetic of the GPU Dense kernel
//! (`shaders/physics/dense.wgsl`, whose CPU twin calls these functions).
//!
//! # How it works
//!
//! 1. Root to tip ([`crate::batch::forward`] with U_Q, V_Q): each element's
//!    A_Q, B_Q and own sums.
//! 2. Tip to root ([`columns`]): the suffix sums give each element's
//!    column factors X_Q = U_Q + X_b and Y_Q = V_Q + Y_b (the moments of
//!    everything element Q moves, itself included), its diagonal block
//!    M_QQ and its generalized force Q_Q, exactly as Exact's sweep 2
//!    ([`super::exact`]) forms them.
//! 3. Assembly ([`assemble`]): with J = A_P − \[r\]×B_P for every sample past
//!    element P, the block of rows P and columns Q > P is
//!    M_PQ = A_Pᵀ X_Q + B_Pᵀ Y_Q (see [`crate::step::mass`]); M is symmetric, so
//!    the block of rows Q and columns P is M_PQᵀ = X_Qᵀ A_P + Y_Qᵀ B_P. The
//!    step matrix is S = s M + diag(D), s = 1 + hν/ρS, D = hγℓ + h²K
//!    ([`crate::batch::suffix::step_terms`]).
//! 4. [`ldlt_solve`]: right-looking square-root-free Cholesky S = L D Lᵀ,
//!    column by column (update the trailing lower triangle from column k),
//!    with the forward substitution L z = rhs folded into the same column
//!    loop, then the back substitution D Lᵀ Δv = z. No pivoting: S is
//!    symmetric positive definite (D > 0). Without the square root a
//!    column needs no scaling pass, which saves the GPU two barriers per
//!    column.
//! 5. Integrate: v ← v + Δv, q ← q + h v.
//!
//! Cost: O(N²) assembly and O(N³) factorisation against Exact's O(N), for
//! the same answer to round-off; memory 9N² numbers per strand. The
//! matrix is stored row-major, `matrix[row * 3N + col]`; the factors
//! overwrite the lower triangle (L d_k below the diagonal, D on it).

use crate::batch::forward::forward;
use crate::batch::lane_model::Constants;
use crate::batch::lanes::Real;
use crate::batch::layout::{ElementData, RootMotion, StepEnv};
use crate::batch::suffix::{Beyond, element_terms, integrate, mass_scale, step_terms};
use crate::batch::vec::{M3, V3};

/// What the tip-to-root sweep leaves for the assembly, per element.
#[derive(Clone, Copy, Debug)]
pub struct DenseColumn<T> {
    /// X_Q = U_Q + X_b = Σ wρS J_Q over every sample element Q moves, kg·m².
    pub x: M3<T>,
    /// Y_Q = V_Q + Y_b = Σ wρS \[r\]×J_Q over the same samples, kg·m³.
    pub y: M3<T>,
    /// M_QQ, kg·m³.
    pub mass_block: M3<T>,
    /// Q_Q, N·m².
    pub force: V3<T>,
}

impl<T: Real> DenseColumn<T> {
    /// All zero.
    pub fn zero() -> Self {
        Self {
            x: M3::zero(),
            y: M3::zero(),
            mass_block: M3::zero(),
            force: V3::zero(),
        }
    }
}

/// A strand's Dense work space: N columns, the 3N×3N matrix, the 3N
/// right-hand side (then solution) and the N step diagonals.
#[derive(Clone, Debug)]
pub struct DenseScratch<T> {
    /// Per element, from [`columns`].
    pub columns: Vec<DenseColumn<T>>,
    /// Row-major 3N×3N: S, then its L D Lᵀ factors in the lower triangle.
    pub matrix: Vec<T>,
    /// 3N: rhs, then y, then Δv.
    pub rhs: Vec<T>,
    /// D_Q = hγℓ + h²K per element.
    pub diagonal: Vec<V3<T>>,
}

impl<T: Real> DenseScratch<T> {
    /// Space for N elements.
    pub fn new(n: usize) -> Self {
        Self {
            columns: vec![DenseColumn::zero(); n],
            matrix: vec![T::splat(0.0); 9 * n * n],
            rhs: vec![T::splat(0.0); 3 * n],
            diagonal: vec![V3::zero(); n],
        }
    }
}

/// Stage 2: tip to root, each element's column factors, diagonal block and
/// force (`elements` from [`forward`] with U and V).
#[inline(always)]
pub fn columns<T: Real>(elements: &[ElementData<T>], out: &mut [DenseColumn<T>]) {
    let mut beyond = Beyond::zero();
    for e in (0..elements.len()).rev() {
        let el = &elements[e];
        let terms = element_terms(el, &beyond);
        out[e] = DenseColumn {
            x: el.u + terms.x_beyond,
            y: el.v + terms.y_beyond,
            mass_block: terms.mass_block,
            force: terms.force,
        };
        beyond.add(el);
    }
}

/// Entry (row, col) of a 3×3 matrix.
#[inline(always)]
fn entry<T: Real>(m: &M3<T>, row: usize, col: usize) -> T {
    let c = [m.c0, m.c1, m.c2][col];
    [c.x, c.y, c.z][row]
}

/// The block of rows `child` and columns `parent` < `child`:
/// M_QP = X_Qᵀ A_P + Y_Qᵀ B_P (the transpose of M_PQ).
#[inline(always)]
pub fn lower_block<T: Real>(parent: &ElementData<T>, child: &DenseColumn<T>) -> M3<T> {
    child.x.t_mul_mat(&parent.a) + child.y.t_mul_mat(&parent.b)
}

/// Stage 3: writes S = s·M + diag(D) into `matrix` (row-major, 3N×3N,
/// both triangles). With s = 1 and D = 0 it writes the mass matrix M.
pub fn assemble<T: Real>(
    elements: &[ElementData<T>],
    columns: &[DenseColumn<T>],
    mass_scale: T,
    diagonal: &[V3<T>],
    matrix: &mut [T],
) {
    let n = elements.len();
    let dim = 3 * n;
    for child in 0..n {
        let block = columns[child]
            .mass_block
            .scale(mass_scale)
            .add_diagonal(diagonal[child]);
        for r in 0..3 {
            for c in 0..3 {
                matrix[(3 * child + r) * dim + 3 * child + c] = entry(&block, r, c);
            }
        }
        for parent in 0..child {
            let block = lower_block(&elements[parent], &columns[child]).scale(mass_scale);
            for r in 0..3 {
                for c in 0..3 {
                    let value = entry(&block, r, c);
                    matrix[(3 * child + r) * dim + 3 * parent + c] = value;
                    matrix[(3 * parent + c) * dim + 3 * child + r] = value;
                }
            }
        }
    }
}

/// Stage 4: solves S x = rhs in place (`rhs` becomes x) by a right-looking
/// square-root-free Cholesky, S = L D Lᵀ with L unit lower triangular, the
/// forward substitution L z = rhs folded into the column loop, then the
/// back substitution D Lᵀ x = z.
///
/// Column k: d_k = S_kk; for every row i > k, c = S_ik / d_k, then
/// S_ij −= c·S_jk for k < j ≤ i and rhs_i −= c·rhs_k. Column k itself is
/// left as it is (S_ik = L_ik d_k) and the diagonal holds D, so a column
/// needs no separate scaling pass: on the GPU that is one barrier per
/// column instead of three. Back substitution, k from the last row up:
/// x_k = rhs_k / d_k, then rhs_i −= S_ki x_k for i < k.
///
/// Reads only the lower triangle of `matrix` (row-major, `dim`×`dim`) and
/// overwrites it with the factors. No pivoting: S is symmetric positive
/// definite (D > 0); a zero or non-finite pivot yields a non-finite
/// result, which the caller sees as a non-finite state.
#[inline(always)]
pub fn ldlt_solve<T: Real>(dim: usize, matrix: &mut [T], rhs: &mut [T]) {
    for k in 0..dim {
        let d_k = matrix[k * dim + k];
        let z_k = rhs[k];
        for i in k + 1..dim {
            let c = matrix[i * dim + k] / d_k;
            for j in k + 1..=i {
                let s_jk = matrix[j * dim + k];
                matrix[i * dim + j] -= c * s_jk;
            }
            rhs[i] -= c * z_k;
        }
    }
    for k in (0..dim).rev() {
        let x_k = rhs[k] / matrix[k * dim + k];
        rhs[k] = x_k;
        for i in 0..k {
            rhs[i] -= matrix[k * dim + i] * x_k;
        }
    }
}

/// One Dense step of every lane's strand; `scratch` has N entries and
/// `dense` was made for N.
pub fn step_dense<T: Real>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    scratch: &mut [ElementData<T>],
    dense: &mut DenseScratch<T>,
) {
    forward::<T, true>(model, env, root, q, v, scratch);
    columns(scratch, &mut dense.columns);
    let n = q.len();
    for e in 0..n {
        let (diagonal, rhs) = step_terms(model, env, e, dense.columns[e].force, q[e], v[e]);
        dense.diagonal[e] = diagonal;
        dense.rhs[3 * e..3 * e + 3].copy_from_slice(&[rhs.x, rhs.y, rhs.z]);
    }
    assemble(
        scratch,
        &dense.columns,
        mass_scale(model, env),
        &dense.diagonal,
        &mut dense.matrix,
    );
    ldlt_solve(3 * n, &mut dense.matrix, &mut dense.rhs);
    for e in 0..n {
        let x = &dense.rhs[3 * e..3 * e + 3];
        integrate(env.h_secs, &mut q[e], &mut v[e], V3::new(x[0], x[1], x[2]));
    }
}

//! The fit's normal equations, assembled point by point, with the points'
//! places eliminated before the solve.
//!
//! The refinement ([`super::refine`]) solves, every iteration,
//! (JᵀJ + λ D) δ = −Jᵀr over the chain's unknowns c (3N strains, 2 root
//! tilts, the element length: 3N + 3) and the places u_i of the M − 1
//! interior points. Two facts about J make this cheap:
//!
//! - **Each point's rows are short.** Point i lies in element e and moves
//!   with the strains of elements 0..=e only, so its 3 rows of J have
//!   3(e + 1) + 3 non-zero columns of c; JᵀJ is summed from these small
//!   blocks (J_iᵀ J_i, symmetric: the upper half is summed, then copied)
//!   instead of multiplying a dense 3M × (3N + 2 + M) matrix by itself.
//! - **Each place is its own point's only.** The column of u_i is ℓ n₀(s_i)
//!   in point i's rows and zero elsewhere, so the places' block of JᵀJ is
//!   diagonal (ℓ², the tangent being a unit vector). Eliminating them
//!   (Schur complement) leaves a system of size 3N + 3 only:
//!   (A − Σ_i b_i b_iᵀ/d_i) δc = −g + Σ_i b_i g_i/d_i with b_i = J_iᵀ ℓn₀
//!   the coupling of place i, g_i = ℓn₀·r_i and d_i its damped diagonal;
//!   then δu_i = −(g_i + b_i·δc)/d_i. Geometrically, each point's residual
//!   is judged only across the strand: sliding along it is the place's
//!   business.
//!
//! The reduced matrix is symmetric positive definite with the damping, and
//! is solved by a dense Cholesky factorization written out here on a flat
//! buffer, reused from iteration to iteration (no allocation per
//! iteration, no generic matrix machinery for a 30 × 30 system).

use glam::DVec3;

use super::curve::UniformHelixChain;
use crate::geometry::helix::skew;

/// Floor of the Marquardt scaling, relative to JᵀJ's largest diagonal
/// entry: keeps unobservable directions (twist of a straight element)
/// damped instead of singular.
const DIAGONAL_FLOOR: f64 = 1e-12;

/// JᵀJ and Jᵀr of one iteration, and the buffers of its solves.
#[derive(Clone, Debug, Default)]
pub struct NormalEquations {
    /// Unknowns of the chain, 3N + 3.
    dim: usize,
    /// JᵀJ over the chain's unknowns, dim × dim, row-major.
    a: Vec<f64>,
    /// Jᵀr over the chain's unknowns.
    g: Vec<f64>,
    /// Per interior point: the coupling b_i (dim), zero past its columns.
    couplings: Vec<f64>,
    /// Per interior point: how many leading strain columns it touches.
    reach: Vec<usize>,
    /// Per interior point: g_i = ℓn₀ · r_i.
    place_g: Vec<f64>,
    /// Σ_i b_i b_iᵀ over the interior points, dim × dim (upper half).
    coupled: Vec<f64>,
    /// Σ_i b_i g_i over the interior points.
    coupled_g: Vec<f64>,
    /// Scratch: one point's column indices in c.
    index: Vec<usize>,
    /// The places' diagonal of JᵀJ, ℓ².
    place_diag: f64,
    /// Scratch: the reduced, damped matrix and its factor.
    reduced: Vec<f64>,
    /// Scratch: the reduced right-hand side, then δc.
    rhs: Vec<f64>,
    /// Scratch: one point's non-zero columns of J.
    columns: Vec<DVec3>,
}

impl NormalEquations {
    /// Assembles JᵀJ and Jᵀr at `chain` with the points at places `u`
    /// (elements) and targets `targets` (relative to the root), and, with
    /// `twist_weight_m` > 0, each element's twist penalty row
    /// w ℓ τ_Q ([`super::refine`]).
    pub fn assemble(
        &mut self,
        chain: &UniformHelixChain,
        u: &[f64],
        targets: &[DVec3],
        twist_weight_m: f64,
    ) {
        let n = chain.elements();
        let m = targets.len();
        let dim = 3 * n + 3;
        self.dim = dim;
        self.a.clear();
        self.a.resize(dim * dim, 0.0);
        self.g.clear();
        self.g.resize(dim, 0.0);
        self.couplings.clear();
        self.couplings.resize(dim * (m - 1), 0.0);
        self.coupled.clear();
        self.coupled.resize(dim * dim, 0.0);
        self.coupled_g.clear();
        self.coupled_g.resize(dim, 0.0);
        self.reach.clear();
        self.place_g.clear();
        let sweep = chain.sweep();
        let l = chain.element_length_m;
        self.place_diag = l * l;
        let (n1, n2) = (chain.root_frame.col(1), chain.root_frame.col(2));
        for (i, (ui, target)) in u.iter().zip(targets).enumerate() {
            let p = chain.point(&sweep, ui * l);
            let x = p.position_m;
            let r = x - *target;
            // Non-zero columns: strains of elements 0..=e, then tilt and ℓ.
            let reach = 3 * (p.element + 1);
            self.columns.clear();
            let mut j_dot_q = DVec3::ZERO;
            let x_skew = skew(x);
            for e in 0..p.element {
                let block = sweep.a[e] - x_skew * sweep.b[e];
                j_dot_q += block * chain.strains_per_m[e];
                self.columns
                    .extend_from_slice(&[block.x_axis, block.y_axis, block.z_axis]);
            }
            let own = p.own_jacobian;
            j_dot_q += own * chain.strains_per_m[p.element];
            self.columns
                .extend_from_slice(&[own.x_axis, own.y_axis, own.z_axis]);
            self.columns
                .extend_from_slice(&[n1.cross(x), n2.cross(x), (x + j_dot_q) / l]);
            self.index.clear();
            self.index.extend(active_columns(reach, dim));
            for (j, cj) in self.columns.iter().enumerate() {
                let row = self.index[j] * dim;
                for (k, ck) in self.columns.iter().enumerate().skip(j) {
                    self.a[row + self.index[k]] += cj.dot(*ck);
                }
                self.g[self.index[j]] += cj.dot(r);
            }
            if i + 1 < m {
                let slide = p.tangent * l;
                let gi = slide.dot(r);
                let b = &mut self.couplings[i * dim..(i + 1) * dim];
                for (j, cj) in self.columns.iter().enumerate() {
                    b[self.index[j]] = cj.dot(slide);
                }
                for (j, &cj) in self.index.iter().enumerate() {
                    let row = cj * dim;
                    for &ck in &self.index[j..] {
                        self.coupled[row + ck] += b[cj] * b[ck];
                    }
                    self.coupled_g[cj] += b[cj] * gi;
                }
                self.reach.push(reach);
                self.place_g.push(gi);
            }
        }
        if twist_weight_m > 0.0 {
            // ρ_Q = w ℓ τ_Q: ∂ρ/∂τ_Q = w ℓ, ∂ρ/∂ℓ = w τ_Q.
            let last = dim - 1;
            for (e, strain) in chain.strains_per_m.iter().enumerate() {
                let (dt, dl) = (twist_weight_m * l, twist_weight_m * strain.x);
                let rho = dt * strain.x;
                let t = 3 * e;
                self.a[t * dim + t] += dt * dt;
                self.a[t * dim + last] += dt * dl;
                self.a[last * dim + last] += dl * dl;
                self.g[t] += dt * rho;
                self.g[last] += dl * rho;
            }
        }
        for j in 0..dim {
            for k in j + 1..dim {
                self.a[k * dim + j] = self.a[j * dim + k];
                self.coupled[k * dim + j] = self.coupled[j * dim + k];
            }
        }
    }

    /// Solves the damped system for `lambda` into `delta` (chain's unknowns,
    /// then the places); false if the reduced matrix is not positive
    /// definite (the caller damps more).
    pub fn solve(&mut self, lambda: f64, delta: &mut Vec<f64>) -> bool {
        let dim = self.dim;
        let places = self.place_g.len();
        let largest = (0..dim)
            .map(|i| self.a[i * dim + i])
            .fold(self.place_diag, f64::max);
        let floor = DIAGONAL_FLOOR * largest;
        // Eliminating the places subtracts Σ b_i b_iᵀ/d and adds Σ b_i g_i/d:
        // every place has the same d, so both sums were taken once, at
        // assembly, and only scale with λ here.
        let d = self.place_diag + lambda * self.place_diag.max(floor);
        self.reduced.clear();
        self.reduced
            .extend(self.a.iter().zip(&self.coupled).map(|(a, p)| a - p / d));
        for i in 0..dim {
            self.reduced[i * dim + i] += lambda * self.a[i * dim + i].max(floor);
        }
        self.rhs.clear();
        self.rhs
            .extend(self.g.iter().zip(&self.coupled_g).map(|(g, p)| p / d - g));
        if !cholesky_in_place(&mut self.reduced, dim) {
            return false;
        }
        cholesky_solve(&self.reduced, dim, &mut self.rhs);
        delta.clear();
        delta.extend_from_slice(&self.rhs);
        for i in 0..places {
            let b = &self.couplings[i * dim..(i + 1) * dim];
            let coupled = dot(b, &self.rhs);
            delta.push(-(self.place_g[i] + coupled) / d);
        }
        delta.iter().all(|x| x.is_finite())
    }
}

/// The columns of c one point touches: strains 0..reach, tilt and ℓ.
fn active_columns(reach: usize, dim: usize) -> impl Iterator<Item = usize> + Clone {
    (0..reach).chain(dim - 3..dim)
}

/// Σ a_k b_k over the shorter of the two.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Overwrites the lower triangle of the symmetric `m` (n × n, row-major)
/// with its Cholesky factor L (m = LLᵀ), row by row (each entry is a dot
/// product of two rows already factored); false if a pivot is not
/// positive.
fn cholesky_in_place(m: &mut [f64], n: usize) -> bool {
    for i in 0..n {
        let (done, rest) = m.split_at_mut(i * n);
        let row_i = &mut rest[..n];
        for j in 0..i {
            let row_j = &done[j * n..j * n + j + 1];
            row_i[j] = (row_i[j] - dot(&row_i[..j], &row_j[..j])) / row_j[j];
        }
        let pivot = row_i[i] - dot(&row_i[..i], &row_i[..i]);
        if pivot.is_nan() || pivot <= 0.0 {
            return false;
        }
        row_i[i] = pivot.sqrt();
    }
    true
}

/// Solves LLᵀ x = b in place, L the lower triangle of `l`.
fn cholesky_solve(l: &[f64], n: usize, b: &mut [f64]) {
    for i in 0..n {
        let row = &l[i * n..i * n + i];
        b[i] = (b[i] - dot(row, &b[..i])) / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut v = b[i];
        for k in i + 1..n {
            v -= l[k * n + i] * b[k];
        }
        b[i] = v / l[i * n + i];
    }
}

//! 3-vectors and 3×3 matrices over any [`Real`]: the few operations the
//! step needs, written so that on [`super::Lanes`] each one is a handful of
//! SIMD instructions. Matrices are column-major like glam's: `m.c1` is the
//! second column and `m * v = c0 v.x + c1 v.y + c2 v.z`.
//!
//! Dot products, matrix products and cross products are chains of fused
//! multiply-adds ([`Real::mul_add`]: one rounding per term instead of two,
//! and one instruction instead of two), and the `*_add` forms start the
//! chain from an accumulator, so `acc + M v` costs no separate add. On an
//! imported groom's frame (Sintel, one thread) fusing the step's products
//! took 17% of its instructions and about 12% of its time.

use std::ops::{Add, AddAssign, Mul, Neg, Sub};

use super::lanes::{Lanes, Real};

/// A 3-vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<T> {
    /// x component.
    pub x: T,
    /// y component.
    pub y: T,
    /// z component.
    pub z: T,
}

impl<T: Real> V3<T> {
    /// A vector from components.
    #[inline(always)]
    pub fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }
    /// The zero vector.
    #[inline(always)]
    pub fn zero() -> Self {
        let z = T::splat(0.0);
        Self::new(z, z, z)
    }
    /// The same constant vector in every lane.
    #[inline(always)]
    pub fn splat(v: [f32; 3]) -> Self {
        Self::new(T::splat(v[0]), T::splat(v[1]), T::splat(v[2]))
    }
    /// The same f64 vector in every lane, each component rounded once to
    /// the type's precision.
    #[inline(always)]
    pub fn splat_f64(v: [f64; 3]) -> Self {
        Self::new(T::splat_f64(v[0]), T::splat_f64(v[1]), T::splat_f64(v[2]))
    }
    /// Dot product.
    #[inline(always)]
    pub fn dot(self, o: Self) -> T {
        self.z.mul_add(o.z, self.y.mul_add(o.y, self.x * o.x))
    }
    /// acc + self·o, fused ([`Real::mul_add`]).
    #[inline(always)]
    pub fn dot_add(self, o: Self, acc: T) -> T {
        self.z
            .mul_add(o.z, self.y.mul_add(o.y, self.x.mul_add(o.x, acc)))
    }
    /// Cross product.
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y.mul_add(o.z, -(self.z * o.y)),
            self.z.mul_add(o.x, -(self.x * o.z)),
            self.x.mul_add(o.y, -(self.y * o.x)),
        )
    }
    /// Scaled by a scalar.
    #[inline(always)]
    pub fn scale(self, s: T) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }
    /// self · s + o, fused per component ([`Real::mul_add`]).
    #[inline(always)]
    pub fn scale_add(self, s: T, o: Self) -> Self {
        Self::new(
            self.x.mul_add(s, o.x),
            self.y.mul_add(s, o.y),
            self.z.mul_add(s, o.z),
        )
    }
}

impl<T: Real> Add for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Real> AddAssign for V3<T> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<T: Real> Sub for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Real> Neg for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

/// A 3×3 matrix by columns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct M3<T> {
    /// First column.
    pub c0: V3<T>,
    /// Second column.
    pub c1: V3<T>,
    /// Third column.
    pub c2: V3<T>,
}

impl<T: Real> M3<T> {
    /// A matrix from its columns.
    #[inline(always)]
    pub fn from_cols(c0: V3<T>, c1: V3<T>, c2: V3<T>) -> Self {
        Self { c0, c1, c2 }
    }
    /// The zero matrix (explicitly zero: no identity default here).
    #[inline(always)]
    pub fn zero() -> Self {
        Self::from_cols(V3::zero(), V3::zero(), V3::zero())
    }
    /// d·I + this matrix.
    #[inline(always)]
    pub fn add_diagonal(self, d: V3<T>) -> Self {
        let mut m = self;
        m.c0.x += d.x;
        m.c1.y += d.y;
        m.c2.z += d.z;
        m
    }
    /// The symmetric matrix with upper triangle `upper` (entries 00, 01,
    /// 02, 11, 12, 22).
    #[inline(always)]
    pub fn symmetric(upper: [T; 6]) -> Self {
        let [m00, m01, m02, m11, m12, m22] = upper;
        Self::from_cols(
            V3::new(m00, m01, m02),
            V3::new(m01, m11, m12),
            V3::new(m02, m12, m22),
        )
    }
    /// The cross-product matrix \[v\]×.
    #[inline(always)]
    pub fn skew(v: V3<T>) -> Self {
        let z = T::splat(0.0);
        Self::from_cols(
            V3::new(z, v.z, -v.y),
            V3::new(-v.z, z, v.x),
            V3::new(v.y, -v.x, z),
        )
    }
    /// The outer product a bᵀ.
    #[inline(always)]
    pub fn outer(a: V3<T>, b: V3<T>) -> Self {
        Self::from_cols(a.scale(b.x), a.scale(b.y), a.scale(b.z))
    }
    /// Every entry scaled.
    #[inline(always)]
    pub fn scale(self, s: T) -> Self {
        Self::from_cols(self.c0.scale(s), self.c1.scale(s), self.c2.scale(s))
    }
    /// self · s + acc, fused entry by entry ([`Real::mul_add`]).
    #[inline(always)]
    pub fn scale_add(self, s: T, acc: Self) -> Self {
        Self::from_cols(
            self.c0.scale_add(s, acc.c0),
            self.c1.scale_add(s, acc.c1),
            self.c2.scale_add(s, acc.c2),
        )
    }
    /// acc + a bᵀ, fused.
    #[inline(always)]
    pub fn outer_add(a: V3<T>, b: V3<T>, acc: Self) -> Self {
        Self::from_cols(
            a.scale_add(b.x, acc.c0),
            a.scale_add(b.y, acc.c1),
            a.scale_add(b.z, acc.c2),
        )
    }
    /// Matrix times vector.
    #[inline(always)]
    pub fn mul_vec(&self, v: V3<T>) -> V3<T> {
        self.c2
            .scale_add(v.z, self.c1.scale_add(v.y, self.c0.scale(v.x)))
    }
    /// acc + M v, fused.
    #[inline(always)]
    pub fn mul_vec_add(&self, v: V3<T>, acc: V3<T>) -> V3<T> {
        self.c2
            .scale_add(v.z, self.c1.scale_add(v.y, self.c0.scale_add(v.x, acc)))
    }
    /// Transpose times vector, Mᵀv.
    #[inline(always)]
    pub fn t_mul_vec(&self, v: V3<T>) -> V3<T> {
        V3::new(self.c0.dot(v), self.c1.dot(v), self.c2.dot(v))
    }
    /// acc + Mᵀv, fused.
    #[inline(always)]
    pub fn t_mul_vec_add(&self, v: V3<T>, acc: V3<T>) -> V3<T> {
        V3::new(
            self.c0.dot_add(v, acc.x),
            self.c1.dot_add(v, acc.y),
            self.c2.dot_add(v, acc.z),
        )
    }
    /// Matrix product.
    #[inline(always)]
    pub fn mul_mat(&self, o: &Self) -> Self {
        Self::from_cols(self.mul_vec(o.c0), self.mul_vec(o.c1), self.mul_vec(o.c2))
    }
    /// acc + M O, fused.
    #[inline(always)]
    pub fn mul_mat_add(&self, o: &Self, acc: &Self) -> Self {
        Self::from_cols(
            self.mul_vec_add(o.c0, acc.c0),
            self.mul_vec_add(o.c1, acc.c1),
            self.mul_vec_add(o.c2, acc.c2),
        )
    }
    /// Mᵀ O.
    #[inline(always)]
    pub fn t_mul_mat(&self, o: &Self) -> Self {
        Self::from_cols(
            self.t_mul_vec(o.c0),
            self.t_mul_vec(o.c1),
            self.t_mul_vec(o.c2),
        )
    }
    /// acc + Mᵀ O, fused.
    #[inline(always)]
    pub fn t_mul_mat_add(&self, o: &Self, acc: &Self) -> Self {
        Self::from_cols(
            self.t_mul_vec_add(o.c0, acc.c0),
            self.t_mul_vec_add(o.c1, acc.c1),
            self.t_mul_vec_add(o.c2, acc.c2),
        )
    }
    /// M Oᵀ = Σ_i m_i o_iᵀ over columns.
    #[inline(always)]
    pub fn mul_mat_t(&self, o: &Self) -> Self {
        Self::outer_add(
            self.c2,
            o.c2,
            Self::outer_add(self.c1, o.c1, Self::outer(self.c0, o.c0)),
        )
    }
    /// acc + M Oᵀ, fused.
    #[inline(always)]
    pub fn mul_mat_t_add(&self, o: &Self, acc: &Self) -> Self {
        Self::outer_add(
            self.c2,
            o.c2,
            Self::outer_add(self.c1, o.c1, Self::outer_add(self.c0, o.c0, *acc)),
        )
    }
    /// \[v\]× M, column by column.
    #[inline(always)]
    pub fn cross_cols(v: V3<T>, m: &Self) -> Self {
        Self::from_cols(v.cross(m.c0), v.cross(m.c1), v.cross(m.c2))
    }
    /// The transpose.
    #[inline(always)]
    pub fn transpose(&self) -> Self {
        Self::from_cols(
            V3::new(self.c0.x, self.c1.x, self.c2.x),
            V3::new(self.c0.y, self.c1.y, self.c2.y),
            V3::new(self.c0.z, self.c1.z, self.c2.z),
        )
    }
    /// The inverse of a matrix with a positive trace (the step's SPD
    /// blocks), by cofactors: rows of M⁻¹ are c1×c2, c2×c0, c0×c1 over the
    /// determinant. The matrix is first scaled by 1/trace: a tip element's
    /// bending block is ρSℓ⁵/20 ≈ 1e-15 kg·m³ and its determinant would
    /// underflow f32 (1e-38) unscaled.
    #[inline(always)]
    pub fn inverse(&self) -> Self {
        let scale = T::splat(1.0) / (self.c0.x + self.c1.y + self.c2.z);
        let m = self.scale(scale);
        let r0 = m.c1.cross(m.c2);
        let r1 = m.c2.cross(m.c0);
        let r2 = m.c0.cross(m.c1);
        let inv_det = scale / m.c0.dot(r0);
        Self::from_cols(r0.scale(inv_det), r1.scale(inv_det), r2.scale(inv_det)).transpose()
    }
}

impl<T: Real> Add for M3<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::from_cols(self.c0 + o.c0, self.c1 + o.c1, self.c2 + o.c2)
    }
}

impl<T: Real> AddAssign for M3<T> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<T: Real> Sub for M3<T> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::from_cols(self.c0 - o.c0, self.c1 - o.c1, self.c2 - o.c2)
    }
}

impl<T: Real> Neg for M3<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::from_cols(-self.c0, -self.c1, -self.c2)
    }
}

impl<T: Real> Mul<V3<T>> for M3<T> {
    type Output = V3<T>;
    #[inline(always)]
    fn mul(self, v: V3<T>) -> V3<T> {
        self.mul_vec(v)
    }
}

/// Sets lane `lane` of `values` (one strand's entries, batch-major) to
/// `lane_values`, entry by entry.
pub fn set_lane(
    values: &mut [V3<Lanes>],
    lane: usize,
    lane_values: impl IntoIterator<Item = [f32; 3]>,
) {
    for (x, [a, b, c]) in values.iter_mut().zip(lane_values) {
        x.x.set_lane(lane, a);
        x.y.set_lane(lane, b);
        x.z.set_lane(lane, c);
    }
}

/// Lane `lane` of `values`, entry by entry.
pub fn lane_of(values: &[V3<Lanes>], lane: usize) -> impl Iterator<Item = [f32; 3]> + '_ {
    values
        .iter()
        .map(move |x| [x.x.lane(lane), x.y.lane(lane), x.z.lane(lane)])
}

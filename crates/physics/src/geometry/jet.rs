//! Second-order forward-mode differentiation in time.
//!
//! A [`Jet`] carries a quantity with its first and second time derivatives
//! (x, ẋ, ẍ). Arithmetic on jets applies the product rule, so running the
//! reconstruction of a strand on jets yields every point's velocity and
//! acceleration exactly, in the same O(N) sweep: the velocity-dependent
//! terms of the dynamics (Coriolis, centrifugal, the root's own motion) then
//! need no hand-derived formula. Seeding the generalized coordinates with
//! (q, q̇, 0) gives ẍ = J̇q̇ + (root terms), the acceleration with q̈ = 0.
//!
//! One generic product covers scalars, vectors and matrices because glam's
//! types already multiply each other: `Jet<DMat3> * Jet<DVec3>` is a
//! `Jet<DVec3>`.

use std::ops::{Add, Mul, Sub};

use glam::{DMat3, DVec3};

/// A value with its first and second time derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet<T> {
    /// x
    pub v: T,
    /// ẋ
    pub d: T,
    /// ẍ
    pub dd: T,
}

impl<T> Jet<T> {
    /// A jet from its three parts.
    pub fn new(v: T, d: T, dd: T) -> Self {
        Self { v, d, dd }
    }

    /// Applies a linear map to each part (valid because the map commutes
    /// with differentiation).
    pub fn map_linear<U>(self, f: impl Fn(T) -> U) -> Jet<U> {
        Jet::new(f(self.v), f(self.d), f(self.dd))
    }
}

impl Jet<f64> {
    /// f(x) given f(x), f'(x) and f''(x): the chain rule to second order,
    /// (f, f'ẋ, f''ẋ² + f'ẍ).
    pub fn chain(self, f: [f64; 3]) -> Jet<f64> {
        Jet::new(f[0], f[1] * self.d, f[2] * self.d * self.d + f[1] * self.dd)
    }
}

impl Jet<DVec3> {
    /// Dot product with the product rule.
    pub fn dot(self, o: Jet<DVec3>) -> Jet<f64> {
        Jet::new(
            self.v.dot(o.v),
            self.d.dot(o.v) + self.v.dot(o.d),
            self.dd.dot(o.v) + 2.0 * self.d.dot(o.d) + self.v.dot(o.dd),
        )
    }

    /// Cross product with the product rule.
    pub fn cross(self, o: Jet<DVec3>) -> Jet<DVec3> {
        Jet::new(
            self.v.cross(o.v),
            self.d.cross(o.v) + self.v.cross(o.d),
            self.dd.cross(o.v) + 2.0 * self.d.cross(o.d) + self.v.cross(o.dd),
        )
    }
}

impl Jet<DMat3> {
    /// A constant matrix.
    pub fn constant(m: DMat3) -> Self {
        Jet::new(m, DMat3::ZERO, DMat3::ZERO)
    }
}

impl<T: Add<Output = T>> Add for Jet<T> {
    type Output = Jet<T>;
    fn add(self, o: Jet<T>) -> Jet<T> {
        Jet::new(self.v + o.v, self.d + o.d, self.dd + o.dd)
    }
}

impl<T: Sub<Output = T>> Sub for Jet<T> {
    type Output = Jet<T>;
    fn sub(self, o: Jet<T>) -> Jet<T> {
        Jet::new(self.v - o.v, self.d - o.d, self.dd - o.dd)
    }
}

/// The product rule: (ab, ȧb + aḃ, äb + 2ȧḃ + ab̈).
impl<A, B, C> Mul<Jet<B>> for Jet<A>
where
    A: Mul<B, Output = C> + Copy,
    B: Copy,
    C: Add<Output = C> + Mul<f64, Output = C>,
{
    type Output = Jet<C>;
    fn mul(self, o: Jet<B>) -> Jet<C> {
        Jet::new(
            self.v * o.v,
            self.d * o.v + self.v * o.d,
            self.dd * o.v + (self.d * o.d) * 2.0 + self.v * o.dd,
        )
    }
}

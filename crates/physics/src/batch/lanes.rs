//! Numbers that hold one value per strand of a batch.
//!
//! The fast path steps [`LANES`] strands at once: every quantity of the
//! step (a strain, a frame entry, a mass moment) is a [`Lanes`], one f32 per
//! strand, and every operation acts lane by lane. The arrays are plain
//! `[f32; LANES]` with element-wise loops, which LLVM turns into SIMD
//! instructions of whatever width the target has (two SSE registers on
//! baseline x86-64, one AVX register with `-C target-cpu=native`), so the
//! code is portable and needs no `unsafe` and no intrinsics.
//!
//! The step's arithmetic is written once, generic over [`Real`], and runs on
//! [`Lanes`] (the batch path) or on plain `f32` (the CPU twins of the GPU
//! kernels, which compute one strand per invocation).

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// Strands per batch: 8 f32 lanes fill one AVX register.
#[cfg(target_feature = "avx")]
pub const LANES: usize = 8;
/// Strands per batch: 4 f32 lanes fill one SSE register (baseline x86-64
/// and other targets); wider lanes would only add register spills. Results
/// do not depend on the width: every lane runs the same IEEE operations.
#[cfg(not(target_feature = "avx"))]
pub const LANES: usize = 4;

/// The scalar operations the step's arithmetic needs.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
{
    /// Lanes in one value (1 for `f32`).
    const WIDTH: usize;
    /// The same value in every lane.
    fn splat(x: f32) -> Self;
    /// Lane `i` from `f(i)`, for `i` in `0..WIDTH`.
    fn from_fn(f: impl Fn(usize) -> f32) -> Self;
    /// The value of lane `i`.
    fn lane(self, i: usize) -> f32;
    /// Square root, lane by lane.
    fn sqrt(self) -> Self;
    /// (sin, cos), lane by lane.
    fn sin_cos(self) -> (Self, Self);
    /// Lane-wise maximum.
    fn max(self, o: Self) -> Self;
    /// Whether every lane is below `limit`.
    fn all_below(self, limit: f32) -> bool;
    /// Per lane: `if_below` where `self < limit`, else `otherwise`.
    fn select_below(self, limit: f32, if_below: Self, otherwise: Self) -> Self;
}

impl Real for f32 {
    const WIDTH: usize = 1;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        x
    }
    #[inline(always)]
    fn from_fn(f: impl Fn(usize) -> f32) -> Self {
        f(0)
    }
    #[inline(always)]
    fn lane(self, _i: usize) -> f32 {
        self
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        f32::sin_cos(self)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        f32::max(self, o)
    }
    #[inline(always)]
    fn all_below(self, limit: f32) -> bool {
        self < limit
    }
    #[inline(always)]
    fn select_below(self, limit: f32, if_below: Self, otherwise: Self) -> Self {
        if self < limit { if_below } else { otherwise }
    }
}

/// One f32 per strand of a batch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lanes(pub [f32; LANES]);

impl Default for Lanes {
    fn default() -> Self {
        Lanes([0.0; LANES])
    }
}

impl Lanes {
    #[inline(always)]
    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        let mut out = self.0;
        for x in &mut out {
            *x = f(*x);
        }
        Lanes(out)
    }

    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        let mut out = self.0;
        for (x, y) in out.iter_mut().zip(o.0) {
            *x = f(*x, y);
        }
        Lanes(out)
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $assign_trait:ident, $assign:ident, $op:tt) => {
        impl $trait for Lanes {
            type Output = Lanes;
            #[inline(always)]
            fn $method(self, o: Lanes) -> Lanes {
                self.zip(o, |a, b| a $op b)
            }
        }
        impl $assign_trait for Lanes {
            #[inline(always)]
            fn $assign(&mut self, o: Lanes) {
                *self = self.zip(o, |a, b| a $op b);
            }
        }
    };
}

lane_op!(Add, add, AddAssign, add_assign, +);
lane_op!(Sub, sub, SubAssign, sub_assign, -);

impl Mul for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn mul(self, o: Lanes) -> Lanes {
        self.zip(o, |a, b| a * b)
    }
}

impl Div for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn div(self, o: Lanes) -> Lanes {
        self.zip(o, |a, b| a / b)
    }
}

impl Neg for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn neg(self) -> Lanes {
        self.map(|a| -a)
    }
}

impl Real for Lanes {
    const WIDTH: usize = LANES;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Lanes([x; LANES])
    }
    #[inline(always)]
    fn from_fn(f: impl Fn(usize) -> f32) -> Self {
        Lanes(std::array::from_fn(f))
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f32 {
        self.0[i]
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f32::sqrt)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        (self.map(f32::sin), self.map(f32::cos))
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        self.zip(o, f32::max)
    }
    #[inline(always)]
    fn all_below(self, limit: f32) -> bool {
        self.0.iter().all(|x| *x < limit)
    }
    #[inline(always)]
    fn select_below(self, limit: f32, if_below: Self, otherwise: Self) -> Self {
        let mut out = otherwise.0;
        for ((o, y), b) in out.iter_mut().zip(self.0).zip(if_below.0) {
            if y < limit {
                *o = b;
            }
        }
        Lanes(out)
    }
}

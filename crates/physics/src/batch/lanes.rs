//! Numbers that hold one value per strand of a batch.
//!
//! The fast path steps [`LANES`] strands at once: every quantity of the
//! step (a strain, a frame entry, a mass moment) is a [`Lanes`], one f32 per
//! strand, and every operation acts lane by lane. [`Lanes`] wraps
//! `wide::f32x8`, whose operators are explicit SIMD instructions of the
//! width the build enables (one AVX register, or two SSE registers on
//! baseline x86-64; a portable fallback elsewhere), with no `unsafe` here.
//!
//! The step's arithmetic is written once, generic over [`Real`], and runs on
//! [`Lanes`] (the batch path) or on plain `f32` (the CPU twins of the GPU
//! kernels, which compute one strand per invocation).

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use wide::{f32x8, f64x4};

/// Strands per batch: one [`wide::f32x8`]. The width is the same on every
/// build, so the data layout is too; results do not depend on the
/// instruction set, since every lane runs the same IEEE operations.
pub const LANES: usize = 8;

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
    /// The same value in every lane, from an f64 constant: rounded once to
    /// the type's own precision (kept exact by `f64`).
    fn splat_f64(x: f64) -> Self;
    /// Terms of the helix coefficients' power series that this precision
    /// needs below [`crate::batch::geometry::SERIES_LIMIT_Y`]: the first
    /// neglected term, 16ⁿ/(2n + 1)!, under the type's round-off.
    const SERIES_TERMS: usize;
    /// Lane `i` from `f(i)`, for `i` in `0..WIDTH`.
    fn from_fn(f: impl Fn(usize) -> f32) -> Self;
    /// Lane `i` from `f(i)`, rounded once to the type's own precision.
    fn from_fn_f64(f: impl Fn(usize) -> f64) -> Self;
    /// The value of lane `i`.
    fn lane(self, i: usize) -> f32;
    /// The value of lane `i`, in f64 (exact).
    fn lane_f64(self, i: usize) -> f64;
    /// Square root, lane by lane.
    fn sqrt(self) -> Self;
    /// (sin, cos), lane by lane.
    fn sin_cos(self) -> (Self, Self);
    /// self · a + b, lane by lane: with one rounding (a fused multiply-add)
    /// where the build has FMA, else a multiply and an add ([`FUSED`]).
    fn mul_add(self, a: Self, b: Self) -> Self;
    /// Lane-wise maximum.
    fn max(self, o: Self) -> Self;
    /// Lane-wise floor (largest integer not above).
    fn floor(self) -> Self;
    /// Whether every lane is below `limit`.
    fn all_below(self, limit: f32) -> bool;
    /// Per lane: `if_below` where `self < limit`, else `otherwise`.
    fn select_below(self, limit: f32, if_below: Self, otherwise: Self) -> Self;
    /// Per lane: `if_greater` where `self > than` (a per-lane bound),
    /// else `otherwise` (a NaN compares false).
    fn select_greater(self, than: Self, if_greater: Self, otherwise: Self) -> Self;
}

impl Real for f32 {
    const WIDTH: usize = 1;
    const SERIES_TERMS: usize = 11;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        x
    }
    #[inline(always)]
    fn splat_f64(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn from_fn(f: impl Fn(usize) -> f32) -> Self {
        f(0)
    }
    #[inline(always)]
    fn from_fn_f64(f: impl Fn(usize) -> f64) -> Self {
        f(0) as f32
    }
    #[inline(always)]
    fn lane(self, _i: usize) -> f32 {
        self
    }
    #[inline(always)]
    fn lane_f64(self, _i: usize) -> f64 {
        f64::from(self)
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
    fn mul_add(self, a: Self, b: Self) -> Self {
        if FUSED {
            f32::mul_add(self, a, b)
        } else {
            self * a + b
        }
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        f32::max(self, o)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        f32::floor(self)
    }
    #[inline(always)]
    fn all_below(self, limit: f32) -> bool {
        self < limit
    }
    #[inline(always)]
    fn select_below(self, limit: f32, if_below: Self, otherwise: Self) -> Self {
        if self < limit { if_below } else { otherwise }
    }
    #[inline(always)]
    fn select_greater(self, than: Self, if_greater: Self, otherwise: Self) -> Self {
        if self > than { if_greater } else { otherwise }
    }
}

/// The step's arithmetic in f64, one strand at a time: the f64 reference's
/// precision, with constants given in f64 ([`Real::splat_f64`]).
impl Real for f64 {
    const WIDTH: usize = 1;
    const SERIES_TERMS: usize = 16;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        x as f64
    }
    #[inline(always)]
    fn splat_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn from_fn(f: impl Fn(usize) -> f32) -> Self {
        f(0) as f64
    }
    #[inline(always)]
    fn from_fn_f64(f: impl Fn(usize) -> f64) -> Self {
        f(0)
    }
    #[inline(always)]
    fn lane(self, _i: usize) -> f32 {
        self as f32
    }
    #[inline(always)]
    fn lane_f64(self, _i: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        f64::sin_cos(self)
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        if FUSED {
            f64::mul_add(self, a, b)
        } else {
            self * a + b
        }
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        f64::max(self, o)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        f64::floor(self)
    }
    #[inline(always)]
    fn all_below(self, limit: f32) -> bool {
        self < limit as f64
    }
    #[inline(always)]
    fn select_below(self, limit: f32, if_below: Self, otherwise: Self) -> Self {
        if self < limit as f64 {
            if_below
        } else {
            otherwise
        }
    }
    #[inline(always)]
    fn select_greater(self, than: Self, if_greater: Self, otherwise: Self) -> Self {
        if self > than { if_greater } else { otherwise }
    }
}

/// One f32 per strand of a batch: a [`wide::f32x8`], which is one AVX
/// register where the build enables AVX (see `.cargo/config.toml`) and two
/// SSE registers otherwise. Its operators are explicit SIMD instructions,
/// so the step vectorises whatever LLVM's auto-vectoriser makes of a very
/// long straight-line function (it gives up on plain `[f32; 8]` arrays
/// there: measured, no faster than 4 lanes).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Lanes(pub f32x8);

impl Lanes {
    /// The lanes as an array.
    #[inline(always)]
    pub fn to_array(self) -> [f32; LANES] {
        self.0.to_array()
    }

    /// Lanes from an array.
    #[inline(always)]
    pub fn from_array(a: [f32; LANES]) -> Self {
        Lanes(f32x8::new(a))
    }

    /// Sets lane `i` to `x`.
    #[inline(always)]
    pub fn set_lane(&mut self, i: usize, x: f32) {
        self.0.as_mut_array()[i] = x;
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $assign_trait:ident, $assign:ident, $op:tt) => {
        impl $trait for Lanes {
            type Output = Lanes;
            #[inline(always)]
            fn $method(self, o: Lanes) -> Lanes {
                Lanes(self.0 $op o.0)
            }
        }
        impl $assign_trait for Lanes {
            #[inline(always)]
            fn $assign(&mut self, o: Lanes) {
                self.0 = self.0 $op o.0;
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
        Lanes(self.0 * o.0)
    }
}

impl Div for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn div(self, o: Lanes) -> Lanes {
        Lanes(self.0 / o.0)
    }
}

impl Neg for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn neg(self) -> Lanes {
        Lanes(-self.0)
    }
}

impl Real for Lanes {
    const WIDTH: usize = LANES;
    const SERIES_TERMS: usize = 11;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Lanes(f32x8::splat(x))
    }
    #[inline(always)]
    fn splat_f64(x: f64) -> Self {
        Lanes(f32x8::splat(x as f32))
    }
    #[inline(always)]
    fn from_fn(f: impl Fn(usize) -> f32) -> Self {
        Self::from_array(std::array::from_fn(f))
    }
    #[inline(always)]
    fn from_fn_f64(f: impl Fn(usize) -> f64) -> Self {
        Self::from_array(std::array::from_fn(|i| f(i) as f32))
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f32 {
        self.0.as_array()[i]
    }
    #[inline(always)]
    fn lane_f64(self, i: usize) -> f64 {
        f64::from(self.0.as_array()[i])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Lanes(self.0.sqrt())
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        // In f64 lanes, rounded to f32 once: wide's f64x4 sin/cos (Agner
        // Fog's vector class library: a three-part reduction by π/2 and
        // degree-13 polynomials) is within about an ulp of f64, far below
        // half an f32 ulp, so each result is the f32 nearest the true value
        // but in the rarest ties, as the standard library's f32 functions
        // give (wide's f32x8 sin/cos, a few f32 ulps off, would differ
        // from the f64 reference by more than f32 round-off). Only batches
        // with a tight coil (y ≥ 4 in some lane) get here; lane by lane
        // with the standard library, sin and cos were 6% of an imported
        // groom's frame (perf).
        let a = self.to_array();
        let half = |i: usize| f64x4::from([0, 1, 2, 3].map(|j| f64::from(a[i + j])));
        let (sin_low, cos_low) = half(0).sin_cos();
        let (sin_high, cos_high) = half(4).sin_cos();
        let join = |low: f64x4, high: f64x4| {
            let (low, high) = (low.to_array(), high.to_array());
            Self::from_array(std::array::from_fn(|i| {
                (if i < 4 { low[i] } else { high[i - 4] }) as f32
            }))
        };
        (join(sin_low, sin_high), join(cos_low, cos_high))
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        fused_mul_add(self, a, b)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        Lanes(self.0.max(o.0))
    }
    #[inline(always)]
    fn floor(self) -> Self {
        Lanes(self.0.floor())
    }
    #[inline(always)]
    fn all_below(self, limit: f32) -> bool {
        self.0.simd_lt(f32x8::splat(limit)).all()
    }
    #[inline(always)]
    fn select_below(self, limit: f32, if_below: Self, otherwise: Self) -> Self {
        Lanes(
            self.0
                .simd_lt(f32x8::splat(limit))
                .select(if_below.0, otherwise.0),
        )
    }
    #[inline(always)]
    fn select_greater(self, than: Self, if_greater: Self, otherwise: Self) -> Self {
        Lanes(self.0.simd_gt(than.0).select(if_greater.0, otherwise.0))
    }
}

/// Whether [`Real::mul_add`] is fused on this build: where the build
/// enables FMA (`.cargo/config.toml`'s native target, on any x86-64 since
/// 2013), one FMA instruction; elsewhere a multiply and an
/// add, whose last bits differ. A fused product in software instead (each
/// lane's `f32::mul_add`, a call into libm's correctly rounded `fmaf`)
/// would keep the bits the same on every build, and was tried: on a
/// baseline x86-64 build (`-C target-cpu=x86-64`) the Sintel groom's
/// frame took 942 ms on one thread (`fmaf` 70% of it) against 33.6 ms
/// unfused (`bench --study groom --quick`; 15 ms natively). So results
/// agree between builds with and without FMA to round-off, not bit for
/// bit.
pub const FUSED: bool = cfg!(target_feature = "fma");

/// self · a + b per lane: one FMA instruction where the build has FMA,
/// else a multiply and an add ([`FUSED`]).
#[inline(always)]
fn fused_mul_add(x: Lanes, a: Lanes, b: Lanes) -> Lanes {
    #[cfg(target_feature = "fma")]
    {
        Lanes(x.0.mul_add(a.0, b.0))
    }
    #[cfg(not(target_feature = "fma"))]
    {
        x * a + b
    }
}

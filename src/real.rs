//! `Real`: the two precisions the scalar kernels run in (f64 for the oracle, f32 to measure the
//! SIMD speedup against scalar code of the same precision). Only the operations the kernels use.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A floating-point scalar (implemented for f32 and f64) that the generic scalar kernels are
/// written over: arithmetic, comparison, a few constants, conversion and `sqrt`.
pub trait Real:
    Copy
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + std::fmt::Debug
    + Send
    + Sync
    + 'static
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 0.5.
    const HALF: Self;
    /// Positive infinity: the starting nearest distance, and a bound hit distances stay below.
    const INFINITY: Self;
    /// Unit roundoff u = 2^-p (p = 24 for f32, 53 for f64).
    const UNIT_ROUNDOFF: Self;
    /// Converts from f64, rounding to nearest for f32.
    fn from_f64(v: f64) -> Self;
    /// Converts to f64 (exact for both precisions).
    fn to_f64(self) -> f64;
    /// The correctly rounded square root.
    fn sqrt(self) -> Self;
}

impl Real for f32 {
    const ZERO: f32 = 0.0;
    const ONE: f32 = 1.0;
    const TWO: f32 = 2.0;
    const HALF: f32 = 0.5;
    const INFINITY: f32 = f32::INFINITY;
    const UNIT_ROUNDOFF: f32 = f32::EPSILON / 2.0;
    #[inline]
    fn from_f64(v: f64) -> f32 {
        v as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn sqrt(self) -> f32 {
        f32::sqrt(self)
    }
}

impl Real for f64 {
    const ZERO: f64 = 0.0;
    const ONE: f64 = 1.0;
    const TWO: f64 = 2.0;
    const HALF: f64 = 0.5;
    const INFINITY: f64 = f64::INFINITY;
    const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;
    #[inline]
    fn from_f64(v: f64) -> f64 {
        v
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
}

/// A 3-vector in either precision, as the scalar kernels see it.
pub type V3<T> = [T; 3];

/// Dot product, summed left to right: ((a0*b0 + a1*b1) + a2*b2). The 8-lane kernels sum in the
/// same order with no fused multiply-add, so f32 scalar and f32 packet results are bit-identical.
#[inline]
pub fn dot<T: Real>(a: V3<T>, b: V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Rounds an f64 vector to `T`.
#[inline]
pub fn v3<T: Real>(v: glam::DVec3) -> V3<T> {
    [T::from_f64(v.x), T::from_f64(v.y), T::from_f64(v.z)]
}

/// The largest f32 not above `x` (rounding toward -inf): a lower bound that stays one.
#[inline]
pub fn f32_down(x: f64) -> f32 {
    let f = x as f32;
    if f as f64 > x { f.next_down() } else { f }
}

/// The smallest f32 not below `x` (rounding toward +inf): an upper bound that stays one.
#[inline]
pub fn f32_up(x: f64) -> f32 {
    let f = x as f32;
    if (f as f64) < x { f.next_up() } else { f }
}

/// The f32 unit roundoff u = 2^-24 as an f64: the unit of every f32 error bound (the kernels,
/// the tiles' margins, `--precision auto`'s limits, `compare`'s edge band).
pub const U32: f64 = <f32 as Real>::UNIT_ROUNDOFF as f64;

/// The f64 unit roundoff u = 2^-53: the unit of the f64 setup's error bounds (the range
/// check, the clusters' bounds).
pub const U64: f64 = <f64 as Real>::UNIT_ROUNDOFF;

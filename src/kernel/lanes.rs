//! One formula, two lane types: the packet kernels (`polygon_lanes`, `sphere_lanes`, [`HitLanes`])
//! are written once over [`Lanes`], which `wide::f32x8` (the default 8-ray packets) and
//! `wide::f64x4` (the f64 packets of `kernel::wide64`) implement with their own
//! instructions. Each generic function is `#[inline(always)]` and monomorphised per lane type,
//! so the f32x8 code is what it was when written for f32x8 alone (the render bench and
//! `lanecast -time` give the same figures as the f32x8-only code did; docs/architecture.md, "The kernels").

use crate::real::Real;
use std::ops::{Add, BitAnd, BitAndAssign, BitOr, Div, Mul, Sub};
use wide::{f32x8, f64x4};

/// A SIMD vector of rays' values: arithmetic lane by lane, comparisons giving lane masks
/// (all bits set where true), and the mask operations the kernels use.
pub trait Lanes:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + BitAnd<Output = Self>
    + BitAndAssign
    + BitOr<Output = Self>
{
    /// The scalar of one lane (f32 or f64), in which per-primitive constants are stored.
    type Scalar: Real;
    /// Every lane zero.
    const ZERO: Self;
    /// `x` in every lane.
    fn splat(x: Self::Scalar) -> Self;
    /// Mask of `self >= o` (false for NaN).
    fn simd_ge(self, o: Self) -> Self;
    /// Mask of `self > o` (false for NaN).
    fn simd_gt(self, o: Self) -> Self;
    /// Mask of `self < o` (false for NaN).
    fn simd_lt(self, o: Self) -> Self;
    /// Mask of `self == o` (false for NaN).
    fn simd_eq(self, o: Self) -> Self;
    /// Whether any lane of the mask is set.
    fn any(self) -> bool;
    /// Lane by lane, `t` where the mask `self` is set, else `f`.
    fn select(self, t: Self, f: Self) -> Self;
    /// Square root, correctly rounded, lane by lane.
    fn sqrt(self) -> Self;
    /// Lane-by-lane minimum (either operand where one is NaN: the BVH slab test's use).
    fn fast_min(self, o: Self) -> Self;
    /// Lane-by-lane maximum (either operand where one is NaN).
    fn fast_max(self, o: Self) -> Self;
    /// Absolute value, lane by lane.
    fn abs(self) -> Self;
    /// The value of the first lane.
    fn first(self) -> Self::Scalar;
}

macro_rules! lanes {
    ($v:ty, $s:ty) => {
        impl Lanes for $v {
            type Scalar = $s;
            const ZERO: Self = <$v>::ZERO;
            #[inline(always)]
            fn splat(x: $s) -> Self {
                <$v>::splat(x)
            }
            #[inline(always)]
            fn simd_ge(self, o: Self) -> Self {
                <$v>::simd_ge(self, o)
            }
            #[inline(always)]
            fn simd_gt(self, o: Self) -> Self {
                <$v>::simd_gt(self, o)
            }
            #[inline(always)]
            fn simd_lt(self, o: Self) -> Self {
                <$v>::simd_lt(self, o)
            }
            #[inline(always)]
            fn simd_eq(self, o: Self) -> Self {
                <$v>::simd_eq(self, o)
            }
            #[inline(always)]
            fn any(self) -> bool {
                <$v>::any(self)
            }
            #[inline(always)]
            fn select(self, t: Self, f: Self) -> Self {
                <$v>::select(self, t, f)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$v>::sqrt(self)
            }
            #[inline(always)]
            fn fast_min(self, o: Self) -> Self {
                <$v>::fast_min(self, o)
            }
            #[inline(always)]
            fn fast_max(self, o: Self) -> Self {
                <$v>::fast_max(self, o)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$v>::abs(self)
            }
            #[inline(always)]
            fn first(self) -> $s {
                self.to_array()[0]
            }
        }
    };
}

lanes!(f32x8, f32);
lanes!(f64x4, f64);

/// A dot product of broadcast constants `n` with lane vectors `d`, summed in the order of
/// `real::dot` (x, then y, then z; no fused multiply-add).
#[inline(always)]
pub fn dot_splat<L: Lanes>(n: &[L::Scalar; 3], d: &[L; 3]) -> L {
    L::splat(n[0]) * d[0] + L::splat(n[1]) * d[1] + L::splat(n[2]) * d[2]
}

/// The nearest hits of a packet's rays: ids carried in the lanes' own type (exact: at most
/// `limits::MAX_PRIMITIVES` = 2^24 ids), so every mask stays in one domain. An inactive lane (a
/// pixel past the image border) starts with `t = 0`: no hit can be closer, so the lane comes
/// back unchanged. The rule is `kernel::closer`, lane by lane.
#[derive(Debug, Clone, Copy)]
pub struct HitLanes<L> {
    /// Distance of each lane's nearest hit so far (+inf: none yet; 0: inactive lane).
    pub t: L,
    /// Primitive id of each lane's nearest hit (-1: none).
    pub id: L,
}

impl<L: Lanes> HitLanes<L> {
    /// No hit yet in the `active` lanes; the others are frozen.
    #[inline(always)]
    pub fn new(active: L) -> HitLanes<L> {
        HitLanes {
            t: active.select(L::splat(L::Scalar::INFINITY), L::ZERO),
            id: L::splat(-L::Scalar::ONE),
        }
    }

    /// [`crate::kernel::closer`], lane by lane, for candidate distances `t` of primitive `id`
    /// in the lanes of `mask`. Returns the mask of the lanes it took (callers that track more
    /// about the winner use it; the others ignore it, and it compiles away).
    #[inline(always)]
    pub fn update(&mut self, mask: L, t: L, id: L::Scalar) -> L {
        let id = L::splat(id);
        let wins = t.simd_lt(self.t) | (t.simd_eq(self.t) & id.simd_lt(self.id));
        let take = mask & t.simd_gt(L::ZERO) & wins;
        self.t = take.select(t, self.t);
        self.id = take.select(id, self.id);
        take
    }
}

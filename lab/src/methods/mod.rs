//! The intersection methods other than lanecast's own, measured against the default kernels
//! (`lanecast::experimental::kernel::{polygon, sphere}`) and the f64 oracle by this lab
//! (`cargo bench -p lanecast-lab --bench lab`, `lab-render`). They live here, not in the engine:
//! the product renders with its own kernels only. One file per method family, each with its 1-lane form (`*_x1`, generic over
//! [`Real`]: f32 and f64) and its 8-lane form (`*_x8`, `wide::f32x8`) side by side under a
//! header: formula, source, assumptions, precision, where it fails, which test proves it.
//!
//! - `mt.rs`: Möller–Trumbore (1997), triangles.
//! - `woop.rs`: Woop, Benthin, Wald (2013), watertight triangles, with the double-precision
//!   fallback for edge functions that are exactly zero.
//! - `plane.rs`: the seed's plane hit + inside test by edge cross products.
//! - `sphere_naive.rs`: the textbook quadratic b^2 - 4ac.
//! - `world.rs`: the default methods' constants computed the classic way, in f32 from world
//!   coordinates rounded to f32 (what eye-relative f64 setup avoids).
//!
//! All rays start at the eye and have unit directions; every per-primitive constant is stored
//! relative to the eye (computed in f64, then rounded) unless the file says otherwise. Quads are
//! two triangles (A,B,C) and (A,C,D) for the triangle-only methods ([`quad_split`]).

// `!(x >= 0)` is deliberate throughout: a NaN must fail every test, as it does in the
// 8-lane masks.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod mt;
pub mod plane;
pub mod sphere_naive;
pub mod woop;
pub mod world;

use glam::DVec3;
use lanecast::experimental::real::{Real, V3};
use wide::f32x8;

/// The two triangles (A,B,C) and (A,C,D) of a quad given in perimeter order.
pub fn quad_split(v: &[DVec3; 4]) -> [[DVec3; 3]; 2] {
    [[v[0], v[1], v[2]], [v[0], v[2], v[3]]]
}

/// a x b, component order (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0); [`cross8`] is the same.
#[inline(always)]
pub fn cross<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// a - b.
#[inline(always)]
pub fn sub<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// |x| for the generic scalar forms.
#[inline(always)]
pub fn abs<T: Real>(x: T) -> T {
    if x < T::ZERO { -x } else { x }
}

/// A constant vector broadcast to eight lanes.
#[inline(always)]
pub fn splat3(v: V3<f32>) -> [f32x8; 3] {
    v.map(f32x8::splat)
}

/// [`lanecast::experimental::real::dot`] in eight lanes, same summation order.
#[inline(always)]
pub fn dot8(a: &[f32x8; 3], b: &[f32x8; 3]) -> f32x8 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// [`cross`] in eight lanes.
#[inline(always)]
pub fn cross8(a: &[f32x8; 3], b: &[f32x8; 3]) -> [f32x8; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

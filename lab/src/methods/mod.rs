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
//! two triangles (A,B,C) and (A,C,D) for the triangle-only methods ([`TwoTriangles`]).
//!
//! A method re-implements some of lanecast's primitive families: each such family is an [`Own`]
//! kernel in the method's file, naming the family it replaces; the brute-force drivers
//! (`kits.rs`) run every other family through lanecast's own kernel.

// `!(x >= 0)` is deliberate throughout: a NaN must fail every test, as it does in the
// 8-lane masks.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod mt;
pub mod plane;
pub mod sphere_naive;
pub mod woop;
pub mod world;

pub use mt::MtOwn;
pub use plane::PlaneOwn;
pub use sphere_naive::NaiveOwn;
pub use woop::{WoopOwn, WoopRays};
pub use world::WorldOwn;

use glam::DVec3;
use lanecast::experimental::kernel::{Family, Quad};
use lanecast::experimental::real::{Real, V3};
use std::marker::PhantomData;
use wide::f32x8;

/// What a method's own kernels read of each ray, computed once per ray (or packet) and shared by
/// every family the method re-implements.
pub trait Rays: 'static {
    /// One ray's data.
    type R1;
    /// Eight rays' data.
    type R8;
    /// The data of unit direction `d`.
    fn ray1(d: V3<f32>) -> Self::R1;
    /// The data of eight unit directions `d`.
    fn ray8(d: &[f32x8; 3]) -> Self::R8;
}

/// The unit direction itself: the per-ray data of every method but the watertight one.
pub struct Direction;
impl Rays for Direction {
    type R1 = V3<f32>;
    type R8 = [f32x8; 3];
    #[inline(always)]
    fn ray1(d: V3<f32>) -> V3<f32> {
        d
    }
    #[inline(always)]
    fn ray8(d: &[f32x8; 3]) -> [f32x8; 3] {
        *d
    }
}

/// A method's own kernel for one of lanecast's families ([`Own::Family`]), replacing lanecast's
/// kernel for it: the constants (setup and precision the method's own) and the 1- and 8-lane
/// forms.
pub trait Own: 'static {
    /// The family it re-implements.
    type Family: Family;
    /// The per-ray data its kernels read.
    type Rays: Rays;
    /// One primitive's constants, in f32.
    type K: Copy + Send + Sync;
    /// The constants of `g` seen from `eye`; `None`: it covers no pixel.
    fn setup(g: &<Self::Family as Family>::Geometry, eye: DVec3) -> Option<Self::K>;
    /// Distance along ray `r` from the eye to the hit, when it is ahead of the eye.
    fn x1(k: &Self::K, r: &<Self::Rays as Rays>::R1) -> Option<f32>;
    /// [`Own::x1`] for eight rays: `None` when no lane can hit, else the lane mask and
    /// distances (the caller keeps the lanes with 0 < t).
    fn x8(k: &Self::K, r: &<Self::Rays as Rays>::R8) -> Option<(f32x8, f32x8)>;
}

/// The two triangles (A,B,C) and (A,C,D) of a quad given in perimeter order.
pub fn quad_split(v: &[DVec3; 4]) -> [[DVec3; 3]; 2] {
    [[v[0], v[1], v[2]], [v[0], v[2], v[3]]]
}

/// A triangle-only method's quads: each quad as its two triangles ([`quad_split`]) through the
/// method's triangle kernel `T`, the nearer hit kept.
pub struct TwoTriangles<T>(PhantomData<T>);

impl<T: Own> Own for TwoTriangles<T>
where
    T::Family: Family<Geometry = [DVec3; 3]>,
{
    type Family = Quad;
    type Rays = T::Rays;
    type K = [T::K; 2];
    fn setup(v: &[DVec3; 4], eye: DVec3) -> Option<Self::K> {
        let [a, b] = quad_split(v).map(|t| T::setup(&t, eye));
        Some([a?, b?])
    }
    fn x1(k: &Self::K, r: &<T::Rays as Rays>::R1) -> Option<f32> {
        nearer(T::x1(&k[0], r), T::x1(&k[1], r))
    }
    #[inline(always)]
    fn x8(k: &Self::K, r: &<T::Rays as Rays>::R8) -> Option<(f32x8, f32x8)> {
        nearer8(T::x8(&k[0], r), T::x8(&k[1], r))
    }
}

/// The nearer of two optional positive distances (the quad of two triangles).
#[inline(always)]
fn nearer(a: Option<f32>, b: Option<f32>) -> Option<f32> {
    match (a, b) {
        (Some(a), Some(b)) => Some(if b < a { b } else { a }),
        (a, None) => a,
        (None, b) => b,
    }
}

/// [`nearer`] lane by lane.
#[inline(always)]
fn nearer8(a: Option<(f32x8, f32x8)>, b: Option<(f32x8, f32x8)>) -> Option<(f32x8, f32x8)> {
    let zero = f32x8::ZERO;
    let inf = f32x8::splat(f32::INFINITY);
    let keep = |(m, t): (f32x8, f32x8)| m & t.simd_gt(zero) & t.simd_lt(inf);
    match (a, b) {
        (Some(a), Some(b)) => {
            let (ma, mb) = (keep(a), keep(b));
            let take_b = mb & (!ma | b.1.simd_lt(a.1));
            Some((ma | mb, take_b.select(b.1, a.1)))
        }
        (a, None) => a,
        (None, b) => b,
    }
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

//! The seed's ray/triangle test: intersect the triangle's plane, then decide
//! inside/outside by the sign of three determinants (edge cross products against the normal).
//! The classic textbook form (e.g. Shirley & Marschner, "Fundamentals of Computer Graphics",
//! 4.4.2, "inside-outside test").
//!
//! Per triangle (A, B, C relative to the eye O, computed in f64 and rounded):
//! `n = (B - A) x (C - A)` (unit), `h = n . A`, edges `E0 = B - A, E1 = C - B, E2 = A - C`.
//! Per ray (unit direction d):
//! ```text
//! t = h / (n . d)                          the plane hit; a hit needs t > 0
//! P = t d                                  the hit point
//! inside iff (E_i x (P - V_i)) . n >= 0    for i = 0, 1, 2 (V_0 = A, V_1 = B, V_2 = C)
//! ```
//! No tolerance: the determinants are compared with exact 0.
//!
//! Precision: P is rounded (~2u|P| per component) before the inside test, and each determinant
//! is a product of differences of rounded values: the test decides hit/miss to within a few u
//! of the triangle's distance, not of its size, and two triangles sharing an edge evaluate it
//! from different vertices (V_i and P - V_i differ), so their answers are not complementary.
//! Known to fail: leaks through shared edges and vertices (closed meshes, quad grids, quad
//! diagonals); wrong answers when the hit point is far compared with the triangle (P's rounding
//! exceeds the triangle). Proven by `tests/stability.rs` and the lab's tables.

use super::{Direction, Own, TwoTriangles, cross, cross8, dot8, splat3, sub};
use glam::DVec3;
use lanecast::experimental::kernel::Triangle;
use lanecast::experimental::real::{Real, V3, dot, v3};
use wide::f32x8;

/// One triangle's constants, relative to the eye.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneK<T> {
    /// A, B, C - eye.
    pub v: [V3<T>; 3],
    /// B - A, C - B, A - C.
    pub e: [V3<T>; 3],
    /// Unit normal (B - A) x (C - A).
    pub n: V3<T>,
    /// n . (A - eye).
    pub h: T,
}

impl PlaneK<f64> {
    /// Constants of triangle `v` (A, B, C) seen from `eye`, in f64.
    pub fn new(v: &[DVec3; 3], eye: DVec3) -> PlaneK<f64> {
        let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        PlaneK {
            v: v.map(|p| v3(p - eye)),
            e: std::array::from_fn(|i| v3(v[(i + 1) % 3] - v[i])),
            n: v3(n),
            h: n.dot(v[0] - eye),
        }
    }

    /// The same constants rounded to `T`.
    pub fn cast<T: Real>(&self) -> PlaneK<T> {
        let r = |a: V3<f64>| a.map(T::from_f64);
        PlaneK {
            v: self.v.map(r),
            e: self.e.map(r),
            n: r(self.n),
            h: T::from_f64(self.h),
        }
    }
}

/// Distance along unit `d` from the eye, when the triangle is hit ahead of it.
#[inline]
pub fn plane_x1<T: Real>(k: &PlaneK<T>, d: V3<T>) -> Option<T> {
    // plane hit
    let t = k.h / dot(k.n, d);
    if !(t > T::ZERO && t < T::INFINITY) {
        return None;
    }
    let p = [t * d[0], t * d[1], t * d[2]];
    // inside test
    for i in 0..3 {
        let det = dot(cross(k.e[i], sub(p, k.v[i])), k.n);
        if !(det >= T::ZERO) {
            return None;
        }
    }
    Some(t)
}

/// [`plane_x1`] for eight directions: `None` when no lane is inside, else the mask of lanes
/// inside and their distances (the caller keeps 0 < t).
#[inline(always)]
pub fn plane_x8(k: &PlaneK<f32>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
    let zero = f32x8::ZERO;
    // plane hit
    let n = splat3(k.n);
    let t = f32x8::splat(k.h) / dot8(&n, d);
    let mut valid = t.simd_gt(zero) & t.simd_lt(f32x8::splat(f32::INFINITY));
    if !valid.any() {
        return None;
    }
    let p = [t * d[0], t * d[1], t * d[2]];
    // inside test
    for i in 0..3 {
        let v = splat3(k.v[i]);
        let w = [p[0] - v[0], p[1] - v[1], p[2] - v[2]];
        let det = dot8(&cross8(&splat3(k.e[i]), &w), &n);
        valid &= det.simd_ge(zero);
        if !valid.any() {
            return None;
        }
    }
    Some((valid, t))
}

/// The families the plane + determinants test re-implements: triangles, and quads as two
/// triangles.
pub type PlaneOwn = (PlaneTriangle, TwoTriangles<PlaneTriangle>);

/// The plane + determinants test in place of lanecast's triangles: [`PlaneK`], [`plane_x1`],
/// [`plane_x8`].
pub struct PlaneTriangle;
impl Own for PlaneTriangle {
    type Family = Triangle;
    type Rays = Direction;
    type K = PlaneK<f32>;
    fn setup(v: &[DVec3; 3], eye: DVec3) -> Option<PlaneK<f32>> {
        Some(PlaneK::new(v, eye).cast())
    }
    fn x1(k: &PlaneK<f32>, d: &V3<f32>) -> Option<f32> {
        plane_x1(k, *d)
    }
    #[inline(always)]
    fn x8(k: &PlaneK<f32>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
        plane_x8(k, d)
    }
}

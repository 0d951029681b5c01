//! Möller–Trumbore ray/triangle intersection: T. Möller, B. Trumbore, "Fast, Minimum Storage
//! Ray/Triangle Intersection", Journal of Graphics Tools 2(1), 1997 (the non-culling branch).
//!
//! With `e1 = V1 - V0`, `e2 = V2 - V0`, origin O (the eye: 0 in eye-relative coordinates),
//! unit direction d:
//! ```text
//! p = d x e2;  det = e1 . p            det == 0: ray parallel to the plane, miss
//! s = O - V0;  u = (s . p) / det       miss unless 0 <= u <= 1
//! q = s x e1;  v = (d . q) / det       miss unless 0 <= v and u + v <= 1
//! t = (e2 . q) / det                   a hit when t > 0
//! ```
//! Divisions are multiplications by `inv = 1 / det`, as in the paper. Epsilon convention: the
//! paper rejects `|det| < EPSILON = 1e-6`; that epsilon is absolute (units of length^2 for a
//! unit d) and would drop every triangle whose `|e1 x e2| cos` is below 1e-6, e.g. all of
//! `scenes/stress/tiny_far.sc` (1e-3-sized triangles). Here only `det == 0` (or NaN) is
//! rejected; no tolerance widens the triangle (u, v tested against exact 0 and 1).
//! Constants `V0 - eye`, `e1`, `e2` are computed in f64 and rounded; `s = -(V0 - eye)` and
//! `q = s x e1` depend on the triangle only, so [`mt_x8`] evaluates them once per call.
//!
//! Precision: u, v err by ~a few u relative to the triangle's size, but each triangle computes
//! its barycentrics from its own V0, e1, e2: two triangles sharing an edge round the shared
//! edge's test differently (u + v <= 1 in one, v >= 0 in the other), so a ray through the
//! shared edge or vertex can fail both. Known to fail: leaks (holes) through shared edges and
//! vertices of closed meshes and quad grids; quads split into two triangles also leak along
//! their diagonal. Proven by `tests/stability.rs` (`mt_leaks_through_shared_edges`,
//! `x8_equals_x1_*`).

use super::{Direction, Own, TwoTriangles, cross, cross8, dot8, splat3, sub};
use glam::DVec3;
use lanecast::experimental::kernel::Triangle;
use lanecast::experimental::real::{Real, V3, dot, v3};
use wide::f32x8;

/// One triangle's constants, relative to the eye.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MtK<T> {
    /// V0 - eye.
    pub v0: V3<T>,
    /// Edge e1 = V1 - V0.
    pub e1: V3<T>,
    /// Edge e2 = V2 - V0.
    pub e2: V3<T>,
}

impl MtK<f64> {
    /// Constants of triangle `v` (V0, V1, V2) seen from `eye`, in f64.
    pub fn new(v: &[DVec3; 3], eye: DVec3) -> MtK<f64> {
        MtK {
            v0: v3(v[0] - eye),
            e1: v3(v[1] - v[0]),
            e2: v3(v[2] - v[0]),
        }
    }

    /// The same constants rounded to `T`.
    pub fn cast<T: Real>(&self) -> MtK<T> {
        let r = |a: V3<f64>| a.map(T::from_f64);
        MtK {
            v0: r(self.v0),
            e1: r(self.e1),
            e2: r(self.e2),
        }
    }
}

/// Distance along unit `d` from the eye, when the triangle is hit ahead of it.
#[inline]
pub fn mt_x1<T: Real>(k: &MtK<T>, d: V3<T>) -> Option<T> {
    let p = cross(d, k.e2);
    let det = dot(k.e1, p);
    if det == T::ZERO {
        return None;
    }
    let inv = T::ONE / det;
    let s = sub([T::ZERO; 3], k.v0);
    let u = dot(s, p) * inv;
    if !(u >= T::ZERO && u <= T::ONE) {
        return None;
    }
    let q = cross(s, k.e1);
    let v = dot(d, q) * inv;
    if !(v >= T::ZERO && u + v <= T::ONE) {
        return None;
    }
    let t = dot(k.e2, q) * inv;
    (t > T::ZERO && t < T::INFINITY).then_some(t)
}

/// [`mt_x1`] for eight directions: `None` when no lane is inside, else the mask of lanes inside
/// and their distances (the caller keeps 0 < t).
#[inline(always)]
pub fn mt_x8(k: &MtK<f32>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
    let zero = f32x8::ZERO;
    let one = f32x8::ONE;
    let e2 = splat3(k.e2);
    let p = cross8(d, &e2);
    let det = dot8(&splat3(k.e1), &p);
    let mut valid = det.simd_gt(zero) | det.simd_lt(zero);
    if !valid.any() {
        return None;
    }
    let inv = one / det;
    // per-triangle constants, the same scalar operations as in mt_x1
    let s = sub([0.0; 3], k.v0);
    let q = cross(s, k.e1);
    let e2q = dot(k.e2, q);
    // barycentric u
    let u = dot8(&splat3(s), &p) * inv;
    valid &= u.simd_ge(zero) & u.simd_le(one);
    if !valid.any() {
        return None;
    }
    // barycentric v
    let v = dot8(d, &splat3(q)) * inv;
    valid &= v.simd_ge(zero) & (u + v).simd_le(one);
    if !valid.any() {
        return None;
    }
    Some((valid, f32x8::splat(e2q) * inv))
}

/// The families Möller–Trumbore re-implements: triangles, and quads as two triangles.
pub type MtOwn = (MtTriangle, TwoTriangles<MtTriangle>);

/// Möller–Trumbore in place of lanecast's triangles: [`MtK`], [`mt_x1`], [`mt_x8`].
pub struct MtTriangle;
impl Own for MtTriangle {
    type Family = Triangle;
    type Rays = Direction;
    type K = MtK<f32>;
    fn setup(v: &[DVec3; 3], eye: DVec3) -> Option<MtK<f32>> {
        Some(MtK::new(v, eye).cast())
    }
    fn x1(k: &MtK<f32>, d: &V3<f32>) -> Option<f32> {
        mt_x1(k, *d)
    }
    #[inline(always)]
    fn x8(k: &MtK<f32>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
        mt_x8(k, d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_centre_and_misses_outside() {
        let v = [
            DVec3::new(-1.0, -1.0, -4.0),
            DVec3::new(1.0, -1.0, -4.0),
            DVec3::new(0.0, 1.0, -4.0),
        ];
        let k = MtK::new(&v, DVec3::ZERO);
        assert_eq!(mt_x1(&k, [0.0, 0.0, -1.0]), Some(4.0));
        assert_eq!(mt_x1(&k, [0.0, 0.0, 1.0]), None);
        assert_eq!(mt_x1(&k, [0.0, 1.0, 0.0]), None);
    }
}

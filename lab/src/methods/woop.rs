//! Watertight ray/triangle intersection: S. Woop, C. Benthin, I. Wald, "Watertight Ray/Triangle
//! Intersection", Journal of Computer Graphics Techniques 2(1), 2013, with its double-precision
//! fallback (section 4.2) and without backface culling.
//!
//! Per ray (unit direction d, origin O = the eye, 0 in eye-relative coordinates):
//! ```text
//! kz = axis of the largest |d_k|; kx = kz + 1, ky = kx + 1 (mod 3); swap kx, ky if d_kz < 0
//! Sx = d_kx / d_kz;  Sy = d_ky / d_kz;  Sz = 1 / d_kz          (shear to ray space)
//! ```
//! Per triangle (A, B, C relative to O):
//! ```text
//! Ax = A_kx - Sx A_kz;  Ay = A_ky - Sy A_kz       (same for B, C)
//! U = Cx By - Cy Bx;  V = Ax Cy - Ay Cx;  W = Bx Ay - By Ax        (2D edge functions)
//! if U, V or W == 0: recompute the three in f64 (exact products of f32 values) -> exact sign
//! miss if (U < 0 or V < 0 or W < 0) and (U > 0 or V > 0 or W > 0)
//! det = U + V + W; miss if det == 0
//! T = U Sz A_kz + V Sz B_kz + W Sz C_kz;  t = T / det (as T * (1/det))
//! ```
//! Watertightness: a shared edge's function is computed from the same two sheared vertices in
//! both triangles, in opposite order, so it evaluates to exact negatives; the sheared vertices
//! depend on the vertex and the ray only. A ray on the edge gets exactly 0 in both, and the
//! fallback then decides its sign exactly, so at least one triangle (or both: an edge hit
//! counts) accepts the ray. Vertices are stored relative to the eye (f64, rounded), so each
//! shared vertex is one f32 value in every triangle that uses it.
//!
//! Packets: the ray transform is per ray; [`WoopRay8`] computes it once per packet and, when
//! all eight lanes share the axis permutation (the common case for primary rays), permutes the
//! triangle's vertices once in scalar code and broadcasts them; otherwise each lane selects its
//! own components. Both paths give each lane exactly the values of [`woop_x1`].
//!
//! Precision: hit/miss is exact for the rounded vertices and the rounded sheared ray (no
//! tolerance needed); t errs by a few u relative. Known to fail: nothing leaks, but the rounded
//! ray direction itself (~3u rad in f32) moves silhouettes, and a triangle smaller than f32 can
//! place relative to the eye (size < ~u * distance) is mis-hit like in every f32 method. Proven
//! by `tests/stability.rs` (`watertight_leaves_no_holes`, `x8_equals_x1_*`).

use super::{Own, Rays, TwoTriangles, abs};
use glam::DVec3;
use lanecast::experimental::kernel::Triangle;
use lanecast::experimental::real::{Real, V3, v3};
use wide::f32x8;

/// One triangle's vertices relative to the eye.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WoopK<T> {
    /// A, B, C - eye.
    pub v: [V3<T>; 3],
}

impl WoopK<f64> {
    /// Constants of triangle `v` (A, B, C) seen from `eye`, in f64.
    pub fn new(v: &[DVec3; 3], eye: DVec3) -> WoopK<f64> {
        WoopK {
            v: v.map(|p| v3(p - eye)),
        }
    }

    /// The same constants rounded to `T`.
    pub fn cast<T: Real>(&self) -> WoopK<T> {
        WoopK {
            v: self.v.map(|a| a.map(T::from_f64)),
        }
    }
}

/// One ray in ray space: axis permutation `k = [kx, ky, kz]` and shear `s = [Sx, Sy, Sz]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WoopRay<T> {
    /// Axis indices [kx, ky, kz]: kz the largest |d| component, kx and ky swapped if d_kz < 0.
    pub k: [usize; 3],
    /// Shear [Sx, Sy, Sz] = [d_kx / d_kz, d_ky / d_kz, 1 / d_kz].
    pub s: [T; 3],
}

/// The ray transform of unit direction `d`.
#[inline]
pub fn woop_ray<T: Real>(d: V3<T>) -> WoopRay<T> {
    let a = d.map(abs);
    let kz = if a[0] > a[1] {
        if a[0] > a[2] { 0 } else { 2 }
    } else if a[1] > a[2] {
        1
    } else {
        2
    };
    let mut kx = (kz + 1) % 3;
    let mut ky = (kx + 1) % 3;
    if d[kz] < T::ZERO {
        std::mem::swap(&mut kx, &mut ky);
    }
    WoopRay {
        k: [kx, ky, kz],
        s: [d[kx] / d[kz], d[ky] / d[kz], T::ONE / d[kz]],
    }
}

/// The edge functions U, V, W from the sheared 2D vertices, with the double-precision fallback
/// when one is exactly zero (for f64 the fallback recomputes the same values).
#[inline(always)]
fn edges<T: Real>(ax: T, ay: T, bx: T, by: T, cx: T, cy: T) -> [T; 3] {
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if u == T::ZERO || v == T::ZERO || w == T::ZERO {
        edges_f64([ax, ay, bx, by, cx, cy].map(T::to_f64)).map(T::from_f64)
    } else {
        [u, v, w]
    }
}

/// The fallback: products of two f32 values are exact in f64, so each difference is rounded
/// once and its sign is exact.
#[inline(never)]
fn edges_f64([ax, ay, bx, by, cx, cy]: [f64; 6]) -> [f64; 3] {
    [cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax]
}

/// Distance along the ray `r` (of unit direction d) from the eye, when the triangle is hit.
#[inline]
pub fn woop_x1<T: Real>(k: &WoopK<T>, r: &WoopRay<T>) -> Option<T> {
    let [kx, ky, kz] = r.k;
    let [sx, sy, sz] = r.s;
    let [a, b, c] = k.v;
    // shear the vertices
    let (ax, ay) = (a[kx] - sx * a[kz], a[ky] - sy * a[kz]);
    let (bx, by) = (b[kx] - sx * b[kz], b[ky] - sy * b[kz]);
    let (cx, cy) = (c[kx] - sx * c[kz], c[ky] - sy * c[kz]);
    // edge tests
    let [u, v, w] = edges(ax, ay, bx, by, cx, cy);
    let z = T::ZERO;
    if (u < z || v < z || w < z) && (u > z || v > z || w > z) {
        return None;
    }
    let det = u + v + w;
    if det == z {
        return None;
    }
    // depth
    let (az, bz, cz) = (sz * a[kz], sz * b[kz], sz * c[kz]);
    let tt = u * az + v * bz + w * cz;
    let t = tt * (T::ONE / det);
    (t > z && t < T::INFINITY).then_some(t)
}

/// Eight rays in ray space: each lane's [`WoopRay`], and the shared permutation when all lanes
/// have the same one.
#[derive(Debug, Clone, Copy)]
pub struct WoopRay8 {
    /// The permutation [kx, ky, kz] shared by all eight lanes, or `None` when they differ.
    pub uniform: Option<[usize; 3]>,
    /// Per lane, per role (kx, ky, kz): lane masks "axis is 0" and "axis is 1" (else 2).
    pub pick: [[f32x8; 2]; 3],
    /// Per lane shear [Sx, Sy, Sz], as in [`WoopRay::s`].
    pub s: [f32x8; 3],
}

impl WoopRay8 {
    /// The transform of eight unit directions: lane i gets exactly `woop_ray` of lane i.
    pub fn new(d: &[f32x8; 3]) -> WoopRay8 {
        let (x, y, z) = (d[0].to_array(), d[1].to_array(), d[2].to_array());
        let rays: [WoopRay<f32>; 8] = std::array::from_fn(|i| woop_ray([x[i], y[i], z[i]]));
        let uniform = rays.iter().all(|r| r.k == rays[0].k).then_some(rays[0].k);
        let mask = |f: &dyn Fn(&WoopRay<f32>) -> bool| {
            f32x8::new(rays.map(|r| if f(&r) { 1.0 } else { 0.0 })).simd_gt(f32x8::ZERO)
        };
        let pick =
            std::array::from_fn(|role| [mask(&|r| r.k[role] == 0), mask(&|r| r.k[role] == 1)]);
        WoopRay8 {
            uniform,
            pick,
            s: std::array::from_fn(|i| f32x8::new(rays.map(|r| r.s[i]))),
        }
    }

    /// Component `role` (0: kx, 1: ky, 2: kz) of vertex `p`, per lane.
    #[inline(always)]
    fn get(&self, p: &V3<f32>, role: usize) -> f32x8 {
        match self.uniform {
            Some(k) => f32x8::splat(p[k[role]]),
            None => {
                let [m0, m1] = self.pick[role];
                m0.select(
                    f32x8::splat(p[0]),
                    m1.select(f32x8::splat(p[1]), f32x8::splat(p[2])),
                )
            }
        }
    }
}

/// [`woop_x1`] for eight rays: `None` when no lane is inside, else the mask of lanes inside and
/// their distances (the caller keeps 0 < t).
#[inline(always)]
pub fn woop_x8(k: &WoopK<f32>, r: &WoopRay8) -> Option<(f32x8, f32x8)> {
    let [sx, sy, sz] = r.s;
    let [a, b, c] = &k.v;
    // shear the vertices
    let (az0, bz0, cz0) = (r.get(a, 2), r.get(b, 2), r.get(c, 2));
    let (ax, ay) = (r.get(a, 0) - sx * az0, r.get(a, 1) - sy * az0);
    let (bx, by) = (r.get(b, 0) - sx * bz0, r.get(b, 1) - sy * bz0);
    let (cx, cy) = (r.get(c, 0) - sx * cz0, r.get(c, 1) - sy * cz0);
    // edge tests
    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    let zero = f32x8::ZERO;
    let any_zero = u.simd_eq(zero) | v.simd_eq(zero) | w.simd_eq(zero);
    if any_zero.any() {
        // the double-precision fallback, lane by lane where an edge function is exactly 0
        let z = any_zero.to_array();
        let vals = [ax, ay, bx, by, cx, cy].map(|x| x.to_array());
        let (mut ua, mut va, mut wa) = (u.to_array(), v.to_array(), w.to_array());
        for i in 0..8 {
            if z[i] != 0.0 {
                let e = edges_f64(vals.map(|x| x[i] as f64));
                (ua[i], va[i], wa[i]) = (e[0] as f32, e[1] as f32, e[2] as f32);
            }
        }
        (u, v, w) = (f32x8::new(ua), f32x8::new(va), f32x8::new(wa));
    }
    let neg = u.simd_lt(zero) | v.simd_lt(zero) | w.simd_lt(zero);
    let pos = u.simd_gt(zero) | v.simd_gt(zero) | w.simd_gt(zero);
    let det = u + v + w;
    let valid = !(neg & pos) & !det.simd_eq(zero);
    if !valid.any() {
        return None;
    }
    // depth
    let (az, bz, cz) = (sz * az0, sz * bz0, sz * cz0);
    let tt = u * az + v * bz + w * cz;
    Some((valid, tt * (f32x8::ONE / det)))
}

/// The rays in ray space, per ray ([`woop_ray`]) and per packet ([`WoopRay8`]): the per-ray data
/// of the watertight kernels.
pub struct WoopRays;
impl Rays for WoopRays {
    type R1 = WoopRay<f32>;
    type R8 = WoopRay8;
    fn ray1(d: V3<f32>) -> WoopRay<f32> {
        woop_ray(d)
    }
    fn ray8(d: &[f32x8; 3]) -> WoopRay8 {
        WoopRay8::new(d)
    }
}

/// The families the watertight test re-implements: triangles, and quads as two triangles.
pub type WoopOwn = (WoopTriangle, TwoTriangles<WoopTriangle>);

/// The watertight test in place of lanecast's triangles: [`WoopK`], [`woop_x1`], [`woop_x8`].
pub struct WoopTriangle;
impl Own for WoopTriangle {
    type Family = Triangle;
    type Rays = WoopRays;
    type K = WoopK<f32>;
    fn setup(v: &[DVec3; 3], eye: DVec3) -> Option<WoopK<f32>> {
        Some(WoopK::new(v, eye).cast())
    }
    fn x1(k: &WoopK<f32>, r: &WoopRay<f32>) -> Option<f32> {
        woop_x1(k, r)
    }
    #[inline(always)]
    fn x8(k: &WoopK<f32>, r: &WoopRay8) -> Option<(f32x8, f32x8)> {
        woop_x8(k, r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_centre_both_windings() {
        let a = DVec3::new(-1.0, -1.0, -4.0);
        let b = DVec3::new(1.0, -1.0, -4.0);
        let c = DVec3::new(0.0, 1.0, -4.0);
        for v in [[a, b, c], [a, c, b]] {
            let k = WoopK::new(&v, DVec3::ZERO);
            assert_eq!(woop_x1(&k, &woop_ray([0.0, 0.0, -1.0])), Some(4.0));
            assert_eq!(woop_x1(&k, &woop_ray([0.0, 0.0, 1.0])), None);
        }
    }
}

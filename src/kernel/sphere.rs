//! Ray/sphere intersection, in the numerically stable form of Haines, Günther and Akenine-Möller,
//! "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems (2019), chapter 7,
//! specialised to unit directions and a shared ray origin (the eye).
//!
//! With `oc = centre - eye` (computed in f64), unit direction `d`, radius `r`:
//! ```text
//! b    = oc . d                  distance along the ray to the point nearest the centre
//! l    = oc - b d                perpendicular from the ray line to the centre
//! disc = r^2 - l . l             (RTG eq. 7.5: no b^2 - c cancellation)
//! q    = b + sqrt(disc)          far root; b and sqrt(disc) add with the same sign when the
//!                                sphere is in front, so no cancellation
//! t    = c / q  with c = |oc|^2 - r^2     near root, from t0 * t1 = c (Vieta), eye outside
//! t    = q                                eye inside (c <= 0): the far root is the exit point
//! ```
//! `c` depends on the sphere and the eye only, so it is computed once in f64 and rounded; so is
//! the inside/outside decision, which is therefore uniform across the lanes of a packet.
//!
//! Precision (f32, u = 2^-24): `b` errs by ~3u|oc|, `l` by ~4u|oc| per component, so the
//! silhouette moves by about 4u|oc| in absolute terms: 2.4e-3 for a sphere 1e4 away, a small
//! fraction of a sphere of radius 1 (the textbook `b^2 - c` loses the whole sphere there, since
//! b^2 ~ 1e8 has an ulp of 8). The distance `t = c/q` errs by ~5u relative where the ray meets
//! the sphere well inside its silhouette; towards the silhouette `sqrt(disc)` magnifies the
//! absolute error of `disc` (~8u|oc|^2) by 1/(2 sqrt(disc)), so tangent rays lose precision
//! (measured: 1.6e-5 relative at the outline of scene5's spheres).
//! `--precision auto` re-decides in f64 the hits these bounds cannot vouch for to 1e-5
//! (`render::redecide`), which guarantees every depth within 1e-5 of the oracle's (docs/precision.md;
//! `tests/auto.rs`).
//! Known to fail: a
//! sphere whose radius is below ~4u|oc| (smaller than f32 can place it) flickers at its edge;
//! rays exactly tangent to a sphere may hit or miss (disc ~ 0 within rounding).
//! Proven by: `tests::far_small_sphere_*`, `tests::x8_equals_x1_*`, and the agreement tests.

use crate::kernel::family::{Ball, Family};
use crate::kernel::lanes::Lanes;
use crate::real::{Real, V3, dot, v3};
use crate::scene::Shape;
use glam::DVec3;
use wide::f32x8;

/// One sphere's eye-relative constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereK<T> {
    /// centre - eye.
    pub oc: V3<T>,
    /// radius^2.
    pub r2: T,
    /// |oc|^2 - r^2, computed in f64.
    pub c: T,
    /// Eye inside or on the sphere (c <= 0).
    pub inside: bool,
}

impl SphereK<f64> {
    /// Constants of the sphere (`center`, `radius`) seen from `eye`, in f64.
    pub fn new(center: DVec3, radius: f64, eye: DVec3) -> SphereK<f64> {
        let oc = center - eye;
        let r2 = radius * radius;
        let c = oc.length_squared() - r2;
        SphereK {
            oc: v3(oc),
            r2,
            c,
            inside: c <= 0.0,
        }
    }

    /// The same constants rounded to `T`.
    pub fn cast<T: Real>(&self) -> SphereK<T> {
        let [x, y, z] = self.oc;
        SphereK {
            oc: [T::from_f64(x), T::from_f64(y), T::from_f64(z)],
            r2: T::from_f64(self.r2),
            c: T::from_f64(self.c),
            inside: self.inside,
        }
    }
}

/// The sphere family (`sphere CX CY CZ RADIUS`): [`SphereK`], [`sphere_x1`], `sphere_lanes`.
#[derive(Debug, Clone, Copy)]
pub struct Sphere;

impl Family for Sphere {
    const KIND: usize = 0;
    /// Centre and radius.
    type Geometry = (DVec3, f64);
    type K<T: Real> = SphereK<T>;

    #[inline(always)]
    fn geometry(shape: Shape) -> Option<(DVec3, f64)> {
        match shape {
            Shape::Sphere { center, radius } => Some((center, radius)),
            _ => None,
        }
    }
    #[inline(always)]
    fn setup(&(center, radius): &(DVec3, f64), eye: DVec3) -> Option<SphereK<f64>> {
        Some(SphereK::new(center, radius, eye))
    }
    #[inline(always)]
    fn cast<T: Real>(k: &SphereK<f64>) -> SphereK<T> {
        k.cast()
    }
    #[inline(always)]
    fn hit_x1<T: Real>(k: &SphereK<T>, d: V3<T>) -> Option<T> {
        sphere_x1(k, d)
    }
    #[inline(always)]
    fn hit_lanes<L: Lanes>(k: &SphereK<L::Scalar>, d: &[L; 3]) -> Option<(L, L)> {
        sphere_lanes(k, d)
    }
    /// The radius grown by `slack` times the centre's distance.
    fn hit_with_slack(
        &(center, radius): &(DVec3, f64),
        eye: DVec3,
        d: V3<f64>,
        slack: f64,
    ) -> Option<f64> {
        let r = radius + slack * (center - eye).length();
        (r > 0.0)
            .then(|| sphere_x1(&SphereK::new(center, r, eye), d))
            .flatten()
    }
    fn plane(_: &(DVec3, f64), _: DVec3) -> Option<(V3<f64>, f64)> {
        None
    }
    /// Outward from the centre, or inward when the eye is inside (it sees the inner side).
    fn normal(&(center, radius): &(DVec3, f64), eye: DVec3, point: DVec3) -> (DVec3, bool) {
        let out = (point - center).normalize_or_zero();
        let inside = (eye - center).length() < radius;
        (if inside { -out } else { out }, false)
    }

    // For the acceleration structures (`accel`): bounded as a ball.

    type Outline = Ball;
    #[inline(always)]
    fn outline(k: &SphereK<f32>) -> Ball {
        Ball {
            oc: k.oc,
            r2: k.r2,
            c: k.c,
            inside: k.inside,
        }
    }
    #[inline(always)]
    fn ball(&(center, radius): &(DVec3, f64), eye: DVec3) -> Option<(DVec3, f64)> {
        Some((center - eye, radius))
    }
    #[inline(always)]
    fn hit_lanes_all<L: Lanes>(k: &SphereK<L::Scalar>, d: &[L; 3]) -> (L, L) {
        sphere_lanes_all(k, d)
    }

    // For the world engine (`--accel world`).

    /// Drawn through its bounding sphere ([`Bounded`](crate::kernel::family::Bounded)).
    fn class<C: crate::kernel::family::Class<Sphere>>(class: C) -> C::Out {
        class.bounded()
    }
}

// For the world engine (`--accel world`).

/// A sphere's bounding sphere is itself.
impl crate::kernel::family::Bounded for Sphere {
    #[inline(always)]
    fn bound(&(center, radius): &(DVec3, f64)) -> (DVec3, f64) {
        (center, radius)
    }
}

/// Distance to the first hit along unit direction `d`, when it is ahead of the eye.
#[inline]
pub fn sphere_x1<T: Real>(s: &SphereK<T>, d: V3<T>) -> Option<T> {
    let b = dot(s.oc, d);
    let l = [s.oc[0] - b * d[0], s.oc[1] - b * d[1], s.oc[2] - b * d[2]];
    let disc = s.r2 - dot(l, l);
    // `partial_cmp` is `None` for a NaN disc: refused too
    if disc.partial_cmp(&T::ZERO).is_none_or(|o| o.is_lt()) {
        return None;
    }
    let q = b + disc.sqrt();
    let t = if s.inside { q } else { s.c / q };
    (t > T::ZERO && t < T::INFINITY).then_some(t)
}

/// [`sphere_x1`] for eight directions: `None` when no lane's line meets the sphere, else the mask
/// of lanes whose line does and their distances (the caller keeps those with 0 < t).
#[inline(always)]
pub fn sphere_x8(s: &SphereK<f32>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
    sphere_lanes(s, d)
}

/// `b = oc . d` and `disc = r^2 - |oc - b d|^2`, the steps of [`sphere_x1`] before its square
/// root, in the lanes of `L` with the same operations in the same order: with `oc` and `r2`
/// splatted from one sphere (the packet kernels) or one sphere per lane (`--precision auto`'s
/// measurement of a strip's suspects, `render::redecide::verify`), each lane gives the 1-lane
/// form's bits.
#[inline(always)]
pub fn sphere_disc<L: Lanes>(oc: [L; 3], r2: L, d: &[L; 3]) -> (L, L) {
    let b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    let l = [oc[0] - b * d[0], oc[1] - b * d[1], oc[2] - b * d[2]];
    (b, r2 - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]))
}

/// [`sphere_x1`] in the lanes of `L` (f32x8: [`sphere_x8`]; f64x4: `kernel::wide64`), the same
/// operations in the same order as the 1-lane form.
#[inline(always)]
pub fn sphere_lanes<L: Lanes>(s: &SphereK<L::Scalar>, d: &[L; 3]) -> Option<(L, L)> {
    let (b, disc) = sphere_disc(s.oc.map(L::splat), L::splat(s.r2), d);
    let meets = disc.simd_ge(L::ZERO);
    if !meets.any() {
        return None;
    }
    let q = b + disc.sqrt();
    let t = if s.inside { q } else { L::splat(s.c) / q };
    Some((meets, t))
}

/// [`sphere_lanes`] with no early exit: the distance is computed for every packet and the
/// mask may be empty (lanes whose line misses take a NaN distance, masked off). The same
/// operations give the same bits where the mask is set. For the tiles' per-packet lists, where
/// whether a packet meets a small sphere is as likely as not and the branch cannot predict it
/// (as `polygon::polygon_lanes_all`).
#[inline(always)]
pub fn sphere_lanes_all<L: Lanes>(s: &SphereK<L::Scalar>, d: &[L; 3]) -> (L, L) {
    let (b, disc) = sphere_disc(s.oc.map(L::splat), L::splat(s.r2), d);
    let meets = disc.simd_ge(L::ZERO);
    let q = b + disc.sqrt();
    let t = if s.inside { q } else { L::splat(s.c) / q };
    (meets, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn x8_t(s: &SphereK<f32>, d: V3<f32>) -> Option<f32> {
        let d8 = d.map(f32x8::splat);
        let (m, t) = sphere_x8(s, &d8)?;
        let (m, t) = (m.to_array()[0], t.to_array()[0]);
        (m != 0.0 && t > 0.0 && t < f32::INFINITY).then_some(t)
    }

    /// The branch-free form gives the early-exit form's mask and, where it is set, its bits.
    #[test]
    fn lanes_all_agrees_with_lanes_where_the_line_meets() {
        for (center, radius) in [(DVec3::new(0.3, -0.2, -5.0), 1.0), (DVec3::ZERO, 2.0)] {
            let s = SphereK::new(center, radius, DVec3::ZERO).cast::<f32>();
            for k in 0..64 {
                let a = k as f32 * 0.05 - 1.6;
                let dir = |i: usize| {
                    let v = [a * 0.3 + i as f32 * 0.01, a * 0.2, -1.0];
                    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                    v.map(|c| c / n)
                };
                let d: [f32x8; 3] =
                    std::array::from_fn(|c| f32x8::new(std::array::from_fn(|i| dir(i)[c])));
                let (mask, t) = sphere_lanes_all(&s, &d);
                match sphere_lanes(&s, &d) {
                    None => assert_eq!(mask.to_bitmask(), 0),
                    Some((m, t1)) => {
                        assert_eq!(mask.to_bitmask(), m.to_bitmask());
                        for i in 0..8 {
                            if m.to_bitmask() >> i & 1 == 1 {
                                assert_eq!(t.to_array()[i].to_bits(), t1.to_array()[i].to_bits());
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn hits_front_sphere_at_near_root() {
        let s = SphereK::new(DVec3::new(0.0, 0.0, -5.0), 1.0, DVec3::ZERO);
        assert_eq!(sphere_x1(&s, [0.0, 0.0, -1.0]), Some(4.0));
        assert_eq!(
            sphere_x1(&s, [0.0, 0.0, 1.0]),
            None,
            "sphere behind the eye"
        );
        assert_eq!(sphere_x1(&s, [0.0, 1.0, 0.0]), None, "ray passes beside it");
    }

    #[test]
    fn eye_inside_hits_exit_point() {
        let s = SphereK::new(DVec3::new(0.0, 0.0, 0.5), 2.0, DVec3::ZERO);
        assert!(s.inside);
        assert_eq!(sphere_x1(&s, [0.0, 0.0, 1.0]), Some(2.5));
        assert_eq!(sphere_x1(&s, [0.0, 0.0, -1.0]), Some(1.5));
    }

    #[test]
    fn far_small_sphere_keeps_its_depth_in_f32() {
        // Radius 1 at distance 1e4 (and 1e5): the naive b^2 - c form loses it entirely in f32.
        for dist in [1e4, 1e5] {
            let s64 = SphereK::new(DVec3::new(0.3, -0.2, -dist), 1.0, DVec3::ZERO);
            let d64 = DVec3::new(0.3, -0.2, -dist + 0.5).normalize();
            let exact = sphere_x1(&s64, v3(d64)).unwrap();
            let t32 = sphere_x1(&s64.cast::<f32>(), v3::<f32>(d64)).expect("f32 keeps the hit");
            let rel = (t32 as f64 - exact).abs() / exact;
            assert!(
                rel < 8.0 * f32::EPSILON as f64,
                "dist {dist}: rel error {rel}"
            );
        }
    }

    #[test]
    fn far_small_sphere_silhouette_is_stable_in_f32() {
        // Rays sweeping across a radius-1 sphere 1e4 away: f32 and f64 agree on hit/miss except
        // within 4u|oc| of the silhouette (the bound stated above).
        let dist = 1e4;
        let s64 = SphereK::new(DVec3::new(0.0, 0.0, -dist), 1.0, DVec3::ZERO);
        let s32 = s64.cast::<f32>();
        let bound = 4.0 * (f32::EPSILON as f64 / 2.0) * dist;
        for i in 0..2001 {
            let y = -1.5 + 3.0 * i as f64 / 2000.0;
            let d = DVec3::new(0.0, y, -dist).normalize();
            let hit64 = sphere_x1(&s64, v3(d)).is_some();
            let hit32 = sphere_x1(&s32, v3::<f32>(d)).is_some();
            let off_edge = (y.abs() - 1.0).abs() > bound * 2.0;
            if off_edge {
                assert_eq!(hit64, hit32, "y = {y}");
            }
        }
    }

    #[test]
    fn x8_equals_x1_bit_for_bit() {
        let spheres = [
            SphereK::new(DVec3::new(0.1, 0.2, -3.0), 0.7, DVec3::ZERO).cast::<f32>(),
            SphereK::new(DVec3::new(0.0, 0.0, 0.1), 1.0, DVec3::ZERO).cast::<f32>(),
            SphereK::new(DVec3::new(2e4, 1e4, -3e4), 5.0, DVec3::ZERO).cast::<f32>(),
        ];
        let mut rng = crate::test_rng::Rng(0x9E37_79B9_7F4A_7C15);
        let mut rnd = || rng.range(-1.0, 1.0) as f32;
        for s in &spheres {
            for _ in 0..2000 {
                let toward = [s.oc[0] + rnd(), s.oc[1] + rnd(), s.oc[2] + rnd()];
                let len = dot(toward, toward).sqrt();
                let d = toward.map(|c| c / len);
                let a = sphere_x1(s, d).map(f32::to_bits);
                let b = x8_t(s, d).map(f32::to_bits);
                assert_eq!(a, b);
            }
        }
    }
}

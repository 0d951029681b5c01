//! The classic f32 setup, kept as a measured counter-example: every coordinate of the scene and
//! the eye is first rounded to f32, and every per-primitive constant of the default methods
//! (edge planes, stable sphere) is then computed in f32 from those rounded world coordinates
//! (`V - eye` included, as a world-space kernel does per ray with the ray origin `eye` in f32).
//! The default stores the same constants computed in f64 relative to the eye, then rounded.
//!
//! Precision: `V - eye` loses ulp(|V|, |eye|) absolutely: 2^-7 = 0.0078 for coordinates near
//! 1e5, so a scene translated by (1e5, 1e5, 1e5) moves its vertices by up to ~0.004 relative
//! to the eye, and the cross products of those rounded vectors and the sphere's
//! `|oc|^2 - r^2` add their own f32 cancellation (a radius-1e4 ground 1.5 below the eye:
//! `|oc|^2 - r^2 = 3e4` from two ~1e8 terms with ulp 8). Shared edges still get exactly
//! negated normals (the same two rounded vectors), so the leaks are at shared vertices. Known to fail:
//! `scenes/stress/translated.sc`, `ground.sc`. Measured by the lab (`world-f32` rows).

use super::{Direction, Own, cross, sub};
use glam::DVec3;
use lanecast::experimental::kernel::polygon::{PolyK, polygon_x1, polygon_x8};
use lanecast::experimental::kernel::sphere::{SphereK, sphere_x1, sphere_x8};
use lanecast::experimental::kernel::{Family, Quad, Sphere, Triangle};
use lanecast::experimental::real::{V3, dot, v3};
use std::marker::PhantomData;
use wide::f32x8;

/// Sphere constants computed in f32 from f32 world coordinates.
pub fn sphere(center: DVec3, radius: f64, eye: DVec3) -> SphereK<f32> {
    let oc = sub(v3::<f32>(center), v3::<f32>(eye));
    let r = radius as f32;
    let r2 = r * r;
    let c = dot(oc, oc) - r2;
    SphereK {
        oc,
        r2,
        c,
        inside: c <= 0.0,
    }
}

/// Edge-plane constants computed in f32 from f32 world coordinates (`raw_normal` from the
/// rounded vertices too), the steps of `PolyK::new`. `None` when edge-on or not finite.
pub fn polygon<const N: usize>(v: &[DVec3; N], eye: DVec3) -> Option<PolyK<f32, N>> {
    let w: [V3<f32>; N] = v.map(v3::<f32>);
    let raw = if N == 3 {
        cross(sub(w[1], w[0]), sub(w[2], w[0]))
    } else {
        cross(sub(w[2], w[0]), sub(w[3], w[1]))
    };
    let e = v3::<f32>(eye);
    let rel: [V3<f32>; N] = w.map(|p| sub(p, e));
    let facing = dot(rel[0], raw);
    if facing == 0.0 || !facing.is_finite() {
        return None;
    }
    let s = facing.signum();
    let unit = |a: V3<f32>| {
        let len = dot(a, a).sqrt();
        if len > 0.0 {
            a.map(|c| c / len)
        } else {
            [0.0; 3]
        }
    };
    let nrm = unit(raw).map(|c| c * s);
    let p = rel.iter().map(|r| dot(*r, nrm)).sum::<f32>() / N as f32;
    let n = std::array::from_fn(|i| unit(cross(rel[i], rel[(i + 1) % N])).map(|c| c * s));
    let finite = p.is_finite() && nrm.iter().all(|c| c.is_finite());
    (p > 0.0 && finite).then_some(PolyK { n, nrm, p })
}

/// The families whose constants this setup computes (each through lanecast's kernel): spheres,
/// triangles, quads.
pub type WorldOwn = (
    WorldSphere,
    WorldPolygon<Triangle, 3>,
    WorldPolygon<Quad, 4>,
);

/// lanecast's stable sphere kernel with the constants of [`sphere`].
pub struct WorldSphere;
impl Own for WorldSphere {
    type Family = Sphere;
    type Rays = Direction;
    type K = SphereK<f32>;
    fn setup(&(center, radius): &(DVec3, f64), eye: DVec3) -> Option<SphereK<f32>> {
        Some(sphere(center, radius, eye))
    }
    fn x1(k: &SphereK<f32>, d: &V3<f32>) -> Option<f32> {
        sphere_x1(k, *d)
    }
    #[inline(always)]
    fn x8(k: &SphereK<f32>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
        sphere_x8(k, d)
    }
}

/// lanecast's edge-plane kernel with the constants of [`polygon`], for family `F`, whose
/// primitives are `N`-edge polygons.
pub struct WorldPolygon<F, const N: usize>(PhantomData<F>);
impl<F: Family<Geometry = [DVec3; N]>, const N: usize> Own for WorldPolygon<F, N> {
    type Family = F;
    type Rays = Direction;
    type K = PolyK<f32, N>;
    fn setup(v: &[DVec3; N], eye: DVec3) -> Option<PolyK<f32, N>> {
        polygon(v, eye)
    }
    fn x1(k: &PolyK<f32, N>, d: &V3<f32>) -> Option<f32> {
        polygon_x1(k, *d)
    }
    #[inline(always)]
    fn x8(k: &PolyK<f32, N>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
        polygon_x8(k, d)
    }
}

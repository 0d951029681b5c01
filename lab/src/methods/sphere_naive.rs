//! The textbook ray/sphere quadratic (e.g. Shirley & Marschner, "Fundamentals of Computer
//! Graphics", 4.4.1): with origin O (the eye), unit direction d, centre C, radius r,
//! `|O + t d - C|^2 = r^2` is `a t^2 + b t + c = 0` with
//! ```text
//! f = O - C;  a = d . d;  b = 2 f . d;  c = f . f - r^2
//! disc = b^2 - 4 a c                       miss when disc < 0
//! t = (-b - sqrt(disc)) / 2a               near root; if t <= 0, t = (-b + sqrt(disc)) / 2a
//! ```
//! all evaluated per ray in the kernel's precision (f = -(C - eye), stored eye-relative after
//! f64 setup, so this measures the formula, not the storage).
//!
//! Precision: `b^2` and `4ac` are each ~4|f|^2 and cancel: disc = 4(r^2 - l^2), l the distance
//! from C to the ray line, loses ~u * 4|f|^2 absolute, so in f32 a sphere of radius r at
//! distance D vanishes or turns into noise once r^2 < ~u D^2 (r = 1 at D = 1e4: u D^2 = 6;
//! ulp(4e8) = 32). The near root `-b - sqrt(disc)` also cancels when the eye is close to a big
//! sphere (t << |f|): a radius-1e4 ground seen from 1.5 above has t errors ~ulp(2e4) = 2e-3
//! absolute. Known to fail: `scenes/stress/far_sphere.sc`, `ground.sc`. Proven by
//! `tests/stability.rs` (`naive_loses_the_far_sphere_in_f32`).

use super::{Direction, Own, dot8, splat3};
use glam::DVec3;
use lanecast::experimental::kernel::Sphere;
use lanecast::experimental::real::{Real, V3, dot, v3};
use wide::f32x8;

/// One sphere: centre relative to the eye and radius^2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NaiveK<T> {
    /// f = eye - centre.
    pub f: V3<T>,
    /// radius^2.
    pub r2: T,
}

impl NaiveK<f64> {
    /// Constants of the sphere (`center`, `radius`) seen from `eye`, in f64.
    pub fn new(center: DVec3, radius: f64, eye: DVec3) -> NaiveK<f64> {
        NaiveK {
            f: v3(eye - center),
            r2: radius * radius,
        }
    }

    /// The same constants rounded to `T`.
    pub fn cast<T: Real>(&self) -> NaiveK<T> {
        NaiveK {
            f: self.f.map(T::from_f64),
            r2: T::from_f64(self.r2),
        }
    }
}

/// Distance along unit `d` from the eye to the first hit ahead of it.
#[inline]
pub fn naive_x1<T: Real>(k: &NaiveK<T>, d: V3<T>) -> Option<T> {
    let a = dot(d, d);
    let b = T::TWO * dot(k.f, d);
    let c = dot(k.f, k.f) - k.r2;
    let disc = b * b - T::from_f64(4.0) * a * c;
    if !(disc >= T::ZERO) {
        return None;
    }
    let sq = disc.sqrt();
    let two_a = T::TWO * a;
    let mut t = (-b - sq) / two_a;
    if !(t > T::ZERO) {
        t = (-b + sq) / two_a;
    }
    (t > T::ZERO && t < T::INFINITY).then_some(t)
}

/// [`naive_x1`] for eight directions: `None` when no lane's line meets the sphere, else the
/// mask of lanes whose line does and their distances (the caller keeps 0 < t).
#[inline(always)]
pub fn naive_x8(k: &NaiveK<f32>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
    let zero = f32x8::ZERO;
    let a = dot8(d, d);
    let b = f32x8::splat(2.0) * dot8(&splat3(k.f), d);
    let c = f32x8::splat(dot(k.f, k.f) - k.r2);
    let disc = b * b - f32x8::splat(4.0) * a * c;
    let meets = disc.simd_ge(zero);
    if !meets.any() {
        return None;
    }
    let sq = disc.sqrt();
    let two_a = f32x8::splat(2.0) * a;
    let near = (-b - sq) / two_a;
    let far = (-b + sq) / two_a;
    Some((meets, near.simd_gt(zero).select(near, far)))
}

/// The families the textbook quadratic re-implements: spheres.
pub type NaiveOwn = (NaiveSphere,);

/// The textbook quadratic in place of lanecast's spheres: [`NaiveK`], [`naive_x1`],
/// [`naive_x8`].
pub struct NaiveSphere;
impl Own for NaiveSphere {
    type Family = Sphere;
    type Rays = Direction;
    type K = NaiveK<f32>;
    fn setup(&(center, radius): &(DVec3, f64), eye: DVec3) -> Option<NaiveK<f32>> {
        Some(NaiveK::new(center, radius, eye).cast())
    }
    fn x1(k: &NaiveK<f32>, d: &V3<f32>) -> Option<f32> {
        naive_x1(k, *d)
    }
    #[inline(always)]
    fn x8(k: &NaiveK<f32>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
        naive_x8(k, d)
    }
}

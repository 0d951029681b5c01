//! When an f32 hit cannot be trusted: first-order error bounds of the f32 kernels' distance `t`
//! against the oracle's distance for the same primitive along the pixel's f64 ray, solved for
//! `t` once per primitive ([`Bounds::polygon`], [`Bounds::sphere`]).
//!
//! u = 2^-24. Each bound adds the kernel's own rounding and the change of the exact distance
//! between the f32 ray and the f64 ray. The two rays differ by an angle of at most
//! `a = Camera::direction_error` (measured from the camera's tables: about 6u to 8u up to 90
//! degrees of field of view) and in length by at most 3.5u (derived there). Every term is a
//! worst case (errors of one sign, aligned), so a hit is trusted while its bound stays within
//! [`BUDGET`], 0.9 of the tolerance. The rest of the tolerance covers second-order terms and
//! the rounding of a re-decided depth to the f32 output buffer (u/2).
//!
//! # Polygons: `t = p / (d . N)`
//!
//! - `d . N` is a three-term dot product of rounded vectors: it errs by at most 3u `sum |d_i N_i|`
//!   <= 3u (Cauchy-Schwarz, both unit), and N's rounding adds u.
//! - The f32 ray turned by `a` changes `d . N` by at most `a`. Its length, off by 3.5u, scales
//!   `d . N` by as much.
//! - `p` and the division round once each.
//! - With `cos = d . N = p / t`:
//!   `err <= u (POLY_A + POLY_B t / p)`, where `POLY_A = 2 + 3.5` and `POLY_B = 4 + a / u`.
//! - Grazing incidence, where `t` is many times the plane's distance, is the failing case
//!   (the lab's `grazing`, scene 7's far corner).
//!
//! # Spheres: `t = c / q` (eye outside) or `q` (eye inside)
//!
//! The kernel computes `q = b + s`, with `b = oc . d`, `l = oc - b d`, `s = sqrt(r^2 - l . l)`,
//! and `c = |oc|^2 - r^2` rounded once from f64. Let `m = max(|oc|, r)` (`|oc|` from outside).
//!
//! - `b`: the dot product errs by 3u |oc|, and the rounding of `oc` adds u |oc|.
//! - `l`: the error of `b` moves `l` along `d`, perpendicular to `l`, which leaves `l . l`
//!   unchanged to first order. The rounding of `oc` (perpendicular part), of the products
//!   `b d_i` and of the differences moves `l` by at most `u (|oc| + |b| + |l|) <= u (2m + r)`
//!   (`|b| <= |oc|`, and `|l| <= r` on a ray that meets the sphere). So `l . l` moves by
//!   `2 |l| u (2m + r) <= u (4 r m + 2 r^2)`, and its own dot product rounds by `3u r^2`.
//! - `disc`: with the roundings of `r^2` and of the difference (`|disc| <= r^2`), `disc` errs
//!   by `u (4 r m + 7 r^2)`. That moves `s` by `u r (2m + 3.5r) / s`, and the square root
//!   rounds by `u s`.
//! - `q`: the sum rounds by `u q`. Inside the sphere `b` may be negative, and then
//!   `s <= q + |oc|`; `u s` is counted as `u q + u m`.
//! - The ray turned by `a` moves the far root by at most `a |l| (1 + |b| / s) <= a (m + r m / s)`
//!   (`dq/dφ` for the angle φ between `d` and `oc`).
//! - The ray's length, off by 3.5u, scales `b` and leaves `l . l` unchanged to first order:
//!   3.5u |oc|.
//! - `t = c / q` adds the roundings of `c` and of the division. Its relative error is
//!   otherwise that of `q`, since `t q = c`.
//! - So `err <= u (SPHERE_A + (SPHERE_B m + r (SPHERE_C m + SPHERE_D r) / s) / q)`, where
//!   `SPHERE_A = 4`, `SPHERE_B = 3 + 1 + 3.5 + 1 + a / u`, `SPHERE_C = 2 + a / u` and
//!   `SPHERE_D = 3.5`.
//!   `s = |b - t|` and `q = b + s` are recovered from the hit (`t = b -+ s`).
//! - The error grows towards the silhouette (`s -> 0`), and for spheres far larger than their
//!   distance to the eye (`m / q` large: the lab's `ground`, a radius-1e4 sphere seen from 1.5
//!   above). These are the two failing cases.
//!
//! # Ids: the f32 edge band and sharp corners
//!
//! An f32 polygon accepts rays up to 8u outside an edge plane (`kernel::edge_eps`), its dot
//! product and rounded normal err by 4u, and the ray by `a`: its outline moves by at most
//! `E = 12u + a` radians (`kernel::f32_edge_band`) across each edge. Where two edges meet at an angle
//! `theta` on the sphere of directions, moving both by `E` moves the corner by
//! `E / sin(theta / 2)` along its bisector: a sliver's sharp tip (a silhouette triangle seen
//! nearly edge-on, or any triangle through a telephoto lens) reaches many pixels past the true
//! one. `cos theta = -n_a . n_b` for the corner's edge-plane normals, so
//! `sin(theta / 2) = sqrt((1 + n_a . n_b) / 2)`. A polygon with a corner that reaches past the
//! view's id band (`Camera::id_band`, an eighth of a pixel) is *sharp* ([`SHARP`]): every hit
//! on it is decided again in f64, whatever its distance. (Measuring each such hit with the
//! oracle's own kernel for that one polygon, edges and all, re-decided fewer pixels but took
//! 1.7x the frame on the armadillo at 1080p: its f64 constants, made from the mesh per strip,
//! cost more than the re-decisions.) A view whose `E` itself is not
//! within half the id band (a field of view under about 0.65 degrees at 640 pixels wide, 1.9
//! at 1920) is not
//! drawn in f32 at all (`kernel::f32_resolves`): `auto` runs it in f64, through every engine.
//!
//! `tests` below check both bounds against the kernels themselves, the f32 kernel along the
//! f32 ray against the oracle along the f64 ray, on grazing planes and on spheres near their
//! silhouettes, with the eye outside and inside, through cameras turned off the axes.

use crate::kernel::family::Ball;
use crate::kernel::polygon::PolyK;
use crate::par::prelude::*;
use crate::real::{U32 as U, f32_down, f32_up};
use wide::f64x4;

/// The guarantee of `--precision auto`: every pixel's depth is within this relative distance
/// of the f64 oracle's depth for the same primitive.
pub const TOLERANCE: f64 = 1e-5;

/// A hit is trusted while its bound stays within this (the bounds add worst cases; the rest
/// of the tolerance covers second-order terms and the f32 output buffer's rounding, u/2).
pub(super) const BUDGET: f64 = 0.9 * TOLERANCE;

/// The limits of a sharp polygon (module comment, "Ids"): no hit on it is trusted at any
/// distance (a lane it wins carries -0.0), and its measurement always fails
/// (`Redecide::make_oracle`), so its pixels are decided again in f64.
pub(super) const SHARP: [f32; 2] = [0.0, -0.0];

/// Whether limits `l` are [`SHARP`]'s, bit for bit.
pub(super) fn is_sharp(l: [f32; 2]) -> bool {
    l.map(f32::to_bits) == SHARP.map(f32::to_bits)
}

/// The constants of the two bounds for one camera (module comment), in units of u.
#[derive(Debug, Clone, Copy)]
pub(super) struct Bounds {
    poly_a: f64,
    poly_b: f64,
    sphere_a: f64,
    sphere_b: f64,
    sphere_c: f64,
    sphere_d: f64,
    /// A polygon with a corner whose `sin(theta / 2)` is below this is sharp: the edge band
    /// over the id band (module comment, "Ids").
    sharp_sine: f64,
}

impl Bounds {
    /// The bounds for rays whose f32 and f64 directions differ by at most `angle` radians
    /// (`Camera::direction_error`), in a view where a polygon with a corner whose
    /// `sin(theta / 2)` is below `sharp_sine` is sharp: the view's f32 edge band over its id
    /// band (module comment, "Ids"; 0: none is).
    pub(super) fn new(angle: f64, sharp_sine: f64) -> Bounds {
        let a = angle / U;
        Bounds {
            sharp_sine,
            poly_a: 2.0 + 3.5,
            poly_b: 4.0 + a,
            sphere_a: 4.0,
            sphere_b: 3.0 + 1.0 + 3.5 + 1.0 + a,
            sphere_c: 2.0 + a,
            sphere_d: 3.5,
        }
    }

    /// The relative error bound of an f32 hit at distance `t` on a polygon at plane distance
    /// `p`.
    #[cfg(test)]
    fn polygon_error(&self, p: f64, t: f64) -> f64 {
        U * (self.poly_a + self.poly_b * t / p)
    }

    /// The distances at which a hit on a polygon with plane distance `p` is trusted:
    /// `u (POLY_A + POLY_B t / p) <= BUDGET`.
    pub(super) fn polygon(&self, p: f32) -> [f32; 2] {
        [
            0.0,
            f32_down(p as f64 * (BUDGET / U - self.poly_a) / self.poly_b),
        ]
    }

    /// The relative error bound of an f32 hit at distance `t` on the sphere of `|oc|` `len`,
    /// radius `r` and `c = |oc|^2 - r^2`, through `q` and `s` recovered from `t` (Vieta:
    /// `t q = c` and `s = |q - t| / 2`, the eye outside; `q = t` and `s = (t^2 - c) / 2t`,
    /// inside).
    #[cfg(test)]
    fn sphere_error(&self, len: f64, r: f64, c: f64, t: f64) -> f64 {
        let m = len.max(r);
        let (q, s) = if c > 0.0 {
            (c / t, (c / t - t).abs() / 2.0)
        } else {
            (t, (t * t - c) / (2.0 * t))
        };
        let near_edge = r * (self.sphere_c * m + self.sphere_d * r) / s;
        U * (self.sphere_a + (self.sphere_b * m + near_edge) / q)
    }

    /// Whether [`Bounds::sphere_error`] exceeds [`BUDGET`] at `t`, in four lanes, with its
    /// denominators cleared (no division: setup evaluates it forty times per sphere). With
    /// `β = BUDGET / u - SPHERE_A`, `K = 2 r (SPHERE_C m + SPHERE_D r)`: eye outside (`c > 0`),
    /// `SPHERE_B m t (c - t^2) + K t^2 > β c (c - t^2)` (multiplied by `c (c - t^2) > 0`);
    /// inside, `SPHERE_B m (t^2 - c) + K t > β t (t^2 - c)` (by `t (t^2 - c) > 0`).
    #[inline(always)]
    fn sphere_over(&self, (len, r, c): (f64x4, f64x4, f64x4), t: f64x4) -> f64x4 {
        let m = len.max(r);
        let beta = f64x4::splat(BUDGET / U - self.sphere_a);
        let two = f64x4::splat(2.0);
        let k = two * r * (f64x4::splat(self.sphere_c) * m + f64x4::splat(self.sphere_d) * r);
        let bm = f64x4::splat(self.sphere_b) * m;
        let t2 = t * t;
        let outside = (bm * t * (c - t2) + k * t2).simd_gt(beta * c * (c - t2));
        let inside = (bm * (t2 - c) + k * t).simd_gt(beta * t * (t2 - c));
        c.simd_gt(f64x4::ZERO).select(outside, inside)
    }

    /// The distances at which a hit on each of four spheres (`|oc|`, `r`, `c = |oc|^2 - r^2`
    /// from their f32 constants) is trusted. Along the rays that meet a sphere,
    /// [`Bounds::sphere_error`] is a function of `t` alone. Outside it grows from the centre
    /// ray to the silhouette, so the hits trusted are those up to a `t*`; inside it falls with
    /// `t`, so they are those from a `t*` on. `t*` is found by bisection in the four lanes at
    /// once, keeping the trusted side: 40 halvings leave it within 1e-12 of the interval, far
    /// below the f32 rounding of the result.
    pub(super) fn spheres_x4(&self, len: [f64; 4], r: [f64; 4], c: [f64; 4]) -> [[f32; 2]; 4] {
        let (len, r, c) = (f64x4::new(len), f64x4::new(r), f64x4::new(c));
        let inside = c.simd_le(f64x4::ZERO);
        // outside: increasing on (0, sqrt(c)), the near roots; inside: decreasing on
        // (0, r + |oc|]
        let far = r + len;
        let (mut lo, mut hi) = (f64x4::ZERO, inside.select(far, c.max(f64x4::ZERO).sqrt()));
        for _ in 0..40 {
            let mid = f64x4::splat(0.5) * (lo + hi);
            // t* above mid: outside, where mid is within the budget; inside, where it is over
            let up = self.sphere_over((len, r, c), mid) ^ !inside;
            lo = up.select(mid, lo);
            hi = up.select(hi, mid);
        }
        let none = self.sphere_over((len, r, c), far).to_array();
        let (lo, hi, inside) = (lo.to_array(), hi.to_array(), inside.to_array());
        std::array::from_fn(|i| match (inside[i] != 0.0, none[i] != 0.0) {
            (false, _) => [0.0, f32_down(lo[i])],
            (true, true) => [f32::INFINITY, f32::INFINITY],
            (true, false) => [f32_up(hi[i]), f32::INFINITY],
        })
    }
}

/// The distances at which a primitive's f32 hits are trusted, written once per outline class
/// (`Family::Outline`: what the family's f32 constants bound, a ball or a convex polygon).
pub(super) trait Trusted: Copy {
    /// `put(i, limits)` for each primitive `i` in `0..n` of one store, whose outline is
    /// `get(i)`, on all threads.
    fn each(
        bounds: &Bounds,
        n: usize,
        get: impl Fn(usize) -> Self + Sync,
        put: impl Fn(usize, [f32; 2]) + Sync,
    );
}

/// Balls ([`Bounds::spheres_x4`]), four per call (the last one repeated to fill the last call).
impl Trusted for Ball {
    fn each(
        bounds: &Bounds,
        n: usize,
        get: impl Fn(usize) -> Ball + Sync,
        put: impl Fn(usize, [f32; 2]) + Sync,
    ) {
        (0..n.div_ceil(4)).into_par_iter().for_each(|q| {
            let lane = |l: usize| {
                let b = get((4 * q + l).min(n - 1));
                sphere_inputs(b.oc, b.r2, b.c)
            };
            let v: [(f64, f64, f64); 4] = std::array::from_fn(lane);
            let limits = bounds.spheres_x4(v.map(|v| v.0), v.map(|v| v.1), v.map(|v| v.2));
            for (l, limit) in limits.into_iter().enumerate().take((n - 4 * q).min(4)) {
                put(4 * q + l, limit);
            }
        });
    }
}

/// Convex polygons ([`Bounds::polygon`]: by their plane distance alone).
impl<const N: usize> Trusted for PolyK<f32, N> {
    fn each(
        bounds: &Bounds,
        n: usize,
        get: impl Fn(usize) -> PolyK<f32, N> + Sync,
        put: impl Fn(usize, [f32; 2]) + Sync,
    ) {
        (0..n).into_par_iter().for_each(|i| {
            let k = get(i);
            put(
                i,
                if bounds.sharp(&k) {
                    SHARP
                } else {
                    bounds.polygon(k.p)
                },
            )
        });
    }
}

impl Bounds {
    /// Whether the polygon of f32 constants `k` has a corner sharper than the view allows
    /// (module comment, "Ids"), from its edge-plane normals in f64. NaN normals count as sharp.
    fn sharp<const N: usize>(&self, k: &PolyK<f32, N>) -> bool {
        (0..N).any(|i| {
            let (a, b) = (k.n[(i + N - 1) % N], k.n[i]);
            let c: f64 = (0..3).map(|j| a[j] as f64 * b[j] as f64).sum();
            let sine = ((1.0 + c) / 2.0).max(0.0).sqrt();
            sine.is_nan() || sine < self.sharp_sine
        })
    }
}

/// `|oc|`, `r` and `c` of a sphere from its f32 constants `oc`, `r2`, `c`.
fn sphere_inputs(oc: [f32; 3], r2: f32, c: f32) -> (f64, f64, f64) {
    let len = oc.map(f64::from).iter().map(|x| x * x).sum::<f64>().sqrt();
    (len, (r2 as f64).sqrt(), c as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::kernel::polygon::{PolyK, QuadK, TriangleK, polygon_x1};
    use crate::kernel::sphere::{SphereK, sphere_x1};
    use crate::scene::CameraSpec;
    use glam::{DMat3, DVec3};

    /// Bounds are first order: they are checked where they are small enough for that to hold
    /// (the trust rule only ever uses them below `BUDGET`).
    const CHECKED_UP_TO: f64 = 1e-3;

    /// The camera looking from `eye` at `look`, `fov` degrees wide, 200x150 pixels.
    fn camera(eye: DVec3, look: DVec3, fov: f64) -> Camera {
        let spec = CameraSpec {
            eye,
            look,
            up: DVec3::new(0.1, 1.0, 0.05),
            lens: None,
        };
        Camera::new(&spec, fov, 200, 150)
    }

    /// Over every pixel where the f32 kernel (f32 constants, f32 ray) and the oracle (f64
    /// constants, f64 ray) both hit and `bound(t64)` is checkable: asserts the relative error
    /// is within the bound, and returns the largest error / bound seen and the pixels checked.
    fn check(
        cam: &Camera,
        hit32: impl Fn([f32; 3]) -> Option<f32>,
        hit64: impl Fn([f64; 3]) -> Option<f64>,
        bound: impl Fn(f64) -> f64,
    ) -> (f64, usize) {
        let (t32, t64) = (cam.tables::<f32>(1, 1), cam.tables::<f64>(1, 1));
        let (mut worst, mut n): (f64, usize) = (0.0, 0);
        for y in 0..cam.height as usize {
            for x in 0..cam.width as usize {
                let (Some(a), Some(b)) = (hit32(t32.dir_x1(x, y)), hit64(t64.dir_x1(x, y))) else {
                    continue;
                };
                let (err, limit) = ((a as f64 - b).abs() / b, bound(b));
                if limit <= CHECKED_UP_TO {
                    assert!(err <= limit, "{err:e} > {limit:e} at ({x}, {y}), t {b}");
                    worst = worst.max(err / limit);
                    n += 1;
                }
            }
        }
        (worst, n)
    }

    /// [`check`] of the polygon bound for the polygon of constants `k64` through `cam`.
    fn polygon_case<const N: usize>(cam: &Camera, k64: PolyK<f64, N>) -> (f64, usize) {
        let bounds = Bounds::new(cam.direction_error(), 0.0);
        let k32 = k64.cast::<f32>();
        let bound = |t: f64| bounds.polygon_error(k32.p as f64, t);
        check(cam, |d| polygon_x1(&k32, d), |d| polygon_x1(&k64, d), bound)
    }

    #[test]
    fn polygon_bound_holds_at_grazing_incidence() {
        let tilt = DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.3);
        let eye = DVec3::new(0.3, 1.0, 0.2);
        // the ground under a tilted eye, a wall beside it, scene 7's far-reaching triangle
        let ground = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(a, b)| eye + tilt * DVec3::new(300.0 * a, -0.7, 300.0 * b));
        let wall = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)]
            .map(|(a, b)| eye + tilt * DVec3::new(1.2, 50.0 * a, 400.0 * b));
        let tri = [
            DVec3::new(0.0, -0.15, -0.48),
            DVec3::new(-42.0, 24.0, -80.0),
            DVec3::new(42.0, 24.0, -80.0),
        ];
        let (mut worst, mut n): (f64, usize) = (0.0, 0);
        for fov in [30.0, 60.0, 100.0] {
            let cam = camera(eye, eye + tilt * DVec3::new(0.2, -0.1, -1.0), fov);
            for quad in [ground, wall] {
                let k64 = QuadK::quad(&quad, eye).expect("seen face-on enough");
                let (w, m) = polygon_case(&cam, k64);
                (worst, n) = (worst.max(w), n + m);
            }
            let cam = camera(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), fov);
            let k64 = TriangleK::triangle(&tri, DVec3::ZERO).expect("a triangle");
            let (w, m) = polygon_case(&cam, k64);
            (worst, n) = (worst.max(w), n + m);
        }
        assert!(n > 50_000, "{n} pixels checked");
        // the bound adds worst cases; the errors reach a fair part of it
        eprintln!("polygons: {n} pixels, largest error / bound {worst:.2}");
        assert!(worst > 0.1, "largest error / bound {worst}");
    }

    #[test]
    fn polygon_limit_is_where_the_bound_meets_the_budget() {
        let bounds = Bounds::new(7.0 * U, 0.0);
        for p in [1e-3f32, 0.283, 5.0, 1e4] {
            let hi = bounds.polygon(p)[1] as f64;
            assert!(bounds.polygon_error(p as f64, hi) <= BUDGET);
            assert!(bounds.polygon_error(p as f64, hi * (1.0 + 1e-6)) > BUDGET);
        }
    }

    #[test]
    fn sphere_bound_holds_near_silhouettes_and_horizons() {
        let v = DVec3::new;
        // (eye, look, centre, radius): an ordinary sphere, a radius-1e4 ground seen from 1.5
        // above towards its horizon, the eye inside a sphere, a far large sphere, a far small one
        let cases = [
            (
                v(0.1, 0.2, 0.3),
                v(2.0, 1.0, -40.0),
                v(2.0, 1.0, -40.0),
                1.0,
            ),
            (
                v(0.3, 0.2, 1.0),
                v(0.4, -0.3, -6.0),
                v(0.4, -0.3, -6.0),
                1.5,
            ),
            (
                v(0.0, 0.0, 0.0),
                v(0.3, -0.02, -1.0),
                v(0.0, -1.0e4 - 1.5, -20.0),
                1.0e4,
            ),
            (v(0.2, 0.1, 0.3), v(1.0, 0.5, -3.0), v(0.0, 0.0, 0.0), 5.0),
            (
                v(5.0, -3.0, 2.0),
                v(1e3, 200.0, -3e3),
                v(1e3, 200.0, -3e3),
                100.0,
            ),
        ];
        let (mut worst, mut n): (f64, usize) = (0.0, 0);
        for (eye, look, centre, radius) in cases {
            for fov in [20.0, 60.0, 100.0] {
                let cam = camera(eye, look, fov);
                let bounds = Bounds::new(cam.direction_error(), 0.0);
                let k64 = SphereK::new(centre, radius, eye);
                let k32 = k64.cast::<f32>();
                let (len, r, c) = sphere_inputs(k32.oc, k32.r2, k32.c);
                let bound = |t: f64| bounds.sphere_error(len, r, c, t);
                let (w, m) = check(&cam, |d| sphere_x1(&k32, d), |d| sphere_x1(&k64, d), bound);
                (worst, n) = (worst.max(w), n + m);
            }
        }
        assert!(n > 50_000, "{n} pixels checked");
        eprintln!("spheres: {n} pixels, largest error / bound {worst:.2}");
        assert!(worst > 0.05, "largest error / bound {worst}");
    }

    /// The division-free test the limits are solved with says what the bound says.
    #[test]
    fn sphere_over_is_the_bound_against_the_budget() {
        let bounds = Bounds::new(7.0 * U, 0.0);
        // (|oc|, r): outside near and far, a huge sphere close by, the eye inside
        for (len, r) in [
            (6.0, 1.5),
            (40.0, 1.0),
            (1.0e4 + 1.5, 1.0e4),
            (0.1, 5.0),
            (2.0, 3.0),
        ] {
            let c: f64 = len * len - r * r;
            let end = if c > 0.0 { c.sqrt() } else { r + len };
            let (mut over, mut under) = (0, 0);
            for i in 1..2000 {
                let t = end * i as f64 / 2000.0;
                let err = bounds.sphere_error(len, r, c, t);
                // away from the crossing, where rounding could tip either form
                if (err / BUDGET - 1.0).abs() > 1e-9 {
                    let lanes = (f64x4::splat(len), f64x4::splat(r), f64x4::splat(c));
                    let over_x4 = bounds.sphere_over(lanes, f64x4::splat(t)).to_array();
                    assert_eq!(over_x4[0] != 0.0, err > BUDGET, "{len} {r} {t}");
                    if err > BUDGET { over += 1 } else { under += 1 }
                }
            }
            assert!(
                over > 0 && under > 0,
                "{len} {r}: {over} over, {under} under"
            );
        }
    }

    /// [`Bounds::spheres_x4`] for one sphere (`oc`, `r2`, `c`: its f32 constants).
    fn one_sphere(bounds: &Bounds, oc: [f32; 3], r2: f32, c: f32) -> [f32; 2] {
        let (len, r, c) = sphere_inputs(oc, r2, c);
        bounds.spheres_x4([len; 4], [r; 4], [c; 4])[0]
    }

    #[test]
    fn sphere_limits_keep_the_trusted_side() {
        let bounds = Bounds::new(7.0 * U, 0.0);
        // outside: trusted up to hi; inside: from lo on
        for (oc, r) in [
            ([0.0f32, 0.0, -6.0], 1.5f32),
            ([0.0, -1.0e4 - 1.5, -20.0], 1.0e4),
        ] {
            let len = sphere_inputs(oc, 0.0, 0.0).0;
            let c = (len * len - (r as f64).powi(2)) as f32;
            let [lo, hi] = one_sphere(&bounds, oc, r * r, c);
            assert_eq!(lo, 0.0);
            let err = |t: f64| bounds.sphere_error(len, r as f64, c as f64, t);
            assert!(err(hi as f64) <= BUDGET && err(hi as f64 * (1.0 + 1e-6)) > BUDGET);
        }
        let (oc, r) = ([0.1f32, 0.0, 0.0], 5.0f32);
        let c = 0.01 - 25.0;
        let [lo, hi] = one_sphere(&bounds, oc, r * r, c);
        assert_eq!(hi, f32::INFINITY);
        let err = |t: f64| bounds.sphere_error(0.1, 5.0, c as f64, t);
        assert!(err(lo as f64) <= BUDGET && err(lo as f64 * (1.0 - 1e-6)) > BUDGET);
    }
}

//! Where the kernels can accept a pixel's ray, and how near they can say its hit is: the
//! written error bound the tiles (`footprint.rs`) and the BVH (`build.rs`) cull by. Both must
//! keep every primitive a kernel accepts on a ray, at every distance it may return, or their
//! ids and depths would differ from `--accel none`'s.
//!
//! u = 2^-24. `a` = `Camera::direction_error`: the angle between a pixel's f32 ray and its
//! exact ray (the f64 tables' ray, itself within ~1e-16 of exact). Terms of order u^2 are
//! dropped; every bound below carries a relative slack of at least 1e-9 over them.
//!
//! # Polygons: which rays (the screen region)
//!
//! The f32 kernel accepts its ray `d32` (`|d32| = 1 +- 3.5u`) on an edge when
//! `fl(n . d32) >= -8u`, `n` the edge normal as the packed store holds it (f32, `|n| <= 1 + u`).
//! The three-term dot product errs by at most `3u |n| |d32|`, so `n . d32 >= -11u (1 + 4u)`,
//! and the exact ray `d`, within `a` of `d32 / |d32|`, has `n . d >= -(11u + a)` (to first
//! order). The f64 kernels accept within `8.9e-16` of their own normals, which lie within
//! `u/2` of `n`: far inside. So every ray any kernel accepts has, for every edge,
//! `n . d >= -E`, with `E = max(32u, 2 (8u + a))` taken (at least 1.4 times the bound).
//! A hit also needs `t > 0`, so `c32 = fl(N . d32) > 0` (below: `N . d > -e_c`).
//!
//! Pixel rays are `d = q / |q|`, `q = f + sx r + sy u` with the exact screen coordinates inside
//! the image's rectangle (`Camera::screen`: `|sx| <= half_w`, `|sy| <= half_h` for a field of
//! view), so `|q| <= S = sqrt(1 + max sx^2 + max sy^2)`. The
//! conditions `n . q >= -E |q|` hold only where `n . q >= -E S`: half-planes in `(sx, sy)`.
//! The image rectangle clipped by them (Sutherland-Hodgman) is a convex [`Region`] holding
//! every pixel whose ray a kernel may accept. Nothing else is assumed: not the polygon's
//! projected vertices (an f32 edge normal of a polygon seen nearly edge-on is not the line
//! through its projected vertices), nor its shape. That matters: the accepted rays are the
//! polygon widened by `E` on every edge, and a sliver narrower than `E` (a far polygon seen
//! nearly edge-on: a mesh's silhouette from a telephoto camera) widens by `E` over its
//! inradius times its length, up to a strip across the whole image. A fixed margin around the
//! projected vertices missed those rays.
//!
//! # Polygons: how near (`near`)
//!
//! The kernel returns `t32 = fl(p / c32)`. `c32 = fl(N . d32)` errs by `3u`, `d32`'s length by
//! `3.5u` and its direction by `a`, so `c32 <= N . d + e_c`, with `e_c = 2 (a + 4u)` taken
//! (`a + 6.5u` derived). Hence `t32 >= p (1 - u) / (cmax + e_c)`, `cmax` the largest `N . d`
//! over the region's rays: `|N|` when `N`'s direction lies in the region, else the largest
//! over its edges' arcs (a linear function on a great-circle arc peaks at the projection of
//! `N` onto the arc's plane, or at an end). Also, always, `c32 <= (1 + u)(1 + 3.5u)(1 + 3u)`,
//! so `t32 >= p (1 - u) / (1 + 8u)` (the plane bound, at any angle). The larger of the two is
//! taken. The f64 kernels' distances (`p` within `u/2`, `N` within `u/2`, f64 rounding) are
//! larger still.
//!
//! # Spheres
//!
//! The f32 kernel accepts `d32` when `fl(r2 - fl(l . l)) >= 0`, `l = oc - b d32`,
//! `b = fl(oc . d32)`: `l` errs by at most `4u |oc| + u |l|`, and `fl(l . l) <= r2` gives
//! `|l| <= r (1 + 2u)`; so `d32`'s line passes within `r (1 + 3u) + 4.5u |oc|` of the centre
//! (`oc` rounded to f32 moves it by `u/2 |oc|` more), and the exact ray within
//! `r' = r (1 + 4u) + E |oc|`. The distance is `fl(c / fl(b + s))` with `b <= |oc| (1 + 7u)`
//! and `s = fl(sqrt(disc)) <= r (1 + u)` (`disc <= r2`), so with the eye outside
//! `t32 >= c (1 - u) / ((|oc| (1 + 8u) + r (1 + 2u)) (1 + 2u))` ([`ball_near`]); with the
//! eye inside, 0.
//!
//! # The BVH
//!
//! The BVH's slab test runs on the kernels' own rays, and a node is entered when a ray enters
//! its box no later than the ray's best hit. So each primitive's box must hold a point of
//! every ray a kernel accepts on it, no farther than the distance the kernel returns there,
//! with a margin of `4u` of that distance for the slab test's rounding (2u):
//! [`View::polygon_slice`] (the region's rays at the polygon's `near`) or [`View::polygon_cut`]
//! (the region's rays cut by a plane just nearer than the polygon's), and [`ball_cap`] (the
//! cone of the accepted rays at the sphere's `near`, or the eye itself when it is within
//! `32u (|oc| + r)` of the sphere).
//!
//! # Where it fails
//!
//! Nowhere in the limits `scene::validate` allows, to first order; a region covers the whole
//! image where the bound cannot shrink it (a polygon whose edge planes pass within `E` of every
//! pixel: a sliver seen edge-on across the image). It costs where it is loose: such a sliver
//! is listed in every tile of its strip, and `near` is the plane bound once the region holds
//! rays near the plane's normal. Proven by `tests` below (the bounds against the kernels
//! themselves, over random cameras, scales and sizes within the limits) and by tests/accel.rs
//! and tests/accel_random.rs (every acceleration equal to `none`, bit for bit).

use crate::camera::Camera;
use crate::real::U32;
use glam::DVec3;

mod region;
pub(crate) use region::Region;
#[cfg(test)]
use region::arc_max;

/// Relative slack on every bound computed here in f64, for its own rounding (tens of
/// operations of 1.1e-16) and the dropped terms of order u^2 (3.6e-15).
pub(crate) const SLACK: f64 = 1e-9;

/// Most vertices of a [`Region`]: the image's four, and one per half-plane clipped (four edges
/// and the plane's side).
const MAX_VERTICES: usize = 9;

/// A camera's screen geometry and error bounds (module comment).
#[derive(Debug, Clone, Copy)]
pub(crate) struct View {
    /// The eye, and the orthonormal basis forward, right, up (f64, as `Camera`).
    pub(crate) eye: DVec3,
    pub(crate) f: DVec3,
    pub(crate) r: DVec3,
    pub(crate) u: DVec3,
    /// The screen's half width and height at distance 1.
    pub(crate) half_w: f64,
    pub(crate) half_h: f64,
    /// The principal point in half images, `(2cx/W, 2cy/H)` (`Camera::principal`).
    pub(crate) principal: (f64, f64),
    /// The image's edges in screen coordinates, `[left, right, bottom, top]`.
    pub(crate) screen: [f64; 4],
    /// `S`: the longest `|q|` over the image.
    stretch: f64,
    /// `E`: how far outside an edge plane (radians) an accepted ray's exact direction may lie.
    pub(crate) edge: f64,
    /// `e_c`: how much larger `fl(N . d32)` may be than `N . d` for the exact ray `d`.
    pub(crate) cosine: f64,
    /// `a`: the angle between a pixel's f32 ray and its exact ray.
    pub(crate) ray: f64,
}

impl View {
    /// The view of `camera`.
    pub(crate) fn new(camera: &Camera) -> View {
        let a = camera.direction_error();
        let eps = 8.0 * U32;
        let (sx, sy) = camera.screen_reach();
        View {
            eye: camera.eye,
            f: camera.f,
            r: camera.r,
            u: camera.u,
            half_w: camera.half_w,
            half_h: camera.half_h,
            principal: camera.principal(),
            screen: camera.screen(),
            stretch: (1.0 + sx.powi(2) + sy.powi(2)).sqrt(),
            edge: (32.0 * U32).max(2.0 * (eps + a)),
            cosine: 2.0 * (a + 4.0 * U32),
            ray: a,
        }
    }

    /// `v` (eye-relative) in camera coordinates: along right, up, forward.
    #[inline]
    fn local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.r), v.dot(self.u), v.dot(self.f))
    }

    /// The screen region holding every pixel whose ray a kernel may accept on the polygon of
    /// edge normals `n` and plane normal `nrm` (the packed store's f32 constants).
    pub(crate) fn polygon_region<const N: usize>(
        &self,
        n: &[[f32; 3]; N],
        nrm: [f32; 3],
    ) -> Region {
        let v = |x: [f32; 3]| DVec3::new(x[0].into(), x[1].into(), x[2].into());
        // `n . q >= -E S` for each edge, `N . q > -e_c S` for `t > 0`: offsets rounded up
        let line = |x: [f32; 3], off: f64| {
            let w = self.local(v(x));
            [w.x, w.y, w.z + (off + SLACK) * self.stretch * (1.0 + SLACK)]
        };
        let edges = n.map(|e| line(e, self.edge));
        // most polygons: the edges' lines meet in a polygon inside the image (the plane's side
        // then cuts nothing off it that matters: the region may keep more)
        if let Some(region) = Region::corners(&edges, self.screen) {
            return region;
        }
        let mut region = Region::image(self.screen);
        for [a, b, c] in edges.into_iter().chain([line(nrm, self.cosine)]) {
            region.clip(a, b, c);
        }
        region
    }

    /// A lower bound on every distance a kernel returns on the polygon of plane normal `nrm`
    /// and plane distance `p` (f32 constants) for the rays of `region` (module comment).
    pub(crate) fn polygon_near(&self, region: &Region, nrm: [f32; 3], p: f32) -> f64 {
        let by_plane = plane_near(p);
        let p = f64::from(p) * (1.0 - U32);
        let nrm = self.local(DVec3::new(nrm[0].into(), nrm[1].into(), nrm[2].into()));
        // (no ray of the region with `c32 > 0`, `den <= 0`: no hit; the plane bound stands)
        let den = region
            .max_cosine(nrm)
            .map(|c| c * (1.0 + SLACK) + SLACK + self.cosine);
        let by_region = match den {
            Some(den) if den > 0.0 => p / den,
            _ => by_plane,
        };
        by_plane.max(by_region) * (1.0 - SLACK)
    }

    /// The radius `r'` about the centre (`oc`: centre - eye, f64) within which every ray a
    /// kernel accepts on a sphere of radius `r` passes (module comment).
    pub(crate) fn ball_reach(&self, oc: DVec3, r: f64) -> f64 {
        (r * (1.0 + 4.0 * U32) + self.edge * oc.length()) * (1.0 + SLACK)
    }

    /// An eye-relative box holding, for every ray of `region` (a polygon's, with `near` its
    /// [`View::polygon_near`]), the point at distance `near` along the pixel's f32 ray (or f64
    /// ray), with a margin of `4u near` in every axis: so that the BVH's slab test of that ray
    /// against any box holding this one enters it no later than `near`, hence no later than
    /// any distance the kernels return there (`build.rs`). `None` when no ray reaches.
    ///
    /// The points `near q / |q|` lie in the frustum slice `lambda q`, `q` in the region,
    /// `lambda` from `near / max |q|` to `near / min |q|`: the convex hull of its corners. The
    /// f32 ray lies within `a` of the exact one and its length within `3.5u` of 1, which moves
    /// the point by `(a + 3.5u) near`.
    pub(crate) fn polygon_slice(&self, region: &Region, near: f64) -> Option<(DVec3, DVec3)> {
        if region.is_empty() || near.is_nan() || near <= 0.0 {
            return None;
        }
        let len = |[x, y]: [f64; 2]| (1.0 + x * x + y * y).sqrt();
        let far = region
            .vertices()
            .iter()
            .map(|&v| len(v))
            .fold(1.0, f64::max);
        let close = (1.0 + region.distance2_from_centre()).sqrt();
        let (lo, hi) = (near / far * (1.0 - SLACK), near / close * (1.0 + SLACK));
        let (mut min, mut max) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for &[x, y] in region.vertices() {
            let q = self.f + self.r * x + self.u * y;
            for p in [q * lo, q * hi] {
                (min, max) = (min.min(p), max.max(p));
            }
        }
        let pad = near * (self.ray + 8.0 * U32) * (1.0 + SLACK)
            + SLACK * min.abs().max(max.abs()).max_element();
        Some((min - DVec3::splat(pad), max + DVec3::splat(pad)))
    }
    /// Another box with [`View::polygon_slice`]'s guarantee, for the polygon of plane normal
    /// `nrm` and plane distance `p` (f32 constants) whose rays are those of `region`: the
    /// region's rays cut by the plane `N . x = p_lo`, nearer than the polygon's own plane.
    /// `None` when a ray of the region may run parallel to the plane (`N . d <= 0`).
    ///
    /// Each accepted ray has `t >= p (1 - u) / (N . d + e_c)` (module comment), which, on the
    /// rays with `N . d >= c_min > 0`, is at least `p_lo / N . d` with
    /// `p_lo = p (1 - u) c_min / (c_min + e_c)`: the distance to that plane. The cut is the
    /// region projected from the eye onto the plane, a convex polygon whose corners are the
    /// region's corners' images. `c_min`, the smallest `N . d` over the region, is minus the
    /// largest `-N . d`. The margin is [`View::polygon_slice`]'s, at the cut's farthest
    /// distance, `p_lo / c_min`. For a polygon seen face-on this is the polygon itself, moved
    /// towards the eye by `e_c / c_min` of its distance; the slice at `near`, a sphere's cap
    /// through the nearest point, reaches out of the polygon's box towards the eye by its depth.
    pub(crate) fn polygon_cut(
        &self,
        region: &Region,
        nrm: [f32; 3],
        p: f32,
    ) -> Option<(DVec3, DVec3)> {
        let n = DVec3::new(nrm[0].into(), nrm[1].into(), nrm[2].into());
        let c_min = -(region.max_cosine(-self.local(n))? * (1.0 + SLACK) + SLACK);
        if c_min.is_nan() || c_min <= 0.0 {
            return None;
        }
        let p_lo = f64::from(p) * (1.0 - U32) * c_min / (c_min + self.cosine) * (1.0 - SLACK);
        let (mut min, mut max) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for &[x, y] in region.vertices() {
            let q = self.f + self.r * x + self.u * y;
            let point = q * (p_lo / n.dot(q));
            (min, max) = (min.min(point), max.max(point));
        }
        let pad = p_lo / c_min * (self.ray + 8.0 * U32) * (1.0 + SLACK)
            + SLACK * min.abs().max(max.abs()).max_element();
        Some((min - DVec3::splat(pad), max + DVec3::splat(pad)))
    }
}

/// The plane bound of [`View::polygon_near`] alone, `p (1 - u) / (1 + 8u)` (f32 plane
/// distance `p`): it holds for every ray, at any angle of incidence, but is weaker than the
/// region's bound for a polygon seen obliquely.
pub(crate) fn plane_near(p: f32) -> f64 {
    f64::from(p) * (1.0 - U32) / (1.0 + 8.0 * U32)
}

/// A lower bound on every distance a kernel returns on the sphere of f32 constants `oc`, `r2`,
/// `c` (0 with the eye inside: `c <= 0`; module comment).
pub(crate) fn ball_near(oc: [f32; 3], r2: f32, c: f32) -> f64 {
    if c.is_nan() || c <= 0.0 {
        return 0.0;
    }
    let len = oc.map(f64::from).iter().map(|v| v * v).sum::<f64>().sqrt();
    let q =
        (len * (1.0 + 8.0 * U32) + f64::from(r2).sqrt() * (1.0 + 2.0 * U32)) * (1.0 + 2.0 * U32);
    f64::from(c) * (1.0 - U32) / (q * (1.0 + SLACK))
}

/// An eye-relative box holding, for every ray the kernels may accept on the sphere of f32
/// constants `oc`, `r2`, `c`, a point of the ray no farther than the distance they return,
/// with a margin of `4u` of that distance in every axis (as [`View::polygon_slice`]; no
/// camera: the BVH tests the kernels' own rays).
///
/// - The eye within `32u (|oc| + r)` of the sphere or inside: a box around the eye (every ray
///   enters it at 0).
/// - Else every accepted ray's line passes within `r_a = r (1 + 3u) + 5u |oc|` of the centre,
///   and towards it: `b = oc . d > 0`. With `b < 0`, `|b|^2 = |oc|^2 - |l|^2` and
///   `s^2 <= r^2 - |l|^2 + 8u |oc| |l|` give `|b|^2 - s^2 >= |oc|^2 - r^2 - 8u |oc|^2 >=
///   24u |oc|^2`, so `|b| - s >= 12u |oc|`, more than the error of `b` (`3.5u |oc|`): then
///   `q = b + s < 0` and `t <= 0`. Its direction lies within `alpha`, `sin alpha = r_a / |oc|`,
///   of the centre's, and its point at `near` ([`ball_near`]) within
///   `2 near sin(alpha / 2) + 3.5u near` of `near oc / |oc|`.
pub(crate) fn ball_cap(oc: [f32; 3], r2: f32, c: f32) -> (DVec3, DVec3) {
    let oc = DVec3::new(oc[0].into(), oc[1].into(), oc[2].into());
    let (len, r) = (oc.length(), f64::from(r2).sqrt());
    if c.is_nan() || c <= 0.0 || len - r <= 32.0 * U32 * (len + r) {
        let half = (len + r) * 8.0 * U32;
        return (DVec3::splat(-half), DVec3::splat(half));
    }
    // (the f32 components went to f64 exactly, and come back so)
    let near = ball_near(oc.to_array().map(|v| v as f32), r2, c);
    let sin = ((r * (1.0 + 3.0 * U32) + 5.0 * U32 * len) / len).min(1.0);
    let chord = 2.0 * (sin.asin() / 2.0).sin();
    let half = near * (chord + 8.0 * U32) * (1.0 + SLACK);
    let at = oc * (near / len);
    (at - DVec3::splat(half), at + DVec3::splat(half))
}

#[cfg(test)]
mod tests;

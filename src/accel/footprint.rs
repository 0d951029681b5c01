//! Where a primitive can appear on screen, for the tiles (`tiles.rs`): the screen geometry, a
//! primitive's pixel rectangle and `near` bound from the kernels' written error bound
//! (`accel::reach`), and the centre rays of each tile's packets ([`PacketCones`]), which leave
//! out of a tile's entry the packets none of whose rays the kernel can accept.

use super::reach::{Region, View, ball_near, plane_near};
use super::{TILE_H, TILE_W};
use crate::camera::Camera;
use crate::kernel::family::Ball;
use crate::kernel::polygon::PolyK;
use crate::soa::{Columns, Packed, Stored};
use glam::DVec3;

use crate::real::U32;
/// A point closer to the eye's plane than this fraction of its distance makes a primitive's
/// projection unbounded: it gets the whole image.
pub(super) const NEAR_PLANE_REL: f64 = 1e-6;
/// Points this far behind the eye's plane (relative to their distance: a sine) cannot be hit
/// by a forward ray: ~1e3 times the kernels' angular tolerance.
pub(super) const BEHIND_REL: f64 = 1e-3;
/// Angular margin of the packets' cones ([`PacketCones`]), radians: twice (8u edge tolerance +
/// 8u ray error), more where `Camera::direction_error` exceeds 8u.
pub(super) const ANGLE_MARGIN: f64 = 32.0 * U32;
/// Margin of a projected point, pixels, for the f64 rounding of the projection itself (a few
/// units of 1e-16 relative to coordinates of at most ~1e9 pixels in front of the near plane:
/// under 1e-6 pixels): 1e-3 is far beyond it.
pub(super) const PROJECTION_PX: f64 = 1e-3;

/// The screen geometry a footprint is measured in.
pub(super) struct Screen {
    pub(super) view: View,
    w: f64,
    h: f64,
}

impl Screen {
    pub(super) fn new(c: &Camera) -> Screen {
        Screen {
            view: View::new(c),
            w: c.width as f64,
            h: c.height as f64,
        }
    }

    /// Pixel coordinates (pixel x at coordinate x) of screen coordinates `(sx, sy)`:
    /// `camera.rs` inverted.
    fn pixel(&self, (sx, sy): (f64, f64)) -> (f64, f64) {
        let v = &self.view;
        let (px, py) = v.principal;
        (
            (sx / v.half_w + px) * self.w / 2.0 - 0.5,
            (py - sy / v.half_h) * self.h / 2.0 - 0.5,
        )
    }

    /// Pixel coordinates of eye-relative point `q`, or `None` when it is not safely in front.
    pub(super) fn project(&self, q: DVec3) -> Option<(f64, f64)> {
        let v = &self.view;
        let z = q.dot(v.f);
        // written so that a NaN is "not in front"
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(z > NEAR_PLANE_REL * q.length()) {
            return None;
        }
        Some(self.pixel((q.dot(v.r) / z, q.dot(v.u) / z)))
    }

    /// The pixel rectangle (inclusive, clipped) covering the projections of `points`; the
    /// whole image when a point is not in front; `None` when off screen or when every point is
    /// clearly behind the eye (`BEHIND_REL`: no forward ray reaches the convex hull of such
    /// points).
    pub(super) fn rect(&self, points: impl Iterator<Item = DVec3>) -> Option<[u16; 4]> {
        let (mut x0, mut y0) = (f64::INFINITY, f64::INFINITY);
        let (mut x1, mut y1) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        let (mut unbounded, mut all_behind) = (false, true);
        for q in points {
            all_behind &= q.dot(self.view.f) < -BEHIND_REL * q.length();
            match self.project(q) {
                Some((x, y)) => (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y)),
                None => unbounded = true,
            }
        }
        if all_behind {
            return None;
        }
        if unbounded {
            return Some(self.whole());
        }
        self.pixels([x0, y0, x1, y1])
    }

    /// The pixels (inclusive, clipped) whose centres lie in the box `[x0, y0, x1, y1]` of pixel
    /// coordinates, widened by [`PROJECTION_PX`]; `None` when none does. A NaN box gives the
    /// whole image.
    fn pixels(&self, [x0, y0, x1, y1]: [f64; 4]) -> Option<[u16; 4]> {
        let m = PROJECTION_PX;
        let (x0, x1) = ((x0 - m).ceil().max(0.0), (x1 + m).floor().min(self.w - 1.0));
        let (y0, y1) = ((y0 - m).ceil().max(0.0), (y1 + m).floor().min(self.h - 1.0));
        if x0.is_nan() || x1.is_nan() || y0.is_nan() || y1.is_nan() {
            return Some(self.whole());
        }
        (x0 <= x1 && y0 <= y1).then_some([x0 as u16, y0 as u16, x1 as u16, y1 as u16])
    }

    /// The pixels of a screen region (`accel::reach`), `None` when it holds none.
    pub(super) fn region_pixels(&self, region: &Region) -> Option<[u16; 4]> {
        let [sx0, sy0, sx1, sy1] = region.bounds()?;
        // y grows downwards: the top row has the largest sy
        let ((x0, y0), (x1, y1)) = (self.pixel((sx0, sy1)), self.pixel((sx1, sy0)));
        self.pixels([x0, y0, x1, y1])
    }

    pub(super) fn whole(&self) -> [u16; 4] {
        [0, 0, self.w as u16 - 1, self.h as u16 - 1]
    }
}

/// `near` (margins already taken) rounded down to f32.
pub(super) fn near_f32(near: f64) -> f32 {
    crate::real::f32_down(near.max(0.0))
}

/// The rectangle and `near` of a convex polygon of f32 constants `k` (its packed store's): the
/// pixels of its screen region and the region's distance bound (`accel::reach`).
pub(super) fn polygon_footprint<const N: usize>(
    screen: &Screen,
    k: &PolyK<f32, N>,
) -> (Option<[u16; 4]>, f64) {
    let region = screen.view.polygon_region(&k.n, k.nrm);
    match screen.region_pixels(&region) {
        // (a polygon on no pixel is binned nowhere: its `near` is never read, and the plane
        // bound, which holds at any angle, spares the region's arcs)
        None => (None, plane_near(k.p)),
        rect => (rect, screen.view.polygon_near(&region, k.nrm, k.p)),
    }
}

/// The rectangle and `near` of the ball of centre `oc` (minus the eye, f64) and `radius` whose
/// f32 constants are `oc32`, `r2` and `c`: the projection of the cube about its centre of half
/// size `r'` (`View::ball_reach`: every ray a kernel accepts passes within it of the centre),
/// the whole image when the eye is within `r'`; and [`ball_near`].
pub(super) fn ball_footprint(
    screen: &Screen,
    (oc, radius): (DVec3, f64),
    (oc32, r2, c): ([f32; 3], f32, f32),
) -> (Option<[u16; 4]>, f64) {
    let v = &screen.view;
    let r = v.ball_reach(oc, radius);
    let rect = if oc.length() <= r {
        Some(screen.whole())
    } else {
        let corners = (0..8).map(|i| {
            let s = |bit: usize| if i >> bit & 1 == 1 { r } else { -r };
            oc + v.r * s(0) + v.u * s(1) + v.f * s(2)
        });
        screen.rect(corners)
    };
    (rect, ball_near(oc32, r2, c))
}

/// The outline (`Family::outline`) of primitive `i` of family `F` in `packed`'s columns.
#[inline(always)]
pub(crate) fn outline<F: Stored>(packed: &Packed, i: usize) -> F::Outline {
    F::outline(&Columns::<F>::get(F::columns(packed), i))
}

/// What the tiles bound a primitive by, per outline class (`Family::Outline`: a [`Ball`] or a
/// convex polygon's f32 constants), so that binning and `Tiles::attach` are written once for
/// every family.
pub(super) trait Footprint: Copy {
    /// The pixel rectangle (`None`: no pixel) and `near` bound of the primitive seen on
    /// `screen`; `ball` gives, when asked, the ball's centre minus the eye and radius in f64
    /// (`Family::ball`), which only a ball's rectangle reads.
    fn footprint(
        &self,
        screen: &Screen,
        ball: impl FnOnce() -> Option<(DVec3, f64)>,
    ) -> (Option<[u16; 4]>, f64);

    /// The packets (bits) of the tile with centre points `c` that a kernel may accept a ray of
    /// on the primitive ([`PacketCones::polygon`], [`PacketCones::ball`]).
    fn packets(&self, cones: &PacketCones, c: &[wide::f32x8; 3]) -> u32;

    /// The packets (bits) of the tile with centre points `c` where some pixel's exact ray may
    /// meet the primitive farther than `reach` ([`PacketCones::polygon_beyond`],
    /// [`PacketCones::ball_beyond`]).
    fn beyond(&self, cones: &PacketCones, c: &[wide::f32x8; 3], reach: f64) -> u32;
}

impl Footprint for Ball {
    #[inline(always)]
    fn footprint(
        &self,
        screen: &Screen,
        ball: impl FnOnce() -> Option<(DVec3, f64)>,
    ) -> (Option<[u16; 4]>, f64) {
        let exact = ball().expect("a family bounded by a ball gives its centre and radius");
        ball_footprint(screen, exact, (self.oc, self.r2, self.c))
    }
    #[inline(always)]
    fn packets(&self, cones: &PacketCones, c: &[wide::f32x8; 3]) -> u32 {
        cones.ball(c, self)
    }
    #[inline(always)]
    fn beyond(&self, cones: &PacketCones, c: &[wide::f32x8; 3], reach: f64) -> u32 {
        cones.ball_beyond(c, self, reach)
    }
}

impl<const N: usize> Footprint for PolyK<f32, N> {
    #[inline(always)]
    fn footprint(
        &self,
        screen: &Screen,
        _: impl FnOnce() -> Option<(DVec3, f64)>,
    ) -> (Option<[u16; 4]>, f64) {
        polygon_footprint(screen, self)
    }
    #[inline(always)]
    fn packets(&self, cones: &PacketCones, c: &[wide::f32x8; 3]) -> u32 {
        cones.polygon(c, &self.n)
    }
    #[inline(always)]
    fn beyond(&self, cones: &PacketCones, c: &[wide::f32x8; 3], reach: f64) -> u32 {
        cones.polygon_beyond(c, self.nrm, self.p, reach)
    }
}

/// The 4x2 packets of the image, for leaving out of a tile entry's packets those whose rays
/// all lie outside one of a polygon's edge planes or all pass too far from a sphere (binning,
/// `tiles/bin.rs`), one f32x8 lane per packet of a tile (packet `k` at column `k % 2`, row
/// `k / 2` of the tile).
///
/// Derivation. A packet's rays go through the points `a = f + sx r + sy u` of the image plane
/// at distance 1 (`f`, `r`, `u` orthonormal, so `|a| >= 1`), with `sx`, `sy` its pixels' screen
/// coordinates from the f32 ray tables the kernel reads. They lie in the rectangle
/// `c + x r + y u`, `|x| <= hx`, `|y| <= hy`, around the packet's centre point `c` (`hx`, `hy`:
/// the largest half widths of a packet's `sx` and `sy` ranges over the image; `R`, the half
/// diagonal `hypot(hx, hy)`). For a unit edge normal `n`, a linear function is largest over a
/// rectangle at a corner: `n . a <= n . c + hx |n . r| + hy |n . u|` (at most `n . c + R`). The
/// kernel accepts a ray only when `n . a / |a| >= -eps` (8u edge tolerance) to within its
/// rounding, with `|a| <= A + R` (`A`: the largest `|a|` over the image). So when
/// `n . c < -(hx |n . r| + hy |n . u| + (eps + m) (A + R))`, no ray of the packet is accepted
/// by that edge: `m` = [`ANGLE_MARGIN`] (32u) covers the kernel's f32 dot product and ray
/// (~8u) and this test's own f32 centre and dot products (~6u A); the f32 sum of the slack's
/// three positive terms is rounded up by a relative 1e-5.
///
/// Spheres: the kernel meets a ray `d` only when the sphere's centre lies within `r + m |oc|`
/// of its line (the f32 silhouette errs by ~4u |oc|; see `reaches_sphere`), `|oc x d| <=
/// r + m |oc|`, so `|oc x a| <= (r + m |oc|) (A + R)`; and `|oc x a| >= |oc x c| - |oc| R`.
/// So when `|oc x c| > |oc| R + (r + m |oc|) (A + R) + m |oc| A` (the last term for this
/// test's f32 cross product), no ray of the packet meets it. With the eye inside (`|oc| <= r`)
/// the right side exceeds `|oc| A >= |oc x c|`: never left out. Equal ids and depths to the
/// whole list follow (tests/accel.rs: tiles == none, bit for bit).
pub(crate) struct PacketCones {
    /// `(eps + m) (A + R)`, rounded up.
    tol: f32,
    /// `hx` and `hy`, rounded up.
    half: [f32; 2],
    /// The tables' right and up vectors.
    r: [f32; 3],
    u: [f32; 3],
    /// `R` and `A`, rounded up.
    rad: f32,
    far: f32,
    /// Angle between a pixel's exact ray and the f32 tables' point, plus an f32 silhouette's
    /// band, radians: `max(32u, 2 (eps + Camera::direction_error))`, rounded up (for
    /// [`PacketCones::ball_beyond`] and [`PacketCones::polygon_beyond`]).
    ray: f32,
}

impl PacketCones {
    /// The bound for the ray tables `t` (padded to whole packets) of a camera whose f32 rays
    /// err by `direction_error` radians (`Camera::direction_error`).
    pub(crate) fn new(t: &crate::camera::RayTables<f32>, direction_error: f64) -> PacketCones {
        use crate::kernel::packet::{BLOCK_H, BLOCK_W};
        let eps = f64::from(crate::kernel::edge_eps::<f32>());
        let half = |v: &[f32], n: usize| {
            (0..v.len().saturating_sub(n - 1))
                .map(|i| (f64::from(v[i + n - 1]) - f64::from(v[i])).abs() / 2.0)
                .fold(0.0, f64::max)
        };
        let (hx, hy) = (half(&t.sx, BLOCK_W), half(&t.sy, BLOCK_H));
        let rad = hx.hypot(hy);
        let (f, r, u) = (t.f.map(f64::from), t.r.map(f64::from), t.u.map(f64::from));
        let ends = |v: &[f32]| [v[0], v[v.len() - 1]].map(f64::from);
        let mut far: f64 = 1.0;
        for sx in ends(&t.sx) {
            for sy in ends(&t.sy) {
                let a: [f64; 3] = std::array::from_fn(|i| f[i] + sx * r[i] + sy * u[i]);
                far = far.max((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt());
            }
        }
        PacketCones {
            tol: crate::real::f32_up((eps + ANGLE_MARGIN) * (far + rad)),
            half: [hx, hy].map(crate::real::f32_up),
            r: t.r,
            u: t.u,
            rad: crate::real::f32_up(rad),
            far: crate::real::f32_up(far),
            ray: crate::real::f32_up(ANGLE_MARGIN.max(2.0 * (eps + direction_error))),
        }
    }

    /// The centre points of tile `(tx, ty)`'s packets (x, y and z, one lane per packet).
    #[inline]
    pub(crate) fn centres(
        t: &crate::camera::RayTables<f32>,
        (tx, ty): (usize, usize),
    ) -> [wide::f32x8; 3] {
        use crate::kernel::packet::{BLOCK_H, BLOCK_W};
        let at = |v: &[f32], i: usize| v[i.min(v.len() - 1)];
        let mid = |v: &[f32], i: usize, n: usize| (at(v, i) + at(v, i + n - 1)) * 0.5;
        let sx: [f32; 8] = std::array::from_fn(|k| {
            mid(
                &t.sx,
                tx * TILE_W + k % (TILE_W / BLOCK_W) * BLOCK_W,
                BLOCK_W,
            )
        });
        let sy: [f32; 8] = std::array::from_fn(|k| {
            mid(
                &t.sy,
                ty * TILE_H + k / (TILE_W / BLOCK_W) * BLOCK_H,
                BLOCK_H,
            )
        });
        let (sx, sy) = (wide::f32x8::new(sx), wide::f32x8::new(sy));
        std::array::from_fn(|i| {
            wide::f32x8::splat(t.f[i])
                + sx * wide::f32x8::splat(t.r[i])
                + sy * wide::f32x8::splat(t.u[i])
        })
    }

    /// The packets (bits) of the tile with centre points `c` that a polygon of f32 edge
    /// normals `n` may accept: those not wholly outside any one edge plane.
    #[inline]
    pub(crate) fn polygon<const N: usize>(&self, c: &[wide::f32x8; 3], n: &[[f32; 3]; N]) -> u32 {
        use wide::f32x8;
        let mut out = f32x8::ZERO;
        for &edge in n {
            let (dot, slack) = self.spread(c, edge);
            out |= dot.simd_lt(-slack);
        }
        !out.to_bitmask() & 0xFF
    }

    /// For a unit vector `n`: `c . n` at each packet's centre point `c`, and the slack by
    /// which `a . n` can differ from it over the packet's rectangle, `hx |n . r| + hy |n . u|`,
    /// plus `tol`, rounded up by 1e-5 (the derivation above).
    #[inline]
    fn spread(&self, c: &[wide::f32x8; 3], n: [f32; 3]) -> (wide::f32x8, wide::f32x8) {
        use wide::f32x8;
        let along = |v: [f32; 3]| (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]).abs();
        let [hx, hy] = self.half;
        let slack = (hx * along(self.r) + hy * along(self.u) + self.tol) * (1.0 + 1e-5);
        let dot = c[0] * f32x8::splat(n[0]) + c[1] * f32x8::splat(n[1]) + c[2] * f32x8::splat(n[2]);
        (dot, f32x8::splat(slack))
    }

    /// `|o x c|^2` in each lane, for the centre points `c`.
    #[inline]
    fn cross2(o: [f32; 3], c: &[wide::f32x8; 3]) -> wide::f32x8 {
        let o = o.map(wide::f32x8::splat);
        let x = [
            o[1] * c[2] - o[2] * c[1],
            o[2] * c[0] - o[0] * c[2],
            o[0] * c[1] - o[1] * c[0],
        ];
        x[0] * x[0] + x[1] * x[1] + x[2] * x[2]
    }

    /// The packets (bits) of the tile with centre points `c` that the ball `b` may meet.
    #[inline]
    pub(crate) fn ball(&self, c: &[wide::f32x8; 3], b: &Ball) -> u32 {
        use wide::f32x8;
        let oc = b.oc;
        let len = (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2]).sqrt();
        let r = b.r2.sqrt();
        let m = ANGLE_MARGIN as f32;
        let (a, rad) = (self.far, self.rad);
        // in f32, rounded up by the margin's 1 + 1e-5 (the terms are positive)
        let rhs = (len * (rad + m * (2.0 * a + rad)) + r * (a + rad)) * (1.0 + 1e-5);
        !Self::cross2(oc, c)
            .simd_gt(f32x8::splat(rhs * rhs))
            .to_bitmask()
            & 0xFF
    }

    /// The packets (bits) of the tile with centre points `c` where some pixel's exact ray may
    /// meet the ball `b` farther than `reach` (every packet when the eye is inside it).
    ///
    /// Derivation. The sphere the f32 constants give (centre `oc`, radius `r`) is within
    /// `e = 4u (L + r)` of the exact one (`L = |oc|`; centre and radius rounded once), so the
    /// sphere of radius `r' = r - e` about `oc` lies inside the exact sphere: a ray that meets
    /// it meets the exact sphere no farther. With the eye outside (`L > r'`, `k = L^2 - r'^2`),
    /// a unit ray at distance `rho = |oc x d|` from the centre meets it first at
    /// `t(rho) = sqrt(L^2 - rho^2) - sqrt(r'^2 - rho^2)`, which grows with `rho` on `[0, r']`.
    /// The roots sum to `2 sqrt(L^2 - rho^2)` and multiply to `k` (Vieta), so `t(rho) = T` at
    /// `rho_T^2 = L^2 - ((T + k/T) / 2)^2`, for `L - r' <= T < sqrt(k)`; below `L - r'` no ray
    /// is known to stay within `T`. A packet's rays `a / |a|` (the rectangle of
    /// [`PacketCones`], `|a| >= |c| - R`) have `rho <= (|oc x c| + L R) / (|c| - R)`, and the
    /// exact rays lie within `ray` of the f32 tables' points. So when
    /// `|oc x c| <= (rho_T - 2 ray L)(|c| - R) - L R`, every exact ray of the packet passes at
    /// most `rho_T - ray L` from the centre: it meets the small sphere within `T`, hence the
    /// exact one too, and stays `ray L` inside the small sphere's silhouette. That is more than
    /// the band (`6u` plus the ray's error, under half of `ray`) where the f32 kernel may meet
    /// a ray the exact one misses; the rest covers this test's f32 cross product. The f64 terms
    /// are rounded towards the safe side, the f32 lanes by 1e-5 relative.
    #[inline]
    pub(crate) fn ball_beyond(&self, c: &[wide::f32x8; 3], b: &Ball, reach: f64) -> u32 {
        use wide::f32x8;
        let oc = b.oc;
        let l = oc.map(f64::from).iter().map(|v| v * v).sum::<f64>().sqrt();
        let r = f64::from(b.r2).sqrt();
        let r = r - 4.0 * U32 * (l + r);
        let (k, t, ray) = (l * l - r * r, reach, f64::from(self.ray));
        let rho2 = l * l - ((t + k / t) / 2.0).powi(2);
        let slope = rho2.max(0.0).sqrt() * (1.0 - 1e-6) - 2.0 * ray * l;
        // the eye inside, `t` at or past the silhouette or short of the sphere (or NaN)
        if b.inside || !(r > 0.0 && l > r && t > 0.0 && t * t < k && slope > 0.0) {
            return 0xFF;
        }
        let slope = crate::real::f32_down(slope);
        let off = crate::real::f32_up(l * f64::from(self.rad) * (1.0 + 1e-6));
        let cross2 = Self::cross2(oc, c) * f32x8::splat(1.0 + 1e-5);
        let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() * f32x8::splat(1.0 - 1e-5);
        let rhs = (f32x8::splat(slope) * (len - f32x8::splat(self.rad)) - f32x8::splat(off))
            * f32x8::splat(1.0 - 1e-5);
        let within = rhs.simd_gt(f32x8::ZERO) & cross2.simd_le(rhs * rhs);
        !within.to_bitmask() & 0xFF
    }

    /// The packets (bits) of the tile with centre points `c` where some pixel's exact ray may
    /// meet the plane of a polygon (f32 unit normal `nrm`, distance `p > 0`, oriented so that
    /// hits have `d . nrm > 0`) farther than `reach`.
    ///
    /// Derivation. A unit ray meets the plane at `t = p / (d . N)` where `d . N > 0`. Over a
    /// packet's rectangle (as in [`PacketCones::polygon`]) `a . N >= c . N - S` with
    /// `S = hx |N . r| + hy |N . u|`, and `|a| <= |c| + R`, so every hit of the packet has
    /// `t <= p (|c| + R) / (c . N - S)` when `c . N > S`, and there is none when
    /// `c . N < -S`. `tol` (as there) covers the exact rays' distance from the tables' points
    /// and this test's f32 rounding; the lanes are rounded towards the safe side by 1e-5.
    #[inline]
    pub(crate) fn polygon_beyond(
        &self,
        c: &[wide::f32x8; 3],
        nrm: [f32; 3],
        p: f32,
        reach: f64,
    ) -> u32 {
        use wide::f32x8;
        if reach.is_nan() || reach <= 0.0 {
            return 0xFF;
        }
        let (dot, slack) = self.spread(c, nrm);
        let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        let far = f32x8::splat(p) * (len + f32x8::splat(self.rad)) * f32x8::splat(1.0 + 1e-5);
        let cos = dot - slack;
        let within = (cos.simd_gt(f32x8::ZERO)
            & far.simd_le(cos * f32x8::splat(crate::real::f32_down(reach) * (1.0 - 1e-5))))
            | (dot + slack).simd_lt(f32x8::ZERO);
        !within.to_bitmask() & 0xFF
    }
}

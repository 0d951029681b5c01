//! A view's pixel work: projection and boxes, then each band's f32 pass and its f64 re-decisions.

use super::clusters::Cluster;
use super::setup::{self, Basis, EPS_MAX, Poly};
use super::{BAND, Item, Others, Polys, Precision, Scratch, T_TIGHT, World};
use crate::camera::{Camera, RayTables};
use crate::frame::Frame;
use crate::kernel::family::{Bounded, Class, Polygon};
use crate::kernel::{Family, Hit};
use crate::par::prelude::*;
use crate::soa::with_family;
use glam::DVec3;

/// What every pass of one view reads: the camera, its f32 and f64 ray tables, its basis.
pub struct View {
    pub eye: DVec3,
    w: usize,
    h: usize,
    t32: RayTables<f32>,
    t64: RayTables<f64>,
    basis: Basis,
    half_w: f32,
    half_h: f32,
    /// The principal point in half images, `(2cx/W, 2cy/H)`: (1, 1) for a field of view.
    principal: (f32, f32),
    /// Pixels of box margin: the projection's rounding and the widest edge tolerance.
    margin: f32,
}

/// Pixels of box margin for the projection's rounding (a few u of the image's size), for a
/// centred principal point; it grows with the principal point's distance from the centre
/// (`View::new`), as the projection's intermediate `sx / half_w + 2cx/W` does.
const MARGIN_PX: f64 = 0.01;

/// Cosine (of a vertex's angle to the view axis) below which a polygon is boxed to the whole
/// image: every pixel ray is within 90 - 0.0006 degrees of the axis for fov < 180 and any
/// size the limits allow, far from it.
const NEAR_COS: f32 = 1e-5;

impl View {
    pub fn new(camera: &Camera) -> View {
        let t32 = camera.tables::<f32>(1, 1);
        let t64 = camera.tables::<f64>(1, 1);
        let (sx, sy) = camera.screen_reach();
        let lmax = (1.0 + sx * sx + sy * sy).sqrt();
        // pixels per radian, at most: d(sx)/d(angle) <= 1 + sx^2 <= lmax^2, times the larger
        // focal length (fx = fy for a field of view)
        let focal = (camera.width as f64 / (2.0 * camera.half_w))
            .max(camera.height as f64 / (2.0 * camera.half_h));
        let px_per_rad = focal * lmax * lmax;
        let (px, py) = camera.principal();
        // the projection's largest intermediate, in half images: 1 for a centred point
        let span = [px, 2.0 - px, py, 2.0 - py]
            .iter()
            .fold(1.0f64, |m, v| m.max(v.abs()));
        View {
            eye: camera.eye,
            w: camera.width as usize,
            h: camera.height as usize,
            basis: Basis {
                f: t32.f,
                r: t32.r,
                u: t32.u,
                lmax,
            },
            t32,
            t64,
            half_w: camera.half_w as f32,
            half_h: camera.half_h as f32,
            principal: (px as f32, py as f32),
            margin: (MARGIN_PX * span + EPS_MAX * lmax * px_per_rad) as f32,
        }
    }

    pub fn bands(&self) -> usize {
        self.h.div_ceil(BAND)
    }

    /// A vertex's pixel coordinates and the cosine of its angle to the view axis.
    #[inline(always)]
    pub fn project(&self, r: [f32; 3]) -> [f32; 3] {
        let b = &self.basis;
        let z = setup::dot(r, b.f);
        let len = setup::dot(r, r).sqrt();
        let sx = setup::dot(r, b.r) / z;
        let sy = setup::dot(r, b.u) / z;
        let (cx, cy) = self.principal;
        let px = (sx / self.half_w + cx) * (self.w as f32 * 0.5) - 0.5;
        let py = (cy - sy / self.half_h) * (self.h as f32 * 0.5) - 0.5;
        [px, py, z / len]
    }

    fn full(&self) -> [u16; 4] {
        [0, (self.w - 1) as u16, 0, (self.h - 1) as u16]
    }

    fn clip(&self, x0: f32, x1: f32, y0: f32, y1: f32) -> Option<[u16; 4]> {
        let m = self.margin;
        let (x0, x1) = (
            (x0 - m).ceil().max(0.0),
            (x1 + m).floor().min(self.w as f32 - 1.0),
        );
        let (y0, y1) = (
            (y0 - m).ceil().max(0.0),
            (y1 + m).floor().min(self.h as f32 - 1.0),
        );
        // (NaN fails these)
        if x0 <= x1 && y0 <= y1 {
            Some([x0 as u16, x1 as u16, y0 as u16, y1 as u16])
        } else {
            None
        }
    }

    /// The pixel box of a polygon from its vertices' projections `p`, or, when a vertex lies
    /// near or behind the eye plane, from the part of the polygon (world-space vertices `w`)
    /// the frustum can reach ([`View::clipped_box`]).
    #[inline(always)]
    pub fn polygon_box<const N: usize>(
        &self,
        p: [[f32; 3]; N],
        w: impl FnOnce() -> [DVec3; N],
    ) -> Option<[u16; 4]> {
        if p.iter().all(|q| q[2] < -NEAR_COS) {
            return None;
        }
        if p.iter().any(|q| q[2].is_nan() || q[2] <= NEAR_COS) {
            return self.clipped_box(&w());
        }
        let (mut x0, mut x1, mut y0, mut y1) = (p[0][0], p[0][0], p[0][1], p[0][1]);
        for q in &p[1..] {
            x0 = x0.min(q[0]);
            x1 = x1.max(q[0]);
            y0 = y0.min(q[1]);
            y1 = y1.max(q[1]);
        }
        self.clip(x0, x1, y0, y1)
    }

    /// The pixel box of a polygon (world-space vertices `w`) that reaches near or behind the
    /// eye plane, in f64. Every point P a pixel ray reaches has `z = P . f >= |P| / lmax`
    /// (`lmax` the longest pixel ray's length over its forward component), and every point
    /// of the polygon is at least `R = max |w_i - eye| - diam` from the eye: so the rays meet
    /// only its part with `z >= R / lmax`. That part (the polygon clipped to the plane
    /// `z = R / (2 lmax)`, Sutherland-Hodgman) is convex and in front of the eye, so its
    /// vertices' projections bound it; they are boxed with one more pixel of margin than a
    /// polygon's box (the f64 clip's rounding is far below it). `None` when no part is left;
    /// the whole image when the polygon passes within rounding of the eye (`R <= 0`).
    pub fn clipped_box<const N: usize>(&self, w: &[DVec3; N]) -> Option<[u16; 4]> {
        let (f, r, u) = (self.t64.f, self.t64.r, self.t64.u);
        let cam = |p: DVec3| {
            let d = p - self.eye;
            let c = |a: [f64; 3]| d.x * a[0] + d.y * a[1] + d.z * a[2];
            [c(r), c(u), c(f)]
        };
        let q: [[f64; 3]; N] = std::array::from_fn(|i| cam(w[i]));
        let reach = reach(&w.map(|p| p - self.eye)) * (1.0 - 1e-9);
        if reach.is_nan() || reach <= 0.0 {
            return Some(self.full());
        }
        let z0 = reach / (2.0 * self.basis.lmax);
        let (hw, hh) = (self.half_w as f64, self.half_h as f64);
        let (cx, cy) = (self.principal.0 as f64, self.principal.1 as f64);
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        let mut any = false;
        let mut add = |x: f64, y: f64, z: f64| {
            let px = (x / z / hw + cx) * self.w as f64 * 0.5 - 0.5;
            let py = (cy - y / z / hh) * self.h as f64 * 0.5 - 0.5;
            (x0, x1, y0, y1) = (x0.min(px), x1.max(px), y0.min(py), y1.max(py));
            any = true;
        };
        for i in 0..N {
            let (a, b) = (q[i], q[(i + 1) % N]);
            if a[2] >= z0 {
                add(a[0], a[1], a[2]);
            }
            if (a[2] - z0) * (b[2] - z0) < 0.0 {
                let s = (z0 - a[2]) / (b[2] - a[2]);
                add(a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s, z0);
            }
        }
        if !any {
            return None;
        }
        let clamp = |v: f64| v.clamp(-1e9, 1e9) as f32;
        self.clip(
            clamp(x0 - 1.0),
            clamp(x1 + 1.0),
            clamp(y0 - 1.0),
            clamp(y1 + 1.0),
        )
    }

    /// The pixel box of a ball (a cluster's or a primitive's bounding sphere, centre `c`,
    /// radius `r`): interval bounds on `sx` and `sy` over its bounding cube.
    pub fn ball_box(&self, c: DVec3, r: f64) -> Option<[u16; 4]> {
        let oc = c - self.eye;
        let (f, rr, u) = (self.t64.f, self.t64.r, self.t64.u);
        let d = |a: [f64; 3]| oc.x * a[0] + oc.y * a[1] + oc.z * a[2];
        let (z, x, y) = (d(f), d(rr), d(u));
        let pad = r * (1.0 + 1e-6) + 1e-9 * oc.length();
        if z + pad < 0.0 {
            return None;
        }
        if z - pad <= 1e-6 * oc.length() {
            return Some(self.full());
        }
        let (zl, zh) = (z - pad, z + pad);
        let range = |a: f64| {
            let (lo, hi) = (a - pad, a + pad);
            let lo = if lo < 0.0 { lo / zl } else { lo / zh };
            let hi = if hi > 0.0 { hi / zl } else { hi / zh };
            (lo, hi)
        };
        let (sx0, sx1) = range(x);
        let (sy0, sy1) = range(y);
        let (hw, hh) = (self.half_w as f64, self.half_h as f64);
        let (cx, cy) = (self.principal.0 as f64, self.principal.1 as f64);
        let px = |sx: f64| ((sx / hw + cx) * self.w as f64 * 0.5 - 0.5) as f32;
        let py = |sy: f64| ((cy - sy / hh) * self.h as f64 * 0.5 - 0.5) as f32;
        self.clip(px(sx0), px(sx1), py(sy1), py(sy0))
    }
}

/// One band's per-pixel state, kept in [`Scratch`] from view to view.
#[derive(Debug, Default)]
pub(crate) struct Band {
    x: usize,
    y0: usize,
    rows: usize,
    /// Nearest t' (= t / |v|) so far and its id.
    t: Vec<f32>,
    id: Vec<i32>,
    /// Lowest lower bound of a loose candidate's t'.
    loose: Vec<f32>,
    /// Re-decided in f64 whatever the f32 answer.
    flag: Vec<bool>,
    /// The polygons, then the primitives of bounded families, whose test ran at some pixel of
    /// the band, each as its family's kind, its index in that family's store, its id and its
    /// box: every primitive the oracle may hit here (the outline test leaves out only pixels
    /// no primitive's exact test accepts, and a polygon is passed over only where a trusted
    /// nearer hit is proven, [`hidden`]).
    polys: Vec<(u8, u32, i32, [u16; 4])>,
    others: Vec<(u8, u32, i32, [u16; 4])>,
    /// The front items, nearest first.
    front: Vec<(f64, u32)>,
    /// Polygons facing away from the eye, waiting for every polygon facing it: (index in its
    /// family's store, kind).
    waiting: Vec<(u32, u8)>,
    /// Each flagged pixel's nearest f64 hit and oracle ray.
    best: Vec<(Hit<f64>, [f64; 3])>,
}

impl Band {
    /// Band `b`'s state for a fresh view, every pixel flagged when `flag`.
    fn reset(&mut self, w: usize, b: usize, rows: usize, flag: bool) {
        let n = rows * w;
        (self.x, self.y0, self.rows) = (w, b * BAND, rows);
        let fill = |v: &mut Vec<_>, x| {
            v.clear();
            v.resize(n, x);
        };
        fill(&mut self.t, f32::INFINITY);
        fill(&mut self.loose, f32::INFINITY);
        self.id.clear();
        self.id.resize(n, -1);
        self.flag.clear();
        self.flag.resize(n, flag);
        self.polys.clear();
        self.others.clear();
        self.front.clear();
        self.waiting.clear();
    }

    #[inline(always)]
    fn rows(&self, b: [u16; 4]) -> std::ops::Range<usize> {
        (b[2] as usize).max(self.y0)..(b[3] as usize + 1).min(self.y0 + self.rows)
    }
}

/// Passes 3 and 4 over every band, written into `frame` (every pixel: a reused frame's old
/// values do not show through); the pixels decided in f64, ascending.
pub fn bands(
    world: &World,
    view: &View,
    s: &mut Scratch,
    precision: Precision,
    frame: &mut Frame<f32>,
) -> Vec<usize> {
    let w = view.w;
    let mut states = std::mem::take(&mut s.bands);
    states.resize_with(view.bands(), Band::default);
    let shared = &*s;
    let redone: Vec<Vec<usize>> = frame
        .ids
        .par_chunks_mut(BAND * w)
        .zip(frame.depth.par_chunks_mut(BAND * w))
        .zip(states.par_iter_mut())
        .enumerate()
        .map(|(b, ((ids, depth), st))| band(world, view, shared, precision, b, st, ids, depth))
        .collect();
    s.bands = states;
    redone.concat()
}

/// The order a band takes its items in, so that what is drawn first can prove the rest hidden:
/// 1. the front items (clusters with a polygon that may face the eye, and spheres), nearest
///    first; a cluster whose box already holds proven nearer hits ([`hidden`]) is passed over,
///    and the polygons of the others that face away from the eye wait;
/// 2. the deferred clusters not proven hidden: every polygon of theirs waits too;
/// 3. the waiting polygons, each passed over where every pixel it may cover holds a proven
///    nearer hit ([`proven_nearer`]): on a closed mesh, the back faces.
///
/// Passing over is exact: a primitive passed over at a pixel is farther there, in f32 and in
/// f64, than a trusted hit of a polygon the band keeps, so neither the f32 answer nor the f64
/// re-decision (a minimum over the band's polygons) could have chosen it. The order is fixed
/// by the scene and the camera (nearest point, then index), never by the threads.
#[allow(clippy::too_many_arguments)]
fn band(
    world: &World,
    view: &View,
    s: &Scratch,
    precision: Precision,
    b: usize,
    st: &mut Band,
    ids: &mut [i32],
    depth: &mut [f32],
) -> Vec<usize> {
    let w = view.w;
    let rows = ids.len() / w;
    let n = rows * w;
    st.reset(w, b, rows, precision == Precision::F64);
    for e in s.bins.iter().flat_map(|c| c[b].iter()).filter(|e| !e.1) {
        let near = match world.item(e.0 as usize) {
            Item::Cluster(_, _, k) => k.nearest(view.eye),
            Item::Bounded(..) => f64::NEG_INFINITY,
        };
        st.front.push((near, e.0));
    }
    st.front
        .sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let front = std::mem::take(&mut st.front);
    for &(_, i) in &front {
        let (kind, j) = match world.item(i as usize) {
            Item::Cluster(kind, j, _) | Item::Bounded(kind, j, ..) => (kind, j),
        };
        with_family!(kind, F => F::class(Front { world, j, view, s, st }));
    }
    st.front = front;
    for e in s.bins.iter().flat_map(|c| c[b].iter()).filter(|e| e.1) {
        let Item::Cluster(kind, _, k) = world.item(e.0 as usize) else {
            unreachable!("only clusters are deferred")
        };
        if !hidden(k, view, st) {
            st.waiting
                .extend((k.first..k.first + k.len).map(|p| (p, kind as u8)));
        }
    }
    let waiting = std::mem::take(&mut st.waiting);
    for &(p, kind) in &waiting {
        with_family!(kind as usize, F => F::class(Waiting { world, p, view, s, st }));
    }
    st.waiting = waiting;
    // Which pixels the f32 answer is not trusted at.
    let mut any = false;
    if precision != Precision::F32 {
        for k in 0..n {
            let l = st.loose[k];
            let f =
                st.flag[k] || (l < f32::INFINITY && l <= st.t[k] * (1.0 + 2.0 * T_TIGHT as f32));
            st.flag[k] = f;
            any |= f;
        }
    }
    let mut best = std::mem::take(&mut st.best);
    if any {
        // each flagged pixel's oracle ray, once, beside its nearest f64 hit
        best.clear();
        best.extend((0..n).map(|k| {
            let d = if st.flag[k] {
                view.t64.dir_x1(k % w, st.y0 + k / w)
            } else {
                [0.0; 3]
            };
            (Hit::<f64>::NONE, d)
        }));
        for &(kind, j, id, bx) in st.polys.iter().chain(&st.others) {
            if flagged(bx, st) {
                let (j, best) = (j as usize, &mut best[..]);
                let again = Redecide {
                    world,
                    j,
                    id,
                    bx,
                    view,
                    st,
                    best,
                };
                with_family!(kind as usize, F => F::class(again));
            }
        }
    }
    let mut redone = Vec::new();
    for y in 0..rows {
        let sy = view.t32.sy[st.y0 + y];
        for x in 0..w {
            let k = y * w + x;
            if any && st.flag[k] {
                ids[k] = best[k].0.id;
                depth[k] = best[k].0.t as f32;
                redone.push(st.y0 * w + k);
            } else if st.id[k] >= 0 {
                let sx = view.t32.sx[x];
                ids[k] = st.id[k];
                depth[k] = st.t[k] * (1.0 + sx * sx + sy * sy).sqrt();
            } else {
                ids[k] = -1;
                depth[k] = f32::INFINITY;
            }
        }
    }
    st.best = best;
    redone
}

/// Whether pixel `j` of the band (column `x`, row `y`) holds a trusted f32 hit (tight, no
/// loose candidate that could beat it, not flagged) whose distance, with its error bound, is
/// below `near`. Then no primitive whose points all lie at `near` or farther can be the
/// nearest there, in f32 or in f64.
#[inline(always)]
fn proven_nearer(st: &Band, view: &View, x: usize, y: usize, j: usize, near: f64) -> bool {
    // (what the flag pass will decide: a loose candidate that could beat the hit)
    let loose = st.loose[j] <= st.t[j] * (1.0 + 2.0 * T_TIGHT as f32);
    if st.id[j] < 0 || st.flag[j] || loose {
        return false;
    }
    let (sx, sy) = (view.t32.sx[x] as f64, view.t32.sy[y] as f64);
    let t = st.t[j] as f64 * (1.0 + sx * sx + sy * sy).sqrt();
    !t.is_nan() && t * (1.0 + 4.0 * T_TIGHT) < near
}

/// Whether cluster `k` is proven hidden in this band: every pixel of its box (in the band)
/// holds a proven nearer hit than the cluster's nearest point.
fn hidden(k: &Cluster, view: &View, st: &Band) -> bool {
    let Some(bx) = view.ball_box(k.centre, k.radius) else {
        return true;
    };
    let near = k.nearest(view.eye);
    st.rows(bx).all(|y| {
        let row = (y - st.y0) * st.x;
        (bx[0] as usize..=bx[1] as usize).all(|x| proven_nearer(st, view, x, y, row + x, near))
    })
}

/// A lower bound on the distance from the eye to any point of the polygon with eye-relative
/// vertices `d` (f64): every point lies within the polygon's diameter of each vertex, so it is
/// at least `max |d_i| - diam` away.
#[inline(always)]
fn reach<const N: usize>(d: &[DVec3; N]) -> f64 {
    let far = d.iter().fold(0.0f64, |m, v| m.max(v.length()));
    let mut diam = 0.0f64;
    for i in 0..N {
        for j in i + 1..N {
            diam = diam.max((d[i] - d[j]).length());
        }
    }
    far - diam
}

/// [`reach`] of the polygon with eye-relative f32 vertices `a`, evaluated in f64 from the f32
/// vectors (exactly enough): `a_i` is within 0.87u|a_i| of the exact vertex, so the exact bound
/// is lower by at most 3uM (M = max |a_i|), and 1e-6 M is taken off.
#[inline(always)]
fn nearest<const N: usize>(a: &[[f32; 3]; N]) -> f64 {
    let d = a.map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64));
    let m = d.iter().fold(0.0f64, |m, v| m.max(v.length()));
    reach(&d) - 1e-6 * m
}

/// Pixels a polygon's box may hold before the 2D outline test is skipped (the exact test
/// then runs at every pixel of the box).
const OUTLINE_MAX: usize = 64;

/// The pixels of the band inside the projected outline `p` of a polygon of family `P`, widened
/// by `margin` pixels (plus the projection's own rounding), as offsets into the band; `None`
/// when the outline test does not apply (a vertex near or behind the eye plane, a box past
/// [`OUTLINE_MAX`] pixels, an outline of no area). The outline's orientation is the sign of
/// the 2D cross product of the two vectors of its raw normal (`Polygon::NORMAL`).
#[inline(always)]
fn outline<P: Polygon<N>, const N: usize>(
    p: &[[f32; 3]; N],
    bx: [u16; 4],
    view: &View,
    st: &Band,
    out: &mut [u32; OUTLINE_MAX],
) -> Option<usize> {
    let rows = st.rows(bx);
    let (x0, x1) = (bx[0] as usize, bx[1] as usize);
    if rows.len() * (x1 + 1 - x0) > OUTLINE_MAX
        || p.iter().any(|q| q[2].is_nan() || q[2] <= NEAR_COS)
    {
        return None;
    }
    let [i, j, k, l] = P::NORMAL;
    let area =
        (p[i][0] - p[j][0]) * (p[k][1] - p[l][1]) - (p[i][1] - p[j][1]) * (p[k][0] - p[l][0]);
    if !(area != 0.0 && area.is_finite()) {
        return None;
    }
    let sign = if area > 0.0 { 1.0f32 } else { -1.0 };
    let big = p
        .iter()
        .fold(0.0f32, |m, q| m.max(q[0].abs()).max(q[1].abs()));
    let margin = view.margin + OUTLINE_REL * (big + (view.w + view.h) as f32);
    let edges: [[f32; 5]; N] = std::array::from_fn(|i| {
        let (a, b) = (p[i], p[(i + 1) % N]);
        let (dx, dy) = ((b[0] - a[0]) * sign, (b[1] - a[1]) * sign);
        [dx, dy, a[0], a[1], -margin * (dx.abs() + dy.abs())]
    });
    let mut n = 0;
    for y in rows {
        let fy = y as f32;
        let row = (y - st.y0) * st.x;
        for x in x0..=x1 {
            let fx = x as f32;
            let inside = edges
                .iter()
                .all(|e| e[0] * (fy - e[3]) - e[1] * (fx - e[2]) >= e[4]);
            if inside {
                out[n] = (row + x) as u32;
                n += 1;
            }
        }
    }
    Some(n)
}

/// The 2D outline test's allowance for the projection's rounding, relative to the largest
/// pixel coordinate involved: about 30u, each coordinate having passed through a dozen f32
/// operations.
const OUTLINE_REL: f32 = 2e-6;

/// Polygon `i` of `polys`, of family `P`, in this band. In the front pass (`front`) a polygon
/// facing away from the eye waits ([`band`]); a waiting polygon (not `front`) is passed over
/// when every pixel it may cover holds a proven nearer hit.
#[inline(always)]
fn raster_polygon<P: Polygon<N>, const N: usize>(
    polys: &Polys,
    i: u32,
    front: bool,
    (view, verts): (&View, &[DVec3]),
    s: &Scratch,
    st: &mut Band,
) {
    let (v, id, g) = (
        polys.vertices::<N>(i as usize),
        polys.ids[i as usize],
        polys.shape[i as usize],
    );
    let p = v.map(|i| s.proj[i as usize]);
    // most polygons of a cluster that reaches into this band lie outside it: their rows first
    // (NaN rows, from vertices behind the eye, pass on to the full box test)
    let (lo, hi) = p
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), q| {
            (l.min(q[1]), h.max(q[1]))
        });
    let m = view.margin;
    let outside = hi + m < st.y0 as f32 || lo - m > (st.y0 + st.rows - 1) as f32;
    if outside && p.iter().all(|q| q[2] > NEAR_COS) {
        return;
    }
    let a = v.map(|i| s.rel[i as usize]);
    if front && setup::faces_away::<P, N>(&a) {
        st.waiting.push((i, P::KIND as u8));
        return;
    }
    let Some(bx) = view.polygon_box(p, || v.map(|i| verts[i as usize])) else {
        return;
    };
    if st.rows(bx).is_empty() {
        return;
    }
    let mut cand = [0u32; OUTLINE_MAX];
    let picked = outline::<P, N>(&p, bx, view, st, &mut cand);
    if picked == Some(0) {
        return;
    }
    if !front {
        let near = nearest(&a);
        let covered = match picked {
            Some(n) => cand[..n].iter().all(|&j| {
                let j = j as usize;
                proven_nearer(st, view, j % st.x, st.y0 + j / st.x, j, near)
            }),
            None => st.rows(bx).all(|y| {
                let row = (y - st.y0) * st.x;
                (bx[0] as usize..=bx[1] as usize)
                    .all(|x| proven_nearer(st, view, x, y, row + x, near))
            }),
        };
        if covered {
            return;
        }
    }
    let k = setup::polygon::<P, N>(a, g, &view.basis);
    st.polys.push((P::KIND as u8, i, id, bx));
    if k.class == setup::Class::Opaque {
        if let Some(k) = P::setup(&v.map(|i| verts[i as usize]), view.eye) {
            by_kernel::<P>(&k, id, bx, view, st);
        }
        return;
    }
    match picked {
        Some(n) => {
            for &j in &cand[..n] {
                let j = j as usize;
                let (x, y) = (j % st.x, st.y0 + j / st.x);
                test_polygon(&k, id, x, y, j, view, st);
            }
        }
        None => {
            for y in st.rows(bx) {
                let row = (y - st.y0) * st.x;
                for x in bx[0] as usize..=bx[1] as usize {
                    test_polygon(&k, id, x, y, row + x, view, st);
                }
            }
        }
    }
}

/// The f32 test of polygon `k` at pixel (x, y), offset `j` in the band.
#[inline(always)]
fn test_polygon<const N: usize>(
    k: &Poly<N>,
    id: i32,
    x: usize,
    y: usize,
    j: usize,
    view: &View,
    st: &mut Band,
) {
    if k.class == setup::Class::Opaque {
        st.flag[j] = true;
        return;
    }
    let (sx, sy) = (view.t32.sx[x], view.t32.sy[y]);
    let mut inside = true;
    for i in 0..N {
        inside &= (k.e[i][0] + sy * k.e[i][2]) + sx * k.e[i][1] >= -k.eps;
    }
    if !inside {
        return;
    }
    let den = (k.den[0] + sy * k.den[2]) + sx * k.den[1];
    if den.is_nan() || den <= 0.0 {
        if k.class == setup::Class::Loose {
            st.loose[j] = 0.0;
        }
        return;
    }
    let t = k.p / den;
    if k.class == setup::Class::Loose {
        st.loose[j] = st.loose[j].min(t * k.lower);
    }
    if t < st.t[j] || (t == st.t[j] && id < st.id[j]) {
        st.t[j] = t;
        st.id[j] = id;
    }
}

/// Primitive `j` of `others`, of the bounded family `F`, in this band: every pixel of its
/// bounding sphere's box flagged for the f64 re-decision, and its f32 hits kept meanwhile (so
/// that the flag pass and the proofs of [`hidden`] see them).
fn raster_bounded<F: Bounded>(others: &Others, j: usize, view: &View, st: &mut Band) {
    let (c, r) = others.bounds[j];
    let Some(bx) = view.ball_box(c, r) else {
        return;
    };
    if st.rows(bx).is_empty() {
        return;
    }
    let Some(k) = F::setup(&others.geometry::<F>(j), view.eye) else {
        return;
    };
    let id = others.ids[j];
    st.others.push((F::KIND as u8, j as u32, id, bx));
    by_kernel::<F>(&k, id, bx, view, st);
}

/// Every pixel of box `bx` flagged for the f64 re-decision, and the primitive with the
/// oracle's constants `k` tested there with its family's f32 kernel ([`Family::hit_x1`]), its
/// hits kept meanwhile: a bounded family's primitives, and a polygon whose projected
/// constants are not usable ([`setup::Class::Opaque`]: seen from near its plane, say), so that
/// `--precision f32` draws it too.
fn by_kernel<F: Family>(k: &F::K<f64>, id: i32, bx: [u16; 4], view: &View, st: &mut Band) {
    let k = F::cast::<f32>(k);
    let (x0, x1) = (bx[0] as usize, bx[1] as usize);
    for y in st.rows(bx) {
        let row = (y - st.y0) * st.x;
        let sy = view.t32.sy[y];
        for x in x0..=x1 {
            let j = row + x;
            st.flag[j] = true;
            if let Some(t) = F::hit_x1(&k, view.t32.dir_x1(x, y)) {
                let sx = view.t32.sx[x];
                let t = t / (1.0 + sx * sx + sy * sy).sqrt();
                if t < st.t[j] || (t == st.t[j] && id < st.id[j]) {
                    st.t[j] = t;
                    st.id[j] = id;
                }
            }
        }
    }
}

/// The front pass's work on item `j` of a family ([`band`]): a cluster of polygons, unless it
/// is proven hidden, or a primitive of a bounded family.
struct Front<'a> {
    world: &'a World,
    j: usize,
    view: &'a View,
    s: &'a Scratch,
    st: &'a mut Band,
}

impl<F: Family> Class<F> for Front<'_> {
    type Out = ();
    #[inline(always)]
    fn polygon<const N: usize>(self)
    where
        F: Polygon<N>,
    {
        let polys = self.world.polys(F::KIND);
        let k = &polys.clusters[self.j];
        if !hidden(k, self.view, self.st) {
            let at = (self.view, &self.world.verts[..]);
            for p in k.first..k.first + k.len {
                raster_polygon::<F, N>(polys, p, true, at, self.s, self.st);
            }
        }
    }
    #[inline(always)]
    fn bounded(self)
    where
        F: Bounded,
    {
        raster_bounded::<F>(self.world.others(F::KIND), self.j, self.view, self.st);
    }
}

/// A waiting polygon's turn ([`band`]): polygon `p` of a polygon family.
struct Waiting<'a> {
    world: &'a World,
    p: u32,
    view: &'a View,
    s: &'a Scratch,
    st: &'a mut Band,
}

impl<F: Family> Class<F> for Waiting<'_> {
    type Out = ();
    #[inline(always)]
    fn polygon<const N: usize>(self)
    where
        F: Polygon<N>,
    {
        let (polys, at) = (
            self.world.polys(F::KIND),
            (self.view, &self.world.verts[..]),
        );
        raster_polygon::<F, N>(polys, self.p, false, at, self.s, self.st);
    }
    fn bounded(self)
    where
        F: Bounded,
    {
        unreachable!("only polygons wait")
    }
}

/// Pass 4 for primitive `j` of a family (id `id`, box `bx`): the oracle's constants
/// ([`Family::setup`] of its f64 geometry) and test ([`Family::hit_x1`]) at each flagged pixel
/// of its box.
struct Redecide<'a> {
    world: &'a World,
    j: usize,
    id: i32,
    bx: [u16; 4],
    view: &'a View,
    st: &'a Band,
    best: &'a mut [(Hit<f64>, [f64; 3])],
}

impl Redecide<'_> {
    /// The test of `F`'s primitive `g` at each flagged pixel.
    fn run<F: Family>(self, g: &F::Geometry) {
        if let Some(k) = F::setup(g, self.view.eye) {
            redecide_box(self.bx, self.id, self.st, self.best, |d| F::hit_x1(&k, d));
        }
    }
}

impl<F: Family> Class<F> for Redecide<'_> {
    type Out = ();
    fn polygon<const N: usize>(self)
    where
        F: Polygon<N>,
    {
        let v = self.world.polys(F::KIND).vertices::<N>(self.j);
        let g = v.map(|i| self.world.verts[i as usize]);
        self.run::<F>(&g);
    }
    fn bounded(self)
    where
        F: Bounded,
    {
        let g = self.world.others(F::KIND).geometry::<F>(self.j);
        self.run::<F>(&g);
    }
}

fn flagged(bx: [u16; 4], st: &Band) -> bool {
    let (x0, x1) = (bx[0] as usize, bx[1] as usize);
    st.rows(bx).any(|y| {
        let row = (y - st.y0) * st.x;
        st.flag[row + x0..=row + x1].contains(&true)
    })
}

#[inline(always)]
fn redecide_box(
    bx: [u16; 4],
    id: i32,
    st: &Band,
    best: &mut [(Hit<f64>, [f64; 3])],
    test: impl Fn([f64; 3]) -> Option<f64>,
) {
    let (x0, x1) = (bx[0] as usize, bx[1] as usize);
    for y in st.rows(bx) {
        let row = (y - st.y0) * st.x;
        for x in x0..=x1 {
            let (hit, d) = &mut best[row + x];
            if st.flag[row + x]
                && let Some(t) = test(*d)
            {
                hit.update(t, id);
            }
        }
    }
}

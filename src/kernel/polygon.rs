//! Ray/triangle and ray/quad intersection through edge planes that contain the eye: the Plücker
//! side test (Teller 1992; Jones, "Intersecting a Ray and a Triangle with Plücker Coordinates",
//! Ray Tracing News 13(1), 2000) specialised to rays that all start at the eye O.
//!
//! For rays through O, the Plücker side product of a ray with direction d and an edge P->Q is
//! `d . ((P - O) x (Q - O))`: the sign of the ray's side of the plane through O, P and Q. A convex
//! polygon with vertices V0..V(N-1) in perimeter order is hit iff d lies on the inner side of all
//! N edge planes; the distance is then the plane hit `t = p / (d . N)`. Per primitive (in f64,
//! relative to O, then rounded):
//! ```text
//! N   = polygon normal, oriented away from O, unit     (triangle: (B-A) x (C-A); quad:
//!                                                        (C-A) x (D-B), both diagonals)
//! s   = sign((A - O) . N_raw)                           which way the polygon faces O
//! n_i = s * normalize((V_i - O) x (V_i+1 - O))         edge plane normals, interior >= 0
//! p   = mean_i (V_i - O) . N                            distance from O to the plane, > 0
//! ```
//! Per ray: `e_i = d . n_i` (N dot products), `inside = all e_i >= -eps`, `t = p / (d . N)`.
//! A quad (planar, convex: validated) is one polygon with four edges, which is the union of its
//! triangles (A,B,C) and (A,C,D) without the diagonal.
//!
//! Watertightness, for shared edges: two polygons that share an edge P-Q compute its plane
//! normal from the same two eye-relative vectors, in the opposite order. A cross product is
//! exactly antisymmetric in IEEE arithmetic (a.y*b.z - a.z*b.y vs b.y*a.z - b.z*a.y: same
//! products, negated difference), and so are normalisation, the orientation sign flip and
//! rounding to f32 (round-to-nearest is symmetric). For two polygons seen from the same side the
//! stored normals are therefore exact negatives, and `d . n` evaluates to exact negatives: at
//! least one of the two tests passes on every ray. At a shared vertex, each polygon's normals
//! were rounded separately, so their planes may miss the vertex direction by ~1u; `eps`
//! (`kernel::edge_eps`, 8u, twice the error of `d . n`) covers that gap, so a ray through a
//! vertex hits at least one polygon around it. Proven by
//! `tests::fan_leaves_no_hole_at_shared_edges_and_vertex` here, the closed-mesh and grid tests of
//! tests/agreement/meshes.rs (`*_has_no_holes`, pixel rays through shared edges and vertices) and
//! `default_leaves_no_holes_on_closed_meshes` in tests/stability.rs.
//!
//! Precision (f32, u = 2^-24): hit/miss is decided to within ~4u radians of each edge plane; the
//! `eps` margin widens every polygon by 8u radians (4.8e-7 rad: 1e-4 of a pixel at 1920 wide and
//! 60 degrees), so silhouettes may differ from the f64 oracle in rays that close to an edge.
//! `t` errs by ~4u / cos(theta) relative, theta the angle between the ray and the normal: `d . N`
//! carries an absolute error of ~4u, and it is cos(theta) itself; grazing hits lose precision
//! (tests/agreement/main.rs bounds the relative error times cos(theta) by 48u; measured max 4.2u).
//! `--precision auto` turns this bound into its re-decision rule (`render::redecide`): a hit
//! whose bound exceeds 0.9e-5 relative is decided again in f64, which guarantees every depth
//! within 1e-5 of the oracle's (docs/precision.md; `tests/auto.rs`).
//! Known to fail: a polygon seen edge-on (every point of it within [`EDGE_ON_SINE`] of the
//! eye's horizon of its plane: no pixel's worth of area) is never hit, nor is one with an edge
//! whose ends are parallel seen from O (no edge plane: `tests::collapsed_edge_is_dropped`); the
//! eye within ~u|V - O| of an edge's line gives an ill-conditioned edge plane. Widening every
//! edge plane by `eps` moves a corner of interior angle `theta` (on the sphere of directions)
//! by `eps / sin(theta / 2)`: in f32, a sliver's tip can reach pixels past the true one, which
//! `--precision auto` checks (`render::redecide`'s bounds, "Ids"); in f64 that takes a polygon
//! seen from within ~1e-12 of its plane and a ray within ~1e-15 rad of that plane.

use crate::kernel::edge_eps;
use crate::kernel::family::{Family, facing};
use crate::kernel::lanes::{Lanes, dot_splat};
use crate::limits::MIN_EDGE_ANGLE;
use crate::real::{Real, V3, dot, v3};
use crate::scene::Shape;
use glam::DVec3;
use wide::f32x8;

pub mod triangle_setup;
use triangle_setup::triangles_x4;

/// A polygon every point of which lies within this sine of the eye's horizon of its plane (the
/// plane through the eye parallel to it) is treated as seen edge-on and never drawn: every ray
/// that could meet it passes within 1e-12 rad of its plane, a band no pixel resolves (the
/// narrowest view the limits accept has pixels of ~1e-8 rad), and 1e-12 is ~4000 times the
/// f64 rounding of that sine. The sine is the eye's height over the plane divided by its
/// distance to the polygon's nearest point ([`elevation_sine`]), not to one vertex: an eye
/// just above a polygon's interior sees it covering half the sky.
pub const EDGE_ON_SINE: f64 = 1e-12;

/// The sine of the largest elevation, seen from the eye, of any point of the convex polygon
/// with eye-relative vertices `rel` over the eye's horizon of its plane (unit normal `nrm`):
/// `h / dist`, `h` the eye's height over the plane and `dist` its distance to the polygon's
/// nearest point. 1 when the eye's foot on the plane is inside the polygon. In f64: the foot
/// and the in-plane vertices `q_i = r_i - (r_i . N) N` err by ~u |r_i|, so the sine errs by
/// ~u |r| / dist relative, far below the 1e-12 it is compared with wherever `dist` is not
/// itself at rounding level. NaN when a vertex is not finite.
pub fn elevation_sine<const N: usize>(rel: &[DVec3; N], nrm: DVec3) -> f64 {
    let h = (rel.iter().map(|r| r.dot(nrm)).sum::<f64>() / N as f64).abs();
    let q = rel.map(|r| r - nrm * r.dot(nrm));
    // the foot (the origin of `q`) inside: every edge turns the same way around it
    let turn = |i: usize| q[i].cross(q[(i + 1) % N]).dot(nrm);
    let (pos, neg) = (0..N).fold((true, true), |(p, n), i| {
        let w = turn(i);
        (p && w >= 0.0, n && w <= 0.0)
    });
    if pos || neg {
        return if h > 0.0 { 1.0 } else { 0.0 };
    }
    // else the nearest point is on an edge
    let along = (0..N)
        .map(|i| {
            let (a, b) = (q[i], q[(i + 1) % N]);
            let e = b - a;
            let s = (-a.dot(e) / e.length_squared()).clamp(0.0, 1.0);
            let s = if s.is_finite() { s } else { 0.0 };
            (a + e * s).length_squared()
        })
        .fold(f64::INFINITY, f64::min);
    h / (h * h + along).sqrt()
}

/// One convex polygon's eye-relative constants: `N` edge planes and the polygon's plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolyK<T, const N: usize> {
    /// Unit edge plane normals, the interior on their non-negative side.
    pub n: [V3<T>; N],
    /// Unit plane normal, pointing away from the eye.
    pub nrm: V3<T>,
    /// Distance from the eye to the plane (> 0).
    pub p: T,
}

/// A triangle's constants: three edge planes.
pub type TriangleK<T> = PolyK<T, 3>;
/// A quad's constants: four edge planes, no diagonal.
pub type QuadK<T> = PolyK<T, 4>;

impl<const N: usize> PolyK<f64, N> {
    /// Constants for vertices `v` (perimeter order) and plane normal `raw_normal` (any length,
    /// either orientation), seen from `eye`. `None` when the eye lies in the polygon's plane
    /// (seen edge-on, it covers no pixel) or a constant is not finite.
    pub fn new(v: &[DVec3; N], raw_normal: DVec3, eye: DVec3) -> Option<PolyK<f64, N>> {
        let rel = v.map(|p| p - eye);
        // (every length is taken once: the operations are glam's `length`, `normalize` and
        // `try_normalize`, `x * (1 / |x|)`, so the constants are theirs bit for bit)
        let len = rel.map(|r| r.length());
        let raw_len = raw_normal.length();
        let facing = rel[0].dot(raw_normal);
        // Edge-on up to rounding (the sine of the angle between the eye's view of A and the
        // plane below EDGE_ON_SINE): no pixel's worth of area, and edge planes that f32 rounding
        // can turn into a wedge over empty pixels (found by the accuracy lab on an icosphere
        // whose vertices were snapped onto pixel rays: sine 5.6e-17, false hits at t = 2.5e-8).
        // (a NaN sine, from a vertex that is not finite, is edge-on too)
        let edge_on = |sine: f64| sine.is_nan() || sine <= EDGE_ON_SINE;
        if !facing.is_finite()
            || facing.abs() <= EDGE_ON_SINE * len[0] * raw_len
                && edge_on(elevation_sine(&rel, raw_normal * (1.0 / raw_len)))
        {
            return None;
        }
        let s = facing.signum();
        let nrm = raw_normal * (1.0 / raw_len) * s;
        let p = Self::plane_distance(&rel, nrm);
        // An edge subtending less than `limits::MIN_EDGE_ANGLE` from the eye has no reliable
        // plane: its cross product is rounding noise (or zero), and a wrong or zero normal
        // passes every ray on one side (an endless wedge). Such a polygon is never drawn.
        // `range::f32_range` refuses these scenes with a message; this keeps the kernels
        // safe for any caller of the library.
        let mut n = [DVec3::ZERO; N];
        for (i, e) in n.iter_mut().enumerate() {
            let c = rel[i].cross(rel[(i + 1) % N]);
            let c_len = c.length();
            if c_len < MIN_EDGE_ANGLE * len[i] * len[(i + 1) % N] {
                return None;
            }
            let rcp = 1.0 / c_len;
            // (NaN too)
            if !(rcp.is_finite() && rcp > 0.0) {
                return None;
            }
            *e = c * rcp * s;
        }
        let finite = p.is_finite() && nrm.is_finite();
        (p > 0.0 && finite).then(|| PolyK {
            n: n.map(v3),
            nrm: v3(nrm),
            p,
        })
    }

    /// The plane's distance from the eye, the mean of the vertices' along the unit normal.
    #[inline]
    fn plane_distance(rel: &[DVec3; N], nrm: DVec3) -> f64 {
        rel.iter().map(|r| r.dot(nrm)).sum::<f64>() / N as f64
    }

    /// [`PolyK::new`]'s `nrm` and `p` alone, bit for bit (the same operations), without the
    /// edge planes or the checks: for a polygon `new` accepted (`--precision auto` measures a
    /// hit against its plane).
    pub fn plane(v: &[DVec3; N], raw_normal: DVec3, eye: DVec3) -> (V3<f64>, f64) {
        let rel = v.map(|p| p - eye);
        let s = rel[0].dot(raw_normal).signum();
        let nrm = raw_normal.normalize() * s;
        (v3(nrm), Self::plane_distance(&rel, nrm))
    }

    /// The same constants rounded to `T`.
    pub fn cast<T: Real>(&self) -> PolyK<T, N> {
        let r = |a: V3<f64>| a.map(T::from_f64);
        PolyK {
            n: self.n.map(r),
            nrm: r(self.nrm),
            p: T::from_f64(self.p),
        }
    }
}

impl TriangleK<f64> {
    /// Constants of triangle `v` (A, B, C) seen from `eye`, normal (B - A) x (C - A); `None`
    /// as for [`PolyK::new`].
    pub fn triangle(v: &[DVec3; 3], eye: DVec3) -> Option<TriangleK<f64>> {
        PolyK::new(v, Self::raw_normal(v), eye)
    }

    /// The triangle's `nrm` and `p` alone ([`PolyK::plane`]).
    pub fn triangle_plane(v: &[DVec3; 3], eye: DVec3) -> (V3<f64>, f64) {
        PolyK::plane(v, Self::raw_normal(v), eye)
    }

    fn raw_normal(v: &[DVec3; 3]) -> DVec3 {
        (v[1] - v[0]).cross(v[2] - v[0])
    }
}

impl QuadK<f64> {
    /// Constants of quad `v` (A, B, C, D in perimeter order) seen from `eye`, normal
    /// (C - A) x (D - B) from the diagonals; `None` as for [`PolyK::new`].
    pub fn quad(v: &[DVec3; 4], eye: DVec3) -> Option<QuadK<f64>> {
        PolyK::new(v, Self::raw_normal(v), eye)
    }

    /// The quad's `nrm` and `p` alone ([`PolyK::plane`]).
    pub fn quad_plane(v: &[DVec3; 4], eye: DVec3) -> (V3<f64>, f64) {
        PolyK::plane(v, Self::raw_normal(v), eye)
    }

    fn raw_normal(v: &[DVec3; 4]) -> DVec3 {
        (v[2] - v[0]).cross(v[3] - v[1])
    }
}

/// The triangle family (`triangle` lines and mesh faces): [`TriangleK`] and the edge-plane
/// kernel [`polygon_x1`], `polygon_lanes`.
#[derive(Debug, Clone, Copy)]
pub struct Triangle;

/// The quad family (`quad` lines: planar, convex): [`QuadK`] and the edge-plane kernel.
#[derive(Debug, Clone, Copy)]
pub struct Quad;

impl Family for Triangle {
    const KIND: usize = 1;
    /// Vertices A, B, C.
    type Geometry = [DVec3; 3];
    type K<T: Real> = TriangleK<T>;

    #[inline(always)]
    fn geometry(shape: Shape) -> Option<[DVec3; 3]> {
        match shape {
            Shape::Triangle(v) => Some(v),
            _ => None,
        }
    }
    #[inline(always)]
    fn setup(v: &[DVec3; 3], eye: DVec3) -> Option<TriangleK<f64>> {
        TriangleK::triangle(v, eye)
    }
    #[inline(always)]
    fn setup_x4(v: &[[DVec3; 3]; 4], eye: DVec3) -> [Option<TriangleK<f64>>; 4] {
        triangles_x4(v, eye)
    }
    #[inline(always)]
    fn cast<T: Real>(k: &TriangleK<f64>) -> TriangleK<T> {
        k.cast()
    }
    #[inline(always)]
    fn hit_x1<T: Real>(k: &TriangleK<T>, d: V3<T>) -> Option<T> {
        polygon_x1(k, d)
    }
    #[inline(always)]
    fn hit_lanes<L: Lanes>(k: &TriangleK<L::Scalar>, d: &[L; 3]) -> Option<(L, L)> {
        polygon_lanes(k, d)
    }
    /// The edge tolerance widened by `slack`.
    fn hit_with_slack(v: &[DVec3; 3], eye: DVec3, d: V3<f64>, slack: f64) -> Option<f64> {
        polygon_x1_within(&TriangleK::triangle(v, eye)?, d, edge_eps::<f64>() + slack)
    }
    fn near_boundary(v: &[DVec3; 3], eye: DVec3, d: V3<f64>, band: f64) -> bool {
        edge_angle(v, eye, d) <= band
    }
    fn plane(v: &[DVec3; 3], eye: DVec3) -> Option<(V3<f64>, f64)> {
        Some(TriangleK::triangle_plane(v, eye))
    }
    /// `(B - A) x (C - A)`, turned to the eye.
    fn normal(&[a, b, c]: &[DVec3; 3], eye: DVec3, _: DVec3) -> (DVec3, bool) {
        (facing((b - a).cross(c - a), a - eye), true)
    }

    // For the world engine (`--accel world`).

    /// A convex polygon of 3 edges.
    fn class<C: crate::kernel::family::Class<Triangle>>(class: C) -> C::Out {
        class.polygon::<3>()
    }

    // For the acceleration structures (`accel`): bounded as a convex polygon.

    type Outline = TriangleK<f32>;
    #[inline(always)]
    fn outline(k: &TriangleK<f32>) -> TriangleK<f32> {
        *k
    }
    #[inline(always)]
    fn hit_lanes_all<L: Lanes>(k: &TriangleK<L::Scalar>, d: &[L; 3]) -> (L, L) {
        polygon_lanes_all(k, d)
    }
}

impl Family for Quad {
    const KIND: usize = 2;
    /// Vertices A, B, C, D in perimeter order.
    type Geometry = [DVec3; 4];
    type K<T: Real> = QuadK<T>;

    #[inline(always)]
    fn geometry(shape: Shape) -> Option<[DVec3; 4]> {
        match shape {
            Shape::Quad(v) => Some(v),
            _ => None,
        }
    }
    #[inline(always)]
    fn setup(v: &[DVec3; 4], eye: DVec3) -> Option<QuadK<f64>> {
        QuadK::quad(v, eye)
    }
    #[inline(always)]
    fn cast<T: Real>(k: &QuadK<f64>) -> QuadK<T> {
        k.cast()
    }
    #[inline(always)]
    fn hit_x1<T: Real>(k: &QuadK<T>, d: V3<T>) -> Option<T> {
        polygon_x1(k, d)
    }
    #[inline(always)]
    fn hit_lanes<L: Lanes>(k: &QuadK<L::Scalar>, d: &[L; 3]) -> Option<(L, L)> {
        polygon_lanes(k, d)
    }
    /// The edge tolerance widened by `slack`.
    fn hit_with_slack(v: &[DVec3; 4], eye: DVec3, d: V3<f64>, slack: f64) -> Option<f64> {
        polygon_x1_within(&QuadK::quad(v, eye)?, d, edge_eps::<f64>() + slack)
    }
    fn near_boundary(v: &[DVec3; 4], eye: DVec3, d: V3<f64>, band: f64) -> bool {
        edge_angle(v, eye, d) <= band
    }
    fn plane(v: &[DVec3; 4], eye: DVec3) -> Option<(V3<f64>, f64)> {
        Some(QuadK::quad_plane(v, eye))
    }
    /// The diagonals' cross product `(C - A) x (D - B)`, turned to the eye.
    fn normal(&[a, b, c, d]: &[DVec3; 4], eye: DVec3, _: DVec3) -> (DVec3, bool) {
        (facing((c - a).cross(d - b), a - eye), true)
    }

    // For the world engine (`--accel world`).

    /// A convex polygon of 4 edges.
    fn class<C: crate::kernel::family::Class<Quad>>(class: C) -> C::Out {
        class.polygon::<4>()
    }

    // For the acceleration structures (`accel`): bounded as a convex polygon.

    type Outline = QuadK<f32>;
    #[inline(always)]
    fn outline(k: &QuadK<f32>) -> QuadK<f32> {
        *k
    }
    #[inline(always)]
    fn hit_lanes_all<L: Lanes>(k: &QuadK<L::Scalar>, d: &[L; 3]) -> (L, L) {
        polygon_lanes_all(k, d)
    }
}

/// The angle, in radians, between the unit direction `d` and the nearest point of the outline
/// of the convex polygon `v` seen from `eye`, on the sphere of directions: each edge is the
/// minor arc between its ends' directions `w_i`, `w_i+1` (a segment not through the eye seen
/// from it), and the angle to an arc is `asin |d . n|` (`n` the arc's unit plane normal)
/// where `d` projects inside the arc, else the angle to the nearer end. In f64, to ~u radians
/// where the arc is longer than ~u; NaN for a degenerate edge, which counts as far.
pub fn edge_angle<const N: usize>(v: &[DVec3; N], eye: DVec3, d: V3<f64>) -> f64 {
    let d = DVec3::from_array(d);
    let w = v.map(|p| (p - eye).normalize());
    (0..N)
        .map(|i| {
            let (a, b) = (w[i], w[(i + 1) % N]);
            let n = a.cross(b).normalize();
            let e = d - n * d.dot(n);
            if a.cross(e).dot(n) >= 0.0 && e.cross(b).dot(n) >= 0.0 && e.dot(a + b) > 0.0 {
                d.dot(n).abs().min(1.0).asin()
            } else {
                d.angle_between(a).min(d.angle_between(b))
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// Distance to the polygon along unit direction `d`, when it is hit ahead of the eye.
#[inline]
pub fn polygon_x1<T: Real, const N: usize>(k: &PolyK<T, N>, d: V3<T>) -> Option<T> {
    polygon_x1_within(k, d, edge_eps::<T>())
}

/// [`polygon_x1`] with edge tolerance `eps` (radians; negative shrinks the polygon). `compare`
/// uses it to tell rays that pass within a band of an edge from clear mismatches.
#[inline]
pub fn polygon_x1_within<T: Real, const N: usize>(k: &PolyK<T, N>, d: V3<T>, eps: T) -> Option<T> {
    // edge tests
    if !k.n.iter().all(|n| dot(d, *n) >= -eps) {
        return None;
    }
    // plane distance
    let t = k.p / dot(d, k.nrm);
    (t > T::ZERO && t < T::INFINITY).then_some(t)
}

/// [`polygon_x1`] for eight directions: `None` when no lane passes the edge tests, else the mask
/// of lanes that do and their plane distances (the caller keeps those with 0 < t).
#[inline(always)]
pub fn polygon_x8<const N: usize>(k: &PolyK<f32, N>, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
    polygon_lanes(k, d)
}

/// [`polygon_x1`] in the lanes of `L` (f32x8: [`polygon_x8`]; f64x4: `kernel::wide64`), the
/// same operations in the same order as the 1-lane form.
#[inline(always)]
pub fn polygon_lanes<L: Lanes, const N: usize>(
    k: &PolyK<L::Scalar, N>,
    d: &[L; 3],
) -> Option<(L, L)> {
    // Leave as soon as no lane is inside an edge: most packets miss most polygons, and the
    // first edge or two rejects them (measured with the render bench when the kernel was written).
    let mut inside = edge_inside(k, 0, d);
    for e in 1..N {
        if !inside.any() {
            return None;
        }
        inside &= edge_inside(k, e, d);
    }
    if !inside.any() {
        return None;
    }
    Some((inside, plane_t(k, d)))
}

/// [`polygon_lanes`] with no early exit: every edge is tested and the plane distance computed
/// for every packet, and the mask may be empty. The same operations give the same bits where a
/// lane is inside. For packets whose outcome branches cannot predict (tiles' per-packet lists
/// of small polygons: about one test in four hits there, counted with a temporary counter).
#[inline(always)]
pub fn polygon_lanes_all<L: Lanes, const N: usize>(k: &PolyK<L::Scalar, N>, d: &[L; 3]) -> (L, L) {
    let mut inside = edge_inside(k, 0, d);
    for e in 1..N {
        inside &= edge_inside(k, e, d);
    }
    (inside, plane_t(k, d))
}

/// Lanes inside edge `e`'s plane, within the edge tolerance.
#[inline(always)]
fn edge_inside<L: Lanes, const N: usize>(k: &PolyK<L::Scalar, N>, e: usize, d: &[L; 3]) -> L {
    dot_splat(&k.n[e], d).simd_ge(L::splat(-edge_eps::<L::Scalar>()))
}

/// Distance along the rays to the polygon's plane, `p / (d . N)`.
#[inline(always)]
fn plane_t<L: Lanes, const N: usize>(k: &PolyK<L::Scalar, N>, d: &[L; 3]) -> L {
    L::splat(k.p) / dot_splat(&k.nrm, d)
}

// For the world engine (`--accel world`): the raw normals of `TriangleK::triangle` and
// `QuadK::quad`, as vertex indices.

/// `(B - A) x (C - A)`.
impl crate::kernel::family::Polygon<3> for Triangle {
    const NORMAL: [usize; 4] = [1, 0, 2, 0];
}

/// The diagonals' `(C - A) x (D - B)`.
impl crate::kernel::family::Polygon<4> for Quad {
    const NORMAL: [usize; 4] = [2, 0, 3, 1];
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(v: DVec3) -> V3<f64> {
        v3(v.normalize())
    }

    fn x8_t<const N: usize>(k: &PolyK<f32, N>, d: V3<f32>) -> Option<f32> {
        let (m, t) = polygon_x8(k, &d.map(f32x8::splat))?;
        let (m, t) = (m.to_array()[0], t.to_array()[0]);
        (m != 0.0 && t > 0.0 && t < f32::INFINITY).then_some(t)
    }

    #[test]
    fn triangle_hit_distance_and_both_windings() {
        let a = DVec3::new(-1.0, -1.0, -4.0);
        let b = DVec3::new(1.0, -1.0, -4.0);
        let c = DVec3::new(0.0, 1.0, -4.0);
        for v in [[a, b, c], [a, c, b]] {
            let k = TriangleK::triangle(&v, DVec3::ZERO).unwrap();
            assert_eq!(polygon_x1(&k, [0.0, 0.0, -1.0]), Some(4.0));
            assert_eq!(polygon_x1(&k, dir(DVec3::new(0.0, 2.0, -4.0))), None);
            assert_eq!(polygon_x1(&k, [0.0, 0.0, 1.0]), None, "behind the eye");
        }
    }

    #[test]
    fn edges_and_vertices_count() {
        let v = [
            DVec3::new(0.0, 0.0, -2.0),
            DVec3::new(1.0, 0.0, -2.0),
            DVec3::new(0.0, 1.0, -2.0),
        ];
        let k = TriangleK::triangle(&v, DVec3::ZERO).unwrap();
        for p in [v[0], v[1], v[2], (v[0] + v[1]) / 2.0, (v[1] + v[2]) / 2.0] {
            assert!(polygon_x1(&k, dir(p)).is_some(), "{p}");
        }
    }

    #[test]
    fn edge_on_polygon_is_dropped() {
        let v = [
            DVec3::new(0.0, 0.0, -2.0),
            DVec3::new(1.0, 0.0, -2.0),
            DVec3::new(0.0, 0.0, -3.0),
        ];
        assert!(TriangleK::triangle(&v, DVec3::ZERO).is_none());
    }

    #[test]
    fn nearly_edge_on_polygon_is_dropped() {
        // The eye 1e-14 off the plane z = -2 of a unit triangle: sine ~5e-15.
        let eye = DVec3::new(0.0, 0.0, -2.0 + 1e-14);
        let v = [
            DVec3::new(0.0, 1.0, -2.0),
            DVec3::new(1.0, 1.0, -2.0),
            DVec3::new(0.0, 2.0, -2.0),
        ];
        assert!(TriangleK::triangle(&v, eye).is_none());
        let eye = DVec3::new(0.0, 0.0, -2.0 + 1e-6);
        assert!(
            TriangleK::triangle(&v, eye).is_some(),
            "1e-6 off the plane is still drawn"
        );
    }

    #[test]
    fn edge_below_the_smallest_angle_is_dropped() {
        // A 1e-6 triangle 1e7 away: its edges subtend 1e-13 rad from the eye.
        let eye = DVec3::new(0.0, 0.0, 1e7);
        let v = [
            DVec3::ZERO,
            DVec3::new(1e-6, 0.0, 0.0),
            DVec3::new(0.0, 1e-6, 0.0),
        ];
        assert!(TriangleK::triangle(&v, eye).is_none());
        let near = DVec3::new(0.0, 0.0, 1.0);
        assert!(
            TriangleK::triangle(&v, near).is_some(),
            "1e-6 rad edges are drawn"
        );
    }

    /// `PolyK::plane` is `PolyK::new`'s plane, bit for bit, for triangles and quads seen from
    /// either side and far from the origin.
    #[test]
    fn plane_alone_is_the_constants_plane() {
        let mut rng = crate::test_rng::Rng(0x9E37_79B9_7F4A_7C15);
        let mut unit = || rng.unit() - 0.5;
        let mut checked = 0;
        for _ in 0..500 {
            let base = DVec3::new(unit(), unit(), unit()) * 1e4;
            let eye = base + DVec3::new(unit(), unit(), unit()) * 20.0;
            let mut v = || base + DVec3::new(unit(), unit(), unit()) * 3.0;
            let tri = [v(), v(), v()];
            if let Some(k) = TriangleK::triangle(&tri, eye) {
                assert_eq!(TriangleK::triangle_plane(&tri, eye), (k.nrm, k.p));
                checked += 1;
            }
            // a planar quad: a parallelogram
            let (a, b, c) = (v(), v(), v());
            let quad = [a, b, c, a + c - b];
            if let Some(k) = QuadK::quad(&quad, eye) {
                assert_eq!(QuadK::quad_plane(&quad, eye), (k.nrm, k.p));
                checked += 1;
            }
        }
        assert!(checked > 900, "{checked}");
    }

    #[test]
    fn collapsed_edge_is_dropped() {
        // Far enough that subtracting the eye merges B and C: no edge plane for B-C.
        let eye = DVec3::new(-5e17, 5.19, 8.68);
        let v = [
            DVec3::new(-6.0, 2.0, -1.0),
            DVec3::new(6.0, 2.0, 1.0),
            DVec3::new(6.0, 2.0, -1.0),
        ];
        assert!(TriangleK::triangle(&v, eye).is_none());
    }

    #[test]
    fn quad_is_union_of_its_two_triangles() {
        let q = [
            DVec3::new(-1.0, -1.0, -3.0),
            DVec3::new(1.0, -1.2, -3.5),
            DVec3::new(1.3, 1.0, -4.0),
            DVec3::new(-1.0, 0.8, -3.5),
        ];
        let n = (q[2] - q[0]).cross(q[3] - q[1]);
        // make it planar: project D onto the plane of A, B, C
        let nabc = (q[1] - q[0]).cross(q[2] - q[0]).normalize();
        let q = [q[0], q[1], q[2], q[3] - nabc * (q[3] - q[0]).dot(nabc)];
        let _ = n;
        let kq = QuadK::quad(&q, DVec3::ZERO).unwrap();
        let k1 = TriangleK::triangle(&[q[0], q[1], q[2]], DVec3::ZERO).unwrap();
        let k2 = TriangleK::triangle(&[q[0], q[2], q[3]], DVec3::ZERO).unwrap();
        for i in 0..200 {
            for j in 0..200 {
                let d = dir(DVec3::new(
                    -0.6 + i as f64 * 0.006,
                    -0.5 + j as f64 * 0.006,
                    -1.0,
                ));
                let tq = polygon_x1(&kq, d);
                let tt = polygon_x1(&k1, d).or(polygon_x1(&k2, d));
                assert_eq!(tq.is_some(), tt.is_some(), "{d:?}");
                if let (Some(a), Some(b)) = (tq, tt) {
                    assert!((a - b).abs() < 1e-12 * a);
                }
            }
        }
    }

    /// A fan of triangles around one vertex, seen from a generic eye: rays through the shared
    /// vertex and through points on every shared edge hit at least one triangle, in f32.
    #[test]
    fn fan_leaves_no_hole_at_shared_edges_and_vertex() {
        let eye = DVec3::new(0.31, 0.17, 4.0);
        let centre = DVec3::new(0.013, -0.021, 0.0);
        let k = 7;
        let rim: Vec<DVec3> = (0..k)
            .map(|i| {
                let a = i as f64 / k as f64 * std::f64::consts::TAU + 0.1;
                DVec3::new(a.cos() * 1.3, a.sin(), 0.2 * (a * 3.0).sin())
            })
            .collect();
        let tris: Vec<TriangleK<f32>> = (0..k)
            .map(|i| {
                let v = [centre, rim[i], rim[(i + 1) % k]];
                TriangleK::triangle(&v, eye).unwrap().cast::<f32>()
            })
            .collect();
        let mut probes = vec![centre];
        for r in &rim {
            for s in 1..50 {
                probes.push(centre + (*r - centre) * (s as f64 / 50.0));
            }
        }
        for p in probes {
            let d = v3::<f32>((p - eye).normalize());
            let hits = tris.iter().filter(|t| polygon_x1(*t, d).is_some()).count();
            let hits8 = tris.iter().filter(|t| x8_t(*t, d).is_some()).count();
            assert!(hits >= 1, "hole at {p}");
            assert_eq!(hits, hits8);
        }
    }

    #[test]
    fn x8_equals_x1_bit_for_bit() {
        let v = [
            DVec3::new(-1.0, -1.0, -4.0),
            DVec3::new(1.0, -1.0, -4.5),
            DVec3::new(0.0, 1.0, -4.0),
        ];
        let k = TriangleK::triangle(&v, DVec3::ZERO).unwrap().cast::<f32>();
        for i in 0..100 {
            for j in 0..100 {
                let d = v3::<f32>(
                    DVec3::new(-0.4 + i as f64 * 0.008, -0.4 + j as f64 * 0.008, -1.0).normalize(),
                );
                assert_eq!(
                    polygon_x1(&k, d).map(f32::to_bits),
                    x8_t(&k, d).map(f32::to_bits)
                );
            }
        }
    }
}

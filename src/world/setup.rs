//! One polygon's per-view constants in f32, and the bound on their error.
//!
//! Input: the polygon's vertices relative to the eye, `a_i = f32(V_i - eye)` (each rounded once
//! from f64, so within 0.87u|a_i| of exact, u = 2^-24). Output, for the pixel-centre rays
//! `v = f + sx r + sy u` (unnormalised; `|v| = sqrt(1 + sx^2 + sy^2)`):
//! ```text
//! edge i (P = a_i, Q = a_i+1):   m = P x (Q - P) if P <= Q (lexicographically)
//!                                m = -(Q x (P - Q)) otherwise
//!                                n_i = s * m / |m|,  E_i(v) = (n_i.f + sy n_i.u) + sx n_i.r
//! plane:                         N = s * raw / |raw|  (raw = (a1 - a0) x (a2 - a0), or the
//!                                diagonals' cross product for a quad), s = sign(a0 . raw)
//!                                p = mean_i a_i . N,  den(v) = (N.f + sy N.u) + sx N.r
//! hit:                           E_i(v) >= -eps for every i, den > 0;  t' = p / den,
//!                                t = t' |v| (distance along the unit ray)
//! ```
//! The canonical edge order makes two polygons that share an edge compute the same `m` from the
//! same two f32 vectors and store exactly negated `n_i` (negation, normalisation and the dot
//! products are exact under sign change), so their `E_i` are exact negatives at every pixel:
//! no ray passes between them. `eps` covers the vertices, where the planes of different edges
//! meet only up to rounding.
//!
//! Error bound, to first order in u, with M = max |a_i| and p the distance from the eye to
//! the plane (M / p >= 1/cos of the angle between any hit ray and the normal):
//! - edge planes: the cross product of `P` and the edge errs by 3u|P||Q-P| against a length of
//!   |P||Q-P| sin(psi), psi the angle between P and the edge, and sin(psi) >= p / M (the edge's
//!   line is at least p from the eye); with the vertex rounding, the normalisation, the dot
//!   products and the f32 ray's turn from the f64 one (about 8u, `Camera::direction_error`):
//!   `e_edge = u (4 M/p + 8)` radians;
//! - distance: vertex rounding moves the plane by 0.87u M (relative 0.87u M/p along the ray),
//!   `p`'s dot products and `den`'s err by 3u M/p each (den = |v| cos theta >= |v| p/M), the
//!   ray's turn by 8u tan(theta) <= 8u M/p, and the normal's own rounding (3u / sin(alpha),
//!   alpha the angle between the two edges `raw` is made from) tilts the plane by that much
//!   over the polygon's diameter: `e_t = u (16 M/p + 4 diam / (p sin alpha)) + 8u` relative.
//!
//! A polygon with `e_t <= T_TIGHT` and `e_edge <= EDGE_TIGHT` is trusted ([`Class::Tight`]);
//! otherwise its pixels are re-decided in f64 where its widened test passes
//! ([`Class::Loose`]), or everywhere in its box when its constants are not usable
//! ([`Class::Opaque`]: not finite, seen edge-on, or `e_edge` past [`EPS_MAX`]).
//! Tests: `world::tests` hold every class to the f64 oracle over random scenes and cameras.

use super::{EDGE_TIGHT, T_TIGHT};
use crate::kernel::family::Polygon;
use crate::real::U32;

/// Widest edge tolerance (radians) a polygon is tested with; past it, its box is re-decided.
pub const EPS_MAX: f64 = 1e-5;

/// How far a polygon's f32 answer is trusted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    Tight,
    Loose,
    Opaque,
}

/// One polygon's constants for one view.
#[derive(Debug, Clone, Copy)]
pub struct Poly<const N: usize> {
    /// Per edge: (constant, sx coefficient, sy coefficient) of `E_i`.
    pub e: [[f32; 3]; N],
    /// The same for `den`.
    pub den: [f32; 3],
    /// Distance from the eye to the plane.
    pub p: f32,
    /// Edge tolerance times the largest `|v|`.
    pub eps: f32,
    /// `1 - 2 e_t`: a lower bound on the exact t' over the f32 one (loose polygons).
    pub lower: f32,
    pub class: Class,
}

#[inline(always)]
fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline(always)]
fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
#[inline(always)]
pub(super) fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline(always)]
fn scale(a: [f32; 3], s: f32) -> [f32; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}
#[inline(always)]
fn less(a: [f32; 3], b: [f32; 3]) -> bool {
    (a[0], a[1], a[2]) <= (b[0], b[1], b[2])
}

/// A polygon's shape factor `diam / sin(alpha)`: its diameter over the sine of the angle
/// between the two vectors its normal is the cross product of (`Polygon::NORMAL`: edges for a
/// triangle, diagonals for a quad); infinite when they are parallel. Camera-independent.
pub fn shape<P: Polygon<N>, const N: usize>(v: &[glam::DVec3; N]) -> f32 {
    let [i, j, k, l] = P::NORMAL;
    let (e1, e2) = (v[i] - v[j], v[k] - v[l]);
    let mut diam = 0.0f64;
    for i in 0..N {
        for j in i + 1..N {
            diam = diam.max((v[j] - v[i]).length());
        }
    }
    let raw = e1.cross(e2).length();
    let g = diam * e1.length() * e2.length() / raw;
    // (rounded up, and infinite for a degenerate polygon)
    if g.is_finite() {
        (g * (1.0 + 1e-6)) as f32
    } else {
        f32::INFINITY
    }
}

/// The view's basis in f32 and the largest `|v|`.
#[derive(Debug, Clone, Copy)]
pub struct Basis {
    pub f: [f32; 3],
    pub r: [f32; 3],
    pub u: [f32; 3],
    pub lmax: f64,
}

impl Basis {
    #[inline(always)]
    fn coeffs(&self, n: [f32; 3]) -> [f32; 3] {
        [dot(n, self.f), dot(n, self.r), dot(n, self.u)]
    }
}

const OPAQUE: f32 = 0.0;

/// Whether the polygon with eye-relative vertices `a` faces away from the eye by its winding
/// (the normal `raw` below, against `a_0`), in f32. Only an order of work depends on it
/// (`raster`), never an answer, so its rounding near edge-on is harmless.
#[inline(always)]
pub fn faces_away<P: Polygon<N>, const N: usize>(a: &[[f32; 3]; N]) -> bool {
    let (e1, e2) = normal_pair::<P, N>(a);
    dot(a[0], cross(e1, e2)) > 0.0
}

/// The two vectors whose cross product is the raw normal of the polygon with eye-relative
/// vertices `a` (`Polygon::NORMAL`), in f32.
#[inline(always)]
fn normal_pair<P: Polygon<N>, const N: usize>(a: &[[f32; 3]; N]) -> ([f32; 3], [f32; 3]) {
    let [i, j, k, l] = P::NORMAL;
    (sub(a[i], a[j]), sub(a[k], a[l]))
}

/// The constants of the polygon with eye-relative vertices `a` (perimeter order).
///
/// `g` is the polygon's shape factor, `diam / sin(alpha)` ([`shape`]), computed once per scene.
#[inline]
pub fn polygon<P: Polygon<N>, const N: usize>(a: [[f32; 3]; N], g: f32, b: &Basis) -> Poly<N> {
    let opaque = Poly {
        e: [[0.0; 3]; N],
        den: [0.0; 3],
        p: 0.0,
        eps: OPAQUE,
        lower: 0.0,
        class: Class::Opaque,
    };
    let (e1, e2) = normal_pair::<P, N>(&a);
    let raw = cross(e1, e2);
    let facing = dot(a[0], raw);
    let raw_len = dot(raw, raw).sqrt();
    if !(facing.is_finite() && facing != 0.0 && raw_len > 0.0 && raw_len.is_finite()) {
        return opaque;
    }
    let s = if facing > 0.0 { 1.0 } else { -1.0 };
    let nrm = scale(scale(raw, 1.0 / raw_len), s);
    let p = a.iter().map(|&v| dot(v, nrm)).sum::<f32>() / N as f32;
    if !(p > 0.0 && p.is_finite()) {
        return opaque;
    }
    // The bounds are evaluated in f32: each carries a relative error of a few u, far inside
    // the slack of their constants.
    let m = a.iter().map(|&v| dot(v, v)).fold(0.0f32, f32::max).sqrt();
    let u = U32 as f32;
    let rp = 1.0 / p;
    let e_t = u * (16.0 * m + 4.0 * g) * rp + 8.0 * u;
    let e_edge = u * (4.0 * m * rp + 8.0);
    if !(e_edge <= EPS_MAX as f32 && e_t < f32::INFINITY) {
        return opaque;
    }
    let mut e = [[0.0f32; 3]; N];
    for (i, ei) in e.iter_mut().enumerate() {
        let (pv, qv) = (a[i], a[(i + 1) % N]);
        let m = if less(pv, qv) {
            cross(pv, sub(qv, pv))
        } else {
            let c = cross(qv, sub(pv, qv));
            [-c[0], -c[1], -c[2]]
        };
        let len = dot(m, m).sqrt();
        let rcp = 1.0 / len;
        if !(rcp.is_finite() && rcp > 0.0) {
            return opaque;
        }
        *ei = b.coeffs(scale(scale(m, rcp), s));
    }
    let class = if e_t <= T_TIGHT as f32 && e_edge <= EDGE_TIGHT as f32 {
        Class::Tight
    } else {
        Class::Loose
    };
    Poly {
        e,
        den: b.coeffs(nrm),
        p,
        eps: e_edge * b.lmax as f32,
        lower: (1.0 - 2.0 * e_t).max(0.0),
        class,
    }
}

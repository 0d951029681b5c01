//! The screen regions of `accel::reach`: convex polygons in screen coordinates, clipped by the
//! kernels' edge planes, and the largest cosine between their rays and a direction.

use super::{MAX_VERTICES, SLACK};
use glam::DVec3;

/// A convex polygon in screen coordinates `(sx, sy)`, vertices in order (possibly empty).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Region {
    v: [[f64; 2]; MAX_VERTICES],
    n: usize,
}

impl Region {
    /// The whole image, `[left, right, bottom, top]` in screen coordinates
    /// (`Camera::screen`).
    pub(super) fn image([l, r, b, t]: [f64; 4]) -> Region {
        let mut v = [[0.0; 2]; MAX_VERTICES];
        v[..4].copy_from_slice(&[[l, b], [r, b], [r, t], [l, t]]);
        Region { v, n: 4 }
    }

    /// The polygon where the half-planes `a sx + b sy + c >= 0` of `lines` (in order around
    /// it) meet, when each two consecutive lines cross at an angle over 1e-3 rad at a point
    /// that every half-plane holds and that lies inside the image (`screen`, as
    /// [`Region::image`]): the region is then that polygon, whose corners are those points (a
    /// bounded intersection of `N` half-planes with `N` distinct corners on consecutive lines
    /// has no other). `None` otherwise: the caller clips the image instead.
    pub(super) fn corners<const N: usize>(
        lines: &[[f64; 3]; N],
        [l, r, b, t]: [f64; 4],
    ) -> Option<Region> {
        let mut v = [[0.0; 2]; MAX_VERTICES];
        for i in 0..N {
            let ([a0, b0, c0], [a1, b1, c1]) = (lines[(i + N - 1) % N], lines[i]);
            let det = a0 * b1 - a1 * b0;
            // (the sine of the angle between the lines, squared, over 1e-6)
            if det.is_nan() || det * det <= 1e-6 * (a0 * a0 + b0 * b0) * (a1 * a1 + b1 * b1) {
                return None;
            }
            let p = [(b0 * c1 - b1 * c0) / det, (c0 * a1 - c1 * a0) / det];
            let holds = lines
                .iter()
                .all(|&[a, b, c]| a * p[0] + b * p[1] + c >= -1e-9 * (c.abs() + 1e-300));
            let inside = l <= p[0] && p[0] <= r && b <= p[1] && p[1] <= t;
            if !(holds && inside) {
                return None;
            }
            v[i] = p;
        }
        let region = Region { v, n: N };
        // distinct corners: a polygon of area
        (region.orientation().abs() > 0.0).then_some(region)
    }

    /// The vertices, in order.
    pub(crate) fn vertices(&self) -> &[[f64; 2]] {
        &self.v[..self.n]
    }

    /// Whether no point is left.
    pub(crate) fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Keeps the part where `a sx + b sy + c >= 0` (Sutherland-Hodgman, one plane). A
    /// non-finite plane keeps everything (conservative).
    pub(super) fn clip(&mut self, a: f64, b: f64, c: f64) {
        if !(a.is_finite() && b.is_finite() && c.is_finite()) || self.n == 0 {
            return;
        }
        let h = |[x, y]: [f64; 2]| a * x + b * y + c;
        let (mut out, mut m) = ([[0.0; 2]; MAX_VERTICES], 0);
        for i in 0..self.n {
            let (p, q) = (self.v[i], self.v[(i + 1) % self.n]);
            let (hp, hq) = (h(p), h(q));
            if hp >= 0.0 {
                out[m] = p;
                m += 1;
            }
            if (hp >= 0.0) != (hq >= 0.0) {
                let t = hp / (hp - hq);
                out[m] = [p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t];
                m += 1;
            }
        }
        (self.v, self.n) = (out, m);
    }

    /// The bounding box `[x0, y0, x1, y1]` of the vertices, `None` when empty.
    pub(crate) fn bounds(&self) -> Option<[f64; 4]> {
        let v = self.vertices();
        (!v.is_empty()).then(|| {
            v.iter().fold(
                [
                    f64::INFINITY,
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                    f64::NEG_INFINITY,
                ],
                |[x0, y0, x1, y1], &[x, y]| [x0.min(x), y0.min(y), x1.max(x), y1.max(y)],
            )
        })
    }

    /// Twice the signed area (positive: counter-clockwise).
    pub(super) fn orientation(&self) -> f64 {
        let v = self.vertices();
        (0..v.len())
            .map(|i| {
                let (p, q) = (v[i], v[(i + 1) % v.len()]);
                p[0] * q[1] - p[1] * q[0]
            })
            .sum()
    }

    /// Whether the point `p` lies in the region (on its boundary counts).
    pub(super) fn contains(&self, p: [f64; 2]) -> bool {
        let v = self.vertices();
        let s = self.orientation().signum();
        !v.is_empty()
            && (0..v.len()).all(|i| {
                let (a, b) = (v[i], v[(i + 1) % v.len()]);
                s * ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) >= 0.0
            })
    }

    /// The squared distance from the screen's centre `(0, 0)` to the region (0 inside; an
    /// underestimate by rounding only).
    pub(super) fn distance2_from_centre(&self) -> f64 {
        if self.contains([0.0, 0.0]) {
            return 0.0;
        }
        let v = self.vertices();
        (0..v.len())
            .map(|i| {
                let (a, b) = (v[i], v[(i + 1) % v.len()]);
                let e = [b[0] - a[0], b[1] - a[1]];
                let l2 = e[0] * e[0] + e[1] * e[1];
                let t = if l2 > 0.0 {
                    (-(a[0] * e[0] + a[1] * e[1]) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let p = [a[0] + e[0] * t, a[1] + e[1] * t];
                p[0] * p[0] + p[1] * p[1]
            })
            .fold(f64::INFINITY, f64::min)
            * (1.0 - SLACK)
    }

    /// The largest `n . d` over unit directions `d` through the region (`n` in camera
    /// coordinates: right, up, forward; the region's points are `(sx, sy, 1)`), `None` when
    /// empty: `|n|` when `n`'s own direction lies in the region, else the largest over the
    /// arcs of its edges.
    pub(super) fn max_cosine(&self, n: DVec3) -> Option<f64> {
        let v = self.vertices();
        if v.is_empty() {
            return None;
        }
        if n.z > 0.0 && self.contains([n.x / n.z, n.y / n.z]) {
            return Some(n.length());
        }
        // the corners' unit directions and their `n . d`, once each
        let mut unit = [(DVec3::ZERO, 0.0); MAX_VERTICES];
        for (u, &[x, y]) in unit.iter_mut().zip(v) {
            let d = DVec3::new(x, y, 1.0).normalize();
            *u = (d, n.dot(d));
        }
        let arcs = (0..v.len()).map(|i| arc_max(unit[i], unit[(i + 1) % v.len()], n));
        Some(arcs.fold(f64::NEG_INFINITY, f64::max))
    }
}

/// An upper bound on `n . d` over unit directions `d` on the shorter great-circle arc from
/// `a` to `b` (`a`, `b` unit, with their `n . d`).
///
/// Along the arc, `n . d = A cos(phi) + B sin(phi)` (`phi` from `a`), whose slope at `a` has
/// the sign of `n . b - (n . a) cos w` and at `b` that of `(n . b) cos w - n . a` (`w` the
/// arc's angle). Unless it rises into the arc from both ends, the larger end is the largest
/// (the test's rounding, ~4e-16 |n|, can hide a rise of at most ~1e-15 |n| for `w` under a
/// quarter turn). Else the largest is the length of the projection of `n` onto the arc's
/// plane. That plane's normal `a x b` is known to a relative `2e-16 / sin(w)`, so an arc under
/// 1e-6 rad (or nearly half a turn) is bounded instead: every point of a short arc lies within
/// `w / 2` of an end, along a direction orthogonal to it to first order, so
/// `n . d <= n . end + |n_perp| w / 2 + |n| w^2 / 8`, with `n_perp` the part of `n` orthogonal
/// to `a`.
pub(super) fn arc_max((a1, na): (DVec3, f64), (b1, nb): (DVec3, f64), n: DVec3) -> f64 {
    let ends = na.max(nb);
    let cos = a1.dot(b1);
    if cos > 0.0 && !(nb - na * cos > 0.0 && na - nb * cos > 0.0) {
        return ends;
    }
    let m = a1.cross(b1);
    let sin2 = m.length_squared();
    if sin2.is_nan() || sin2 < 1e-12 {
        if cos.is_nan() || cos <= 0.0 {
            return n.length();
        }
        let w = (b1 - a1).length() * (1.0 + 1e-6);
        let perp = (n - a1 * n.dot(a1)).length();
        return ends + perp * w / 2.0 + n.length() * w * w / 8.0;
    }
    let np = n - m * (n.dot(m) / sin2);
    if a1.cross(np).dot(m) >= 0.0 && np.cross(b1).dot(m) >= 0.0 {
        np.length().max(ends)
    } else {
        ends
    }
}

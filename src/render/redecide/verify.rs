//! The one-primitive f64 measurement of `--precision auto` (the parent module's "Checked
//! before re-deciding"): a hit beyond its primitive's worst-case limits is kept when the
//! oracle's own kernel for that primitive, along the pixel's f64 ray, puts it within
//! [`BUDGET`] of its distance.

use super::{BUDGET, ORACLE_SLOTS, Redecide, Walk};
use crate::kernel::sphere::{SphereK, sphere_disc};
use crate::kernel::wide64::dir_x4d;
use crate::real::V3;
use crate::scene::Shape;
use crate::soa::{Stored, Visit, visit};
use glam::DVec3;
use std::cell::Ref;
use wide::f64x4;

/// What the measurement needs of one primitive, from the oracle's f64 constants: a sphere's
/// constants, or a polygon's plane in the camera's basis.
#[derive(Debug, Clone, Copy)]
pub(super) enum Oracle {
    Sphere(SphereK<f64>),
    Plane(Plane),
}

/// A polygon's plane as the measurement takes it: `N . f`, `N . r`, `N . u` (the oracle's unit
/// normal against the camera's forward, right and up vectors), and `((1 - BUDGET) p)^2`,
/// `((1 + BUDGET) p)^2` (`p`: its plane distance).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Plane {
    n: [f64; 3],
    lo2: f64,
    hi2: f64,
}

impl Plane {
    /// The measurement's constants of the polygon with unit normal `nrm` and plane distance
    /// `p`, for the basis of `tables`.
    fn new(nrm: [f64; 3], p: f64, tables: &crate::camera::RayTables<f64>) -> Plane {
        let dot = |v: [f64; 3]| nrm[0] * v[0] + nrm[1] * v[1] + nrm[2] * v[2];
        let (lo, hi) = ((1.0 - BUDGET) * p, (1.0 + BUDGET) * p);
        Plane {
            n: [dot(tables.f), dot(tables.r), dot(tables.u)],
            lo2: lo * lo,
            hi2: hi * hi,
        }
    }
}

/// Where a suspect's measurement constants are kept, when the walk found its primitive among
/// its packet's entries ([`super::check::Pending`]): else they are looked up by id.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) enum Known {
    #[default]
    Unknown,
    /// Index in `Redecide::spheres` (the packed sphere store's order).
    Sphere(u32),
    /// Kind (1 triangle, 2 quad) and packed index, in `Redecide::planes`: there unless all
    /// zeros (a polygon `Tiles::attach` did not mark).
    Polygon(u8, u32),
}

/// A hit to measure: its pixel `(x, y)` in the image, its primitive `id` and f32 distance `t`.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Suspect {
    pub(super) x: usize,
    pub(super) y: usize,
    pub(super) id: f32,
    pub(super) t: f32,
    /// Where its primitive's constants are, if the walk found them.
    pub(super) known: Known,
}

/// Four spheres' oracle constants ([`SphereK<f64>`]), one per lane.
#[derive(Debug, Clone, Copy, Default)]
struct SphereLanes {
    oc: [[f64; 4]; 3],
    r2: [f64; 4],
    c: [f64; 4],
    /// 1.0 where the eye is inside the sphere.
    inside: [f64; 4],
}

impl SphereLanes {
    fn set(&mut self, i: usize, k: &SphereK<f64>) {
        for (a, v) in self.oc.iter_mut().zip(k.oc) {
            a[i] = v;
        }
        (self.r2[i], self.c[i]) = (k.r2, k.c);
        self.inside[i] = f64::from(u8::from(k.inside));
    }
}

/// Four polygons' measurement constants ([`Plane`]), one per lane.
#[derive(Debug, Clone, Copy, Default)]
struct PlaneLanes {
    n: [[f64; 4]; 3],
    lo2: [f64; 4],
    hi2: [f64; 4],
}

impl PlaneLanes {
    fn set(&mut self, i: usize, k: &Plane) {
        for (a, v) in self.n.iter_mut().zip(k.n) {
            a[i] = v;
        }
        (self.lo2[i], self.hi2[i]) = (k.lo2, k.hi2);
    }
}

/// The lanes whose f32 distance `t32` on a polygon is within [`BUDGET`] of the oracle's, for
/// rays at screen coordinates `(sx, sy)` ([`Redecide::verified_row`] derives the test):
/// `v = f + sx r + sy u` with `f, r, u` orthonormal (to f64 rounding), so `v . N` and `v . v`
/// take two multiply-adds each; `(1 - B) p |v| <= t (v . N) <= (1 + B) p |v|`, every side
/// positive, is compared squared.
#[inline(always)]
fn plane_within(k: &PlaneLanes, (sx, sy): (f64x4, f64x4), t32: f64x4) -> f64x4 {
    let n = k.n.map(f64x4::new);
    let dn = n[0] + sx * n[1] + sy * n[2];
    let len2 = f64x4::ONE + sx * sx + sy * sy;
    let td = t32 * dn;
    let td2 = td * td;
    dn.simd_gt(f64x4::ZERO)
        & td2.simd_ge(f64x4::new(k.lo2) * len2)
        & td2.simd_le(f64x4::new(k.hi2) * len2)
}

/// The lanes whose f32 distance `t32` on a sphere is within [`BUDGET`] of the oracle's along
/// the unit f64 rays `d`: `kernel::sphere::sphere_x1`'s operations in the same order
/// (`sphere_disc`, then its root and division), each lane with its own sphere, so each lane's
/// distance is the oracle's bit for bit; a ray the
/// oracle does not see meeting the sphere ahead of the eye (its silhouette) is not verified.
#[inline(always)]
fn sphere_within(k: &SphereLanes, d: &[f64x4; 3], t32: f64x4) -> f64x4 {
    let (hit, t64) = sphere_t64(k, d);
    hit & (t32 - t64).abs().simd_le(f64x4::splat(BUDGET) * t64)
}

/// The oracle's distance to each lane's sphere along its ray, and the lanes where
/// `kernel::sphere::sphere_x1` returns it (the line meets the sphere, ahead of the eye, finite).
#[inline(always)]
fn sphere_t64(k: &SphereLanes, d: &[f64x4; 3]) -> (f64x4, f64x4) {
    let (b, disc) = sphere_disc(k.oc.map(f64x4::new), f64x4::new(k.r2), d);
    let q = b + disc.sqrt();
    let inside = f64x4::new(k.inside).simd_gt(f64x4::ZERO);
    let t64 = inside.select(q, f64x4::new(k.c) / q);
    let hit = disc.simd_ge(f64x4::ZERO)
        & t64.simd_gt(f64x4::ZERO)
        & t64.simd_lt(f64x4::splat(f64::INFINITY));
    (hit, t64)
}

impl Redecide<'_> {
    /// The lanes of `untrusted` (bits) of the four pixels `x0..x0 + 4` of row `y` (hits `t`
    /// on primitives `id`) whose hits stay untrusted once measured against the oracle's kernel
    /// for their own primitive ([`Redecide::verified_lanes`]).
    #[inline]
    pub(super) fn recheck_group(
        &self,
        walk: &Walk,
        (x0, y): (usize, usize),
        t: &[f32; 4],
        id: &[f32; 4],
        untrusted: u32,
    ) -> u32 {
        let s = std::array::from_fn(|i| match untrusted >> i & 1 {
            1 => Suspect {
                x: x0 + i,
                y,
                id: id[i],
                t: t[i],
                known: Known::Unknown,
            },
            _ => Suspect::default(),
        });
        untrusted & !self.verified_lanes(walk, &s, untrusted)
    }

    /// Which of the hits `s` in the lanes `lanes` (bits) are within [`BUDGET`] of the oracle's
    /// distance for their own primitive along their own pixel's f64 ray, measured together in
    /// f64x4 lanes whatever their pixels and primitives: a strip's few suspects, one or two to
    /// a packet, fill the lanes ([`plane_within`], [`sphere_within`]). A polygon the oracle
    /// sees edge-on is not verified.
    pub(super) fn verified_lanes(&self, walk: &Walk, s: &[Suspect; 4], lanes: u32) -> u32 {
        let (mut spheres, mut planes) = (SphereLanes::default(), PlaneLanes::default());
        let (mut is_sphere, mut is_plane) = (0, 0);
        for (i, h) in s.iter().enumerate().filter(|(i, _)| lanes >> i & 1 == 1) {
            let id = h.id as usize;
            let sphere = match h.known {
                Known::Sphere(at) => Some(self.spheres[at as usize]),
                Known::Polygon(..) => None,
                Known::Unknown => self.sphere(id),
            };
            if let Some((center, radius)) = sphere {
                // a sphere's constants cost less to compute than to look up
                spheres.set(i, &SphereK::new(center, radius, self.camera_eye));
                is_sphere |= 1 << i;
                continue;
            }
            // a kept plane is all zeros for a polygon the tiles did not mark
            let kept = match h.known {
                Known::Polygon(kind, at) => Some(self.planes[kind as usize - 1][at as usize]),
                _ => None,
            };
            if super::is_sharp(super::unpack(&self.limits[id])) {
                // never kept on its distance: decided again
                continue;
            }
            if let Some(k) = kept
                .filter(|k| k.hi2 > 0.0)
                .or_else(|| self.oracle_plane(walk, id))
            {
                planes.set(i, &k);
                is_plane |= 1 << i;
            }
        }
        let tb = &self.tables;
        let sx = f64x4::new(s.map(|h| tb.sx[h.x]));
        let sy = f64x4::new(s.map(|h| tb.sy[h.y]));
        let t32 = f64x4::new(s.map(|h| f64::from(h.t)));
        let mut ok = 0;
        if is_plane != 0 {
            ok |= plane_within(&planes, (sx, sy), t32).to_bitmask() & is_plane;
        }
        if is_sphere != 0 {
            ok |= sphere_within(&spheres, &dir_x4d(tb, sx, sy), t32).to_bitmask() & is_sphere;
        }
        ok & lanes
    }

    /// The oracle's constants of primitive `id` (`None`: a polygon seen edge-on, never hit),
    /// from the walk's cache, borrowed in place (a copy out of the cache cost more than the
    /// measurement).
    #[inline]
    pub(super) fn oracle<'w>(&self, walk: &'w Walk, id: usize) -> Ref<'w, Option<Oracle>> {
        let slot = id % ORACLE_SLOTS;
        let hit = walk
            .oracles
            .borrow()
            .get(slot)
            .is_some_and(|s| s.0 == id + 1);
        if !hit {
            let mut slots = walk.oracles.borrow_mut();
            if slots.is_empty() {
                slots.resize(ORACLE_SLOTS, (0, None));
            }
            slots[slot] = (id + 1, self.make_oracle(id));
        }
        Ref::map(walk.oracles.borrow(), |v| &v[slot].1)
    }

    /// The measurement's plane of polygon `id` from the walk's cache (`None` for a sphere).
    fn oracle_plane(&self, walk: &Walk, id: usize) -> Option<Plane> {
        match *self.oracle(walk, id) {
            Some(Oracle::Plane(k)) => Some(k),
            _ => None,
        }
    }

    /// The oracle's constants of primitive `id`, computed; `None` for a sharp polygon
    /// (`bounds`, "Ids"), whose hits are never kept on their distance alone: they are decided
    /// again in f64.
    #[inline(never)]
    fn make_oracle(&self, id: usize) -> Option<Oracle> {
        if super::is_sharp(super::unpack(&self.limits[id])) {
            return None;
        }
        match self.scene.shapes.get(id) {
            Shape::Sphere { center, radius } => Some(Oracle::Sphere(SphereK::new(
                center,
                radius,
                self.camera_eye,
            ))),
            shape => self.plane(shape).map(Oracle::Plane),
        }
    }

    /// The measurement's constants of polygon `shape` (`None` for a sphere): the oracle's
    /// plane alone, since only a polygon the oracle accepts has f32 constants to hit.
    pub(super) fn plane(&self, shape: Shape) -> Option<Plane> {
        struct Flat(DVec3);
        impl Visit<Option<(V3<f64>, f64)>> for Flat {
            fn visit<F: Stored>(self, g: F::Geometry) -> Option<(V3<f64>, f64)> {
                F::plane(&g, self.0)
            }
        }
        let (nrm, p) = visit(shape, Flat(self.camera_eye))?;
        Some(Plane::new(nrm, p, &self.tables))
    }

    /// Which of the f32 hits `t` of the four pixels `x0..x0 + 4` of row `y` (past the image:
    /// its last column again) on the primitive of `k` are within [`BUDGET`] of the oracle's
    /// distance for that primitive, as bits. Spheres through the oracle's kernel
    /// (`sphere_x4d`, each lane `sphere_x1` bit for bit, with the oracle's constants and ray):
    /// a ray it does not see meeting the sphere (its silhouette) is not verified. Polygons are
    /// measured against their plane alone, without
    /// dividing: with `v` the pixel's unnormalised f64 ray (`dir_x4d` before its division),
    /// the oracle's distance is `t64 = p |v| / (v . N)`, and `|t - t64| <= BUDGET t64` is
    /// `(1 - BUDGET) p |v| <= t (v . N) <= (1 + BUDGET) p |v|` for `v . N > 0`, every side
    /// positive, so squared: `((1 -+ BUDGET) p)^2 (v . v)` against `(t (v . N))^2`, with no
    /// square root either (the same test to f64 rounding, ~1e-16; `v . N` and `v . v` from the
    /// plane's constants in the camera's basis, [`Plane`]). Their edges are not tested
    /// again: an f32 edge decision differs from the oracle's only within its band (module
    /// comment, "Ids"), whatever the depth.
    #[inline(always)]
    pub(super) fn verified_row(
        &self,
        k: &Option<Oracle>,
        (x0, y): (usize, usize),
        t: [f32; 4],
    ) -> u32 {
        let tb = &self.tables;
        let sx = match tb.sx.get(x0..x0 + 4) {
            Some(four) => f64x4::new(four.try_into().expect("4 columns")),
            None => f64x4::new(std::array::from_fn(|i| {
                tb.sx[(x0 + i).min(tb.sx.len() - 1)]
            })),
        };
        let sy = f64x4::splat(tb.sy[y]);
        let t32 = f64x4::new(t.map(f64::from));
        match *k {
            Some(Oracle::Plane(k)) => {
                let mut planes = PlaneLanes::default();
                (0..4).for_each(|i| planes.set(i, &k));
                plane_within(&planes, (sx, sy), t32).to_bitmask()
            }
            Some(Oracle::Sphere(k)) => {
                let mut spheres = SphereLanes::default();
                (0..4).for_each(|i| spheres.set(i, &k));
                sphere_within(&spheres, &dir_x4d(tb, sx, sy), t32).to_bitmask()
            }
            None => 0,
        }
    }
}

#[cfg(test)]
mod tests;

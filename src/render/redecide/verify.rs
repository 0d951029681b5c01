//! The one-primitive f64 measurement of `--precision auto` (the parent module's "Checked
//! before re-deciding"): a hit beyond its primitive's worst-case limits is kept when the
//! oracle's own kernel for that primitive, along the pixel's f64 ray, puts it within
//! [`BUDGET`] of its distance.

use super::{BUDGET, ORACLE_SLOTS, Redecide, Walk};
use crate::kernel::methods::wide64::dir_x4d;
use crate::kernel::polygon::{QuadK, TriangleK};
use crate::kernel::sphere::{SphereK, sphere_disc};
use crate::scene::Shape;
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

    /// The oracle's constants of primitive `id`, computed.
    #[inline(never)]
    fn make_oracle(&self, id: usize) -> Option<Oracle> {
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
        let (nrm, p) = match shape {
            Shape::Sphere { .. } => return None,
            Shape::Triangle(v) => TriangleK::triangle_plane(&v, self.camera_eye),
            Shape::Quad(v) => QuadK::quad_plane(&v, self.camera_eye),
        };
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
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::kernel::polygon::polygon_x1;
    use crate::kernel::sphere::sphere_x1;
    use crate::scene::Scene;
    use crate::scene::{CameraSpec, Shapes};
    use crate::soa::Packed;
    use glam::DVec3;

    /// Scene 7's far-reaching triangle (grazing far away) and a sphere far larger than its
    /// distance to the eye, seen near its horizon, through a 64x48 camera.
    fn grazing_scene() -> (Scene, Camera) {
        let mut shapes = Shapes::new();
        let v = |x, y, z| DVec3::new(x, y, z);
        shapes.push(
            Shape::Triangle([
                v(0.0, -0.15, -0.48),
                v(-42.0, 24.0, -80.0),
                v(42.0, 24.0, -80.0),
            ]),
            1,
        );
        shapes.push(
            Shape::Sphere {
                center: v(0.0, -1.0e4 - 1.5, -20.0),
                radius: 1.0e4,
            },
            2,
        );
        let scene = Scene {
            source: "t.sc".into(),
            camera: CameraSpec {
                eye: DVec3::ZERO,
                look: v(0.0, 0.0, -1.0),
                up: DVec3::Y,
                fov_deg: None,
            },
            shapes,
            warnings: Vec::new(),
        };
        let camera = Camera::new(&scene.camera, 60.0, 64, 48);
        (scene, camera)
    }

    /// The oracle's distance to primitive `id` along pixel `(x, y)`'s f64 ray, with the oracle's
    /// own kernel and constants (spheres and triangles: the shapes of [`grazing_scene`]).
    fn oracle_t(scene: &Scene, r: &Redecide, (x, y): (usize, usize), id: usize) -> Option<f64> {
        let d = r.tables.dir_x1(x, y);
        match scene.shapes.get(id) {
            Shape::Sphere { center, radius } => {
                sphere_x1(&SphereK::new(center, radius, r.camera_eye), d)
            }
            Shape::Triangle(v) => {
                TriangleK::triangle(&v, r.camera_eye).and_then(|k| polygon_x1(&k, d))
            }
            Shape::Quad(_) => None,
        }
    }

    /// A hit beyond its primitive's limits is kept exactly when its distance is within
    /// `BUDGET` of the oracle's for that primitive, measured one lane alone and by groups of four, on one primitive or two.
    #[test]
    fn measured_hits_are_kept_only_within_the_budget() {
        let (scene, camera) = grazing_scene();
        let packed = Packed::from_scene(&scene, camera.eye);
        let r = Redecide::new(&scene, &camera, &packed);
        let walk = r.walk(&packed, None, None);
        let (mut kept, mut refused, mut mixed) = (0, 0, 0);
        for y in 0..48 {
            for x0 in (0..64).step_by(4) {
                // the oracle's distance of each lane for each primitive, with the oracle's own
                // kernel and constants
                let t64: [[Option<f64>; 4]; 2] = std::array::from_fn(|id| {
                    std::array::from_fn(|i| oracle_t(&scene, &r, (x0 + i, y), id))
                });
                // each primitive alone, then the two alternating lane by lane where both hit
                let choices: [[usize; 4]; 3] = [[0; 4], [1; 4], [0, 1, 0, 1]];
                for pick in choices {
                    let lanes: u32 = (0..4)
                        .filter(|&i| t64[pick[i]][i].is_some())
                        .fold(0, |m, i| m | 1 << i);
                    if lanes == 0 {
                        continue;
                    }
                    let id = pick.map(|p| p as f32);
                    if (0..4).any(|i| lanes & (1 << i) != 0 && pick[i] == 1)
                        && (0..4).any(|i| lanes & (1 << i) != 0 && pick[i] == 0)
                    {
                        mixed += 1;
                    }
                    // f32 hits at the oracle's distance, and at 2 BUDGET beyond it
                    for (scale, want_kept) in [(1.0, true), (1.0 + 2.0 * BUDGET, false)] {
                        let t: [f32; 4] = std::array::from_fn(|i| {
                            t64[pick[i]][i].map_or(f32::INFINITY, |t| (t * scale) as f32)
                        });
                        // the whole group and one lane alone
                        let single = 1 << lanes.trailing_zeros();
                        for mask in [lanes, single] {
                            let left = r.recheck_group(&walk, (x0, y), &t, &id, mask);
                            if want_kept {
                                assert_eq!(left, 0, "{pick:?} at ({x0}, {y}) lanes {mask:04b}");
                                kept += mask.count_ones();
                            } else {
                                assert_eq!(left, mask, "{pick:?} at ({x0}, {y})");
                                refused += mask.count_ones();
                            }
                        }
                    }
                }
            }
        }
        assert!(mixed > 5, "{mixed} mixed groups");
        assert!(kept > 500 && refused > 500, "{kept} {refused}");
    }

    /// Once attached to the tiles, a marked polygon's plane is kept, bit for bit the one the
    /// measurement computes from the scene's shape, and a suspect found in its packet
    /// (`Known::Polygon`) is measured with it as one looked up by id is: kept at the oracle's
    /// distance, refused at 2 `BUDGET` beyond it. The grazing triangle is marked; the scene
    /// has no other polygon.
    #[test]
    fn a_marked_polygons_kept_plane_measures_as_the_oracles() {
        let (scene, camera) = grazing_scene();
        let mut p = crate::render::PacketScene::new(&scene, &camera, crate::accel::Accel::Tiles);
        let mut r = Redecide::new(&scene, &camera, &p.packed);
        let tiles = p.tiles.as_mut().expect("tiles");
        r.attach_to(tiles, &p.packed, &camera);
        let at = p.packed.triangles.id.iter().position(|&id| id == 0.0);
        let at = at.expect("the triangle, packed");
        let Known::Polygon(1, at) = r.known((1, at)) else {
            panic!("the grazing triangle is marked")
        };
        let kept = r.planes[0][at as usize];
        assert!(kept.hi2 > 0.0, "its plane is kept");
        assert_eq!(Some(kept), r.plane(scene.shapes.get(0)));
        let walk = r.walk(&p.packed, p.tiles.as_ref(), None);
        let mut measured = 0;
        for y in 0..48 {
            for x in 0..64 {
                let Some(t64) = oracle_t(&scene, &r, (x, y), 0) else {
                    continue;
                };
                for (scale, expected) in [(1.0, 1), (1.0 + 2.0 * BUDGET, 0)] {
                    let s = |known| Suspect {
                        x,
                        y,
                        id: 0.0,
                        t: (t64 * scale) as f32,
                        known,
                    };
                    let found = [s(Known::Polygon(1, at)); 4];
                    let by_id = [s(Known::Unknown); 4];
                    assert_eq!(r.verified_lanes(&walk, &found, 1), expected, "({x}, {y})");
                    assert_eq!(r.verified_lanes(&walk, &by_id, 1), expected, "({x}, {y})");
                    measured += 1;
                }
            }
        }
        assert!(measured > 1000, "{measured}");
    }

    /// Suspects measured four at a time whatever their pixels, rows and primitives (as a strip's
    /// pending packets fill the lanes) get each the answer their own oracle distance gives: kept
    /// at it, refused at 2 `BUDGET` beyond it, wherever the batch puts them.
    #[test]
    fn suspects_batched_across_pixels_and_primitives_are_measured_each_alone() {
        let (scene, camera) = grazing_scene();
        let packed = Packed::from_scene(&scene, camera.eye);
        let r = Redecide::new(&scene, &camera, &packed);
        let walk = r.walk(&packed, None, None);
        let mut cases = Vec::new();
        for y in 0..48 {
            for x in 0..64 {
                for id in 0..2 {
                    if let Some(t64) = oracle_t(&scene, &r, (x, y), id) {
                        let at = |scale: f64| Suspect {
                            x,
                            y,
                            id: id as f32,
                            t: (t64 * scale) as f32,
                            known: Known::Unknown,
                        };
                        cases.push((at(1.0), true));
                        cases.push((at(1.0 + 2.0 * BUDGET), false));
                    }
                }
            }
        }
        // a fixed shuffle: neighbours in a batch come from far apart in the image
        let n = cases.len();
        let order: Vec<usize> = (0..n).map(|i| i * 7919 % n).collect();
        assert!(n % 7919 != 0 && n > 1000, "{n} cases");
        let (mut mixed, mut kept) = (0, 0);
        for four in order.chunks(4) {
            let s =
                std::array::from_fn(|i| four.get(i).map_or(Suspect::default(), |&c| cases[c].0));
            let lanes = (1 << four.len()) - 1;
            let ok = r.verified_lanes(&walk, &s, lanes);
            for (i, &c) in four.iter().enumerate() {
                assert_eq!(
                    ok >> i & 1 == 1,
                    cases[c].1,
                    "{:?} in a batch of {}",
                    cases[c].0,
                    four.len()
                );
                kept += u32::from(cases[c].1);
            }
            if four.iter().any(|&c| cases[c].0.id == 0.0)
                && four.iter().any(|&c| cases[c].0.id == 1.0)
            {
                mixed += 1;
            }
        }
        assert!(
            mixed > 50 && kept > 500,
            "{mixed} mixed batches, {kept} kept"
        );
    }

    /// Four spheres in four lanes, each along its own pixel's ray, give `sphere_x1`'s answer
    /// bit for bit: the same hit or miss, the same distance (eye outside and inside).
    #[test]
    fn sphere_lanes_of_four_spheres_are_the_oracle_bit_for_bit() {
        let (scene, camera) = grazing_scene();
        let packed = Packed::from_scene(&scene, camera.eye);
        let r = Redecide::new(&scene, &camera, &packed);
        let spheres = [
            SphereK::new(DVec3::new(0.0, -1.0e4 - 1.5, -20.0), 1.0e4, camera.eye),
            SphereK::new(DVec3::new(0.3, 0.1, -3.0), 0.7, camera.eye),
            SphereK::new(DVec3::new(-0.2, 0.05, 0.1), 2.0, camera.eye),
            SphereK::new(DVec3::new(1.0e3, 2.0e2, -4.0e3), 900.0, camera.eye),
        ];
        let (mut hits, mut misses) = (0, 0);
        for y in 0..48 {
            for x0 in (0..64).step_by(4) {
                // lane i: sphere (i + x0 / 4 + y) % 4 along pixel (x0 + i, y)
                let pick = |i: usize| (i + x0 / 4 + y) % 4;
                let mut k = SphereLanes::default();
                (0..4).for_each(|i| k.set(i, &spheres[pick(i)]));
                let sx = f64x4::new(std::array::from_fn(|i| r.tables.sx[x0 + i]));
                let d = dir_x4d(&r.tables, sx, f64x4::splat(r.tables.sy[y]));
                let (hit, t64) = sphere_t64(&k, &d);
                let (hit, t64) = (hit.to_bitmask(), t64.to_array());
                for i in 0..4 {
                    let one = sphere_x1(&spheres[pick(i)], r.tables.dir_x1(x0 + i, y));
                    match one {
                        Some(t) => {
                            assert!(hit >> i & 1 == 1, "({}, {y}) lane {i}", x0 + i);
                            assert_eq!(t.to_bits(), t64[i].to_bits(), "({}, {y})", x0 + i);
                            hits += 1;
                        }
                        None => {
                            assert!(hit >> i & 1 == 0, "({}, {y}) lane {i}", x0 + i);
                            misses += 1;
                        }
                    }
                }
            }
        }
        assert!(hits > 500 && misses > 100, "{hits} hits, {misses} misses");
    }
}

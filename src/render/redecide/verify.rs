//! The one-primitive f64 measurement of `--precision auto` (the parent module's "Checked
//! before re-deciding"): a hit beyond its primitive's worst-case limits is kept when the
//! oracle's own kernel for that primitive, along the pixel's f64 ray, puts it within
//! [`BUDGET`] of its distance.

use super::{BUDGET, ROW_MIN, Redecide, Walk};
use crate::kernel::Hit8;
use crate::kernel::methods::wide64::{dir_x4d, sphere_x4d};
use crate::kernel::polygon::{QuadK, TriangleK};
use crate::kernel::sphere::SphereK;
use crate::scene::Shape;
use wide::f64x4;

/// What the measurement needs of one primitive, from the oracle's f64 constants: a sphere's
/// constants, or a polygon's plane in the camera's basis.
#[derive(Debug, Clone, Copy)]
pub(super) enum Oracle {
    Sphere(SphereK<f64>),
    /// `N . f`, `N . r`, `N . u` (the oracle's unit normal against the camera's forward, right
    /// and up vectors), and `((1 - BUDGET) p)^2`, `((1 + BUDGET) p)^2` (`p`: its plane distance).
    Plane {
        n: [f64; 3],
        lo2: f64,
        hi2: f64,
    },
}

impl Oracle {
    /// The measurement's constants of the polygon with unit normal `nrm` and plane distance
    /// `p`, for the basis of `tables`.
    fn plane(nrm: [f64; 3], p: f64, tables: &crate::camera::RayTables<f64>) -> Oracle {
        let dot = |v: [f64; 3]| nrm[0] * v[0] + nrm[1] * v[1] + nrm[2] * v[2];
        let (lo, hi) = ((1.0 - BUDGET) * p, (1.0 + BUDGET) * p);
        Oracle::Plane {
            n: [dot(tables.f), dot(tables.r), dot(tables.u)],
            lo2: lo * lo,
            hi2: hi * hi,
        }
    }
}

impl Redecide<'_> {
    /// The lanes of `untrusted` (bits) whose hits stay untrusted once measured against the
    /// oracle's kernel for their own primitive ([`Redecide::verified`]). Lanes on one primitive
    /// (the common case) are measured a row of four at a time in f64x4 lanes, each lane the
    /// scalar kernel's answer bit for bit (`kernel::methods::wide64`).
    #[inline]
    pub(super) fn recheck(
        &self,
        walk: &Walk,
        (bx, by, bw): (usize, usize, usize),
        hit: &Hit8,
        untrusted: u32,
    ) -> u32 {
        if untrusted == 0 {
            return 0;
        }
        let (t, id) = (hit.t.to_array(), hit.id.to_array());
        let first = id[untrusted.trailing_zeros() as usize];
        let same = hit.id.simd_eq(wide::f32x8::splat(first)).to_bitmask();
        let one = same & untrusted == untrusted;
        if bw == 4 && untrusted.count_ones() >= ROW_MIN && one {
            let k = self.oracle(walk, first as usize);
            let mut out = 0;
            for row in 0..2 {
                let lanes = (untrusted >> (4 * row)) & 0xF;
                if lanes != 0 {
                    let t32 = std::array::from_fn(|i| t[4 * row + i]);
                    let ok = self.verified_row(&k, (bx, by + row), t32);
                    out |= (lanes & !ok) << (4 * row);
                }
            }
            return out;
        }
        let (mut left, mut out) = (untrusted, untrusted);
        while left != 0 {
            let lane = left.trailing_zeros() as usize;
            let k = self.oracle(walk, id[lane] as usize);
            if self.verified(k, t[lane], (bx + lane % bw, by + lane / bw)) {
                out &= !(1 << lane);
            }
            left &= left - 1;
        }
        out
    }

    /// The oracle's constants of primitive `id` (`None`: a polygon seen edge-on, never hit),
    /// from the walk's one-entry cache.
    #[inline]
    pub(super) fn oracle(&self, walk: &Walk, id: usize) -> Option<Oracle> {
        if let (key, k) = walk.last.get()
            && key == id + 1
        {
            return k;
        }
        let eye = self.camera_eye;
        let k = match self.scene.shapes.get(id) {
            Shape::Sphere { center, radius } => {
                Some(Oracle::Sphere(SphereK::new(center, radius, eye)))
            }
            Shape::Triangle(v) => {
                TriangleK::triangle(&v, eye).map(|k| Oracle::plane(k.nrm, k.p, &self.tables))
            }
            Shape::Quad(v) => QuadK::quad(&v, eye).map(|k| Oracle::plane(k.nrm, k.p, &self.tables)),
        };
        walk.last.set((id + 1, k));
        k
    }

    /// Whether the f32 hit at distance `t` on the primitive of `k` along pixel `(x, y)`'s ray
    /// is within [`BUDGET`] of the oracle's distance for that primitive: lane 0 of
    /// [`Redecide::verified_row`], so one lane and a row follow one rule.
    fn verified(&self, k: Option<Oracle>, t: f32, (x, y): (usize, usize)) -> bool {
        self.verified_row(&k, (x, y), [t; 4]) & 1 != 0
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
    /// plane's constants in the camera's basis, [`Oracle::Plane`]). Their edges are not tested
    /// again: an f32 edge decision differs from the oracle's only within its band (module
    /// comment, "Ids"), whatever the depth.
    #[inline(always)]
    fn verified_row(&self, k: &Option<Oracle>, (x0, y): (usize, usize), t: [f32; 4]) -> u32 {
        let tb = &self.tables;
        let sx = f64x4::new(std::array::from_fn(|i| {
            tb.sx[(x0 + i).min(tb.sx.len() - 1)]
        }));
        let sy = f64x4::splat(tb.sy[y]);
        let t32 = f64x4::new(t.map(f64::from));
        match *k {
            // v = f + sx r + sy u with f, r, u orthonormal (to f64 rounding): v . N and v . v
            // in two multiply-adds each; (1 - B) p |v| <= t (v . N) <= (1 + B) p |v|, every
            // side positive, compared squared
            Some(Oracle::Plane { n, lo2, hi2 }) => {
                let dn = f64x4::splat(n[0]) + sx * f64x4::splat(n[1]) + sy * f64x4::splat(n[2]);
                let len2 = f64x4::ONE + sx * sx + sy * sy;
                let td = t32 * dn;
                let td2 = td * td;
                let ok = dn.simd_gt(f64x4::ZERO)
                    & td2.simd_ge(f64x4::splat(lo2) * len2)
                    & td2.simd_le(f64x4::splat(hi2) * len2);
                ok.to_bitmask()
            }
            Some(Oracle::Sphere(k)) => {
                let Some((mask, t64)) = sphere_x4d(&k, &dir_x4d(tb, sx, sy)) else {
                    return 0;
                };
                // the scalar kernel's conditions: a hit ahead of the eye, finite
                let ok = mask
                    & t64.simd_gt(f64x4::ZERO)
                    & t64.simd_lt(f64x4::splat(f64::INFINITY))
                    & (t32 - t64).abs().simd_le(f64x4::splat(BUDGET) * t64);
                ok.to_bitmask()
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
    use wide::f32x8;

    /// A hit beyond its primitive's limits is kept exactly when its distance is within
    /// `BUDGET` of the oracle's for that primitive, measured one lane at a time and by rows.
    #[test]
    fn measured_hits_are_kept_only_within_the_budget() {
        // scene 7's far-reaching triangle (grazing far away) and a sphere far larger than its
        // distance to the eye, seen near its horizon
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
        let packed = Packed::from_scene(&scene, camera.eye);
        let r = Redecide::new(&scene, &camera, &packed);
        let walk = r.walk(&packed, None, None);
        let (mut kept, mut refused) = (0, 0);
        for by in (0..48).step_by(2) {
            for bx in (0..64).step_by(4) {
                // the oracle's distance of each lane for each primitive, then f32 hits at it
                // and at 2 BUDGET beyond it
                for id in 0..2 {
                    // the oracle's own kernel and constants for the primitive
                    let t64: [Option<f64>; 8] = std::array::from_fn(|l| {
                        let d = r.tables.dir_x1(bx + l % 4, by + l / 4);
                        match scene.shapes.get(id) {
                            Shape::Sphere { center, radius } => {
                                sphere_x1(&SphereK::new(center, radius, camera.eye), d)
                            }
                            Shape::Triangle(v) => {
                                TriangleK::triangle(&v, camera.eye).and_then(|k| polygon_x1(&k, d))
                            }
                            Shape::Quad(_) => None,
                        }
                    });
                    let lanes: u32 = (0..8)
                        .filter(|&l| t64[l].is_some())
                        .fold(0, |m, l| m | 1 << l);
                    if lanes == 0 {
                        continue;
                    }
                    for (scale, want_kept) in [(1.0, true), (1.0 + 2.0 * BUDGET, false)] {
                        let t = t64.map(|t| t.map_or(f32::INFINITY, |t| (t * scale) as f32));
                        let hit = Hit8 {
                            t: f32x8::new(t),
                            id: f32x8::splat(id as f32),
                        };
                        // rows (two or more lanes) and one lane at a time
                        let single = 1 << lanes.trailing_zeros();
                        for mask in [lanes, single] {
                            let left = r.recheck(&walk, (bx, by, 4), &hit, mask);
                            if want_kept {
                                assert_eq!(left, 0, "id {id} at ({bx}, {by}) lanes {mask:08b}");
                                kept += mask.count_ones();
                            } else {
                                assert_eq!(left, mask, "id {id} at ({bx}, {by})");
                                refused += mask.count_ones();
                            }
                        }
                    }
                }
            }
        }
        assert!(kept > 500 && refused > 500, "{kept} {refused}");
    }
}

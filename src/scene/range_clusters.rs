//! The f32 range check of many views ([`range::f32_range_from`] for each view's eye) settled
//! a cluster of triangles at a time: [`RangeClusters`] is built once per scene, independent
//! of any camera, and each view's check then tests one bound per cluster of [`CLUSTER`]
//! primitives neighbouring in space (runs of a Morton curve through their centroids, so the
//! file's face order does not matter), going down to the per-primitive rules only for the
//! clusters the bound cannot settle (those seen nearly edge-on, near the eye's plane, and any
//! cluster that holds a sphere or a quad). The outcome, and the primitive an error names (the
//! least id that breaks a rule), are [`range::f32_range_from`]'s: a settled cluster holds no
//! offending primitive.
//!
//! **The bound.** Per cluster, in f64: a bounding sphere (centre `c`, radius `rho`); the cone
//! of the faces' normal *lines* (axis `a`, half-angle `theta`: every face's computed unit
//! normal `n_f`, as the exact rules compute it, lies within `theta` of `+a` or `-a`); the
//! shortest edge `l`; and `delta`, a bound on the angle between each computed `n_f` and its
//! face's exact normal. For an eye at `e = eye - c`, `L = |e|`, `phi` the angle between `e`
//! and the axis line, and `reach = L + rho` (no vertex is farther from the eye):
//!
//! - `|(eye - v) . n_f| >= |e . n_f| - rho >= L cos(phi + theta) - rho` for every vertex `v`
//!   of face `f` (the eye is at least that far from each face's plane as the exact rules
//!   measure it), and the exact plane is at most `reach * delta` nearer, so every face's
//!   exact plane is at least `h = L cos(phi + theta) - rho - reach (delta + 1e-12)` from the
//!   eye (the `1e-12 reach` covers this formula's own rounding, a few `u = 2^-53` of `reach`).
//! - Distance rule: every `|r_k| <= reach`, accepted when `reach <= MAX_EYE_DISTANCE / 2`.
//! - Plane rule: the exact rules' plane distance `p` (computed, error a few `u reach`) is at
//!   least `h - 4u reach`; accepted when `h >= 2 f32::MIN_POSITIVE + 1e-10 reach`, so `p` is at
//!   least `f32::MIN_POSITIVE`.
//! - Edge rule: the sine an edge `v_i v_j` subtends from the eye is `|r_i x r_j| / (|r_i|
//!   |r_j|) = |v_j - v_i| dist(eye, line v_i v_j) / (|r_i| |r_j|)`, and the edge's line lies in
//!   the face's exact plane, so the sine is at least `l h / reach^2`; accepted when that is at
//!   least `2 MIN_EDGE_ANGLE`, so the computed sine (error at most `8u`) passes
//!   `MIN_EDGE_ANGLE`.
//! - `delta`: the computed cross product `c' = (B - A) x (C - A)` errs from the exact `c` by at
//!   most `12u |B - A| |C - A|` (each component's two products and subtraction, summed over
//!   components by Cauchy-Schwarz), turning it by at most `2 |c' - c| / |c|`; normalising turns
//!   it by a few `u`. With `q = |B - A| |C - A| / |c'|`: `delta <= 32u q / (1 - 16u q) + 8u`,
//!   and a face with `16u q >= 1/2` (beyond what `DEGENERATE_TOL` lets through) leaves its
//!   cluster to the per-primitive rules.
//!
//! Known to fail: never wrongly (every settled cluster's faces pass the exact rules, tested
//! over random meshes, scales and eyes near planes, on edge lines and near the distance
//! limit); it settles nothing where `cos(phi + theta)` is small, which is the silhouette of a
//! curved cluster, or where a cluster's faces turn through a right angle (a sharp edge, a
//! thin part, a noisy scan) or lie far apart (a Morton run can jump between distant cells).
//! Orbits of the seed scans settle 27% (armadillo), 21% (bunny) and 4% (teapot) of their
//! clusters; of the armadillo subdivided three times, 99.8%.

use super::range;
use super::{Scene, Shape};
use crate::error::Error;
use crate::limits::{MAX_EYE_DISTANCE, MIN_EDGE_ANGLE};
use crate::par::prelude::*;
use glam::DVec3;

/// Primitives per cluster: consecutive ids.
pub const CLUSTER: usize = 64;

use crate::real::U64 as U;

/// One cluster's camera-independent bound (module comment).
#[derive(Debug, Clone, Copy)]
struct Bound {
    centre: DVec3,
    rho: f64,
    axis: DVec3,
    cos_theta: f64,
    sin_theta: f64,
    shortest: f64,
    delta: f64,
    /// The largest over the faces of the farthest vertex's distance from the incentre over
    /// the inradius (at least 2, for an equilateral face; large for a sliver): how far a
    /// face widened by a distance `w` on every edge reaches, `quality * w` at most.
    quality: f64,
    /// A box holding every vertex, in the frame of [`frame`]`(axis)` about `centre`: its
    /// least and greatest coordinates (widened by `1e-9 rho` for their rounding).
    lo: DVec3,
    hi: DVec3,
    /// `Some(true)` when every face's normal by its winding (`(B - A) x (C - A)`) lies on
    /// `+axis`'s side, `Some(false)` when every one lies on `-axis`'s, `None` when they differ.
    winding: Option<bool>,
}

/// The orthonormal frame of a cluster's box: two directions across `axis`, then `axis`.
pub(crate) fn frame(axis: DVec3) -> [DVec3; 3] {
    let (b1, b2) = axis.any_orthonormal_pair();
    [b1, b2, axis]
}

/// What a view needs of one cluster to bound where its faces can be hit
/// (`accel::clusters`): its box, its faces' shape quality and shortest edge, and how far
/// the eye is from the faces' planes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Gap {
    /// A box holding every vertex: coordinates `lo` to `hi` about `centre` along
    /// [`frame`]`(axis)`.
    pub(crate) centre: DVec3,
    pub(crate) axis: DVec3,
    pub(crate) lo: DVec3,
    pub(crate) hi: DVec3,
    /// `Bound::quality`, the shortest edge, and `delta`: the angle between each face's
    /// computed unit normal and its exact one (module comment).
    pub(crate) quality: f64,
    pub(crate) shortest: f64,
    pub(crate) delta: f64,
    /// A lower bound on the eye's distance from every face's exact plane (> 0), and an upper
    /// bound on its distance from every vertex.
    pub(crate) h: f64,
    pub(crate) reach: f64,
    /// With the eye off every face's plane and one winding throughout: `Some(true)` when the
    /// eye sees every face from its front (the side its winding's normal points to),
    /// `Some(false)` when it sees every face from behind; `None` when the windings differ.
    /// On a closed surface wound outwards the clusters seen from behind lie behind its front
    /// (a guess `render::cull` checks, never trusts).
    pub(crate) front: Option<bool>,
}

/// The clusters of one scene: its primitives' ids in space order, [`CLUSTER`] at a time, and
/// each cluster's bound (`None` for a cluster the bound never settles).
#[derive(Debug, Clone)]
pub struct RangeClusters {
    ids: Vec<u32>,
    bounds: Vec<Option<Bound>>,
}

impl RangeClusters {
    /// The clusters of `scene`, built on all threads. First each run of [`CLUSTER`]
    /// consecutive ids: where the file's order is coherent in space (a subdivided or
    /// well-ordered mesh), its bound is tight and the run is kept as a cluster. The primitives
    /// of the other runs are sorted along a Morton (Z-order) curve through their centroids
    /// (ties by id), so that a cluster holds neighbours in space whatever the file's order,
    /// and clustered in runs of that order.
    pub fn new(scene: &Scene) -> RangeClusters {
        let n = scene.shapes.len();
        let bound = |ids: &[u32]| {
            let mut tris = Vec::with_capacity(CLUSTER);
            for &id in ids {
                match scene.shapes.get(id as usize) {
                    Shape::Triangle(v) => tris.push(v),
                    _ => return None,
                }
            }
            Bound::of(&tris)
        };
        // a kept run: a cone of normals within 60 degrees of its axis
        let tight = |b: &Option<Bound>| b.is_some_and(|b| b.cos_theta >= 0.5);
        let runs: Vec<Option<Bound>> = (0..n.div_ceil(CLUSTER))
            .into_par_iter()
            .map(|k| {
                let ids: Vec<u32> = (k * CLUSTER..((k + 1) * CLUSTER).min(n))
                    .map(|i| i as u32)
                    .collect();
                Some(bound(&ids)).filter(tight).flatten()
            })
            .collect();
        let mut ids: Vec<u32> = Vec::with_capacity(n);
        let mut bounds: Vec<Option<Bound>> = Vec::new();
        let mut rest: Vec<u32> = Vec::new();
        for (k, b) in runs.into_iter().enumerate() {
            let run = (k * CLUSTER..((k + 1) * CLUSTER).min(n)).map(|i| i as u32);
            match b {
                // (only a full run joins the kept ones, so clusters stay CLUSTER long)
                Some(b) if run.len() == CLUSTER => {
                    ids.extend(run);
                    bounds.push(Some(b));
                }
                _ => rest.extend(run),
            }
        }
        for cluster in morton_order(scene, rest).chunks(CLUSTER) {
            ids.extend_from_slice(cluster);
        }
        let kept = bounds.len() * CLUSTER;
        bounds.par_extend(ids[kept..].par_chunks(CLUSTER).map(bound));
        RangeClusters { ids, bounds }
    }
    /// [`range::f32_range_from`]`(scene, eye)`, the same outcome and message: the primitives of
    /// the clusters this bound does not settle are checked one by one, and the least id that
    /// breaks a rule is named. `scene` is the one these were built from.
    pub fn check(&self, scene: &Scene, eye: DVec3) -> Result<(), Error> {
        debug_assert_eq!(self.ids.len(), scene.shapes.len());
        let first = (self.bounds.par_iter().zip(self.ids.par_chunks(CLUSTER)))
            .filter(|(b, _)| !b.is_some_and(|b| b.settles(eye)))
            .flat_map_iter(|(_, ids)| {
                ids.iter().filter_map(move |&id| {
                    let shape = scene.shapes.get(id as usize);
                    range::shape_f32(&shape, eye)
                        .err()
                        .map(|m| (id as usize, m))
                })
            })
            .map(Some)
            .reduce(
                || None,
                |a, b| match (a, b) {
                    (Some(a), Some(b)) => Some(if a.0 <= b.0 { a } else { b }),
                    (a, b) => a.or(b),
                },
            );
        range::outcome(scene, first)
    }

    /// How many clusters there are.
    pub(crate) fn len(&self) -> usize {
        self.bounds.len()
    }

    /// How many primitives the clusters hold (the scene's).
    pub(crate) fn ids_len(&self) -> usize {
        self.ids.len()
    }

    /// The ids of cluster `k`.
    pub(crate) fn cluster(&self, k: usize) -> &[u32] {
        &self.ids[k * CLUSTER..((k + 1) * CLUSTER).min(self.ids.len())]
    }

    /// Cluster `k` seen from `eye`, `None` when its bound does not keep the eye off every
    /// face's plane (or it has no bound: spheres, quads, faces too thin).
    pub(crate) fn gap(&self, k: usize, eye: DVec3) -> Option<Gap> {
        let b = self.bounds[k].as_ref()?;
        let (h, reach) = b.plane_gap(eye)?;
        Some(Gap {
            centre: b.centre,
            axis: b.axis,
            lo: b.lo,
            hi: b.hi,
            quality: b.quality,
            shortest: b.shortest,
            delta: b.delta,
            h,
            reach,
            front: b.winding.map(|plus| {
                let d = (eye - b.centre).dot(b.axis);
                if plus { d > 0.0 } else { -d > 0.0 }
            }),
        })
    }

    /// How many clusters the bound settles from `eye`, and how many there are.
    pub fn settled(&self, eye: DVec3) -> (usize, usize) {
        let n = (self.bounds.par_iter())
            .filter(|b| b.is_some_and(|b| b.settles(eye)))
            .count();
        (n, self.bounds.len())
    }
}

/// A triangle's farthest vertex from its incentre over its inradius (`Bound::quality`), with
/// a relative 1e-6 over its rounding; infinite (or NaN) for a collapsed face.
fn face_quality(v: &[DVec3; 3]) -> f64 {
    // sides opposite each vertex; the incentre weights each vertex by its opposite side
    let side = [
        (v[1] - v[2]).length(),
        (v[2] - v[0]).length(),
        (v[0] - v[1]).length(),
    ];
    let perimeter = side[0] + side[1] + side[2];
    let incentre = (v[0] * side[0] + v[1] * side[1] + v[2] * side[2]) / perimeter;
    // inradius = 2 area / perimeter = |cross| / perimeter
    let r = (v[1] - v[0]).cross(v[2] - v[0]).length() / perimeter;
    let far = v
        .iter()
        .map(|p| (*p - incentre).length())
        .fold(0.0, f64::max);
    far / r * (1.0 + 1e-6)
}

/// `ids` sorted by the axis their face's normal line lies nearest to (x, y or z: the lines
/// of one class lie within 54.7 degrees of their axis, so a cluster of one class has a cone
/// of normal lines narrower than a right angle), then along a Morton curve through their
/// primitives' centroids, ties by id.
fn morton_order(scene: &Scene, ids: Vec<u32>) -> Vec<u32> {
    let key = |s: Shape| {
        let class = |n: DVec3| {
            let a = n.abs();
            if a.x >= a.y && a.x >= a.z {
                0
            } else if a.y >= a.z {
                1
            } else {
                2
            }
        };
        match s.centre_and_normal() {
            (centre, Some(n)) => (class(n), centre),
            // (a curved shape: a class of its own)
            (centre, None) => (3u8, centre),
        }
    };
    let (classes, centres): (Vec<u8>, Vec<DVec3>) = (ids.par_iter())
        .map(|&id| key(scene.shapes.get(id as usize)))
        .unzip();
    let far = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    let (lo, hi) = (centres.par_iter())
        .map(|c| (*c, *c))
        .reduce(|| far, |a, b| (a.0.min(b.0), a.1.max(b.1)));
    let cells = DVec3::splat(f64::from((1u32 << 21) - 1));
    let scale = cells / (hi - lo).max(DVec3::splat(1e-300));
    let mut keyed: Vec<(u8, u64, u32)> = (centres.par_iter().zip(&classes).zip(&ids))
        .map(|((c, &class), &id)| {
            // (finite in a validated scene; a non-finite cell saturates, never panics)
            let cell = ((*c - lo) * scale).to_array().map(|x| x as u32);
            (class, morton(cell), id)
        })
        .collect();
    keyed.par_sort_unstable();
    keyed.into_iter().map(|(.., id)| id).collect()
}

/// The Morton code of a cell: the bits of its three 21-bit coordinates interleaved.
fn morton(cell: [u32; 3]) -> u64 {
    // spread 21 bits to every third of 63 (the usual magic-number shifts)
    let spread = |x: u32| {
        let mut x = u64::from(x) & 0x1F_FFFF;
        x = (x | x << 32) & 0x001F_0000_0000_FFFF;
        x = (x | x << 16) & 0x001F_0000_FF00_00FF;
        x = (x | x << 8) & 0x100F_00F0_0F00_F00F;
        x = (x | x << 4) & 0x10C3_0C30_C30C_30C3;
        (x | x << 2) & 0x1249_2492_4924_9249
    };
    spread(cell[0]) | spread(cell[1]) << 1 | spread(cell[2]) << 2
}

impl Bound {
    /// The bound of a cluster of triangles, `None` when it has none (empty, a normal cone
    /// reaching a right angle, a face too thin for `delta`, anything not finite).
    fn of(tris: &[[DVec3; 3]]) -> Option<Bound> {
        let first = tris.first()?;
        let (mut lo, mut hi) = (first[0], first[0]);
        let mut shortest = f64::INFINITY;
        let mut delta = 0f64;
        let mut quality = 0f64;
        let mut normals = Vec::with_capacity(tris.len());
        for v in tris {
            // (a NaN, a collapsed face, counts as infinite: no view bounds the cluster)
            let q = face_quality(v);
            quality = if q.is_nan() {
                f64::INFINITY
            } else {
                quality.max(q)
            };
            for k in 0..3 {
                lo = lo.min(v[k]);
                hi = hi.max(v[k]);
                shortest = shortest.min((v[(k + 1) % 3] - v[k]).length());
            }
            // as the exact rules compute it (`validate::polygon_f32_exact`)
            let (d, e) = (v[1] - v[0], v[2] - v[0]);
            let c = d.cross(e);
            let q = d.length() * e.length() / c.length();
            if q.is_nan() || 16.0 * U * q >= 0.5 {
                return None;
            }
            delta = delta.max(32.0 * U * q / (1.0 - 16.0 * U * q) + 8.0 * U);
            normals.push(c.normalize_or_zero());
        }
        let centre = (lo + hi) * 0.5;
        let rho = tris
            .iter()
            .flatten()
            .map(|p| (*p - centre).length())
            .fold(0.0, f64::max)
            * (1.0 + 1e-9);
        // the axis: the normals' sum, each turned to the first one's side (lines, not
        // directions: the bound takes |e . n_f|)
        let n0 = normals[0];
        let sum: DVec3 = normals
            .iter()
            .map(|n| if n.dot(n0) < 0.0 { -*n } else { *n })
            .sum();
        let axis = sum.normalize_or_zero();
        let side = |n: &DVec3| n.dot(axis).signum();
        let winding = (normals.iter().all(|n| side(n) == side(&n0))).then(|| side(&n0) > 0.0);
        let cos_min = normals
            .iter()
            .map(|n| n.dot(axis).abs())
            .fold(1.0, f64::min);
        // (1e-9 rad over the acos's and the dot products' rounding)
        let theta = cos_min.min(1.0).acos() + 1e-9;
        let f = frame(axis);
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for p in tris.iter().flatten() {
            let q = *p - centre;
            let x = DVec3::new(q.dot(f[0]), q.dot(f[1]), q.dot(f[2]));
            (lo, hi) = (lo.min(x), hi.max(x));
        }
        let pad = DVec3::splat(1e-9 * rho);
        let (lo, hi) = (lo - pad, hi + pad);
        let bound = Bound {
            centre,
            rho,
            axis,
            cos_theta: theta.cos(),
            sin_theta: theta.sin(),
            shortest: shortest * (1.0 - 1e-9),
            delta,
            quality,
            lo,
            hi,
            winding,
        };
        let finite = [centre, axis, lo, hi].iter().all(|v| v.is_finite())
            && [rho, shortest, delta].iter().all(|x| x.is_finite());
        (finite && shortest > 0.0 && axis != DVec3::ZERO && theta < std::f64::consts::FRAC_PI_2)
            .then_some(bound)
    }

    /// True when every face of the cluster passes the exact rules from `eye` (module comment).
    #[inline]
    fn settles(&self, eye: DVec3) -> bool {
        self.plane_gap(eye).is_some_and(|(h, reach)| {
            h >= 2.0 * f64::from(f32::MIN_POSITIVE) + 1e-10 * reach
                && self.shortest * h >= 2.0 * MIN_EDGE_ANGLE * reach * reach
        })
    }

    /// `(h, reach)` of the module comment from `eye`: every face's exact plane is at least `h`
    /// from the eye, every vertex at most `reach`; `None` unless `h > 0` and `reach` is within
    /// the distance rule.
    #[inline]
    fn plane_gap(&self, eye: DVec3) -> Option<(f64, f64)> {
        let e = eye - self.centre;
        let l = e.length();
        let reach = l + self.rho;
        if reach.is_nan() || reach > MAX_EYE_DISTANCE / 2.0 || l == 0.0 {
            return None;
        }
        let cos_phi = (e.dot(self.axis).abs() / l).min(1.0);
        let sin_phi = (1.0 - cos_phi * cos_phi).max(0.0).sqrt();
        let cos = cos_phi * self.cos_theta - sin_phi * self.sin_theta;
        let h = l * cos - self.rho - reach * (self.delta + 1e-12);
        (h > 0.0).then_some((h, reach))
    }
}

#[cfg(test)]
pub(crate) mod tests;

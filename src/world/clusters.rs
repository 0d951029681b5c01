//! Clusters of up to [`CLUSTER`] consecutive polygons, bounded once per scene: a sphere around
//! their vertices and a cone around their normals (the mesh's own winding), so that a view
//! can tell, per cluster, that every polygon in it faces away from the eye.
//!
//! Back-facing test (f64): with `w = centre - eye`, the cluster lies within the angle
//! `beta = asin(radius / |w|)` of `w` seen from the eye, and its normals within `alpha` of
//! `axis`. Every polygon faces away (`(P - eye) . n > 0` for each of its points P and its
//! normal n) when the angle between `w` and `axis` plus `alpha + beta` stays below 90
//! degrees, with [`CONE_SLACK`] radians to spare. Such a cluster is only *deferred*: on an
//! open mesh a back face can be seen, so the view renders it unless it proves it hidden
//! (`raster`).

use crate::kernel::family::Polygon;
use crate::par::prelude::*;
use glam::DVec3;

/// Polygons per cluster.
pub const CLUSTER: usize = 64;

/// Radians kept between the back-facing test's angle sum and 90 degrees.
pub const CONE_SLACK: f64 = 1e-6;

/// One cluster's polygons and bounds.
#[derive(Debug, Clone, Copy)]
pub struct Cluster {
    /// First polygon (index in its kind's arrays) and count.
    pub first: u32,
    pub len: u32,
    /// Bounding sphere of its vertices.
    pub centre: DVec3,
    pub radius: f64,
    /// Normal cone: unit axis and half-angle (radians; `PI` when the normals span too much,
    /// or a polygon has no normal, so it never counts as back-facing).
    pub axis: DVec3,
    pub alpha: f64,
}

/// The Morton order of points in a box, 21 bits an axis: the order [`order`] puts polygons in.
pub struct Morton {
    lo: DVec3,
    scale: DVec3,
}

impl Morton {
    /// The order in the box of `verts` (every polygon vertex of the scene).
    pub fn new(verts: &[DVec3]) -> Morton {
        let (lo, hi) = verts.par_iter().map(|&p| (p, p)).reduce(
            || (DVec3::INFINITY, DVec3::NEG_INFINITY),
            |a, b| (a.0.min(b.0), a.1.max(b.1)),
        );
        let scale = DVec3::splat(((1u64 << 21) - 1) as f64) / (hi - lo).max(DVec3::splat(1e-300));
        Morton { lo, scale }
    }

    /// The key of `c`: its coordinates in the box, quantised and interleaved.
    fn key(&self, c: DVec3) -> u64 {
        let q = ((c - self.lo) * self.scale)
            .clamp(DVec3::ZERO, DVec3::splat(((1u64 << 21) - 1) as f64));
        spread(q.x as u64) | (spread(q.y as u64) << 1) | (spread(q.z as u64) << 2)
    }
}

/// Puts the polygons `idx` (`N` vertex indices each, into `verts`) and their `ids` in spatial
/// order (the Morton order of their centroids), so that each run of [`CLUSTER`] polygons lies
/// together, whatever order the file gave them in. Parallel; deterministic.
pub fn order<const N: usize>(
    idx: &mut Vec<u32>,
    ids: &mut Vec<i32>,
    verts: &[DVec3],
    morton: &Morton,
) {
    let polys = idx.as_chunks::<N>().0;
    let mut keyed: Vec<(u64, u32)> = polys
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let c = p.iter().map(|&v| verts[v as usize]).sum::<DVec3>() / N as f64;
            (morton.key(c), i as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    let sorted: Vec<[u32; N]> = keyed.par_iter().map(|&(_, i)| polys[i as usize]).collect();
    *idx = sorted.into_flattened();
    *ids = keyed.par_iter().map(|&(_, i)| ids[i as usize]).collect();
}

/// The vertices renumbered in the order the polygons first use them, so that a view reads
/// them as it reads the polygons: [`Renumber::polygons`] over each family's vertex indices in
/// turn, then [`Renumber::vertices`]. Vertices no polygon uses are dropped.
pub struct Renumber {
    map: Vec<u32>,
    next: u32,
}

impl Renumber {
    const NONE: u32 = u32::MAX;

    /// Nothing renumbered yet, of `n` vertices.
    pub fn new(n: usize) -> Renumber {
        Renumber {
            map: vec![Self::NONE; n],
            next: 0,
        }
    }

    /// Vertex indices `idx` rewritten to the new numbers, a vertex first met here taking the
    /// next one.
    pub fn polygons(&mut self, idx: &mut [u32]) {
        for v in idx {
            let m = &mut self.map[*v as usize];
            if *m == Self::NONE {
                *m = self.next;
                self.next += 1;
            }
            *v = *m;
        }
    }

    /// `verts` in the new order.
    pub fn vertices(self, verts: &[DVec3]) -> Vec<DVec3> {
        let mut out = vec![DVec3::ZERO; self.next as usize];
        for (v, &m) in verts.iter().zip(&self.map) {
            if m != Self::NONE {
                out[m as usize] = *v;
            }
        }
        out
    }
}

/// The bits of `x` (21 of them) spread to every third bit.
fn spread(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | x << 32) & 0x1f00000000ffff;
    x = (x | x << 16) & 0x1f0000ff0000ff;
    x = (x | x << 8) & 0x100f00f00f00f00f;
    x = (x | x << 4) & 0x10c30c30c30c30c3;
    x = (x | x << 2) & 0x1249249249249249;
    x
}

/// The clusters of the polygons `idx` of family `P` (`N` vertex indices each, into `verts`),
/// `CLUSTER` consecutive ones each.
pub fn build<P: Polygon<N>, const N: usize>(verts: &[DVec3], idx: &[u32]) -> Vec<Cluster> {
    let [n0, n1, n2, n3] = P::NORMAL;
    (idx.as_chunks::<N>().0)
        .par_chunks(CLUSTER)
        .enumerate()
        .map(|(c, chunk)| {
            let pts = || {
                chunk
                    .iter()
                    .flat_map(|p| p.iter().map(|&v| verts[v as usize]))
            };
            let (lo, hi) = pts().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
                (l.min(p), h.max(p))
            });
            let centre = (lo + hi) * 0.5;
            let radius = pts().map(|p| (p - centre).length()).fold(0.0, f64::max) * (1.0 + 1e-9);
            let normals: Vec<Option<DVec3>> = chunk
                .iter()
                .map(|p| {
                    let v = p.map(|i| verts[i as usize]);
                    (v[n0] - v[n1]).cross(v[n2] - v[n3]).try_normalize()
                })
                .collect();
            let (axis, alpha) = match normals.iter().copied().collect::<Option<Vec<_>>>() {
                Some(ns) => match ns.iter().sum::<DVec3>().try_normalize() {
                    Some(axis) => {
                        let cos = ns.iter().map(|n| n.dot(axis)).fold(1.0, f64::min);
                        // (a margin for the rounding of the normals and of acos)
                        (axis, cos.clamp(-1.0, 1.0).acos() + 1e-9)
                    }
                    None => (DVec3::X, std::f64::consts::PI),
                },
                None => (DVec3::X, std::f64::consts::PI),
            };
            Cluster {
                first: (c * CLUSTER) as u32,
                len: chunk.len() as u32,
                centre,
                radius,
                axis,
                alpha,
            }
        })
        .collect()
}

impl Cluster {
    /// Whether every polygon of the cluster faces away from `eye` (see the module comment).
    pub fn faces_away(&self, eye: DVec3) -> bool {
        let w = self.centre - eye;
        let dist = w.length();
        if dist.is_nan()
            || dist <= self.radius * (1.0 + 1e-9)
            || self.alpha >= std::f64::consts::FRAC_PI_2
        {
            return false;
        }
        let beta = (self.radius / dist).asin();
        let sum = self.alpha + beta + CONE_SLACK;
        sum < std::f64::consts::FRAC_PI_2 && w.dot(self.axis) / dist > sum.sin()
    }

    /// A lower bound on the distance from `eye` to any of its points.
    pub fn nearest(&self, eye: DVec3) -> f64 {
        ((self.centre - eye).length() - self.radius) * (1.0 - 1e-12)
    }
}

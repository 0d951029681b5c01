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

/// Puts the polygons in spatial order (the Morton order of their centroids in the scene's
/// box, 21 bits an axis), so that each run of [`CLUSTER`] polygons lies together, whatever
/// order the file gave them in; then numbers the vertices in the order the polygons first use
/// them, so that a view reads them as it reads the polygons. Parallel; deterministic.
pub fn sort(
    verts: &mut Vec<DVec3>,
    tris: &mut Vec<[u32; 3]>,
    tri_ids: &mut Vec<i32>,
    quads: &mut Vec<[u32; 4]>,
    quad_ids: &mut Vec<i32>,
) {
    let (lo, hi) = verts.par_iter().map(|&p| (p, p)).reduce(
        || (DVec3::INFINITY, DVec3::NEG_INFINITY),
        |a, b| (a.0.min(b.0), a.1.max(b.1)),
    );
    let scale = DVec3::splat(((1u64 << 21) - 1) as f64) / (hi - lo).max(DVec3::splat(1e-300));
    let key = |c: DVec3| -> u64 {
        let q = ((c - lo) * scale).clamp(DVec3::ZERO, DVec3::splat(((1u64 << 21) - 1) as f64));
        spread(q.x as u64) | (spread(q.y as u64) << 1) | (spread(q.z as u64) << 2)
    };
    fn order<const N: usize>(
        polys: &mut Vec<[u32; N]>,
        ids: &mut Vec<i32>,
        verts: &[DVec3],
        key: &(dyn Fn(DVec3) -> u64 + Sync),
    ) {
        let mut keyed: Vec<(u64, u32)> = polys
            .par_iter()
            .enumerate()
            .map(|(i, p)| {
                let c = p.iter().map(|&v| verts[v as usize]).sum::<DVec3>() / N as f64;
                (key(c), i as u32)
            })
            .collect();
        keyed.par_sort_unstable();
        *polys = keyed.par_iter().map(|&(_, i)| polys[i as usize]).collect();
        *ids = keyed.par_iter().map(|&(_, i)| ids[i as usize]).collect();
    }
    order(tris, tri_ids, verts, &key);
    order(quads, quad_ids, verts, &key);
    // vertices in the order of first use
    const NONE: u32 = u32::MAX;
    let mut map = vec![NONE; verts.len()];
    let mut next = 0u32;
    let mut renumber = |v: &mut u32| {
        let m = &mut map[*v as usize];
        if *m == NONE {
            *m = next;
            next += 1;
        }
        *v = *m;
    };
    tris.iter_mut().flatten().for_each(&mut renumber);
    quads.iter_mut().flatten().for_each(&mut renumber);
    let mut out = vec![DVec3::ZERO; next as usize];
    for (v, &m) in verts.iter().zip(&map) {
        if m != NONE {
            out[m as usize] = *v;
        }
    }
    *verts = out;
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

/// The clusters of `polys` (vertex indices into `verts`), `CLUSTER` consecutive ones each.
pub fn build<const N: usize>(verts: &[DVec3], polys: &[[u32; N]]) -> Vec<Cluster> {
    polys
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
                    let raw = if N == 3 {
                        (v[1] - v[0]).cross(v[2] - v[0])
                    } else {
                        (v[2] - v[0]).cross(v[3] - v[1])
                    };
                    raw.try_normalize()
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

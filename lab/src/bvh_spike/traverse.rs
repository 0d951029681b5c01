//! A view through the world-space hierarchy, one 8x8 pixel tile at a time: 8 packets of 8 rays
//! (one packet a row), the tile's rays sharing the eye as origin.
//!
//! Node tests:
//! - [`Variant::Packets`]: each node carries the set of packets that reached it; every such
//!   packet is slab-tested (Kay-Kajiya) against the node's box, each lane limited by its
//!   nearest hit so far; the node goes on with the packets that have a lane inside.
//! - [`Variant::Frustum`]: inner nodes are tested once for the whole tile: against the four
//!   planes through the eye and the tile's outer rays, and by distance (a box farther from the
//!   eye than every lane's nearest hit is skipped; with unit directions `t` is the distance).
//!   Leaves get the packets' slab test, which picks the rows a leaf can touch.
//!
//! Both skip a tile whose frustum misses the root's box before making its rays, and visit
//! children nearest first: by the split axis and the sign of the tile's centre
//! direction on it (the left child holds the lower centroids).
//!
//! Conservativeness: the slab test's far distance is scaled by `1 + 2 gamma_3` (Ize 2013;
//! pbrt-v4's `Bounds3::IntersectP`): `lo - o`, its product with `1/d`, and `1/d` itself each
//! round once. The frustum's planes pass through rays 0.01 pixel outside the tile's outer
//! pixel centres (computed in f64), far more than the f32 plane test's rounding (about 1e-7 of
//! the box's distance, against 0.01 pixel = 4e-6 of it at 1080p and 40 degrees). The distance
//! test keeps a relative slack of 1e-5. A direction component of exactly 0 gives an infinite
//! `1/d`, and a NaN where a box face contains the eye (not guarded: a spike).

use super::build::{Bvh, Node};
use super::triangle::EdgeSetup;
use glam::{DVec3, Vec3};
use lanecast::experimental::camera::RayTables;
use lanecast::{Camera, Frame};
use rayon::prelude::*;
use wide::f32x8;

/// Tile side in pixels: 8 rows of one 8-lane packet.
pub const TILE: usize = 8;

/// The node test used above the leaves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    /// Every packet that reached a node is slab-tested at it.
    Packets,
    /// One tile frustum and distance test per inner node; packet slab tests at leaves.
    Frustum,
}

impl Variant {
    pub fn name(self) -> &'static str {
        match self {
            Variant::Packets => "packets",
            Variant::Frustum => "frustum",
        }
    }
}

/// What a view did, summed over its tiles.
#[derive(Debug, Clone, Copy, Default)]
pub struct Counts {
    /// Tiles traced.
    pub tiles: u64,
    /// Node visits (box tests of the tile or its packets).
    pub nodes: u64,
    /// Leaves whose triangles were set up.
    pub leaves: u64,
    /// Triangle setups (one per triangle and tile).
    pub setups: u64,
    /// 8-ray triangle tests.
    pub tests: u64,
}

impl Counts {
    fn add(mut self, o: Counts) -> Counts {
        self.tiles += o.tiles;
        self.nodes += o.nodes;
        self.leaves += o.leaves;
        self.setups += o.setups;
        self.tests += o.tests;
        self
    }
}

/// 1 + 2 gamma_3, gamma_n = n u / (1 - n u), u = 2^-24.
const SLAB_SCALE: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON / 2.0) / (1.0 - 3.0 * f32::EPSILON / 2.0);

/// One tile's rays and their nearest hits.
struct Tile {
    o: Vec3,
    d: [[f32x8; 3]; TILE],
    inv: [[f32x8; 3]; TILE],
    t: [f32x8; TILE],
    id: [[i32; 8]; TILE],
    /// Inward normals of the frustum's four planes through `o`.
    planes: [Vec3; 4],
    /// Sign of the centre direction per axis: nearer child first.
    neg: [bool; 3],
    counts: Counts,
}

impl Tile {
    /// The tile at (`x0`, `y0`): its frustum; its rays wait for [`Tile::rays`].
    fn new(cam: &Camera, o: Vec3, x0: usize, y0: usize) -> Tile {
        // the frustum, in f64, 0.01 pixel outside the outer pixel centres
        let (w, h) = (cam.width as usize, cam.height as usize);
        let (x1, y1) = ((x0 + TILE - 1).min(w - 1), (y0 + TILE - 1).min(h - 1));
        let (mx, my) = (
            0.01 * 2.0 * cam.half_w / w as f64,
            0.01 * 2.0 * cam.half_h / h as f64,
        );
        let (l, r) = (cam.sx::<f64>(x0 as u32) - mx, cam.sx::<f64>(x1 as u32) + mx);
        let (t, b) = (cam.sy::<f64>(y0 as u32) + my, cam.sy::<f64>(y1 as u32) - my);
        let ray = |sx: f64, sy: f64| cam.f + sx * cam.r + sy * cam.u;
        let centre = ray((l + r) / 2.0, (t + b) / 2.0);
        let corners = [ray(l, t), ray(r, t), ray(r, b), ray(l, b)];
        let planes = std::array::from_fn(|i| {
            let n: DVec3 = corners[i].cross(corners[(i + 1) % 4]);
            let n = if n.dot(centre) < 0.0 { -n } else { n };
            n.normalize().as_vec3()
        });
        Tile {
            o,
            d: [[f32x8::ZERO; 3]; TILE],
            inv: [[f32x8::ZERO; 3]; TILE],
            t: [f32x8::splat(f32::INFINITY); TILE],
            id: [[-1; 8]; TILE],
            planes,
            neg: [centre.x < 0.0, centre.y < 0.0, centre.z < 0.0],
            counts: Counts {
                tiles: 1,
                ..Counts::default()
            },
        }
    }

    /// The tile's 64 rays from the library's f32 ray tables, and their reciprocals (a component
    /// under 1e-30 taken as +-1e-30).
    fn rays(&mut self, tables: &RayTables<f32>, x0: usize, y0: usize) {
        let sx = f32x8::from(<[f32; 8]>::try_from(&tables.sx[x0..x0 + 8]).unwrap());
        self.d = std::array::from_fn(|k| tables.dir_x8(sx, f32x8::splat(tables.sy[y0 + k])));
        self.inv = self.d.map(|d| {
            d.map(|c| {
                let tiny = f32x8::splat(1e-30);
                let c = c
                    .abs()
                    .simd_lt(tiny)
                    .select(c.is_sign_negative().select(-tiny, tiny), c);
                f32x8::ONE / c
            })
        });
    }

    /// The packets of `mask` with a lane inside `node`'s box before its nearest hit.
    #[inline(always)]
    fn slab(&self, node: &Node, mask: u8) -> u8 {
        let lo = Vec3::from(node.lo) - self.o;
        let hi = Vec3::from(node.hi) - self.o;
        let mut out = 0u8;
        let mut m = mask;
        while m != 0 {
            let p = m.trailing_zeros() as usize;
            m &= m - 1;
            let inv = &self.inv[p];
            let axis = |a: usize| {
                let t0 = f32x8::splat(lo[a]) * inv[a];
                let t1 = f32x8::splat(hi[a]) * inv[a];
                (t0.fast_min(t1), t0.fast_max(t1))
            };
            let (nx, fx) = axis(0);
            let (ny, fy) = axis(1);
            let (nz, fz) = axis(2);
            let near = nx.fast_max(ny).fast_max(nz.fast_max(f32x8::ZERO));
            let far = (fx.fast_min(fy).fast_min(fz) * f32x8::splat(SLAB_SCALE)).fast_min(self.t[p]);
            if near.simd_le(far).to_bitmask() != 0 {
                out |= 1 << p;
            }
        }
        out
    }

    /// Whether `node`'s box may hold a hit of the tile: inside the frustum, and nearer than
    /// the farthest lane's nearest hit.
    #[inline(always)]
    fn frustum(&self, node: &Node, far: f32) -> bool {
        let lo = Vec3::from(node.lo) - self.o;
        let hi = Vec3::from(node.hi) - self.o;
        for n in &self.planes {
            let p = Vec3::select(n.cmpgt(Vec3::ZERO), hi, lo);
            if n.dot(p) < 0.0 {
                return false;
            }
        }
        let gap = (lo.max(-hi)).max(Vec3::ZERO);
        gap.length_squared() <= far * far * (1.0 + 1e-5)
    }

    /// Every triangle of a leaf against the packets of `mask`; nearest hit kept, ties to the
    /// lower id.
    #[inline(always)]
    fn leaf(&mut self, bvh: &Bvh, node: &Node, mask: u8) {
        self.counts.leaves += 1;
        for tri in &bvh.tris[node.first as usize..][..node.count as usize] {
            let s = EdgeSetup::new(tri, self.o);
            self.counts.setups += 1;
            let mut m = mask;
            while m != 0 {
                let p = m.trailing_zeros() as usize;
                m &= m - 1;
                self.counts.tests += 1;
                let t = s.hit_x8(&self.d[p]);
                let closer = t.simd_lt(self.t[p]).to_bitmask();
                let same = t.simd_eq(self.t[p]).to_bitmask();
                if closer | same == 0 {
                    continue;
                }
                let (ta, mut tb) = (t.to_array(), self.t[p].to_array());
                for l in 0..8 {
                    let c = closer >> l & 1 == 1;
                    if c || (same >> l & 1 == 1 && s.id < self.id[p][l]) {
                        tb[l] = ta[l];
                        self.id[p][l] = s.id;
                    }
                }
                self.t[p] = f32x8::from(tb);
            }
        }
    }

    /// The farthest lane's nearest hit (+inf while a lane has none).
    fn far(&self) -> f32 {
        let m = self.t.iter().fold(f32x8::ZERO, |a, &b| a.max(b));
        m.to_array().into_iter().fold(0.0, f32::max)
    }

    /// Children of inner `node`, nearer first.
    #[inline(always)]
    fn order(&self, node: &Node) -> (u32, u32) {
        let (l, r) = (node.first, node.first + 1);
        if self.neg[node.axis as usize] {
            (r, l)
        } else {
            (l, r)
        }
    }

    fn trace(&mut self, bvh: &Bvh, variant: Variant, stack: &mut Vec<(u32, u8)>) {
        stack.clear();
        stack.push((0, 0xff));
        let mut far = f32::INFINITY;
        while let Some((i, mask)) = stack.pop() {
            let node = &bvh.nodes[i as usize];
            self.counts.nodes += 1;
            let mask = match variant {
                Variant::Packets => self.slab(node, mask),
                Variant::Frustum => {
                    if !self.frustum(node, far) {
                        continue;
                    }
                    if node.count > 0 {
                        self.slab(node, 0xff)
                    } else {
                        0xff
                    }
                }
            };
            if mask == 0 {
                continue;
            }
            if node.count > 0 {
                self.leaf(bvh, node, mask);
                if variant == Variant::Frustum {
                    far = self.far();
                }
            } else {
                let (near, farther) = self.order(node);
                stack.push((farther, mask));
                stack.push((near, mask));
            }
        }
    }
}

/// The view from `camera` through `bvh`, on the current rayon pool: ids and depths (distance
/// along the unit ray) as lanecast's `Frame`, and what the traversal did.
pub fn render(bvh: &Bvh, camera: &Camera, variant: Variant) -> (Frame<f32>, Counts) {
    let w = camera.width as usize;
    let tables = camera.tables::<f32>(TILE as u32, TILE as u32);
    let o = camera.eye.as_vec3();
    let mut frame = Frame::new(camera.width, camera.height, f32::INFINITY);
    let band = TILE * w;
    let counts = frame
        .ids
        .par_chunks_mut(band)
        .zip(frame.depth.par_chunks_mut(band))
        .enumerate()
        .map(|(b, (ids, depth))| {
            let y0 = b * TILE;
            let rows = ids.len() / w;
            let mut stack = Vec::with_capacity(128);
            let mut counts = Counts::default();
            for x0 in (0..w).step_by(TILE) {
                let mut tile = Tile::new(camera, o, x0, y0);
                if !tile.frustum(&bvh.nodes[0], f32::INFINITY) {
                    counts.tiles += 1;
                    continue; // the frame's background already
                }
                tile.rays(&tables, x0, y0);
                tile.trace(bvh, variant, &mut stack);
                for k in 0..rows {
                    let n = TILE.min(w - x0);
                    let at = k * w + x0;
                    ids[at..at + n].copy_from_slice(&tile.id[k][..n]);
                    depth[at..at + n].copy_from_slice(&tile.t[k].to_array()[..n]);
                }
                counts = counts.add(tile.counts);
            }
            counts
        })
        .reduce(Counts::default, Counts::add);
    (frame, counts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use lanecast::CameraSpec;
    use lanecast::compare::compare_frame;
    use lanecast::scene::scene_from_arrays;

    struct Rng(u64);
    impl Rng {
        fn f(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Random scenes (a soup of triangles of sizes spanning three decades, some crossing each
    /// other, some sharing edges), random eyes around them and image sizes that are not
    /// multiples of the tile: both variants give the same bits, on 1 and 3 threads, and ids
    /// the f64 oracle's except ties and the edge band.
    #[test]
    fn variants_and_thread_counts_agree_and_hold_to_the_oracle() {
        let mut r = Rng(0x51ab_1e5e_ed00_0001);
        let pools = [1, 3].map(|n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
        });
        for case in 0..12 {
            let mut vertices = Vec::new();
            let mut faces = Vec::new();
            for _ in 0..(50 + (r.f() * 400.0) as usize) {
                let size = 10f64.powf(r.f() * 3.0 - 2.0);
                let c = [r.f(), r.f(), r.f()].map(|x| x * 4.0 - 2.0);
                let b = vertices.len() as i64;
                for _ in 0..3 {
                    vertices.push([0, 1, 2].map(|a| c[a] + (r.f() - 0.5) * size));
                }
                faces.push([b, b + 1, b + 2]);
                if r.f() < 0.3 {
                    // a neighbour across edge (b, b + 1)
                    vertices.push([0, 1, 2].map(|a| c[a] + (r.f() - 0.5) * size));
                    faces.push([b + 1, b, b + 3]);
                }
            }
            let path = std::path::Path::new("random");
            let scene = scene_from_arrays(path, None, &vertices, &faces, &[], &[]).unwrap();
            let bvh = Bvh::build(&scene).unwrap();
            let dist = 3.0 + r.f() * 20.0;
            let (th, ph) = (r.f() * std::f64::consts::TAU, r.f() * 2.0 - 1.0);
            let eye = DVec3::new(th.cos() * ph.acos().sin(), ph, th.sin() * ph.acos().sin()) * dist;
            let spec = CameraSpec {
                eye,
                look: DVec3::new(r.f() - 0.5, r.f() - 0.5, r.f() - 0.5),
                up: DVec3::Y,
                lens: Some(lanecast::scene::Lens::Fov(20.0 + r.f() * 70.0)),
            };
            let (w, h) = (40 + (r.f() * 60.0) as u32, 30 + (r.f() * 50.0) as u32);
            let camera = Camera::look_at(&spec, w, h).unwrap();
            let first = pools[0].install(|| render(&bvh, &camera, Variant::Packets).0);
            for pool in &pools {
                for v in [Variant::Packets, Variant::Frustum] {
                    let frame = pool.install(|| render(&bvh, &camera, v).0);
                    assert_eq!(frame.ids, first.ids, "case {case} {}", v.name());
                    let bits =
                        |f: &Frame<f32>| f.depth.iter().map(|d| d.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&frame), bits(&first), "case {case} {}", v.name());
                }
            }
            let (report, _) = compare_frame(&scene, &camera, &first);
            assert_eq!(report.unexcused, 0, "case {case}: {report:?}");
            assert!(
                first.ids.iter().any(|&i| i >= 0),
                "case {case}: nothing in view"
            );
        }
    }
}

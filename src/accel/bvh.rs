//! The flattened BVH and its packet traversal.
//!
//! Nodes are 32 bytes, depth first: an inner node's left child follows it, its right child is at
//! `index`; a leaf's `index` names its ranges in the reordered SoA stores. Boxes are f32, rounded
//! outward from the f64 boxes of `build.rs` (each holding a point of every ray its primitive's
//! kernels may accept, no farther than their hit, with a margin), eye-relative (the eye is the
//! origin of every ray, so the slab test needs no origin terms).
//!
//! Traversal (one 8-ray packet): slab test of all lanes against a node's box (Kay and Kajiya
//! 1986, with the origin at 0: `t = bound * (1/d)`); the node is entered when any lane enters the
//! box no later than its nearest hit so far (`<=`, so an exactly tied primitive with a lower id
//! is still found). Children are visited near first along the split axis, by the sign of lane
//! 0's direction. Direction components below 1e-30 in magnitude are replaced by +-1e-30 before
//! inverting, so `0 * inf` (NaN) never occurs; the boxes' margin covers that change.
//!
//! One traversal loop (`walk`) serves three forms: 8 f32 rays (the packet kernel), 4 f64 rays
//! (the f64x4 method) and one ray in f32 or f64 (the scalar kernels, the oracle among them).

use super::build::{self, Built};
use crate::camera::Camera;
use crate::kernel::lanes::Lanes;
use crate::kernel::wide64::Hit4d;
use crate::kernel::{Family, Hit, Hit8, HitLanes};
use crate::real::{Real, V3, f32_down, f32_up};
use crate::scene::Scene;
use crate::soa::trace::{family_x8, ranges_x1, ranges_x4d};
use crate::soa::{Packed, Prepared, Records, for_each_family};
use wide::{f32x8, f64x4};

/// One node: box, child or leaf index, and kind (bit 31: leaf; bits 0-1: split axis).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub struct Node {
    pub min: [f32; 3],
    pub index: u32,
    pub max: [f32; 3],
    pub meta: u32,
}

pub(crate) const LEAF: u32 = 1 << 31;

/// A BVH over one scene's primitives, seen from one eye.
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    pub nodes: Vec<Node>,
    /// Per leaf: [start, end) in the spheres, triangles and quads stores.
    pub leaves: Vec<[(u32, u32); 3]>,
}

impl Bvh {
    /// Builds the BVH over `prepared` (the primitives of `scene` seen by `camera`, whose eye
    /// the boxes are relative to and whose pixels' rays they are sized for) and returns it with
    /// the primitives reordered leaf by leaf, as the traversal expects them packed.
    pub fn new(prepared: &Prepared<f64>, scene: &Scene, camera: &Camera) -> (Bvh, Prepared<f64>) {
        let view = super::reach::View::new(camera);
        let built: Built = build::build(build::boxes(prepared, &scene.shapes, &view));
        let (reordered, leaves) = build::reorder(prepared, &built);
        let nodes = built
            .nodes
            .iter()
            .map(|n| Node {
                min: n.bounds.min.to_array().map(f32_down),
                max: n.bounds.max.to_array().map(f32_up),
                index: n.index,
                meta: if n.leaf { LEAF } else { n.axis as u32 },
            })
            .collect();
        (Bvh { nodes, leaves }, reordered)
    }

    /// Depth of the deepest leaf (root = 1).
    #[cfg(test)]
    fn depth(&self) -> usize {
        fn walk(n: &[Node], i: usize) -> usize {
            if n[i].meta & LEAF != 0 {
                1
            } else {
                1 + walk(n, i + 1).max(walk(n, n[i].index as usize))
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            walk(&self.nodes, 0)
        }
    }
}

/// Most nodes waiting on the traversal stack; the build's depth stays far below (checked).
const STACK: usize = 64;

/// The traversal every form shares: depth first, near child first by the signs `neg` of the
/// first ray's direction, a node entered when `enters(node, hit)`, `leaf(ranges, hit)` on each
/// leaf entered.
#[inline(always)]
fn walk<H>(
    bvh: &Bvh,
    neg: [bool; 3],
    hit: &mut H,
    enters: impl Fn(&Node, &H) -> bool,
    mut leaf: impl FnMut(&[(u32, u32); 3], &mut H),
) {
    if bvh.nodes.is_empty() {
        return;
    }
    let mut stack = [0u32; STACK];
    let mut sp = 0;
    let mut node = 0usize;
    loop {
        let n = &bvh.nodes[node];
        if enters(n, hit) {
            if n.meta & LEAF == 0 {
                let (left, right) = (node as u32 + 1, n.index);
                let (near, far) = if neg[(n.meta & 3) as usize] {
                    (right, left)
                } else {
                    (left, right)
                };
                stack[sp] = far;
                sp += 1;
                node = near as usize;
                continue;
            }
            leaf(&bvh.leaves[n.index as usize], hit);
        }
        if sp == 0 {
            return;
        }
        sp -= 1;
        node = stack[sp] as usize;
    }
}

/// `1 / d` lane by lane, components below 1e-30 in magnitude replaced by 1e-30 of their sign
/// (see the module comment).
#[inline(always)]
fn inverse<L: Lanes>(d: &[L; 3]) -> [L; 3] {
    let tiny = L::splat(L::Scalar::from_f64(1e-30));
    d.map(|c| {
        let signed = c.simd_lt(L::ZERO).select(L::ZERO - tiny, tiny);
        let safe = c.abs().simd_lt(tiny).select(signed, c);
        L::splat(L::Scalar::ONE) / safe
    })
}

/// Does any lane's ray enter the node's box at a distance no greater than its nearest hit
/// `best`? (The f32 bounds are exact in either lane type.)
#[inline(always)]
fn enters<L: Lanes>(n: &Node, inv: &[L; 3], best: L) -> bool {
    let b = |x: f32| L::splat(L::Scalar::from_f64(x as f64));
    let t0 = |a: usize| b(n.min[a]) * inv[a];
    let t1 = |a: usize| b(n.max[a]) * inv[a];
    let (x0, x1, y0, y1, z0, z1) = (t0(0), t1(0), t0(1), t1(1), t0(2), t1(2));
    let near = x0
        .fast_min(x1)
        .fast_max(y0.fast_min(y1))
        .fast_max(z0.fast_min(z1).fast_max(L::ZERO));
    let far = x0
        .fast_max(x1)
        .fast_min(y0.fast_max(y1))
        .fast_min(z0.fast_max(z1));
    (far.simd_ge(near) & best.simd_ge(near)).any()
}

/// Nearest hits of the rays `d` among the primitives of `p` (packed in `bvh`'s leaf order).
#[inline]
pub fn trace_bvh_x8(p: &Packed, bvh: &Bvh, d: &[f32x8; 3], hit: &mut Hit8) {
    walk_lanes(bvh, d, hit, |leaf, h| {
        for_each_family!(F => {
            let (a, b) = leaf[F::KIND];
            family_x8::<F>(p, a as usize..b as usize, d, h)
        });
    });
}

/// [`walk`] for a packet of rays `d` in lanes `L`: the slab test of every lane, children ordered
/// by the first lane's direction.
#[inline(always)]
fn walk_lanes<L: Lanes>(
    bvh: &Bvh,
    d: &[L; 3],
    hit: &mut HitLanes<L>,
    leaf: impl FnMut(&[(u32, u32); 3], &mut HitLanes<L>),
) {
    let inv = inverse(d);
    let neg = d.map(|c| c.first() < L::Scalar::ZERO);
    walk(bvh, neg, hit, |n, h| enters(n, &inv, h.t), leaf);
}

/// Nearest hits of four f64 rays `d` among the primitives of `p` (in `bvh`'s leaf order), with
/// the default kernels in f64x4 lanes (`kernel::wide64`, each lane the oracle's
/// `polygon_x1::<f64>` / `sphere_x1::<f64>` bit for bit). The boxes are sized for the f64
/// kernels' rays and distances too (`build.rs`), and the slab test in f64 errs less than in
/// f32.
#[inline]
pub fn trace_bvh_x4d(p: &impl Records<f64>, bvh: &Bvh, d: &[f64x4; 3], hit: &mut Hit4d) {
    walk_lanes(bvh, d, hit, |leaf, h| {
        ranges_x4d(p, leaf.map(|(a, b)| a as usize..b as usize), d, h)
    });
}

/// Nearest hit of one ray `d` among the primitives of `p` (in `bvh`'s leaf order) with the
/// scalar kernels in precision `T`: the oracle in f64, `scalar-f32` in f32. The slab test runs
/// in f64 for both (an f32 direction and f32 distances are exact in f64), which errs less than
/// the f32 slab test the boxes' margin covers; the f32 scalar kernel is the packet kernel's
/// formula in one lane, and the boxes are sized for the f64 kernels too (`build.rs`). Proven
/// against `--accel none`, bit for bit, by tests/accel.rs and tests/accel_random.rs.
#[inline]
pub fn trace_bvh_x1<T: Real>(p: &impl Records<T>, bvh: &Bvh, d: V3<T>) -> Hit<T> {
    let d64 = d.map(|c| c.to_f64());
    let inv = d64.map(|c| {
        1.0 / if c.abs() < 1e-30 {
            1e-30f64.copysign(c)
        } else {
            c
        }
    });
    let neg = d64.map(|c| c < 0.0);
    let mut hit = Hit::NONE;
    let enters_x1 = |n: &Node, h: &Hit<T>| {
        let slab = |a: usize| {
            let (t0, t1) = (n.min[a] as f64 * inv[a], n.max[a] as f64 * inv[a]);
            (t0.min(t1), t0.max(t1))
        };
        let ((x0, x1), (y0, y1), (z0, z1)) = (slab(0), slab(1), slab(2));
        let near = x0.max(y0).max(z0).max(0.0);
        let far = x1.min(y1).min(z1);
        near <= far && near <= h.t.to_f64()
    };
    walk(bvh, neg, &mut hit, enters_x1, |leaf, h| {
        ranges_x1(p, leaf.map(|(a, b)| a as usize..b as usize), d, h)
    });
    hit
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{CameraSpec, Shape};
    use glam::DVec3;

    /// The traversal stack holds at most one node per level: the build's depth must stay
    /// below `STACK`, here on 20,000 tiny triangles packed along a line (a skewed tree).
    #[test]
    fn depth_stays_below_the_traversal_stack() {
        let shapes: Vec<Shape> = (0..20_000)
            .map(|i| {
                let x = (i as f64).powf(1.5) * 1e-3;
                let v = DVec3::new(x, 0.0, -5.0);
                Shape::Triangle([v, v + DVec3::X * 1e-3, v + DVec3::Y * 1e-3])
            })
            .collect();
        let scene = Scene {
            camera_at: None,
            source: "line.sc".into(),
            camera: CameraSpec {
                eye: DVec3::ZERO,
                look: DVec3::NEG_Z,
                up: DVec3::Y,
                lens: None,
            },
            shapes: shapes.into(),
            warnings: Vec::new(),
        };
        let prepared = Prepared::new(&scene, DVec3::ZERO);
        let camera = Camera::new(&scene.camera, 60.0, 64, 48);
        let (bvh, _) = Bvh::new(&prepared, &scene, &camera);
        let depth = bvh.depth();
        assert!(depth > 10 && depth < STACK, "depth {depth}");
    }
}

//! The flattened BVH and its packet traversal.
//!
//! Nodes are 32 bytes, depth first: an inner node's left child follows it, its right child is at
//! `index`; a leaf's `index` names its ranges in the reordered SoA stores. Boxes are f32, rounded
//! outward from the padded f64 boxes of `build.rs`, eye-relative (the eye is the origin of
//! every ray, so the slab test needs no origin terms).
//!
//! Traversal (one 8-ray packet): slab test of all lanes against a node's box (Kay and Kajiya
//! 1986, with the origin at 0: `t = bound * (1/d)`); the node is entered when any lane enters the
//! box no later than its nearest hit so far (`<=`, so an exactly tied primitive with a lower id
//! is still found). Children are visited near first along the split axis, by the sign of lane
//! 0's direction. Direction components below 1e-30 in magnitude are replaced by +-1e-30 before
//! inverting, so `0 * inf` (NaN) never occurs; the boxes' padding covers that change.

use super::build::{self, Built};
use crate::kernel::Hit8;
use crate::kernel::packet::{polygons_x8, spheres_x8};
use crate::scene::Scene;
use crate::soa::{Packed, Prepared};
use glam::DVec3;
use wide::f32x8;

/// One node: box, child or leaf index, and kind (bit 31: leaf; bits 0-1: split axis).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub struct Node {
    pub min: [f32; 3],
    pub index: u32,
    pub max: [f32; 3],
    pub meta: u32,
}

const LEAF: u32 = 1 << 31;

/// Rounds toward -inf / +inf, so an f32 box contains its f64 box.
fn down(x: f64) -> f32 {
    let f = x as f32;
    if f as f64 > x { f.next_down() } else { f }
}

fn up(x: f64) -> f32 {
    let f = x as f32;
    if (f as f64) < x { f.next_up() } else { f }
}

/// A BVH over one scene's primitives, seen from one eye.
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    pub nodes: Vec<Node>,
    /// Per leaf: [start, end) in the spheres, triangles and quads stores.
    pub leaves: Vec<[(u32, u32); 3]>,
}

impl Bvh {
    /// Builds the BVH over `prepared` (the primitives of `scene` seen from `eye`) and returns it
    /// with the primitives reordered leaf by leaf, as the traversal expects them packed.
    pub fn new(prepared: &Prepared<f64>, scene: &Scene, eye: DVec3) -> (Bvh, Prepared<f64>) {
        let built: Built = build::build(build::boxes(prepared, &scene.shapes, eye));
        let (reordered, leaves) = build::reorder(prepared, &built);
        let nodes = built
            .nodes
            .iter()
            .map(|n| Node {
                min: n.bounds.min.to_array().map(down),
                max: n.bounds.max.to_array().map(up),
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

/// Nearest hits of the rays `d` among the primitives of `p` (packed in `bvh`'s leaf order).
#[inline]
pub fn trace_bvh_x8(p: &Packed, bvh: &Bvh, d: &[f32x8; 3], hit: &mut Hit8) {
    if bvh.nodes.is_empty() {
        return;
    }
    let tiny = f32x8::splat(1e-30);
    let inv = d.map(|c| {
        let safe = c.abs().simd_lt(tiny).select(tiny.copysign(c), c);
        f32x8::ONE / safe
    });
    let neg = d.map(|c| c.to_array()[0] < 0.0);
    let mut stack = [0u32; STACK];
    let mut sp = 0;
    let mut node = 0usize;
    loop {
        let n = &bvh.nodes[node];
        if enters(n, &inv, hit.t) {
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
            let [s, t, q] = bvh.leaves[n.index as usize];
            spheres_x8(&p.spheres, s.0 as usize..s.1 as usize, d, hit);
            polygons_x8(&p.triangles, t.0 as usize..t.1 as usize, d, hit);
            polygons_x8(&p.quads, q.0 as usize..q.1 as usize, d, hit);
        }
        if sp == 0 {
            return;
        }
        sp -= 1;
        node = stack[sp] as usize;
    }
}

/// Does any lane's ray enter the node's box at a distance no greater than its nearest hit?
#[inline(always)]
fn enters(n: &Node, inv: &[f32x8; 3], best: f32x8) -> bool {
    let t0 = |a: usize| f32x8::splat(n.min[a]) * inv[a];
    let t1 = |a: usize| f32x8::splat(n.max[a]) * inv[a];
    let (x0, x1, y0, y1, z0, z1) = (t0(0), t1(0), t0(1), t1(1), t0(2), t1(2));
    let near = x0
        .fast_min(x1)
        .fast_max(y0.fast_min(y1))
        .fast_max(z0.fast_min(z1).fast_max(f32x8::ZERO));
    let far = x0
        .fast_max(x1)
        .fast_min(y0.fast_max(y1))
        .fast_min(z0.fast_max(z1));
    (near.simd_le(far) & near.simd_le(best)).any()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{CameraSpec, Shape};

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
            source: "line.sc".into(),
            camera: CameraSpec {
                eye: DVec3::ZERO,
                look: DVec3::NEG_Z,
                up: DVec3::Y,
                fov_deg: None,
            },
            lines: vec![1; shapes.len()],
            shapes,
            warnings: Vec::new(),
        };
        let prepared = Prepared::new(&scene, DVec3::ZERO);
        let (bvh, _) = Bvh::new(&prepared, &scene, DVec3::ZERO);
        let depth = bvh.depth();
        assert!(depth > 10 && depth < STACK, "depth {depth}");
    }
}

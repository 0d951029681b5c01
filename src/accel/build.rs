//! BVH construction: binned surface area heuristic (Wald, "On fast Construction of SAH-based
//! Bounding Volume Hierarchies", 2007) over primitive boxes relative to the eye, in f64.
//!
//! Boxes are conservative for what the leaf kernels can hit, seen by one camera: each
//! primitive's box holds, for every ray of the camera's pixels that a kernel (f32 or f64) may
//! accept on it, a point of that ray no farther than any distance the kernel returns there,
//! with a margin of 4u of that distance in every axis ([`Reach`]: [`reach_box`] for a convex
//! polygon, `reach::ball_cap` for a ball).
//! The traversal's slab test, which errs by 2u of a distance, then enters every box on the
//! way to the primitive no later than the primitive's hit, and the BVH finds what `--accel
//! none` finds, bit for bit. The primitive's own box (padded by [`PAD_REL`]) is kept in the
//! union for the SAH: alone it is not conservative, since a kernel accepts rays up to `E`
//! (`accel::reach`) outside a polygon's edges, over a strip across the image for a sliver seen
//! nearly edge-on. Rounded outward to f32 in `bvh.rs`.

use super::reach::{View, ball_cap};
use crate::kernel::Family;
use crate::kernel::family::Ball;
use crate::kernel::polygon::PolyK;
use crate::par::prelude::*;
use crate::real::Real;
use crate::soa::{Prepared, Stored, for_each_family, with_family};
use glam::DVec3;

/// Padding of a primitive's own box, relative to the largest eye-relative coordinate magnitude
/// of the box (about 33u): it keeps the box of a flat primitive from being flat. Correctness
/// rests on the reach boxes, not on it.
pub const PAD_REL: f64 = 2e-6;
/// Most primitives in a leaf.
pub const MAX_LEAF: usize = 4;
/// SAH bins per axis.
const BINS: usize = 12;

/// An axis-aligned box in f64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::INFINITY,
        max: DVec3::NEG_INFINITY,
    };

    pub fn grow_point(self, p: DVec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    pub fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    pub fn centre(self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// Half the surface area (the SAH only compares areas).
    pub fn half_area(self) -> f64 {
        let e = (self.max - self.min).max(DVec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// The box padded by `PAD_REL` of its largest coordinate magnitude.
    pub fn padded(self) -> Aabb {
        let m = self.min.abs().max(self.max.abs()).max_element();
        let pad = DVec3::splat(m * PAD_REL);
        Aabb {
            min: self.min - pad,
            max: self.max + pad,
        }
    }
}

/// What the build produces: nodes in depth-first order (node 0 is the root), and for each leaf
/// the primitives it holds, as (kind, index in that kind's group; `Family::KIND`).
#[derive(Debug, Clone)]
pub struct Built {
    pub nodes: Vec<BuildNode>,
    pub leaves: Vec<Vec<(u8, u32)>>,
}

#[derive(Debug, Clone, Copy)]
pub struct BuildNode {
    pub bounds: Aabb,
    /// Inner node: index of the right child (the left child follows the node). Leaf: leaf index.
    pub index: u32,
    pub leaf: bool,
    /// Split axis of an inner node (for front-to-back order).
    pub axis: u8,
}

struct Item {
    bounds: Aabb,
    centre: DVec3,
    tag: (u8, u32),
}

/// Eye-relative boxes of every prepared primitive seen by `view`, tagged (kind, index): each
/// the primitive's own box (`Shape::bounds`) padded ([`Aabb::padded`]), grown to hold its
/// reach ([`Reach`]).
pub fn boxes(
    p: &Prepared<f64>,
    shapes: &crate::scene::Shapes,
    view: &View,
) -> Vec<(Aabb, (u8, u32))> {
    let mut out = Vec::new();
    for_each_family!(F => out.par_extend(kind_boxes::<F>(p, shapes, view)));
    out
}

/// [`boxes`] of the primitives of family `F`.
fn kind_boxes<'a, F: Stored>(
    p: &'a Prepared<f64>,
    shapes: &'a crate::scene::Shapes,
    view: &'a View,
) -> impl IntoParallelIterator<Item = (Aabb, (u8, u32))> + 'a
where
    F::Outline: Reach,
{
    let g = F::group(p);
    g.k.par_iter()
        .zip(&g.id)
        .enumerate()
        .map(move |(i, (k, &id))| {
            let (min, max) = shapes.get(id as usize).bounds(view.eye);
            let own = Aabb { min, max }.padded();
            let outline = F::outline(&F::cast::<f32>(k));
            (outline.reach(own, view), (F::KIND as u8, i as u32))
        })
}

/// What the BVH bounds a primitive by, per outline class (`Family::Outline`: a [`Ball`] or a
/// convex polygon's f32 constants), so that [`boxes`] is written once for every family.
pub(crate) trait Reach: Copy {
    /// `own` (the primitive's own box, padded) grown to hold, for every ray a kernel may accept
    /// on the primitive seen by `view`, a point no farther than any distance it returns there,
    /// with a margin for the slab test's rounding.
    fn reach(&self, own: Aabb, view: &View) -> Aabb;
}

impl Reach for Ball {
    /// `own` grown by the ball's cap (`reach::ball_cap`).
    #[inline]
    fn reach(&self, own: Aabb, _: &View) -> Aabb {
        let (min, max) = ball_cap(self.oc, self.r2, self.c);
        own.union(Aabb { min, max })
    }
}

impl<const N: usize> Reach for PolyK<f32, N> {
    /// [`reach_box`].
    #[inline]
    fn reach(&self, own: Aabb, view: &View) -> Aabb {
        reach_box(own, self, view)
    }
}

/// `own` (the polygon's own box) grown to hold, for every ray a kernel may accept on the
/// polygon of f32 constants `k`, a point at a distance no greater than any it returns there,
/// with a margin for the slab test's rounding: by `View::polygon_slice` or `View::polygon_cut`,
/// whichever grows it less (nothing when no pixel's ray reaches the polygon). With every
/// ancestor's box holding it, the traversal enters each node on the way to the primitive no
/// later than the primitive's hit: the BVH finds every hit `none` finds. The polygon's own box
/// is not enough: the rays a kernel accepts on a sliver seen nearly edge-on form a strip
/// across the image (`accel::reach`).
pub(crate) fn reach_box<const N: usize>(own: Aabb, k: &PolyK<f32, N>, view: &View) -> Aabb {
    let region = view.polygon_region(&k.n, k.nrm);
    let near = view.polygon_near(&region, k.nrm, k.p);
    let grown = |b: Option<(DVec3, DVec3)>| b.map(|(min, max)| own.union(Aabb { min, max }));
    let slice = grown(view.polygon_slice(&region, near));
    let cut = grown(view.polygon_cut(&region, k.nrm, k.p));
    match (slice, cut) {
        // either holds what the traversal needs: the smaller serves the SAH better
        (Some(s), Some(c)) if c.half_area() < s.half_area() => c,
        (Some(b), _) | (None, Some(b)) => b,
        (None, None) => own,
    }
}

/// Builds the hierarchy over `boxes`.
pub fn build(boxes: Vec<(Aabb, (u8, u32))>) -> Built {
    let mut items: Vec<Item> = boxes
        .into_iter()
        .map(|(b, tag)| Item {
            bounds: b,
            centre: b.centre(),
            tag,
        })
        .collect();
    let mut built = Built {
        nodes: Vec::new(),
        leaves: Vec::new(),
    };
    if !items.is_empty() {
        let n = items.len();
        split(&mut items[..n], &mut built);
    }
    built
}

/// Appends the subtree over `items` (depth first) and returns its node index.
fn split(items: &mut [Item], out: &mut Built) -> usize {
    let bounds = items.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
    let me = out.nodes.len();
    out.nodes.push(BuildNode {
        bounds,
        index: 0,
        leaf: true,
        axis: 0,
    });
    let make_leaf = |items: &mut [Item], out: &mut Built| {
        out.nodes[me].index = out.leaves.len() as u32;
        out.leaves.push(items.iter().map(|it| it.tag).collect());
    };
    if items.len() <= MAX_LEAF {
        make_leaf(items, out);
        return me;
    }
    match best_split(items) {
        Some((axis, mid)) => {
            out.nodes[me].leaf = false;
            out.nodes[me].axis = axis as u8;
            let (l, r) = items.split_at_mut(mid);
            split(l, out);
            let right = split(r, out);
            out.nodes[me].index = right as u32;
        }
        None => make_leaf(items, out),
    }
    me
}

/// Binned SAH: the best (axis, count on the left) after partitioning `items` in place, or `None`
/// when no split beats a leaf (and the leaf is small enough) or all centres coincide.
fn best_split(items: &mut [Item]) -> Option<(usize, usize)> {
    let cb = items
        .iter()
        .fold(Aabb::EMPTY, |b, it| b.grow_point(it.centre));
    let extent = cb.max - cb.min;
    let mut best: Option<(f64, usize, f64)> = None; // (cost, axis, split coordinate)
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let bin_of =
            |c: f64| (((c - cb.min[axis]) / extent[axis] * BINS as f64) as usize).min(BINS - 1);
        let mut bins = [(Aabb::EMPTY, 0usize); BINS];
        for it in items.iter() {
            let b = &mut bins[bin_of(it.centre[axis])];
            b.0 = b.0.union(it.bounds);
            b.1 += 1;
        }
        let mut right = [(0.0, 0usize); BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for i in (1..BINS).rev() {
            acc = acc.union(bins[i].0);
            cnt += bins[i].1;
            right[i] = (acc.half_area(), cnt);
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for i in 0..BINS - 1 {
            acc = acc.union(bins[i].0);
            cnt += bins[i].1;
            let (ra, rc) = right[i + 1];
            if cnt == 0 || rc == 0 {
                continue;
            }
            let cost = acc.half_area() * cnt as f64 + ra * rc as f64;
            if best.is_none_or(|b| cost < b.0) {
                let at = cb.min[axis] + extent[axis] * (i + 1) as f64 / BINS as f64;
                best = Some((cost, axis, at));
            }
        }
    }
    let (cost, axis, at) = best?;
    let parent = items.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
    // Leaf cost: one box test saved, every primitive tested. Split when cheaper or too many.
    let leaf_cost = parent.half_area() * items.len() as f64;
    if cost >= leaf_cost && items.len() <= MAX_LEAF * 4 {
        return None;
    }
    let mut mid = 0;
    for i in 0..items.len() {
        if items[i].centre[axis] < at {
            items.swap(i, mid);
            mid += 1;
        }
    }
    (mid > 0 && mid < items.len()).then_some((axis, mid))
}

/// The groups of `p` reordered leaf by leaf, and for each leaf its range in each reordered group
/// (by kind: `Family::KIND`).
pub fn reorder<T: Real + Default>(
    p: &Prepared<T>,
    built: &Built,
) -> (Prepared<T>, Vec<[(u32, u32); 3]>) {
    let mut out = Prepared::default();
    let lens = |out: &Prepared<T>| {
        let mut n = [0u32; 3];
        for_each_family!(F => n[F::KIND] = F::group(out).len() as u32);
        n
    };
    let mut ranges = Vec::with_capacity(built.leaves.len());
    for leaf in &built.leaves {
        let start = lens(&out);
        for &(kind, i) in leaf {
            with_family!(kind, F => F::group_mut(&mut out).push_from(F::group(p), i as usize));
        }
        let end = lens(&out);
        ranges.push(std::array::from_fn(|k| (start[k], end[k])));
    }
    (out, ranges)
}

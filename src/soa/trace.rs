//! The brute-force loops over a store: every primitive of each type against one ray or one
//! packet, type by type, keeping the nearest hit by the kernels' rule ([`Hit::update`],
//! [`Hit8::update`]).
//!
//! - One ray at a time (`trace_x1`, `ranges_x1`): in f64 the oracle, in f32 the baseline the
//!   packet kernel's speedup is measured against. The records come from a store or are computed
//!   when asked ([`Records`]).
//! - Eight rays at a time (`trace_x8`, `spheres_x8`, `polygons_x8`): each primitive's constants
//!   broadcast to the eight lanes from the columns of [`Packed`].
//!
//! A type the scene lacks has an empty store and its loop runs zero times. The acceleration
//! structures call the same loops over the ranges their leaves and tiles list.

use super::{Packed, Polygons, Records, Spheres};
use crate::kernel::polygon::{PolyK, polygon_x1, polygon_x8};
use crate::kernel::sphere::{sphere_x1, sphere_x8};
use crate::kernel::{Hit, Hit8};
use crate::real::{Real, V3};
use std::ops::Range;
use wide::f32x8;

/// Nearest hits of the rays `d` (unit directions from the eye) among every primitive, folded
/// into `hit`: the brute-force driver (`--accel none`).
#[inline]
pub fn trace_x8(p: &Packed, d: &[f32x8; 3], hit: &mut Hit8) {
    spheres_x8(&p.spheres, 0..p.spheres.len(), d, hit);
    polygons_x8(&p.triangles, 0..p.triangles.len(), d, hit);
    polygons_x8(&p.quads, 0..p.quads.len(), d, hit);
}

/// The spheres `range` of the store against eight rays.
#[inline(always)]
pub fn spheres_x8(s: &Spheres, range: Range<usize>, d: &[f32x8; 3], hit: &mut Hit8) {
    for i in range {
        if let Some((mask, t)) = sphere_x8(&s.get(i), d) {
            hit.update(mask, t, s.id[i]);
        }
    }
}

/// The polygons `range` of a triangle or quad store against eight rays.
#[inline(always)]
pub fn polygons_x8<const N: usize>(
    g: &Polygons<N>,
    range: Range<usize>,
    d: &[f32x8; 3],
    hit: &mut Hit8,
) {
    for i in range {
        if let Some((mask, t)) = polygon_x8(&g.get(i), d) {
            hit.update(mask, t, g.id[i]);
        }
    }
}

/// Nearest hit along unit direction `d` from the eye, among every primitive of `p`.
#[inline]
pub fn trace_x1<T: Real>(p: &impl Records<T>, d: V3<T>) -> Hit<T> {
    let [s, t, q] = p.counts();
    let mut hit = Hit::NONE;
    ranges_x1(p, [0..s, 0..t, 0..q], d, &mut hit);
    hit
}

/// The spheres, triangles and quads in `ranges` of `p` against the ray `d`, keeping the nearest
/// hit in `hit` (the scalar kernels' loop, shared with the BVH's leaves).
#[inline(always)]
pub fn ranges_x1<T: Real>(
    p: &impl Records<T>,
    ranges: [Range<usize>; 3],
    d: V3<T>,
    hit: &mut Hit<T>,
) {
    let [s, t, q] = ranges;
    for i in s {
        if let Some((k, id)) = p.sphere(i)
            && let Some(t) = sphere_x1(&k, d)
        {
            hit.update(t, id);
        }
    }
    polygons_x1(|i| p.triangle(i), t, d, hit);
    polygons_x1(|i| p.quad(i), q, d, hit);
}

/// The polygons `range` (records from `get`) against the ray `d`: triangles and quads alike.
#[inline(always)]
fn polygons_x1<T: Real, const N: usize>(
    get: impl Fn(usize) -> Option<(PolyK<T, N>, i32)>,
    range: Range<usize>,
    d: V3<T>,
    hit: &mut Hit<T>,
) {
    for i in range {
        if let Some((k, id)) = get(i)
            && let Some(t) = polygon_x1(&k, d)
        {
            hit.update(t, id);
        }
    }
}

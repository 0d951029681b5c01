//! The scalar driver: one ray at a time against every primitive, in f64 (the oracle) or f32 (the
//! baseline the packet kernel's speedup is measured against). Plain loops, no acceleration;
//! the records come from a store or are computed when asked (`soa::Records`).

use crate::kernel::Hit;
use crate::kernel::polygon::{PolyK, polygon_x1};
use crate::kernel::sphere::sphere_x1;
use crate::real::{Real, V3};
use crate::soa::Records;
use std::ops::Range;

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

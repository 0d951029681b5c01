//! The brute-force loops over a store: every primitive of each type against one ray or one
//! packet, type by type, keeping the nearest hit by the kernels' rule ([`Hit::update`],
//! [`Hit8::update`]).
//!
//! - One ray at a time (`trace_x1`, `ranges_x1`): in f64 the oracle, in f32 the baseline the
//!   packet kernel's speedup is measured against. The records come from a store or are computed
//!   when asked ([`Records`]).
//! - Eight rays at a time (`trace_x8`, `family_x8`): each primitive's constants broadcast to
//!   the eight lanes from the columns of [`Packed`].
//! - Four f64 rays at a time (`ranges_x4d`): `--precision f64`'s lanes, from the records.
//!
//! A type the scene lacks has an empty store and its loop runs zero times. The acceleration
//! structures call the same loops over the ranges their leaves and tiles list.

use super::{Columns, Packed, Prepared, Records, Stored};
use crate::kernel::wide64::Hit4d;
use crate::kernel::{Family, Hit, Hit8};
use crate::real::{Real, V3};
use std::ops::Range;
use wide::{f32x8, f64x4};

/// The eight rays `d` against every primitive of `p`, family by family in kind order.
#[inline]
pub fn trace_x8(p: &Packed, d: &[f32x8; 3], hit: &mut Hit8) {
    for_each_family!(F => family_x8::<F>(p, 0..F::columns(p).len(), d, hit));
}

/// The primitives `range` of family `F` in `p` against the eight rays `d`, keeping the nearest
/// hits in `hit` (the packet loop, shared with the BVH's leaves).
#[inline(always)]
pub fn family_x8<F: Stored>(p: &Packed, range: Range<usize>, d: &[f32x8; 3], hit: &mut Hit8) {
    let cols = F::columns(p);
    for i in range {
        if let Some((mask, t)) = F::hit_lanes(&cols.get(i), d) {
            hit.update(mask, t, cols.id(i));
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

/// The primitives in `ranges` of `p` (one range per kind) against the ray `d`, keeping the
/// nearest hit in `hit` (the scalar kernels' loop, shared with the BVH's leaves).
#[inline(always)]
pub fn ranges_x1<T: Real>(
    p: &impl Records<T>,
    ranges: [Range<usize>; 3],
    d: V3<T>,
    hit: &mut Hit<T>,
) {
    for_each_family!(F => family_x1::<F, T>(p, ranges[F::KIND].clone(), d, hit));
}

/// The primitives `range` of family `F` in `p` against the ray `d`.
#[inline(always)]
fn family_x1<F: Stored, T: Real>(
    p: &impl Records<T>,
    range: Range<usize>,
    d: V3<T>,
    hit: &mut Hit<T>,
) {
    for i in range {
        if let Some((k, id)) = p.record::<F>(i)
            && let Some(t) = F::hit_x1(&k, d)
        {
            hit.update(t, id);
        }
    }
}

/// The primitives in `ranges` of `p` (one range per kind) against four f64 rays `d`, keeping
/// the nearest hits in `hit`: each family's kernel in f64x4 lanes, each lane the oracle's
/// `hit_x1::<f64>` bit for bit (`--precision f64`'s loop, shared by its render without
/// acceleration, the BVH's leaves, the tiles' one-ray walks and the re-decisions of
/// `--precision auto`).
#[inline(always)]
pub fn ranges_x4d(
    p: &impl Records<f64>,
    ranges: [Range<usize>; 3],
    d: &[f64x4; 3],
    hit: &mut Hit4d,
) {
    for_each_family!(F => family_x4d::<F>(p, ranges[F::KIND].clone(), d, hit));
}

/// The primitives `range` of family `F` in `p` against four f64 rays `d`.
#[inline(always)]
fn family_x4d<F: Stored>(
    p: &impl Records<f64>,
    range: Range<usize>,
    d: &[f64x4; 3],
    hit: &mut Hit4d,
) {
    for i in range {
        if let Some((k, id)) = p.record::<F>(i)
            && let Some((m, t)) = F::hit_lanes(&k, d)
        {
            hit.update(m, t, id as f64);
        }
    }
}

/// Every primitive of `p` against four f64 rays `d`, as [`ranges_x4d`] over all of them, read
/// in place from the records (a polygon's record is 16 f64s: copying it out for each packet
/// cost `--precision f64 --accel none` 14% of its time).
#[inline]
pub fn trace_x4d(p: &Prepared<f64>, d: &[f64x4; 3], hit: &mut Hit4d) {
    for_each_family!(F => {
        let g = F::group(p);
        for (k, &id) in g.k.iter().zip(&g.id) {
            if let Some((m, t)) = F::hit_lanes(k, d) {
                hit.update(m, t, id as f64);
            }
        }
    });
}

//! The packet driver: eight rays from one pixel block against every primitive, type by type.
//! Each primitive's constants are broadcast to the eight lanes; a type the scene lacks has an
//! empty store and its loop runs zero times.

use crate::camera::RayTables;
use crate::kernel::polygon::polygon_x8;
use crate::kernel::sphere::sphere_x8;
use crate::kernel::{Hit8, LANES};
use crate::soa::{Packed, Polygons, Spheres};
use std::ops::Range;
use wide::f32x8;

/// Pixel block of one packet: `BLOCK_W` x `BLOCK_H` = `LANES`; lane i covers pixel
/// (x0 + i % BLOCK_W, y0 + i / BLOCK_W). 4x2 was measured against 8x1 with the `block_shape`
/// group of `cargo bench --bench render` (docs/performance.md, "Packet against scalar").
pub const BLOCK_W: usize = 4;
/// Pixel block height: `LANES / BLOCK_W` = 2 rows.
pub const BLOCK_H: usize = LANES / BLOCK_W;

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

/// The rays of the `BW` x (`LANES` / `BW`) block whose top-left pixel is (x0, y0), and the mask
/// of lanes inside a `width` x `height` image. `tables` must be padded to whole blocks.
#[inline(always)]
pub fn block_rays<const BW: usize>(
    tables: &RayTables<f32>,
    x0: usize,
    y0: usize,
    width: usize,
    height: usize,
) -> ([f32x8; 3], f32x8) {
    let sx = f32x8::new(std::array::from_fn(|i| tables.sx[x0 + i % BW]));
    let sy = f32x8::new(std::array::from_fn(|i| tables.sy[y0 + i / BW]));
    let active = if x0 + BW <= width && y0 + (LANES / BW) <= height {
        f32x8::ZERO.simd_eq(f32x8::ZERO)
    } else {
        let inside = |i: usize| x0 + i % BW < width && y0 + i / BW < height;
        f32x8::new(std::array::from_fn(|i| if inside(i) { 1.0 } else { 0.0 })).simd_gt(f32x8::ZERO)
    };
    (tables.dir_x8(sx, sy), active)
}

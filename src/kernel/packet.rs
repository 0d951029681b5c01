//! The packet: eight rays from one pixel block, its shape and its rays. The loops that test a
//! packet against a store's primitives are `soa/trace.rs`.

use crate::camera::RayTables;
use crate::kernel::LANES;
use wide::f32x8;

/// Pixel block of one packet: `BLOCK_W` x `BLOCK_H` = `LANES`; lane i covers pixel
/// (x0 + i % BLOCK_W, y0 + i / BLOCK_W). 4x2 was measured against 8x1 with the `block_shape`
/// group of `cargo bench --bench render` (docs/performance.md, "Packet against scalar").
pub const BLOCK_W: usize = 4;
/// Pixel block height: `LANES / BLOCK_W` = 2 rows.
pub const BLOCK_H: usize = LANES / BLOCK_W;

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

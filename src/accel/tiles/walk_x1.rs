//! The tiles' walks for the one-ray kernels (scalar f32 and the f64 oracle) and the f64x4
//! method: a span of one tile's row, its list nearest first.

use super::{TILE_H, TILE_W, Tiles, packet_bits};
use crate::kernel::Hit;
use crate::kernel::wide64::Hit4d;
use crate::real::{Real, V3};
use crate::soa::Records;
use crate::soa::trace::ranges_x1;
use crate::soa::trace::ranges_x4d;
use wide::f64x4;

impl Tiles {
    /// Nearest hit of the ray `d` of pixel `(x, y)` with the scalar kernels in precision `T`
    /// (the oracle in f64, `scalar-f32`): the pixel's tile list, nearest first, left once the
    /// hit is nearer than the next entry's `near`. `p` holds the same primitives in the same
    /// order as the `Packed` the tiles were built from, once rearranged (`Order`).
    ///
    /// The bounds hold for both precisions (`accel::reach`): the f64 kernel accepts rays within
    /// a far smaller edge tolerance than the f32 one (`kernel::edge_eps`), about normals within
    /// u/2 of the f32 ones the regions are built from, and its distances err by f64 rounding
    /// only, so its hits lie inside the f32 rectangles and packets and beyond the f32 `near`;
    /// the scalar f32 kernel is the packet kernel's formula in one lane. Proven against
    /// `--accel none`, bit for bit, by tests/accel.rs and tests/accel_random.rs.
    #[inline]
    pub fn trace_x1<T: Real>(
        &self,
        p: &impl Records<T>,
        (x, y): (usize, usize),
        d: V3<T>,
    ) -> Hit<T> {
        let mut hit = Hit::NONE;
        let goes_on = |h: &Hit<T>, near: f32| h.t >= T::from_f64(near as f64);
        self.walk_span([x, x, y], &mut hit, goes_on, |h, kind, i| {
            ranges_x1(p, only(kind, i), d, h)
        });
        hit
    }
}

impl Tiles {
    /// Nearest hits of four f64 rays `d`, pixels `x0..=x1` of row `y` (one tile's), with the
    /// default kernels in f64x4 lanes (the f64x4 method; each lane is the oracle bit for bit):
    /// the tile's list, nearest first, left once no entry can win. `p` holds the primitives in
    /// the order of the `Packed` the tiles were built from. The bounds hold as for
    /// [`Tiles::trace_x1`] in f64.
    #[inline]
    pub fn trace_x4d(
        &self,
        p: &impl Records<f64>,
        [x0, x1, y]: [usize; 3],
        d: &[f64x4; 3],
        hit: &mut Hit4d,
    ) {
        let goes_on = |h: &Hit4d, near: f32| h.t.simd_ge(f64x4::splat(near as f64)).any();
        self.walk_span([x0, x1, y], hit, goes_on, |hit, kind, i| {
            ranges_x4d(p, only(kind, i), d, hit)
        });
    }

    /// The walk the scalar and f64x4 traces share: the list of the tile of pixels `x0..=x1` of
    /// row `y`, nearest first, while `goes_on(hit, near)` (some ray may still find a nearer
    /// hit), calling `visit(hit, kind, index)` on each entry whose packets include one of the
    /// span's.
    #[inline(always)]
    fn walk_span<H>(
        &self,
        [x0, x1, y]: [usize; 3],
        hit: &mut H,
        goes_on: impl Fn(&H, f32) -> bool,
        mut visit: impl FnMut(&mut H, u32, usize),
    ) {
        let (tx, ty) = (x0 / TILE_W, y / TILE_H);
        let span = packet_bits([x0, y, x1, y], (tx * TILE_W, ty * TILE_H));
        for e in self.list(tx, ty) {
            if !goes_on(hit, e.near) {
                return;
            }
            if e.packets() & span == 0 {
                continue;
            }
            let (kind, i) = e.kind_index();
            visit(hit, kind, i);
        }
    }
}

/// The ranges (spheres, triangles, quads) holding just primitive `i` of kind `kind`, for the
/// shared kernel loops (`soa::trace::ranges_x1`, `soa::trace::ranges_x4d`).
#[inline(always)]
fn only(kind: u32, i: usize) -> [std::ops::Range<usize>; 3] {
    let mut r = [0..0, 0..0, 0..0];
    r[kind as usize] = i..i + 1;
    r
}

//! f64x4 packets (`--precision f64`; the lab's `f64x4` method): the default kernels in f64x4
//! lanes (`kernel::wide64`, each lane the f64 oracle bit for bit), a 4x2 pixel block traced as
//! two f64x4 rows. Unlike the lab's brute-force drivers (`lab/src/kits.rs`) it takes every
//! acceleration, through the same structures as the scalar oracle ([`super::Structure`]), and
//! renders strips on every thread of the current rayon pool, so ids and depths are
//! bit-identical at any thread count and to `--accel none` (tests/accel.rs).

use super::{Frame, Structure, for_each_strip, prepare_f64};
use crate::accel::Accel;
use crate::accel::bvh::trace_bvh_x4d;
use crate::camera::{Camera, RayTables};
use crate::kernel::wide64::{Hit4d, dir_x4d};
use crate::scene::Scene;
use crate::soa::Prepared;
use crate::soa::trace::trace_x4d;
use wide::f64x4;

/// Pixels per f64x4 row of a block.
const BW: usize = 4;
/// Rows per block: two f64x4 rows make one 4x2 packet.
const BH: usize = 2;

/// The default methods in f64x4 lanes, with their acceleration.
pub struct Kit64 {
    /// The oracle's own f64 constants (in the BVH's leaf order when that is the structure).
    pub prepared: Prepared<f64>,
    /// What the rays trace through.
    pub structure: Structure,
    /// The camera's f64 ray tables, padded to whole 4x2 blocks.
    pub tables: RayTables<f64>,
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
}

impl Kit64 {
    /// The f64 constants and ray tables of `scene` seen by `camera`, without acceleration.
    pub fn new(scene: &Scene, camera: &Camera) -> Kit64 {
        Kit64::with_accel(scene, camera, Accel::None)
    }

    /// As [`Kit64::new`], tracing through the structure `accel` resolves to (the setup phase).
    pub fn with_accel(scene: &Scene, camera: &Camera, accel: Accel) -> Kit64 {
        let (prepared, structure) = prepare_f64(accel, scene, camera);
        Kit64 {
            prepared,
            structure,
            tables: camera.tables(BW as u32, BH as u32),
            width: camera.width as usize,
            height: camera.height as usize,
        }
    }

    /// The acceleration in use.
    pub fn accel(&self) -> Accel {
        self.structure.accel()
    }

    /// Nearest hits of the four rays `d` of pixels `x0..x0 + 4` in row `y`.
    #[inline]
    pub fn trace_x4d(&self, [x0, y]: [usize; 2], d: &[f64x4; 3], hit: &mut Hit4d) {
        let p = &self.prepared;
        match &self.structure {
            Structure::Tiles(tiles) => tiles.trace_x4d(p, [x0, x0 + BW - 1, y], d, hit),
            Structure::Bvh(bvh) => trace_bvh_x4d(p, bvh, d, hit),
            Structure::None => trace_x4d(p, d, hit),
        }
    }

    /// The image in strips on the current rayon pool's threads, each strip in 4x2 blocks of
    /// two f64x4 rows.
    pub fn render(&self) -> Frame<f64> {
        let (w, h) = (self.width, self.height);
        let t = &self.tables;
        let mut f = Frame::new(w as u32, h as u32, f64::INFINITY);
        for_each_strip(&mut f, None, |y_start, ids, depth| {
            let rows = ids.len() / w;
            for by in (0..rows).step_by(BH) {
                for bx in (0..w).step_by(BW) {
                    let sx = f64x4::new(std::array::from_fn(|i| t.sx[bx + i]));
                    for r in 0..BH {
                        let (y, row) = (y_start + by + r, by + r);
                        if row >= rows {
                            break;
                        }
                        let d = dir_x4d(t, sx, f64x4::splat(t.sy[y]));
                        let active =
                            f64x4::new(std::array::from_fn(|i| if bx + i < w { 1.0 } else { 0.0 }));
                        let mut hit = Hit4d::new(active.simd_gt(f64x4::ZERO));
                        self.trace_x4d([bx, y], &d, &mut hit);
                        let (tt, id) = (hit.t.to_array(), hit.id.to_array());
                        for i in 0..BW.min(w - bx) {
                            ids[row * w + bx + i] = id[i] as i32;
                            depth[row * w + bx + i] = tt[i];
                        }
                    }
                }
            }
        });
        f
    }
}

//! Step 3 of `render::cull`: whether a view's frame hides a cluster left out on trial.

use super::Slab;
use crate::accel::{TILE_H, TILE_W};
use crate::par::prelude::*;
use crate::render::Frame;
use glam::DVec3;

/// Per 8x8 tile of a frame, the farthest depth of its pixels (+inf where one is background),
/// NaN where one was re-decided (such a tile proves nothing about its pixels).
pub(super) struct TileDepths {
    across: usize,
    far: Vec<f32>,
}

impl TileDepths {
    pub(super) fn new(frame: &Frame<f32>, redone: &[usize]) -> TileDepths {
        let (w, h) = (frame.width as usize, frame.height as usize);
        let across = w.div_ceil(TILE_W);
        let mut far = vec![0f32; across * h.div_ceil(TILE_H)];
        (far.par_chunks_mut(across).enumerate()).for_each(|(ty, row)| {
            for y in ty * TILE_H..((ty + 1) * TILE_H).min(h) {
                let depth = &frame.depth[y * w..(y + 1) * w];
                for (tx, far) in row.iter_mut().enumerate() {
                    for &t in &depth[tx * TILE_W..((tx + 1) * TILE_W).min(w)] {
                        // (background is +inf; a NaN, never written, counts as background)
                        if t.is_nan() || t > *far {
                            *far = if t.is_nan() { f32::INFINITY } else { t };
                        }
                    }
                }
            }
        });
        // a tile with a re-decided pixel proves nothing: NaN, below no `near`
        for &p in redone {
            far[(p / w) / TILE_H * across + (p % w) / TILE_W] = f32::NAN;
        }
        TileDepths { across, far }
    }

    /// Whether every pixel of `rect` whose ray meets `slab` holds a hit nearer than `near`
    /// that was not re-decided: tile by tile, pixel by pixel only in the tiles whose farthest
    /// depth does not settle it.
    pub(super) fn hides(
        &self,
        c: &Check,
        [x0, y0, x1, y1]: [u16; 4],
        near: f32,
        slab: &Slab,
    ) -> bool {
        let w = c.frame.width as usize;
        let (x0, y0, x1, y1) = (x0 as usize, y0 as usize, x1 as usize, y1 as usize);
        let r = c.rays;
        let [f, right, up] = [r.f, r.r, r.u].map(DVec3::from_array);
        for ty in y0 / TILE_H..=y1 / TILE_H {
            for tx in x0 / TILE_W..=x1 / TILE_W {
                let far = self.far[ty * self.across + tx];
                if far < near {
                    continue;
                }
                let tainted = far.is_nan();
                for y in (ty * TILE_H).max(y0)..=((ty + 1) * TILE_H - 1).min(y1) {
                    for x in (tx * TILE_W).max(x0)..=((tx + 1) * TILE_W - 1).min(x1) {
                        let p = y * w + x;
                        let covered = c.frame.depth[p] < near
                            && !(tainted && c.redone.binary_search(&p).is_ok());
                        if covered {
                            continue;
                        }
                        if slab.meets(f + right * r.sx[x] + up * r.sy[y]) {
                            return false;
                        }
                    }
                }
            }
        }
        true
    }
}

/// What the check of a cluster on trial reads: the frame, its re-decided pixels (ascending),
/// and the view's f64 rays.
pub(super) struct Check<'a> {
    pub(super) frame: &'a Frame<f32>,
    pub(super) redone: &'a [usize],
    pub(super) rays: &'a crate::camera::RayTables<f64>,
}

//! Rendering a whole image: rows of pixels cut into strips, strips spread over rayon's threads,
//! each strip traced block by block (packet kernel) or pixel by pixel (scalar kernels).
//! Every pixel's result depends only on the pixel, so output is bit-identical at any thread
//! count; the caller chooses the count by running inside a rayon pool.
//!
//! [`Renderer`] is the entry point: [`Options`] (precision, acceleration, kernel)
//! and a scene seen by a camera make a prepared renderer (the setup phase), whose
//! [`Renderer::render`] gives a [`Frame`] of ids and depths. The pieces below it
//! ([`Setup`], [`PacketScene`], [`render_packet_blocks`]) are public for benchmarks and
//! experiments that time one kernel alone.

mod cull;
pub mod redecide;
mod renderer;
mod setup;
mod views;
pub mod wide64;

pub use crate::frame::Frame;
pub use renderer::{Options, Renderer};
pub use setup::{Kernel, Plain, Setup, Structure, prepare_f64};
pub use views::{Rendered, Views};

use crate::accel::bvh::{trace_bvh_x1, trace_bvh_x8};
use crate::accel::tiles::PacketLists;
use crate::accel::{Accel, Bvh, Tiles};
use crate::accel::{TILE_H, TILE_W};
use crate::camera::RayTables;
use crate::kernel::packet::{BLOCK_H, BLOCK_W, block_rays};
use crate::kernel::{Hit8, LANES};
use crate::par::prelude::*;
use crate::real::Real;
use crate::soa::trace::trace_x1;
use crate::soa::trace::trace_x8;
use crate::soa::{IdSet, Packed, Prepared};
use redecide::Redecide;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use wide::f32x8;

/// Image rows per strip: the unit of work a thread takes. A multiple of `BLOCK_H`, and one row
/// of `accel::tiles`' tiles.
pub const STRIP_ROWS: usize = TILE_H;

/// What the packet kernel traces against: the SoA stores, and the BVH over them when the
/// acceleration is `bvh` (the stores are then in the BVH's leaf order) or the tile lists when
/// it is `tiles`.
#[derive(Debug, Clone, Default)]
pub struct PacketScene {
    packed: Packed,
    bvh: Option<Bvh>,
    tiles: Option<Tiles>,
}

impl PacketScene {
    /// Prepares `scene` seen by `camera` with acceleration `accel` (`auto` resolved by size).
    pub fn new(
        scene: &crate::scene::Scene,
        camera: &crate::camera::Camera,
        accel: Accel,
    ) -> PacketScene {
        PacketScene::new_in(scene, camera, accel, PacketScene::default(), false, None)
    }

    /// [`PacketScene::new`], written into the buffers of `spare` (another view's of the same
    /// scene) rather than fresh memory where they are rebuilt from the scene: the stores'
    /// columns ([`Packed::from_scene_in`]) and the tiles' lists (`Tiles::new_in`, which
    /// keeps its working buffers for the next view with `keep`).
    pub fn new_in(
        scene: &crate::scene::Scene,
        camera: &crate::camera::Camera,
        accel: Accel,
        spare: PacketScene,
        keep: bool,
        left_out: Option<&IdSet>,
    ) -> PacketScene {
        let eye = camera.eye;
        let PacketScene {
            packed: spare_packed,
            tiles: spare_tiles,
            ..
        } = spare;
        match accel.resolve(scene.shapes.len()) {
            Accel::Bvh => {
                let prepared = Prepared::new(scene, eye);
                let (bvh, reordered) = Bvh::new(&prepared, scene, camera);
                PacketScene {
                    packed: Packed::new(&reordered),
                    bvh: Some(bvh),
                    tiles: None,
                }
            }
            Accel::Tiles => {
                let mut packed = Packed::from_scene_in(scene, eye, spare_packed, left_out);
                let spare_tiles = spare_tiles.unwrap_or_default();
                let (tiles, order) = Tiles::new_in(scene, &packed, camera, spare_tiles, keep);
                packed.permute(&order);
                PacketScene {
                    packed,
                    bvh: None,
                    tiles: Some(tiles),
                }
            }
            _ => PacketScene {
                packed: Packed::from_scene_in(scene, eye, spare_packed, left_out),
                bvh: None,
                tiles: None,
            },
        }
    }

    /// The acceleration in use.
    pub fn accel(&self) -> Accel {
        match (&self.bvh, &self.tiles) {
            (Some(_), _) => Accel::Bvh,
            (_, Some(_)) => Accel::Tiles,
            _ => Accel::None,
        }
    }

    /// Nearest hits of the eight rays `d` of the pixel block `[x0, y0, x1, y1]` (inclusive;
    /// the block lies in one tile of `accel::tiles`).
    #[inline(always)]
    pub fn trace_x8(&self, block: [usize; 4], d: &[f32x8; 3], hit: &mut Hit8) {
        match (&self.bvh, &self.tiles) {
            (Some(bvh), _) => trace_bvh_x8(&self.packed, bvh, d, hit),
            (_, Some(tiles)) => {
                let tile = (block[0] / TILE_W, block[1] / TILE_H);
                tiles.trace_x8(&self.packed, tile, block, d, hit)
            }
            _ => trace_x8(&self.packed, d, hit),
        }
    }
}

/// Runs `f(first_row, ids, depth)` on every strip of `frame` in parallel, counting finished
/// strips in `progress`.
fn for_each_strip<D: Copy + Send>(
    frame: &mut Frame<D>,
    progress: Option<&AtomicUsize>,
    f: impl Fn(usize, &mut [i32], &mut [D]) + Sync,
) {
    let strip = frame.width as usize * STRIP_ROWS;
    frame
        .ids
        .par_chunks_mut(strip)
        .zip(frame.depth.par_chunks_mut(strip))
        .enumerate()
        .for_each(|(s, (ids, depth))| {
            f(s * STRIP_ROWS, ids, depth);
            if let Some(p) = progress {
                p.fetch_add(1, Ordering::Relaxed);
            }
        });
}

/// Strips in a `height`-row image (the unit [`Setup::render_counting`] counts).
pub fn strip_count(height: usize) -> usize {
    height.div_ceil(STRIP_ROWS)
}

/// Renders with the 8-lane packet kernel in `BLOCK_W` x `BLOCK_H` blocks. `tables` padded to
/// whole blocks.
pub fn render_packet(
    p: &PacketScene,
    tables: &RayTables<f32>,
    width: usize,
    height: usize,
) -> Frame<f32> {
    render_packet_blocks::<BLOCK_W>(p, tables, width, height, None)
}

/// [`render_packet`] with blocks `BW` pixels wide and `LANES / BW` high (the block-shape bench
/// compares 4x2 with 8x1), counting finished strips in `progress`. `tables` padded to whole
/// blocks of that shape.
pub fn render_packet_blocks<const BW: usize>(
    p: &PacketScene,
    tables: &RayTables<f32>,
    width: usize,
    height: usize,
    progress: Option<&AtomicUsize>,
) -> Frame<f32> {
    packet_blocks::<BW>(p, tables, (width, height), progress, None, None).0
}

/// Traces the 4x2 packets of tile column `tx` of the strip from row `y_start` (`rows` rows) with
/// `trace(k, (bx, by), rays, hit)`: `k` the packet's index in the tile, `(bx, by)` its first
/// pixel (`by` within the strip), `hit` empty but for the lanes inside the image.
#[inline(always)]
fn tile_packets(
    tables: &RayTables<f32>,
    (width, height): (usize, usize),
    (tx, y_start, rows): (usize, usize, usize),
    mut trace: impl FnMut(usize, (usize, usize), &[f32x8; 3], &mut Hit8),
) {
    for by in (0..rows).step_by(BLOCK_H) {
        for col in 0..TILE_W / BLOCK_W {
            let bx = tx * TILE_W + col * BLOCK_W;
            if bx >= width {
                break;
            }
            let (d, active) = block_rays::<BLOCK_W>(tables, bx, y_start + by, width, height);
            let mut hit = Hit8::new(active);
            trace(
                by / BLOCK_H * (TILE_W / BLOCK_W) + col,
                (bx, by),
                &d,
                &mut hit,
            );
        }
    }
}

/// [`render_packet_blocks`], with the f32 hits that cannot be trusted decided again in f64 when
/// `redo` is given (`--precision auto`), into the buffers of `spare` when it has the size
/// ([`Frame::reuse`]); also returns the re-decided pixels (row-major indices, ascending).
pub(crate) fn packet_blocks<const BW: usize>(
    p: &PacketScene,
    tables: &RayTables<f32>,
    (width, height): (usize, usize),
    progress: Option<&AtomicUsize>,
    redo: Option<&Redecide>,
    spare: Option<Frame<f32>>,
) -> (Frame<f32>, Vec<usize>) {
    let mut frame = Frame::reuse(spare, width as u32, height as u32, f32::INFINITY);
    if let Some(r) = redo {
        r.reset_work();
    }
    // A strip's walk of re-decisions (auto).
    let walk = || redo.map(|r| (r, r.walk(&p.packed, p.tiles.as_ref(), p.bvh.as_ref())));
    let redone = Mutex::new(Vec::new());
    // Adds a strip's re-decided pixels (auto) to the frame's.
    let note = |mine: Vec<usize>| {
        if !mine.is_empty() {
            redone
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .extend(mine);
        }
    };
    // Writes a block's results into its strip (`by`: the block's first row in the strip).
    // (`rows`: the strip's rows; whole blocks are written a row of `BW` pixels at a time)
    let store =
        |(ids, depth): (&mut [i32], &mut [f32]), rows: usize, bx: usize, by: usize, hit: &Hit8| {
            // ids are exact small integers in the lanes: truncation is `as i32`
            let (t, id) = (hit.t.to_array(), hit.id.trunc_int().to_array());
            if bx + BW <= width && by + LANES / BW <= rows {
                for r in 0..LANES / BW {
                    let at = (by + r) * width + bx;
                    ids[at..at + BW].copy_from_slice(&id[r * BW..(r + 1) * BW]);
                    depth[at..at + BW].copy_from_slice(&t[r * BW..(r + 1) * BW]);
                }
                return;
            }
            for lane in 0..LANES {
                let (x, y) = (bx + lane % BW, by + lane / BW);
                if x < width && y < rows {
                    ids[y * width + x] = id[lane];
                    depth[y * width + x] = t[lane];
                }
            }
        };
    match &p.tiles {
        // Tile by tile: each tile's list is split once into its packets' lists. f32 has a strip
        // loop of its own, which no code of auto's shares: sharing one (even with auto's arm
        // apart) moved f32's instruction count by up to 2% as auto's code changed.
        Some(tiles) if BW == BLOCK_W && redo.is_none() => {
            for_each_strip(&mut frame, progress, |y_start, ids, depth| {
                let rows = ids.len() / width;
                let mut lists = PacketLists::default();
                for tx in 0..width.div_ceil(TILE_W) {
                    tiles.split_tile((tx, y_start / TILE_H), &mut lists);
                    let strip = (tx, y_start, rows);
                    tile_packets(tables, (width, height), strip, |k, (bx, by), d, hit| {
                        tiles.trace_packet_x8(&p.packed, &lists, k, d, hit);
                        store((ids, depth), rows, bx, by, hit);
                    });
                }
            })
        }
        // auto: each lane carries its winner's trusted distance, in the tiles where some
        // packet's hits may exceed it; the other tiles walk as f32's loop does
        Some(tiles) if BW == BLOCK_W => {
            for_each_strip(&mut frame, progress, |y_start, ids, depth| {
                let rows = ids.len() / width;
                let mut lists = PacketLists::default();
                let (mut mine, (r, w)) = (Vec::new(), walk().expect("auto"));
                // auto's counts for the strip (`redecide::Work`)
                let mut work = redecide::Work::default();
                // (sized for the few packets with suspects a strip has, about 30 on 65,536
                // spheres, and grown where there are more; one sized for every packet, 40 KiB
                // a strip, made the allocator return and fault in fresh pages strip after
                // strip, doubling auto's render time on the command line)
                let mut pending = Vec::with_capacity(32);
                for tx in 0..width.div_ceil(TILE_W) {
                    tiles.split_tile((tx, y_start / TILE_H), &mut lists);
                    let strip = (tx, y_start, rows);
                    if !lists.carries() {
                        tile_packets(tables, (width, height), strip, |k, (bx, by), d, hit| {
                            tiles.trace_packet_x8(&p.packed, &lists, k, d, hit);
                            store((ids, depth), rows, bx, by, hit);
                        });
                        continue;
                    }
                    let cols = (width - tx * TILE_W).min(TILE_W).div_ceil(BLOCK_W);
                    work.carrying += rows.div_ceil(BLOCK_H) * cols;
                    tile_packets(tables, (width, height), strip, |k, (bx, by), d, hit| {
                        let carried = tiles.trace_packet_x8_carrying(&p.packed, &lists, k, d, hit);
                        // a lane without a hit carries +inf at +inf: never beyond
                        let suspect = hit.t.simd_gt(carried).to_bitmask();
                        if suspect != 0 {
                            let winner = |id| tiles.winner_in_packet(&p.packed, &lists, k, id);
                            let ids = hit.id;
                            pending.push(r.pending((bx, by), suspect, ids, winner));
                        }
                        store((ids, depth), rows, bx, by, hit);
                    });
                }
                // the strip's packets with lanes to check, all at once
                work.packets = width.div_ceil(BLOCK_W) * rows.div_ceil(BLOCK_H);
                work.measured =
                    r.fix_pending(&w, (y_start, width), (ids, depth), &pending, &mut mine);
                r.add_work(work);
                note(mine);
            })
        }
        _ => for_each_strip(&mut frame, progress, |y_start, ids, depth| {
            let rows = ids.len() / width;
            let (mut mine, walk) = (Vec::new(), walk());
            for by in (0..rows).step_by(LANES / BW) {
                for bx in (0..width).step_by(BW) {
                    let (d, active) = block_rays::<BW>(tables, bx, y_start + by, width, height);
                    let mut hit = Hit8::new(active);
                    let y = y_start + by;
                    p.trace_x8([bx, y, bx + BW - 1, y + LANES / BW - 1], &d, &mut hit);
                    store((ids, depth), rows, bx, by, &hit);
                }
            }
            // auto: the finished strip's hits checked, and re-decided where untrusted
            if let Some((r, walk)) = &walk {
                r.fix_strip(walk, (y_start, width), ids, depth, &mut mine);
            }
            note(mine);
        }),
    }
    let mut redone = redone.into_inner().unwrap_or_else(|e| e.into_inner());
    redone.sort_unstable();
    (frame, redone)
}

/// Renders one ray at a time with the scalar kernel in precision `T`, through the acceleration
/// `accel` (bit-identical to without), counting finished strips in `progress`.
pub(crate) fn render_scalar_counting<T: Real>(
    p: &Prepared<T>,
    tables: &RayTables<T>,
    accel: &Structure,
    width: usize,
    height: usize,
    progress: Option<&AtomicUsize>,
) -> Frame<T> {
    let mut frame = Frame::new(width as u32, height as u32, T::INFINITY);
    for_each_strip(&mut frame, progress, |y_start, ids, depth| {
        for (i, (id, t)) in ids.iter_mut().zip(depth.iter_mut()).enumerate() {
            let (x, y) = (i % width, y_start + i / width);
            let d = tables.dir_x1(x, y);
            let hit = match accel {
                Structure::Tiles(tiles) => tiles.trace_x1(p, (x, y), d),
                Structure::Bvh(bvh) => trace_bvh_x1(p, bvh, d),
                Structure::None => trace_x1(p, d),
            };
            *id = hit.id;
            *t = hit.t;
        }
    });
    frame
}

/// An f64 frame (the oracle's, a lab method's) with its depths rounded once to f32, the
/// precision of every output buffer.
pub fn f32_depth(f: Frame<f64>) -> Frame<f32> {
    Frame {
        width: f.width,
        height: f.height,
        ids: f.ids,
        depth: f.depth.iter().map(|&d| d as f32).collect(),
    }
}

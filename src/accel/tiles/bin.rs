//! Binning: every primitive's footprint (pixel rectangle and `near` bound), the screen order of
//! the stores, and each tile's list with the packets of the tile each entry may reach, by a
//! parallel counting sort (the module comment of `tiles.rs` derives the bounds).

use super::{Entry, INDEX_MASK, KIND_SHIFT, PACKETS, TILE_H, TILE_W, Tiles, kind_index};
use crate::accel::footprint::{Footprint, PacketCones, Screen, near_f32, outline};
use crate::camera::Camera;
use crate::kernel::packet::{BLOCK_H, BLOCK_W};
use crate::par::prelude::*;
use crate::scene::Scene;
use crate::soa::{Columns, Order, Packed, Stored, for_each_family, with_family};
use std::sync::atomic::{AtomicU32, Ordering};
use wide::f32x8;

/// One primitive's footprint, computed once per setup.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Print {
    /// Lower bound on any distance the kernel returns for this primitive (f32, rounded down).
    pub(super) near: f32,
    /// Kind (top two bits) and index into that kind's packed store.
    pub(super) prim: u32,
    /// Pixel rectangle the primitive may cover, inclusive: x0, y0, x1, y1.
    pub(super) rect: [u16; 4],
}

/// The rectangle of a primitive that covers no pixel (x0 > x1): binned nowhere.
const OFF_SCREEN: [u16; 4] = [1, 1, 0, 0];

/// A list slot holds the footprint's index below this bit and the entry's packets above.
const PACKETS_SHIFT: u32 = 24;
const _: () = assert!(crate::limits::MAX_PRIMITIVES <= 1 << PACKETS_SHIFT);
const _: () = assert!(PACKETS <= 32 - PACKETS_SHIFT as usize);

impl Print {
    /// The tiles the rectangle touches, inclusive, or `None` when it is off screen.
    pub(super) fn tiles(&self) -> Option<[u32; 4]> {
        let [x0, y0, x1, y1] = self.rect.map(u32::from);
        (x0 <= x1).then_some([
            x0 / TILE_W as u32,
            y0 / TILE_H as u32,
            x1 / TILE_W as u32,
            y1 / TILE_H as u32,
        ])
    }
}

/// The packets (bits, packet `k` at column `k % 2`, row `k / 2` of the tile) that the pixels
/// `x0..=x1`, `y0..=y1` of the tile with top-left pixel `(ox, oy)` overlap, the span clamped to
/// the tile.
#[inline(always)]
pub(super) fn packet_bits([x0, y0, x1, y1]: [usize; 4], (ox, oy): (usize, usize)) -> u32 {
    let c0 = x0.saturating_sub(ox).min(TILE_W - 1) / BLOCK_W;
    let c1 = x1.saturating_sub(ox).min(TILE_W - 1) / BLOCK_W;
    let r0 = y0.saturating_sub(oy).min(TILE_H - 1) / BLOCK_H;
    let r1 = y1.saturating_sub(oy).min(TILE_H - 1) / BLOCK_H;
    // columns c0..=c1 (bits of a row), repeated for rows r0..=r1 (two bits a row)
    let cols = (1u32 << (c1 + 1)) - (1 << c0);
    let rows = ((1u32 << (2 * r1 + 2)) - (1 << (2 * r0))) / 3;
    cols * rows
}

/// Binning's working buffers: every primitive's footprint, and the counting sort's slots.
/// Kept (empty) between views so that the next binning fills memory already in use.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    prints: Vec<Print>,
    slots: Vec<AtomicU32>,
}

impl Clone for Scratch {
    /// Empty: the buffers hold nothing between binnings, and a clone need not keep their room.
    fn clone(&self) -> Scratch {
        Scratch::default()
    }
}

impl Tiles {
    /// Bins the primitives of `packed` (whose ids index `scene.shapes`) for `camera`. The lists
    /// name primitives in screen order, which the stores must then be rearranged to
    /// (`Packed::permute` with the order returned; `tiles.rs`, "Screen order").
    pub fn new(scene: &Scene, packed: &Packed, camera: &Camera) -> (Tiles, Order) {
        Tiles::new_in(scene, packed, camera, Tiles::default(), false)
    }

    /// [`Tiles::new`], the lists written into `spare`'s buffers (another view's tiles of the
    /// same scene), emptied first, rather than fresh memory: the same tiles. With `keep`, the
    /// working buffers (every footprint, the counting sort's slots) are kept in the tiles for
    /// the next view, emptied; without it they are freed once the lists are built, as
    /// [`Tiles::new`] does (they are the largest part of binning's memory).
    pub fn new_in(
        scene: &Scene,
        packed: &Packed,
        camera: &Camera,
        spare: Tiles,
        keep: bool,
    ) -> (Tiles, Order) {
        let Tiles {
            mut start,
            mut entries,
            scratch: Scratch {
                mut prints,
                mut slots,
            },
            ..
        } = spare;
        let screen = Screen::new(camera);
        let (w, h) = (camera.width as usize, camera.height as usize);
        let (cols, rows) = (w.div_ceil(TILE_W), h.div_ceil(TILE_H));
        // Every primitive's footprint, in parallel.
        prints.clear();
        for_each_family!(F => {
            let n = Columns::<F>::len(F::columns(packed));
            let prints_of = (0..n).into_par_iter();
            prints.par_extend(prints_of.map(|i| footprint::<F>(&screen, scene, packed, i)));
        });
        let kinds = packed.ids().map(<[f32]>::len);
        let order = screen_order(&mut prints, kinds, cols, cols * rows);
        // The packets of a tile that a footprint's kernel may reach: those its rectangle
        // overlaps, less those `PacketCones` finds wholly outside one of a polygon's edge
        // planes or too far from a sphere. Read from `packed`, still in its old order.
        let tables = camera.tables::<f32>(BLOCK_W as u32, BLOCK_H as u32);
        let cones = PacketCones::new(&tables, camera.direction_error());
        let centres: Vec<[f32x8; 3]> = (0..cols * rows)
            .into_par_iter()
            .map(|t| PacketCones::centres(&tables, (t % cols, t / cols)))
            .collect();
        let packets = |e: &Print, (tx, ty): (usize, usize)| -> u32 {
            let (kind, index) = kind_index(e.prim);
            let old = order[kind as usize]
                .as_ref()
                .map_or(index, |o| o[index] as usize);
            let rect = e.rect.map(usize::from);
            let c = &centres[ty * cols + tx];
            packet_bits(rect, (tx * TILE_W, ty * TILE_H))
                & with_family!(kind, F => outline::<F>(packed, old).packets(&cones, c))
        };
        // The tiles of a footprint's rectangle with their packets: a rectangle within one tile
        // is listed there whatever its packets (so the counting pass need not find them; an
        // entry whose packets come out empty is never tested), a larger one only in the tiles
        // where some packet is left.
        let covered = |e: &Print, test_single: bool| {
            let e = *e;
            let [tx0, ty0, tx1, ty1] = e.tiles().unwrap_or([1, 1, 0, 0]);
            let single = tx0 == tx1 && ty0 == ty1;
            (ty0..=ty1)
                .flat_map(move |ty| (tx0..=tx1).map(move |tx| (tx as usize, ty as usize)))
                .map(move |tile| {
                    let bits = if single && !test_single {
                        u32::MAX
                    } else {
                        packets(&e, tile)
                    };
                    (tile.1 * cols + tile.0, bits)
                })
                .filter(move |&(_, bits)| single || bits != 0)
        };
        // Counting sort: counts, prefix sum, scatter.
        let counts: Vec<AtomicU32> = (0..cols * rows).map(|_| AtomicU32::new(0)).collect();
        prints.par_iter().for_each(|e| {
            for (t, _) in covered(e, false) {
                counts[t].fetch_add(1, Ordering::Relaxed);
            }
        });
        start.clear();
        start.reserve(cols * rows + 1);
        let mut sum = 0u32;
        start.push(0);
        for c in &counts {
            sum += c.load(Ordering::Relaxed);
            start.push(sum);
        }
        let cursor: Vec<AtomicU32> = start[..cols * rows]
            .iter()
            .map(|&s| AtomicU32::new(s))
            .collect();
        slots.clear();
        slots.par_extend((0..sum).into_par_iter().map(|_| AtomicU32::new(0)));
        prints.par_iter().enumerate().for_each(|(i, e)| {
            for (t, bits) in covered(e, true) {
                let at = cursor[t].fetch_add(1, Ordering::Relaxed);
                slots[at as usize].store(i as u32 | bits << PACKETS_SHIFT, Ordering::Relaxed);
            }
        });
        entries.clear();
        entries.par_extend(slots.par_iter().map(|s| {
            let s = s.load(Ordering::Relaxed);
            let e = &prints[(s & ((1 << PACKETS_SHIFT) - 1)) as usize];
            Entry::new(e.near, e.prim, (s >> PACKETS_SHIFT) as u8)
        }));
        // (the room of a larger view before is given back: a view that leaves primitives out,
        // `render::cull`, holds no more than it uses)
        entries.shrink_to_fit();
        let scratch = match keep {
            true => {
                let (used_prints, used_slots) = (prints.len(), slots.len());
                prints.clear();
                slots.clear();
                prints.shrink_to(used_prints);
                slots.shrink_to(used_slots);
                Scratch { prints, slots }
            }
            false => Scratch::default(),
        };
        // Each tile nearest first; ties by kind and index, so the order is deterministic.
        let mut lists: Vec<&mut [Entry]> = Vec::with_capacity(cols * rows);
        let mut rest = entries.as_mut_slice();
        for t in 0..cols * rows {
            let (list, tail) = rest.split_at_mut((start[t + 1] - start[t]) as usize);
            lists.push(list);
            rest = tail;
        }
        lists.par_iter_mut().for_each(|l| {
            l.sort_unstable_by(|a, b| a.near.total_cmp(&b.near).then(a.prim.cmp(&b.prim)))
        });
        (
            Tiles {
                cols,
                start,
                entries,
                carries: Vec::new(),
                scratch,
            },
            order,
        )
    }
}

/// The footprint of primitive `index` of family `F` in `packed` (whose ids index
/// `scene.shapes`) on `screen`: its outline's rectangle and `near` (`Footprint`), `near`
/// rounded down to f32.
fn footprint<F: Stored>(screen: &Screen, scene: &Scene, packed: &Packed, index: usize) -> Print
where
    F::Outline: Footprint,
{
    let (rect, near) = outline::<F>(packed, index).footprint(screen, || {
        let id = Columns::<F>::id(F::columns(packed), index);
        F::ball(
            &F::geometry(scene.shapes.get(id as usize))?,
            screen.view.eye,
        )
    });
    Print {
        near: near_f32(near),
        prim: (F::KIND as u32) << KIND_SHIFT | index as u32,
        rect: rect.unwrap_or(OFF_SCREEN),
    }
}

/// The screen order of the primitives of `prints` (`counts[k]` of each kind `k` in turn, in
/// `Family::KIND` order, each kind in the stores' order): per kind, by the first tile of the
/// footprint's rectangle in row-major order (`tiles` tiles; off-screen footprints last), in store order
/// within a tile. A counting sort in parallel chunks (per-chunk counts, their offsets, a
/// per-chunk pass placing each footprint), the same at any thread count. Renumbers each
/// footprint's index to its new place, leaving `prints` where it is. A kind whose consecutive
/// primitives mostly start within a tile of each other already is in screen order, near
/// enough, and is kept as it is (`None`).
fn screen_order(prints: &mut [Print], counts: [usize; 3], cols: usize, tiles: usize) -> Order {
    const CHUNK: usize = 1 << 16;
    let first = |e: &Print| {
        e.tiles()
            .map_or(tiles, |[tx, ty, ..]| ty as usize * cols + tx as usize)
    };
    let mut rest = prints;
    let kinds = counts.map(|n| {
        let (kind, tail) = std::mem::take(&mut rest).split_at_mut(n);
        rest = tail;
        kind
    });
    kinds.map(|kind| {
        // already coherent on screen (a subdivided mesh): reordering would cost more in setup
        // than it saves in the render
        let close = kind
            .par_windows(2)
            .filter(|w| match (w[0].tiles(), w[1].tiles()) {
                (Some(a), Some(b)) => a[0].abs_diff(b[0]) <= 1 && a[1].abs_diff(b[1]) <= 1,
                _ => false,
            })
            .count();
        if 2 * close >= kind.len() {
            return None;
        }
        let mut next: Vec<Vec<u32>> = kind
            .par_chunks(CHUNK)
            .map(|c| {
                let mut n = vec![0u32; tiles + 1];
                c.iter().for_each(|e| n[first(e)] += 1);
                n
            })
            .collect();
        // chunk j's first place in tile t: every footprint of earlier tiles, then of tile t in
        // earlier chunks
        let mut at = 0u32;
        for t in 0..=tiles {
            for c in next.iter_mut() {
                (c[t], at) = (at, at + c[t]);
            }
        }
        kind.par_chunks_mut(CHUNK)
            .zip(next)
            .for_each(|(c, mut next)| {
                for e in c {
                    let t = first(e);
                    e.prim = (e.prim & !INDEX_MASK) | next[t];
                    next[t] += 1;
                }
            });
        let mut order = vec![0u32; kind.len()];
        for (old, e) in kind.iter().enumerate() {
            order[(e.prim & INDEX_MASK) as usize] = old as u32;
        }
        Some(order)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::{Family, Triangle};

    const TRIANGLE: u32 = Triangle::KIND as u32;

    fn print(kind: u32, index: u32, rect: [u16; 4]) -> Print {
        Print {
            near: 1.0,
            prim: kind << KIND_SHIFT | index,
            rect,
        }
    }

    /// Footprints scattered over a 4x3-tile screen come out in row-major order of their first
    /// tile, store order within a tile and off-screen ones last, each renumbered to its place.
    #[test]
    fn screen_order_sorts_by_first_tile_and_renumbers() {
        let (cols, rows) = (4, 3);
        // first tiles (tx, ty) of triangles 0..8, and one off screen
        let firsts = [
            (3, 2),
            (0, 0),
            (2, 1),
            (0, 0),
            (1, 2),
            (3, 0),
            (2, 1),
            (0, 1),
        ];
        let mut prints: Vec<Print> = firsts
            .iter()
            .enumerate()
            .map(|(i, &(tx, ty))| {
                let (x, y) = (tx * TILE_W as u16 + 1, ty * TILE_H as u16 + 2);
                print(TRIANGLE, i as u32, [x, y, x + 9, y + 3])
            })
            .collect();
        prints.push(print(TRIANGLE, 8, OFF_SCREEN));
        let order = screen_order(&mut prints, [0, 9, 0], cols, cols * rows);
        assert!(
            order[0].is_none() && order[2].is_none(),
            "no spheres, no quads"
        );
        let order = order[1]
            .as_ref()
            .expect("scattered footprints are rearranged");
        // by first tile index ty * cols + tx: 0 (#1, #3), 3 (#5), 4 (#7), 6 (#2, #6), 9 (#4),
        // 11 (#0), then off screen (#8)
        assert_eq!(order, &[1, 3, 5, 7, 2, 6, 4, 0, 8]);
        for (new, &old) in order.iter().enumerate() {
            let e = prints[old as usize];
            assert_eq!(e.prim, TRIANGLE << KIND_SHIFT | new as u32, "#{old}");
        }
    }

    /// `packet_bits` names the packets a pixel span overlaps, clamped to the tile.
    #[test]
    fn packet_bits_of_spans() {
        let o = (16, 8);
        // the whole tile and beyond: all eight packets
        assert_eq!(packet_bits([0, 0, 99, 99], o), 0xFF);
        // one pixel in column 1, row 2 of the tile's packets: packet 5
        assert_eq!(packet_bits([21, 13, 21, 13], o), 1 << 5);
        // a row of pixels across both columns, packet row 0
        assert_eq!(packet_bits([16, 8, 23, 8], o), 0b11);
        // column 0, rows 1 to 3
        assert_eq!(packet_bits([17, 10, 18, 15], o), 1 << 2 | 1 << 4 | 1 << 6);
    }
}

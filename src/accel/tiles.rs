//! Object-order casting for primary rays: every primitive is taken to the screen tiles it may
//! cover, and each tile's packets test only that tile's list, nearest first.
//!
//! All rays start at the eye, and the polygon kernel already tests a ray against the planes
//! through the eye and each edge: the 3D edge functions of a rasterizer (Davidovič, Engelhardt,
//! Georgiev, Slusallek, Hachisuka, "3D Rasterization: a bridge between rasterization and ray
//! casting", Graphics Interface 2012). So a primitive's pixels can be bounded in setup, from a
//! written bound on the kernels' error (`accel::reach`, which derives it):
//!
//! - Polygons. Every ray a kernel (f32 or f64) accepts lies within `E` radians of each edge
//!   plane of the polygon's stored f32 normals (`E = max(32u, 2 (8u + a))`, `a` =
//!   `Camera::direction_error`; derived: `11u + a`), and on the plane's side. In screen
//!   coordinates those are half-planes; the image clipped by them is the polygon's screen
//!   region, and its pixel rectangle those pixels whose centres lie in the region's box
//!   (widened by 1e-3 pixel for the f64 rounding). The region, not the polygon's projected
//!   vertices with a margin: a sliver narrower than `E` (a far mesh's silhouette triangle seen
//!   nearly edge-on through a narrow field of view) is accepted over a strip many times its
//!   length, up to across the whole image.
//! - Spheres. Every ray a kernel accepts passes within `r' = r (1 + 4u) + E |oc|` of the
//!   centre: the rectangle covers the projected corners of the camera-aligned cube of half
//!   size `r'`; the eye within `r'` gets the whole image.
//! - Each entry names the tile's packets (4x2 pixels) that the rectangle overlaps, less those
//!   whose rays all lie outside one of a polygon's edge planes or all pass too far from a
//!   sphere's centre (`footprint::PacketCones`, derived there); a tile where no packet is left
//!   gets no entry. A packet walks only its own entries.
//! - A sphere's cube reaching to or behind the eye's plane (a corner within `NEAR_PLANE_REL` of
//!   it) gets the whole image; one wholly and clearly behind it, none. Rectangles are clipped
//!   to the image; one wholly outside it is dropped.
//!
//! Binning (`tiles/bin.rs`) is a parallel counting sort: per-primitive rectangles in parallel,
//! per-tile counts with atomic adds, a prefix sum, a parallel scatter, then each tile's list
//! sorted by (near distance, primitive) in parallel, so the order is the same at any thread
//! count. An entry's packets are found in setup, once, not per frame.
//!
//! Screen order: the stores are rearranged so that primitives whose rectangles start in the same
//! tile lie together, tiles in row-major order (the order a strip of the render walks them).
//! A tile then reads its primitives' columns from a few neighbouring cache lines, rather than
//! from anywhere in them: with primitives in file order, a tile's
//! entries of a random 65,536-triangle scene each cost about 14 cache misses.
//!
//! Occlusion without a tree: each list entry carries `near`, a lower bound on any distance the
//! f32 kernel can return for that primitive (below). A packet walks its tile's list in order of
//! `near` and leaves it once every active lane already has a hit nearer than the next entry's
//! `near`: no later entry can win. Ids and depths are bit-identical to `--accel none`: the same
//! kernels, the same (t, id) minimum, and every entry that could win is tested.
//!
//! `near` (f64, rounded down to f32; `accel::reach` derives both), u = 2^-24:
//! - polygon: `p (1 - u) / (cmax + e_c)`, with `p` the kernel's own f32 plane distance, `cmax`
//!   the largest cosine between the plane's normal and a ray of the polygon's screen region and
//!   `e_c = 2 (a + 4u)` the error of the kernel's `d . N`; never below the plane bound
//!   `p (1 - u) / (1 + 8u)`, which holds at any angle of incidence.
//! - sphere: `c (1 - u) / ((|oc| (1 + 8u) + r (1 + 2u)) (1 + 2u))` from the f32 constants
//!   (`c = |oc|^2 - r^2`), the kernel's `c / q` with `q` at its largest; 0 with the eye inside.
//!
//! `kernels_accept_rays_only_in_their_packets_and_beyond_near` checks the packets and
//! `t >= near` ray by ray.
//!
//! The screen geometry, the rectangles, the `near` bounds and the packets' cones are computed
//! in `footprint.rs`, from the derivations above.
//!
//! Precision assumed: f32 kernels fed by f64 setup (as `soa`), and the f64 kernels, whose
//! accepted rays and distances lie inside the f32 bounds; the bounds hold for any scene
//! `scene::range::f32_range` accepts and any camera `scene::validate::camera` accepts.
//! Known to cost, not to fail: a primitive crossing the eye's plane is in every tile its region
//! reaches (correct, slow if there are many); a sliver seen edge-on is in every tile of its
//! strip; a deep stack of large overlapping primitives fills every list (the BVH culls those
//! better). Proven by `accel::reach`'s tests (the bounds against the kernels, over random
//! cameras, scales and shapes), tests/accel.rs and tests/accel_random.rs (tiles == none, bit for
//! bit: seed scenes, random scenes, primitives crossing the eye's plane, the eye inside a
//! sphere, rectangles clipped at the border, random telephoto cameras on the meshes).

use super::footprint::{Footprint, PacketCones, outline};
use super::{TILE_H, TILE_W};
use crate::kernel::packet::{BLOCK_H, BLOCK_W};
use crate::kernel::{Family, Hit8};
use crate::par::prelude::*;
use crate::soa::{Columns, Packed, Stored, with_family};
use wide::f32x8;

/// The kind of a list entry (`Family::KIND`) is the top two bits of [`Entry::prim`], its
/// index in that kind's packed store the bits below.
const KIND_SHIFT: u32 = 30;
const INDEX_MASK: u32 = (1 << KIND_SHIFT) - 1;
const _: () = assert!(crate::scene::KINDS.len() <= 1 << (32 - KIND_SHIFT));

/// One primitive in one tile's list: 12 bytes (checked below).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Entry {
    /// Lower bound on any distance the kernel returns for this primitive (f32, rounded down).
    near: f32,
    /// Kind (top two bits) and index into that kind's packed store.
    prim: u32,
    /// Low 8 bits: the tile's packets (bits, packet `k` at column `k % 2`, row `k / 2`) whose
    /// rays the kernel may accept: those the primitive's rectangle overlaps, less those
    /// `PacketCones` finds out of reach. The whole word read as an f32: the value the caller
    /// attached to the primitive ([`Tiles::attach`]; +inf until then) rounded down
    /// ([`lower_bits`]), handed back with the lanes the primitive wins. Kept in the entry the
    /// walk already reads, it costs no memory access of its own, and is read with no masking.
    word: u32,
}

const _: () = assert!(std::mem::size_of::<Entry>() == 12);

/// The kind (top two bits) and index in that kind's packed store of an entry's `prim`.
#[inline(always)]
fn kind_index(prim: u32) -> (u32, usize) {
    (prim >> KIND_SHIFT, (prim & INDEX_MASK) as usize)
}

/// The bits of [`Entry::word`] holding the packets.
const PACKETS_MASK: u32 = 0xFF;

impl Entry {
    fn new(near: f32, prim: u32, packets: u8) -> Entry {
        Entry {
            near,
            prim,
            word: lower_bits(f32::INFINITY) | u32::from(packets),
        }
    }

    /// The primitive's kind (`Family::KIND`) and index in that kind's packed store.
    #[inline(always)]
    fn kind_index(&self) -> (u32, usize) {
        kind_index(self.prim)
    }

    /// The tile's packets the entry may reach (bits).
    #[inline(always)]
    fn packets(&self) -> u32 {
        self.word & PACKETS_MASK
    }

    /// The value attached to the primitive ([`Tiles::attach`]), rounded down: the word as it
    /// stands, read as an f32 ([`lower_bits`]).
    #[inline(always)]
    fn attached(&self) -> f32 {
        f32::from_bits(self.word)
    }
}

/// The top 24 bits of an f32 at most `v`, whatever the low 8 bits (the entry's packets) are:
/// `v` rounded toward zero to 24 bits, less one unit of the 24th bit, so below `v` (by less
/// than 2^-14 relative where `v` is normal; a subnormal `v` may fall much further, still below). +inf becomes a finite value above 3.4e38 (no f32 hit distance in a
/// scene `scene::validate` accepts comes near it), and every `v <= 0` (and NaN) a value below
/// -3.4e38, whose sign alone then tells it apart.
fn lower_bits(v: f32) -> u32 {
    let top = v.to_bits() & !PACKETS_MASK;
    if v > 0.0 && top > PACKETS_MASK {
        top - (PACKETS_MASK + 1)
    } else {
        (-f32::MAX).to_bits() & !PACKETS_MASK
    }
}

/// Per-tile lists of primitives, nearest first.
#[derive(Debug, Clone, Default)]
pub struct Tiles {
    cols: usize,
    /// `start[t]..start[t + 1]` is tile t's range of `entries` (tiles in row-major order).
    start: Vec<u32>,
    entries: Vec<Entry>,
    /// Per tile, once values are attached ([`Tiles::attach`]; empty until then): the packets
    /// (bits) where some entry's hits may lie beyond its value. A tile with none walks without
    /// carrying ([`PacketLists::carries`]).
    carries: Vec<u8>,
    /// Binning's working buffers, emptied, kept for the next view's [`Tiles::new_in`].
    scratch: bin::Scratch,
}

impl Tiles {
    fn list(&self, tx: usize, ty: usize) -> &[Entry] {
        let t = ty * self.cols + tx;
        &self.entries[self.start[t] as usize..self.start[t + 1] as usize]
    }

    /// Nearest hits of the eight rays `d` of the pixel block `[x0, y0, x1, y1]` (inclusive), in
    /// tile (tx, ty): the tile's list, nearest first, left once no entry can win.
    #[inline]
    pub fn trace_x8(
        &self,
        p: &Packed,
        (tx, ty): (usize, usize),
        [x0, y0, bx1, by1]: [usize; 4],
        d: &[f32x8; 3],
        hit: &mut Hit8,
    ) {
        let block = packet_bits([x0, y0, bx1, by1], (tx * TILE_W, ty * TILE_H));
        for e in self.list(tx, ty) {
            // every active lane has a hit nearer than anything left in the list
            if !hit.t.simd_ge(f32x8::splat(e.near)).any() {
                return;
            }
            if e.packets() & block == 0 {
                continue;
            }
            test_entry(p, e, d, hit);
        }
    }

    /// Splits tile (tx, ty)'s list into its eight 4x2 packets' lists (packet `k` at column
    /// `k % 2`, row `k / 2` of the tile) by each entry's packets,
    /// keeping the nearest-first order: each packet then walks only the entries that may reach
    /// it, with no test per entry (docs/performance.md, "Growth").
    #[inline]
    pub(crate) fn split_tile(&self, (tx, ty): (usize, usize), lists: &mut PacketLists) {
        let list = self.list(tx, ty);
        let n = list.len();
        lists.tile = (tx, ty);
        lists.carry = self.carries.get(ty * self.cols + tx).copied().unwrap_or(0);
        lists.len = [0; PACKETS];
        lists.stride = n;
        if lists.index.len() < PACKETS * n {
            lists.index.resize(PACKETS * n, 0);
        }
        for (i, e) in list.iter().enumerate() {
            for k in 0..PACKETS {
                lists.index[k * n + lists.len[k]] = i as u32;
                lists.len[k] += (e.packets() >> k & 1) as usize;
            }
        }
    }

    /// Nearest hits of the eight rays `d` of packet `k` of the tile `lists` was split for
    /// ([`Tiles::split_tile`]): that packet's entries, nearest first, left once no entry can win.
    /// Always inlined, as the `--precision auto` form is: through a call, the packet's rays and
    /// hits went through memory (f32 rendered triangles_256 about 10% slower than auto).
    #[inline(always)]
    pub fn trace_packet_x8(
        &self,
        p: &Packed,
        lists: &PacketLists,
        k: usize,
        d: &[f32x8; 3],
        hit: &mut Hit8,
    ) {
        self.walk_packet::<false>(p, lists, k, d, hit);
    }

    /// [`Tiles::trace_packet_x8`], also returning for each lane the value attached to the
    /// primitive that won it ([`Tiles::attach`]; +inf where none did): one blend per entry
    /// tested (`--precision auto` carries each lane's trusted distance that way).
    #[inline(always)]
    pub fn trace_packet_x8_carrying(
        &self,
        p: &Packed,
        lists: &PacketLists,
        k: usize,
        d: &[f32x8; 3],
        hit: &mut Hit8,
    ) -> f32x8 {
        self.walk_packet::<true>(p, lists, k, d, hit)
    }

    /// The kind (0 sphere, 1 triangle, 2 quad, as [`Tiles::attach`] numbers them) and index
    /// in `p`'s store of that kind of the primitive with id `id` among packet `k`'s entries
    /// (`lists` split for its tile), if one is: the winner of a lane the walk gave that id.
    /// Found in the packet's own list, which the walk has just read, rather than through a
    /// table by id (a cache miss on 65,536 primitives).
    #[inline]
    pub fn winner_in_packet(
        &self,
        p: &Packed,
        lists: &PacketLists,
        k: usize,
        id: f32,
    ) -> Option<(usize, usize)> {
        self.packet_entries(lists, k)
            .map(Entry::kind_index)
            .find(|&(kind, i)| p.ids()[kind as usize][i] == id)
            .map(|(kind, i)| (kind as usize, i))
    }

    /// Packet `k`'s entries, nearest first (`lists` split for its tile).
    #[inline(always)]
    fn packet_entries<'a>(
        &'a self,
        lists: &'a PacketLists,
        k: usize,
    ) -> impl Iterator<Item = &'a Entry> + 'a {
        let list = self.list(lists.tile.0, lists.tile.1);
        lists.index[k * lists.stride..][..lists.len[k]]
            .iter()
            .map(move |&i| &list[i as usize])
    }

    /// The walk of [`Tiles::trace_packet_x8`], carrying the winners' attached values when
    /// `CARRY`. The hits and carried values are locals for the walk, stored back once: kept
    /// behind `hit` (and a closure's capture), they were stored to memory at every entry.
    #[inline(always)]
    fn walk_packet<const CARRY: bool>(
        &self,
        p: &Packed,
        lists: &PacketLists,
        k: usize,
        d: &[f32x8; 3],
        hit: &mut Hit8,
    ) -> f32x8 {
        let (mut h, mut carried) = (*hit, f32x8::splat(f32::INFINITY));
        for e in self.packet_entries(lists, k) {
            if !h.t.simd_ge(f32x8::splat(e.near)).any() {
                break;
            }
            let take = test_entry(p, e, d, &mut h);
            if CARRY {
                carried = take.select(f32x8::splat(e.attached()), carried);
            }
        }
        *hit = h;
        carried
    }

    /// Attaches `value(kind, index)` to every primitive (kind 0 sphere, 1 triangle, 2 quad;
    /// index into `packed`, the store the tiles were built over, rearranged), to be handed back
    /// by [`Tiles::trace_packet_x8_carrying`] with the lanes the primitive wins. Stored in the
    /// top 24 bits of the entry, rounded down ([`lower_bits`]): by less than 2^-14 relative,
    /// +inf to above 3.4e38, any `v <= 0` to below -3.4e38. `--precision auto` attaches each
    /// primitive's trusted distance, which rounding down only makes safer.
    ///
    /// Also marks, per tile, the packets whose hits on an entry's primitive may lie beyond the
    /// value stored, `s`: those where some pixel's exact ray (`camera`'s) may meet it beyond
    /// `s (1 - 2 error)` (`PacketCones::ball_beyond`, `PacketCones::polygon_beyond`), where
    /// `error` bounds the relative error of the kernel's f32 distances against the exact ones
    /// up to `s`: a hit there is at most `s (1 - 2 error)(1 + error) < s`. A +inf value marks
    /// none, a value `<= 0` all the entry's packets. A tile where no packet is marked walks
    /// without carrying (`PacketLists::carries`).
    ///
    /// Returns the primitives marked in some tile, as `(kind, index)` in ascending order: the
    /// only ones whose hits may lie beyond their values.
    pub fn attach(
        &mut self,
        packed: &Packed,
        camera: &crate::camera::Camera,
        error: f64,
        value: impl Fn(usize, usize) -> f32 + Sync,
    ) -> Vec<(usize, usize)> {
        let tables = camera.tables::<f32>(BLOCK_W as u32, BLOCK_H as u32);
        let cones = PacketCones::new(&tables, camera.direction_error());
        let mut lists = Vec::with_capacity(self.start.len() - 1);
        let mut rest = self.entries.as_mut_slice();
        for w in self.start.windows(2) {
            let (list, tail) = rest.split_at_mut((w[1] - w[0]) as usize);
            lists.push(list);
            rest = tail;
        }
        let cols = self.cols;
        let (carries, marked): (Vec<u8>, Vec<Vec<u32>>) = lists
            .into_par_iter()
            .enumerate()
            .map(|(t, list)| {
                let mut marked = Vec::new();
                if list.is_empty() {
                    return (0, marked);
                }
                let c = PacketCones::centres(&tables, (t % cols, t / cols));
                let mut marks = 0;
                for e in list {
                    let (kind, i) = e.kind_index();
                    let v = value(kind as usize, i);
                    e.word = lower_bits(v) | e.packets();
                    let reach = f64::from(e.attached()) * (1.0 - 2.0 * error);
                    let beyond = match kind {
                        _ if v == f32::INFINITY => 0,
                        kind => with_family!(kind, F => {
                            outline::<F>(packed, i).beyond(&cones, &c, reach)
                        }),
                    };
                    if beyond & e.packets() != 0 {
                        marks |= beyond & e.packets();
                        marked.push(e.prim);
                    }
                }
                (marks as u8, marked)
            })
            .unzip();
        self.carries = carries;
        let mut marked: Vec<u32> = marked.into_iter().flatten().collect();
        marked.par_sort_unstable();
        marked.dedup();
        marked
            .into_iter()
            .map(|prim| {
                let (kind, i) = kind_index(prim);
                (kind as usize, i)
            })
            .collect()
    }
}

/// Packets per tile: 4x2 blocks of the packet kernel.
pub const PACKETS: usize = (TILE_W / BLOCK_W) * (TILE_H / BLOCK_H);

/// One tile's list split per packet ([`Tiles::split_tile`]); reused from tile to tile.
#[derive(Debug, Clone, Default)]
pub struct PacketLists {
    tile: (usize, usize),
    /// Packet k's entries (indices into the tile's list) are `index[k * stride..][..len[k]]`.
    index: Vec<u32>,
    stride: usize,
    len: [usize; PACKETS],
    /// The packets (bits) some entry of the tile may hit beyond its attached value
    /// ([`Tiles::attach`]; none before a value is attached).
    carry: u8,
}

impl PacketLists {
    /// Whether some packet of the tile may have hits beyond the values attached to their
    /// primitives: when none may, [`Tiles::trace_packet_x8`] stands for
    /// [`Tiles::trace_packet_x8_carrying`], whose carried values would never be exceeded.
    #[inline(always)]
    pub fn carries(&self) -> bool {
        self.carry != 0
    }

    /// Whether packet `k`'s hits may lie beyond the values attached to their primitives (the
    /// render decides per tile: per packet, the branch cost what the blends saved).
    #[cfg(test)]
    pub(crate) fn carries_packet(&self, k: usize) -> bool {
        self.carry >> k & 1 != 0
    }
}

/// Tests entry `e` against the rays `d`, keeping the nearest hits in `hit`, with its family's
/// kernel without early exit (`Family::hit_lanes_all`): which packets a small primitive meets
/// is as likely as not, and a branch cannot predict it.
#[inline(always)]
fn test_entry(p: &Packed, e: &Entry, d: &[f32x8; 3], hit: &mut Hit8) -> f32x8 {
    let (kind, i) = e.kind_index();
    with_family!(kind, F => {
        let s = F::columns(p);
        let (mask, t) = F::hit_lanes_all(&Columns::<F>::get(s, i), d);
        hit.update(mask, t, Columns::<F>::id(s, i))
    })
}

mod bin;
mod walk_x1;
use bin::packet_bits;

#[cfg(test)]
mod tests;

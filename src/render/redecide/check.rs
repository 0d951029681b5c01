//! The checks of `--precision auto` (the parent module): which f32 hits lie outside their
//! primitive's trusted distances, measured four at a time ([`Redecide::verified_lanes`]) and,
//! where the measurement fails, decided again in f64, a group of four pixels of a row at a time.
//!
//! - Through the tiles: each packet's lanes carry the trusted distance of their winner, so a
//!   packet's check is one compare ([`Redecide::pending`]); the few packets with
//!   lanes to check are checked at the end of the strip, their suspects measured together
//!   whatever their packets ([`Redecide::fix_pending`]).
//! - Through the BVH, or without acceleration: the finished strip is scanned, eight pixels per
//!   compare, against the least trusted distance in the scene ([`Redecide::fix_strip`]), and
//!   the packet loop is the f32 one, unchanged.

use super::verify::{Known, Oracle, Suspect};
use super::{ROW_MIN, Redecide, Walk};
use crate::kernel::packet::BLOCK_W;
use wide::{f32x8, i32x8};

impl Redecide<'_> {
    /// Checks the hits of a finished strip (`ids`, `depth`: whole rows of `width` pixels from
    /// row `y_start`) and decides again in f64 each pixel whose hit lies outside its primitive's
    /// trusted distances, noting its index in the image in `mine`. The scan reads eight
    /// pixels per compare (a pixel nearer than `safe` needs no lookup), after the strip's
    /// packets: the packet loop is the f32 one, unchanged (`--accel none` and `bvh`).
    pub(crate) fn fix_strip(
        &self,
        walk: &Walk,
        (y_start, width): (usize, usize),
        ids: &mut [i32],
        depth: &mut [f32],
        mine: &mut Vec<usize>,
    ) {
        for (r, (ids, depth)) in ids
            .chunks_exact_mut(width)
            .zip(depth.chunks_exact_mut(width))
            .enumerate()
        {
            let y = y_start + r;
            let suspects = |depth: &[f32], x0: usize| {
                self.beyond_safe(f32x8::new(depth[x0..x0 + 8].try_into().expect("8 pixels")))
            };
            // sixteen pixels per branch: the scan runs over every pixel of the image; runs of
            // blocks with suspects are checked together
            let (pairs, whole) = (width / 16 * 16, width / 8 * 8);
            let mut start = None;
            for x0 in (0..pairs).step_by(16) {
                if suspects(depth, x0) | suspects(depth, x0 + 8) != 0 {
                    start.get_or_insert(x0);
                } else if let Some(s) = start.take() {
                    self.fix_span(walk, (s, x0, y), (ids, depth), width, mine);
                }
            }
            if let Some(s) = start {
                self.fix_span(walk, (s, pairs, y), (ids, depth), width, mine);
            }
            if pairs < whole && suspects(depth, pairs) != 0 {
                self.fix_span(walk, (pairs, whole, y), (ids, depth), width, mine);
            }
            // the last few pixels of the row (fewer than eight), in groups of four
            let suspect = (whole..width)
                .filter(|&x| depth[x] > self.safe && depth[x] < f32::INFINITY)
                .fold(0, |m, x| m | 1 << (x - whole));
            for g in (whole..width).step_by(4) {
                let lanes = (suspect >> (g - whole)) & 0xF;
                self.check_group(walk, (g, y, width), (ids, depth), (0, lanes), mine);
            }
        }
    }

    /// The pixels of `d` beyond `safe` (bits; background is +inf, and `safe` is below it).
    #[inline(always)]
    fn beyond_safe(&self, d: f32x8) -> u32 {
        let (safe, inf) = (f32x8::splat(self.safe), f32x8::splat(f32::INFINITY));
        (d.simd_gt(safe) & d.simd_lt(inf)).to_bitmask()
    }

    /// The rest of [`Redecide::fix_strip`] for the blocks of eight pixels `x0..x1` of row `y`
    /// (`ids`, `depth`: that row, `width` wide), a run of blocks the scan found pixels beyond
    /// `safe` in: kept out of the scan. A block whose suspects lie on one primitive (the
    /// common case) takes one compare against that primitive's limits, and its two halves are
    /// measured with the oracle's constants of that primitive; the limits and constants are
    /// kept from block to block while the primitive stays the same.
    #[inline(never)]
    fn fix_span(
        &self,
        walk: &Walk,
        (x0, x1, y): (usize, usize, usize),
        (ids, depth): (&mut [i32], &mut [f32]),
        width: usize,
        mine: &mut Vec<usize>,
    ) {
        // (primitive, its limits, its oracle's constants once fetched)
        let mut same: Option<(i32, [f32; 2], Option<Option<Oracle>>)> = None;
        for b in (x0..x1).step_by(8) {
            let t: [f32; 8] = depth[b..b + 8].try_into().expect("8 pixels");
            let d = f32x8::new(t);
            let suspect = self.beyond_safe(d);
            if suspect == 0 {
                continue;
            }
            let first = ids[b + suspect.trailing_zeros() as usize];
            if !self.one_primitive(&ids[b..b + 8], first, suspect) {
                for g in (b..b + 8).step_by(4) {
                    let lanes = (suspect >> (g - b)) & 0xF;
                    self.check_group(walk, (g, y, width), (ids, depth), (0, lanes), mine);
                }
                continue;
            }
            if same.as_ref().is_none_or(|s| s.0 != first) {
                same = Some((first, self.limit(first as f32), None));
            }
            let (_, [lo, hi], k) = same.as_mut().expect("set above");
            let out = d.simd_lt(f32x8::splat(*lo)) | d.simd_gt(f32x8::splat(*hi));
            let untrusted = suspect & out.to_bitmask();
            if untrusted == 0 {
                continue;
            }
            // both halves measured, whatever their lanes: two independent chains, no branch
            let k = *k.get_or_insert_with(|| *self.oracle(walk, first as usize));
            let half = |h: usize| std::array::from_fn(|i| t[4 * h + i]);
            let ok = self.verified_row(&k, (b, y), half(0))
                | self.verified_row(&k, (b + 4, y), half(1)) << 4;
            let left = untrusted & !ok;
            for h in 0..2 {
                let lanes = (left >> (4 * h)) & 0xF;
                if lanes != 0 {
                    let (g, mut t, mut id) = (b + 4 * h, half(h), [first as f32; 4]);
                    self.redo_group(walk, (g, y), &mut t, &mut id, lanes);
                    self.write_back((g, y, width), (&t, &id), lanes, (ids, depth), mine);
                }
            }
        }
    }

    /// Checks the pixels `x0..x0 + 4` of row `y` (`ids`, `depth`: that row, `width` wide; past
    /// its end, none): the lanes `known` (bits) are untrusted as they stand, those of `look`
    /// once their limits say so ([`Redecide::outside`]). Those are measured, and the ones that
    /// stay untrusted are decided again in f64, written back and noted in `mine`.
    fn check_group(
        &self,
        walk: &Walk,
        (x0, y, width): (usize, usize, usize),
        (ids, depth): (&mut [i32], &mut [f32]),
        (known, look): (u32, u32),
        mine: &mut Vec<usize>,
    ) {
        if known | look == 0 {
            return;
        }
        let (mut t, mut id) = group((ids, depth), x0, width);
        let untrusted = known | self.outside(&t, &id, look);
        let redone = self.fix_group(walk, (x0, y), &mut t, &mut id, untrusted);
        self.write_back((x0, y, width), (&t, &id), redone, (ids, depth), mine);
    }

    /// Whether every pixel of `suspect` (bits) among the eight `ids` holds primitive `first`
    /// (compared all eight at once).
    #[inline(always)]
    fn one_primitive(&self, ids: &[i32], first: i32, suspect: u32) -> bool {
        let ids = i32x8::new(ids.try_into().expect("8 pixels"));
        let same = ids.simd_eq(i32x8::splat(first)).to_bitmask();
        suspect & !same == 0
    }

    /// Writes the lanes `lanes` (bits) of the group at pixel `(x0, y)` (`t`, `id`) into their
    /// row (`ids`, `depth`) and notes their indices in the `width`-wide image in `mine`.
    fn write_back(
        &self,
        (x0, y, width): (usize, usize, usize),
        (t, id): (&[f32; 4], &[f32; 4]),
        lanes: u32,
        (ids, depth): (&mut [i32], &mut [f32]),
        mine: &mut Vec<usize>,
    ) {
        let mut m = lanes;
        while m != 0 {
            let i = m.trailing_zeros() as usize;
            (depth[x0 + i], ids[x0 + i]) = (t[i], id[i] as i32);
            mine.push(y * width + x0 + i);
            m &= m - 1;
        }
    }

    /// The trusted distances `[lo, hi]` of primitive `id` (exact in f32, below `limits.len()`
    /// for a hit; anything else is trusted everywhere, as background is).
    #[inline(always)]
    fn limit(&self, id: f32) -> [f32; 2] {
        self.limits
            .get(id as usize)
            .map_or([0.0, f32::INFINITY], super::unpack)
    }

    /// The lanes of `lanes` (bits) whose hit `t` lies outside the trusted distances of its
    /// primitive `id`: one lookup when they share a primitive (the common case).
    #[inline]
    fn outside(&self, t: &[f32; 4], id: &[f32; 4], lanes: u32) -> u32 {
        if lanes == 0 {
            return 0;
        }
        let first = id[lanes.trailing_zeros() as usize % 4];
        let one = (0..4).all(|i| lanes & (1 << i) == 0 || id[i] == first);
        let lim: [[f32; 2]; 4] = if one {
            [self.limit(first); 4]
        } else {
            std::array::from_fn(|i| self.limit(id[i]))
        };
        (0..4)
            .filter(|&i| lanes & (1 << i) != 0 && (t[i] < lim[i][0] || t[i] > lim[i][1]))
            .fold(0, |m, i| m | 1 << i)
    }

    /// Measures the `untrusted` lanes (bits) of the four pixels `x0..x0 + 4` of row `y`
    /// ([`Redecide::recheck_group`]) and decides again in f64 those that stay untrusted,
    /// writing the oracle's answers into `t` and `id`. Returns those lanes.
    #[inline]
    fn fix_group(
        &self,
        walk: &Walk,
        (x0, y): (usize, usize),
        t: &mut [f32; 4],
        id: &mut [f32; 4],
        untrusted: u32,
    ) -> u32 {
        if untrusted == 0 {
            return 0;
        }
        let left = self.recheck_group(walk, (x0, y), t, id, untrusted);
        if left != 0 {
            self.redo_group(walk, (x0, y), t, id, left);
        }
        left
    }

    /// Decides again in f64 the lanes `lanes` (bits) of the four pixels `x0..x0 + 4` of row
    /// `y`, writing the oracle's answers into `t` and `id`.
    #[inline(never)]
    fn redo_group(
        &self,
        walk: &Walk,
        (x0, y): (usize, usize),
        t: &mut [f32; 4],
        id: &mut [f32; 4],
        lanes: u32,
    ) {
        if lanes.count_ones() >= ROW_MIN {
            // f64x4 lanes: each lane is the oracle's answer, bit for bit
            let (rt, rid) = self.trace_row(walk, (x0, y), lanes);
            for i in 0..4 {
                if lanes & (1 << i) != 0 {
                    (t[i], id[i]) = (rt[i], rid[i]);
                }
            }
        } else {
            let i = lanes.trailing_zeros() as usize;
            (t[i], id[i]) = self.trace(walk, (x0 + i, y));
        }
    }

    /// The packet at `(bx, by)` of a strip (`by`: its first row there), traced with each
    /// lane's trusted distance carried along (the `hi` of the primitive that won the lane,
    /// negative where the primitive has a lower limit too; [`super::carry`]), whose lanes
    /// `suspect` (bits) lie beyond their carried distance. Each looks its primitive's limits
    /// up before it is measured ([`Redecide::fix_pending`]): the carried `hi` is rounded down
    /// (by up to 2^-14 relative, `Tiles::attach`), so a lane just below its `hi` arrives here,
    /// and is kept as the strip scan of `--accel none` and `bvh` keeps it. The pixels measured
    /// are then those outside their limits whatever the acceleration. The packet loop finds
    /// `suspect` with one compare, and calls this for the few packets where it is not empty:
    /// out of line, and cold, so that the loop's own code stays as it is
    /// without it (inlined, it cost auto 4-5% on 65,536 spheres in the precision bench). `ids`
    /// are the lanes' winners, and `winner_of(id)` the kind and packed index of such a winner,
    /// found where the packet's data is still in cache (the tiles: `Tiles::winner_in_packet`).
    #[inline(never)]
    #[cold]
    pub(crate) fn pending(
        &self,
        (bx, by): (usize, usize),
        suspect: u32,
        ids: f32x8,
        winner_of: impl Fn(f32) -> Option<(usize, usize)>,
    ) -> Pending {
        let (mut known, ids) = ([Known::Unknown; 8], ids.to_array());
        // (the lanes of a packet mostly share their winner: found once)
        let mut last = (f32::NAN, Known::Unknown);
        let mut m = suspect;
        while m != 0 {
            let lane = m.trailing_zeros() as usize;
            m &= m - 1;
            if ids[lane] == last.0 {
                known[lane] = last.1;
                continue;
            }
            let k = winner_of(ids[lane]).map_or(Known::Unknown, |w| self.known(w));
            (known[lane], last) = (k, (ids[lane], k));
            // what the lane's measurement reads, asked for now and read once the strip is
            // done: a cache miss a suspect on 65,536 primitives (docs/precision.md, "Speed")
            let (start, len) = match k {
                Known::Sphere(at) => bytes(&self.spheres[at as usize]),
                Known::Polygon(kind, at) => bytes(&self.planes[kind as usize - 1][at as usize]),
                Known::Unknown => self.scene.shapes.address(ids[lane] as usize),
            };
            prefetch_bytes(start, len);
            if let Some(limit) = self.limits.get(ids[lane] as usize) {
                let (start, len) = bytes(limit);
                prefetch_bytes(start, len);
            }
        }
        Pending {
            bx,
            by,
            suspect,
            known,
        }
    }

    /// Checks the suspect lanes of a finished strip's packets (`pending`, from
    /// [`Redecide::pending`]; `ids`, `depth`: whole rows of `width` pixels from row
    /// `y_start`) and decides again in f64 each that cannot be trusted, noting its index in the
    /// image in `mine`. The strip's suspects are measured four at a time, whatever their
    /// packets and primitives ([`Redecide::verified_lanes`]): most packets have one, and
    /// measured packet by packet three of the four f64 lanes went unused. Each suspect's sphere
    /// or plane was asked for as its packet was traced ([`Redecide::pending`]), so that its
    /// cache miss (on 65,536 random primitives, most of a suspect's cost when each was read as
    /// it was measured) overlaps the rest of the strip. Returns how many hits it measured.
    pub(crate) fn fix_pending(
        &self,
        walk: &Walk,
        (y_start, width): (usize, usize),
        (ids, depth): (&mut [i32], &mut [f32]),
        pending: &[Pending],
        mine: &mut Vec<usize>,
    ) -> usize {
        // (packet, lane, hit) of every lane to measure, in packet order
        let lanes = pending.iter().map(|p| p.suspect.count_ones());
        let mut suspects = Vec::with_capacity(lanes.sum::<u32>() as usize);
        for (k, p) in pending.iter().enumerate() {
            let mut m = p.suspect;
            while m != 0 {
                let lane = m.trailing_zeros();
                m &= m - 1;
                let (x, y) = (
                    p.bx + lane as usize % BLOCK_W,
                    p.by + lane as usize / BLOCK_W,
                );
                let (id, t) = (ids[y * width + x] as f32, depth[y * width + x]);
                // within its limits (the carried `hi` was rounded down): trusted, as without
                // the tiles
                let [lo, hi] = self.limit(id);
                if (lo..=hi).contains(&t) {
                    continue;
                }
                let known = p.known[lane as usize];
                let y = y_start + y;
                suspects.push((k, lane, Suspect { x, y, id, t, known }));
            }
        }
        // the lanes that stay untrusted once measured, still in packet order
        let mut left = Vec::new();
        for four in suspects.chunks(4) {
            let s = std::array::from_fn(|i| four.get(i).map_or(Suspect::default(), |h| h.2));
            let ok = self.verified_lanes(walk, &s, (1 << four.len()) - 1);
            let failed = four.iter().enumerate().filter(|(i, _)| ok >> i & 1 == 0);
            left.extend(failed.map(|(_, &(k, lane, _))| (k, lane)));
        }
        // decided again a packet row (four pixels) at a time
        const W: u32 = BLOCK_W as u32;
        for row in left.chunk_by(|a, b| (a.0, a.1 / W) == (b.0, b.1 / W)) {
            let (p, r) = (&pending[row[0].0], row[0].1 as usize / BLOCK_W);
            let lanes = row.iter().fold(0, |m, &(_, lane)| m | 1 << (lane % W));
            let y = p.by + r;
            let (ids, depth) = (
                &mut ids[y * width..(y + 1) * width],
                &mut depth[y * width..(y + 1) * width],
            );
            let (mut t, mut id) = group((ids, depth), p.bx, width);
            self.redo_group(walk, (p.bx, y_start + y), &mut t, &mut id, lanes);
            self.write_back(
                (p.bx, y_start + y, width),
                (&t, &id),
                lanes,
                (ids, depth),
                mine,
            );
        }
        suspects.len()
    }
}

/// [`prefetch`] of every cache line of the `len` bytes from `start` (a 104-byte shape lies on
/// three lines for half its offsets in a line).
#[inline(always)]
fn prefetch_bytes(start: *const u8, len: usize) {
    let lines = (start as usize % 64 + len.max(1) - 1) / 64 + 1;
    for line in 0..lines {
        prefetch(start.wrapping_add(64 * line));
    }
}

/// Asks the processor to bring the cache line of `p` into its nearest cache (T0), without
/// waiting for it: a hint, which changes no result. (With the T1 hint, into L2, the read of a
/// suspect's sphere in `verified_lanes` still took 70% of that function's samples on 65,536
/// spheres, under `perf record`; with T0, 10%.)
#[inline(always)]
fn prefetch(p: *const u8) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch never faults and reads nothing into the program's state, whatever
    // the address. SSE is part of every x86-64 processor.
    unsafe {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>(p.cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

/// The depths and ids of the four pixels `x0..x0 + 4` of a row (`ids`, `depth`, `width` wide),
/// as the group checks take them: past the row's end, depth 0 and id -1 (no hit).
fn group((ids, depth): (&[i32], &[f32]), x0: usize, width: usize) -> ([f32; 4], [f32; 4]) {
    let n = (width - x0).min(4);
    (
        std::array::from_fn(|i| if i < n { depth[x0 + i] } else { 0.0 }),
        std::array::from_fn(|i| if i < n { ids[x0 + i] as f32 } else { -1.0 }),
    )
}

/// A packet of a strip with lanes to check ([`Redecide::fix_pending`]): its first pixel
/// (`by`: the row within the strip) and its lanes as bits.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pending {
    bx: usize,
    by: usize,
    /// The lanes beyond their carried trusted distance.
    suspect: u32,
    /// Per suspect lane, where its winner's measurement constants are kept.
    known: [Known; 8],
}

/// The start and length in bytes of `v`, for [`prefetch_bytes`].
fn bytes<T>(v: &T) -> (*const u8, usize) {
    ((v as *const T).cast(), size_of_val(v))
}

#[cfg(test)]
mod tests;

//! `--precision auto`: the f32 packets decide every pixel, and each hit whose f32 distance cannot
//! be trusted to [`TOLERANCE`] is decided again in f64 for that pixel alone, with the oracle's
//! scalar kernel through the same acceleration structure (the tile list of the pixel, the BVH,
//! or every primitive), its constants computed from the scene's shapes as it reaches them
//! (`soa::SceneRecords`: bit for bit the oracle's, with no f64 copy of the scene kept).
//! A re-decided pixel gets the f64 id and depth, which are the oracle's.
//!
//! # When an f32 hit cannot be trusted
//!
//! `bounds.rs` derives, for each kernel, a first-order bound on the relative error of its f32
//! distance against the oracle's for the same primitive: the kernel's roundings plus the
//! difference between the pixel's f32 and f64 rays (`Camera::direction_error`). For polygons
//! it is `u (5.5 + (4 + a/u) t / p)` (`a`: the rays' angle, ~7u; grazing incidence fails); for
//! spheres it grows towards the silhouette and for spheres far larger than their distance to
//! the eye. Solved for `t` once per primitive in setup, they give the distances `[lo, hi]`
//! within which an f32 hit is trusted.
//!
//! # Checked before re-deciding
//!
//! The bounds are worst cases (every error of one sign, `sum |d_i N_i|` at its maximum 1); the
//! lab's axis-aligned `grazing` plane and scene 7's far-reaching triangle exceed them on many
//! pixels whose f32 distance is in fact good to ~1e-6. So a hit beyond its limits is first
//! measured rather than bounded (`Redecide::verified`): the oracle's own scalar kernel for that
//! one primitive, along that pixel's f64 ray, gives the oracle's distance `t64` for the same
//! primitive, and the hit is kept when `|t - t64| <= 0.9e-5 t64`: exactly the quantity the
//! guarantee bounds, measured to f64 precision. One primitive's test costs a fraction of a
//! re-decision's walk through the pixel's candidates. A polygon is measured by its plane: the
//! f32 edge decision is kept, since it differs from the oracle's only within its band (below),
//! whatever the depth. A sphere is measured with the oracle's kernel, and a ray it does not see
//! meeting the sphere (at its silhouette) is re-decided.
//!
//! Ids: a re-decided pixel takes the oracle's id. An f32 pixel that is not re-decided keeps
//! its id. It can differ from the oracle's only in two places:
//! - where an f32 edge test or sphere silhouette flips. An f32 polygon accepts rays up to 8u
//!   outside an edge plane, its dot product and rounded normal err by 4u, and the ray by `a`
//!   (`Camera::direction_error`), so within `12u + a` of the edge (1.1e-6 rad at 60 degrees);
//!   a silhouette moves by `6u + a`;
//! - where two hits are within the trusted error of each other (a genuine tie, 1e-5 relative).
//!
//! Primitives that subtend less than ~1e-6 rad lie wholly inside that band. Eye-relative f64
//! setup keeps scenes far from the origin as precise as near it (the lab's `translated`). So
//! neither needs a condition of its own. `tests/auto.rs` checks the guarantee against the
//! oracle, with every acceleration, on the stress scenes and on scenes written for each failure
//! class. It holds ids to the stricter band of 1e-6 rad, and they pass.
//!
//! Cost: the bounds are solved for `t` once per primitive in setup (12 bytes per primitive).
//! Through the tiles (the default) each lane carries the trusted distance of the primitive that
//! won it, one blend per entry tested, so a packet's check is one compare; through the BVH or
//! without acceleration the check looks each lane's limits up. A re-decision walks that
//! pixel's candidates in f64.

use crate::accel::bvh::{ranges_x4d, trace_bvh_x1, trace_bvh_x4d};
use crate::accel::{Bvh, Tiles};
use crate::camera::{Camera, RayTables};
use crate::kernel::Hit8;
use crate::kernel::methods::wide64::{Hit4d, dir_x4d};
use crate::kernel::polygon::{QuadK, TriangleK};
use crate::kernel::scalar::trace_x1;
use crate::kernel::sphere::SphereK;
use crate::scene::Scene;
use crate::soa::{Packed, Records, SceneRecords};
use rayon::prelude::*;
use std::cell::RefCell;
use wide::{f32x8, f64x4};

mod bounds;
mod verify;
pub use bounds::TOLERANCE;
use bounds::{BUDGET, Bounds};
use verify::Oracle;

/// What `--precision auto` needs beside the packet kernel's setup.
pub struct Redecide<'s> {
    scene: &'s Scene,
    camera_eye: glam::DVec3,
    /// Per scene id: the distances `[lo, hi]` between which an f32 hit on that primitive is
    /// trusted (the bounds above solved for `t` once per primitive; f32, rounded inward).
    limits: Vec<[f32; 2]>,
    /// A distance up to which a hit on any primitive is trusted (the least `hi`; -inf where
    /// one needs `lo`): a packet whose hits are all nearer skips the per-lane check.
    safe: f32,
    /// Per kind (sphere, triangle, quad), per index in the packed stores: the distance to
    /// carry with a lane that primitive wins ([`Redecide::carried`]).
    carried: [Vec<f32>; 3],
    /// The oracle's f64 ray tables, padded to whole 4x2 blocks (`dir_x1` is the oracle's ray).
    tables: RayTables<f64>,
}

/// Where a strip's re-decisions walk: the packet kernel's structure, over f64 records of its
/// stores computed when first reached and kept in a small cache (neighbouring re-decided pixels
/// mostly meet the same primitives).
pub(crate) struct Walk<'a> {
    records: Cached<'a>,
    /// The oracle's constants of the primitive last measured by [`Redecide::verified`], keyed
    /// by its id + 1 (0: none yet): neighbouring lanes mostly hit the same primitive.
    last: RefCell<(usize, Option<Oracle>)>,
    tiles: Option<&'a Tiles>,
    bvh: Option<&'a Bvh>,
}

/// From this many untrusted lanes in a packet on, its rows are decided again in f64x4 lanes
/// rather than one ray at a time.
const ROW_MIN: u32 = 2;

/// Slots per kind in a strip's record cache (direct-mapped by index).
const CACHE_SLOTS: usize = 256;

/// [`SceneRecords`] with a direct-mapped cache per kind: slot `i % CACHE_SLOTS` holds the
/// record of index `i` when its key is `i + 1`. Each kind's slots are allocated on its first
/// use, so a strip with nothing to re-decide allocates nothing.
struct Cached<'a> {
    inner: SceneRecords<'a>,
    triangles: Slots<TriangleK<f64>>,
    quads: Slots<QuadK<f64>>,
}

type Slots<K> = RefCell<Vec<(usize, Option<(K, i32)>)>>;

/// The cached record of index `i`, computed by `make` on a miss.
#[inline(always)]
fn cached<K: Copy>(
    slots: &Slots<K>,
    i: usize,
    make: impl FnOnce() -> Option<(K, i32)>,
) -> Option<(K, i32)> {
    let mut slots = slots.borrow_mut();
    if slots.is_empty() {
        slots.resize(CACHE_SLOTS, (0, None));
    }
    let slot = &mut slots[i % CACHE_SLOTS];
    if slot.0 != i + 1 {
        *slot = (i + 1, make());
    }
    slot.1
}

impl Records<f64> for Cached<'_> {
    fn counts(&self) -> [usize; 3] {
        self.inner.counts()
    }
    fn sphere(&self, i: usize) -> Option<(SphereK<f64>, i32)> {
        // a sphere's constants cost less to compute than to cache
        self.inner.sphere(i)
    }
    fn triangle(&self, i: usize) -> Option<(TriangleK<f64>, i32)> {
        cached(&self.triangles, i, || self.inner.triangle(i))
    }
    fn quad(&self, i: usize) -> Option<(QuadK<f64>, i32)> {
        cached(&self.quads, i, || self.inner.quad(i))
    }
}

impl<'s> Redecide<'s> {
    /// The trusted distances of every primitive of `packed` (which `scene` seen by `camera`
    /// was packed into), and the camera's f64 ray tables.
    pub fn new(scene: &'s Scene, camera: &Camera, packed: &Packed) -> Redecide<'s> {
        let bounds = Bounds::new(camera.direction_error());
        let mut limits = vec![[0.0, f32::INFINITY]; scene.shapes.len()];
        let s = &packed.spheres;
        let spheres: Vec<[f32; 2]> = (0..s.len())
            .into_par_iter()
            .map(|i| bounds.sphere([s.ocx[i], s.ocy[i], s.ocz[i]], s.r2[i], s.c[i]))
            .collect();
        for (&id, l) in s.id.iter().zip(spheres) {
            limits[id as usize] = l;
        }
        for (ids, p) in [
            (&packed.triangles.id, &packed.triangles.p),
            (&packed.quads.id, &packed.quads.p),
        ] {
            for (&id, &p) in ids.iter().zip(p) {
                limits[id as usize] = bounds.polygon(p);
            }
        }
        let ids: [&[f32]; 3] = [&packed.spheres.id, &packed.triangles.id, &packed.quads.id];
        // the least `hi` over the scene (-inf if any primitive needs `lo`): a packet whose hits
        // are all nearer needs no lookup (the BVH and no acceleration; tiles carry each lane's)
        let safe = ids
            .iter()
            .flat_map(|v| v.iter())
            .map(|&id| match limits[id as usize] {
                [lo, _] if lo > 0.0 => f32::NEG_INFINITY,
                [_, hi] => hi,
            })
            .fold(f32::INFINITY, f32::min);
        let carried = ids.map(|v| {
            v.par_iter()
                .map(|&id| match limits[id as usize] {
                    [lo, _] if lo > 0.0 => f32::NEG_INFINITY,
                    [_, hi] => hi,
                })
                .collect()
        });
        Redecide {
            scene,
            camera_eye: camera.eye,
            limits,
            safe,
            carried,
            tables: camera.tables(4, 2),
        }
    }

    /// The walk of one strip's re-decisions through `packed` and its structure.
    pub(crate) fn walk<'a>(
        &'a self,
        packed: &'a Packed,
        tiles: Option<&'a Tiles>,
        bvh: Option<&'a Bvh>,
    ) -> Walk<'a> {
        Walk {
            records: Cached {
                inner: SceneRecords::new(self.scene, packed, self.camera_eye),
                triangles: RefCell::new(Vec::new()),
                quads: RefCell::new(Vec::new()),
            },
            last: RefCell::new((0, None)),
            tiles,
            bvh,
        }
    }

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
        let (safe, inf) = (f32x8::splat(self.safe), f32x8::splat(f32::INFINITY));
        for (r, (ids, depth)) in ids
            .chunks_exact_mut(width)
            .zip(depth.chunks_exact_mut(width))
            .enumerate()
        {
            let y = y_start + r;
            // sixteen pixels per branch: the scan runs over every pixel of the image
            let suspects = |depth: &[f32], x0: usize| {
                let d = f32x8::new(depth[x0..x0 + 8].try_into().expect("8 pixels"));
                // background is +inf, and `safe` is below it
                (d.simd_gt(safe) & d.simd_lt(inf)).to_bitmask()
            };
            let (pairs, whole) = (width / 16 * 16, width / 8 * 8);
            for x0 in (0..pairs).step_by(16) {
                let (a, b) = (suspects(depth, x0), suspects(depth, x0 + 8));
                if a | b != 0 {
                    for (x0, suspect) in [(x0, a), (x0 + 8, b)] {
                        if suspect != 0 {
                            let run = (x0, x0 + 8, y);
                            self.fix_run(walk, run, ids, depth, suspect, width, mine);
                        }
                    }
                }
            }
            if pairs < whole {
                let suspect = suspects(depth, pairs);
                if suspect != 0 {
                    let run = (pairs, whole, y);
                    self.fix_run(walk, run, ids, depth, suspect, width, mine);
                }
            }
            if whole < width {
                let suspect = (whole..width)
                    .filter(|&x| depth[x] > self.safe && depth[x] < f32::INFINITY)
                    .fold(0, |m, x| m | 1 << (x - whole));
                if suspect != 0 {
                    let run = (whole, width, y);
                    self.fix_run(walk, run, ids, depth, suspect, width, mine);
                }
            }
        }
    }

    /// The rest of [`Redecide::fix_strip`] for the pixels `x0..x1` (at most eight) of row `y`
    /// of which `suspect` (bits from `x0`) lie beyond `safe`, in groups of four: kept out of
    /// the scan.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn fix_run(
        &self,
        walk: &Walk,
        (x0, x1, y): (usize, usize, usize),
        ids: &mut [i32],
        depth: &mut [f32],
        suspect: u32,
        width: usize,
        mine: &mut Vec<usize>,
    ) {
        let first = ids[x0 + suspect.trailing_zeros() as usize];
        if x1 - x0 == 8 && self.one_primitive(&ids[x0..x1], first, suspect) {
            // one primitive under every suspect pixel (the common case): one lookup, one
            // compare, and the oracle's constants fetched once for the eight
            let [lo, hi] = self
                .limits
                .get(first as usize)
                .copied()
                .unwrap_or([0.0, f32::INFINITY]);
            let d = f32x8::new(depth[x0..x0 + 8].try_into().expect("8 pixels"));
            let out = d.simd_lt(f32x8::splat(lo)) | d.simd_gt(f32x8::splat(hi));
            let untrusted = suspect & out.to_bitmask();
            if untrusted == 0 {
                return;
            }
            // both halves measured, whatever their lanes: two independent chains, no branch
            let k = self.oracle(walk, first as usize);
            let t: [f32; 8] = depth[x0..x0 + 8].try_into().expect("8 pixels");
            let half = |h: usize| std::array::from_fn(|i| t[4 * h + i]);
            let ok = self.verified_row(&k, (x0, y), half(0))
                | self.verified_row(&k, (x0 + 4, y), half(1)) << 4;
            let left = untrusted & !ok;
            for h in 0..2 {
                let lanes = (left >> (4 * h)) & 0xF;
                if lanes != 0 {
                    let (g, mut t, mut id) = (x0 + 4 * h, half(h), [first as f32; 4]);
                    self.redo_group(walk, (g, y), &mut t, &mut id, lanes);
                    self.write_back((g, y, width), (&t, &id), lanes, (ids, depth), mine);
                }
            }
            return;
        }
        for g in (x0..x1).step_by(4) {
            let lanes = (suspect >> (g - x0)) & 0xF;
            if lanes == 0 {
                continue;
            }
            let n = (x1 - g).min(4);
            let mut t = std::array::from_fn(|i| if i < n { depth[g + i] } else { 0.0 });
            let mut id = std::array::from_fn(|i| if i < n { ids[g + i] as f32 } else { -1.0 });
            let untrusted = self.outside(&t, &id, lanes);
            let redone = self.fix_group(walk, (g, y), &mut t, &mut id, untrusted);
            self.write_back((g, y, width), (&t, &id), redone, (ids, depth), mine);
        }
    }

    /// Whether every pixel of `suspect` (bits) among the eight `ids` holds primitive `first`
    /// (compared all eight at once).
    #[inline(always)]
    fn one_primitive(&self, ids: &[i32], first: i32, suspect: u32) -> bool {
        let ids: [i32; 8] = ids.try_into().expect("8 pixels");
        let same = (0..8).fold(0, |m, i| m | u32::from(ids[i] == first) << i);
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

    /// The lanes of `lanes` (bits) whose hit `t` lies outside the trusted distances of its
    /// primitive `id`: one lookup when they share a primitive (the common case).
    #[inline]
    fn outside(&self, t: &[f32; 4], id: &[f32; 4], lanes: u32) -> u32 {
        if lanes == 0 {
            return 0;
        }
        // ids are exact in f32 and below `limits.len()`
        let limit = |id: f32| {
            self.limits
                .get(id as usize)
                .copied()
                .unwrap_or([0.0, f32::INFINITY])
        };
        let first = id[lanes.trailing_zeros() as usize % 4];
        let one = (0..4).all(|i| lanes & (1 << i) == 0 || id[i] == first);
        let lim: [[f32; 2]; 4] = if one {
            [limit(first); 4]
        } else {
            std::array::from_fn(|i| limit(id[i]))
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

    /// Checks the hits of the packet at pixel `(bx, by)` (`bw` pixels wide, lanes in rows),
    /// traced with each lane's trusted distance carried along (`carried`: the `hi` of the
    /// primitive that won the lane, -inf where the primitive has a lower limit too;
    /// [`Redecide::carried`]), and decides again in f64 each lane that cannot be trusted.
    /// Returns the lanes re-decided, as a bit mask.
    #[inline]
    pub(crate) fn fix_packet_carried(
        &self,
        walk: &Walk,
        (bx, by, bw): (usize, usize, usize),
        hit: &mut Hit8,
        carried: f32x8,
    ) -> u32 {
        let hits = hit.id.simd_ge(f32x8::ZERO);
        let suspect = (hits & hit.t.simd_gt(carried)).to_bitmask();
        if suspect == 0 {
            return 0;
        }
        // beyond a finite carried `hi`, a lane is untrusted as it stands; -inf (a primitive
        // with a `lo`) needs its limits looked up
        let lookup = carried
            .simd_eq(f32x8::splat(f32::NEG_INFINITY))
            .to_bitmask()
            & suspect;
        self.fix_suspects(walk, (bx, by, bw), hit, (suspect & !lookup, lookup))
    }

    /// The rest of [`Redecide::fix_packet_carried`] for the lanes `untrusted` and `lookup`
    /// (bits: beyond their trusted distance, and to be checked against their limits), a group
    /// of four pixels at a time ([`Redecide::fix_group`]): kept out of the packet loop, which
    /// rarely comes here.
    #[cold]
    #[inline(never)]
    fn fix_suspects(
        &self,
        walk: &Walk,
        (bx, by, bw): (usize, usize, usize),
        hit: &mut Hit8,
        (untrusted, lookup): (u32, u32),
    ) -> u32 {
        let (mut t, mut id) = (hit.t.to_array(), hit.id.to_array());
        let mut redone = 0;
        for g in (0..8).step_by(4) {
            let (known, look) = ((untrusted >> g) & 0xF, (lookup >> g) & 0xF);
            if known | look == 0 {
                continue;
            }
            let mut gt: [f32; 4] = t[g..g + 4].try_into().expect("4 lanes");
            let mut gid: [f32; 4] = id[g..g + 4].try_into().expect("4 lanes");
            let untrusted = known | self.outside(&gt, &gid, look);
            // lanes g..g + 4 are one row of four pixels (blocks 4 or 8 wide)
            let at = (bx + g % bw, by + g / bw);
            let m = self.fix_group(walk, at, &mut gt, &mut gid, untrusted);
            if m != 0 {
                t[g..g + 4].copy_from_slice(&gt);
                id[g..g + 4].copy_from_slice(&gid);
                redone |= m << g;
            }
        }
        if redone != 0 {
            hit.t = f32x8::new(t);
            hit.id = f32x8::new(id);
        }
        redone
    }

    /// The trusted distance to carry for a lane won by primitive `index` of kind `kind`
    /// (0 sphere, 1 triangle, 2 quad): its `hi`, or -inf when it also has a `lo`.
    #[inline(always)]
    pub(crate) fn carried(&self, kind: usize, index: usize) -> f32 {
        self.carried[kind][index]
    }

    /// The oracle's hits for the pixels `x0..x0 + 4` of row `y` in the lanes of `lanes` (bits),
    /// in f64x4 lanes (`kernel::methods::wide64`, each lane the oracle's scalar answer bit for
    /// bit), depths rounded once to f32.
    fn trace_row(&self, walk: &Walk, (x0, y): (usize, usize), lanes: u32) -> ([f32; 4], [f32; 4]) {
        let t = &self.tables;
        let sx = f64x4::new(std::array::from_fn(|i| t.sx[x0 + i]));
        let d = dir_x4d(t, sx, f64x4::splat(t.sy[y]));
        let active = f64x4::new(std::array::from_fn(|i| (lanes >> i & 1) as f64));
        let mut hit = Hit4d::new(active.simd_gt(f64x4::ZERO));
        match (walk.tiles, walk.bvh) {
            (Some(tiles), _) => tiles.trace_x4d(&walk.records, [x0, x0 + 3, y], &d, &mut hit),
            (_, Some(bvh)) => trace_bvh_x4d(&walk.records, bvh, &d, &mut hit),
            _ => {
                let [s, tr, q] = walk.records.counts();
                ranges_x4d(&walk.records, [0..s, 0..tr, 0..q], &d, &mut hit)
            }
        }
        (
            hit.t.to_array().map(|v| v as f32),
            hit.id.to_array().map(|v| v as f32),
        )
    }

    /// The oracle's hit for pixel `(x, y)`: f64 through the walk's structure, depth rounded
    /// once to f32 (id -1 and +inf for none).
    fn trace(&self, walk: &Walk, (x, y): (usize, usize)) -> (f32, f32) {
        let d = self.tables.dir_x1(x, y);
        let h = match (walk.tiles, walk.bvh) {
            (Some(tiles), _) => tiles.trace_x1(&walk.records, (x, y), d),
            (_, Some(bvh)) => trace_bvh_x1(&walk.records, bvh, d),
            _ => trace_x1(&walk.records, d),
        };
        (h.t as f32, h.id as f32)
    }
}

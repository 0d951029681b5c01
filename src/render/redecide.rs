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
//! Cost: the bounds are solved for `t` once per primitive in setup (8 bytes per primitive),
//! and the measurement's plane is computed for each polygon the tiles mark (40 bytes per packed
//! polygon once any is marked).
//! Through the tiles (the default) each lane carries the trusted distance of the primitive that
//! won it, kept in the top 24 bits of the tile entry the walk already reads (`Tiles::attach`,
//! rounded down), one blend per entry tested, so a packet's check is one compare. Only the tiles
//! where some packet's hits may pass a trusted distance carry it: in setup, each entry's packets
//! are bounded by the exact distances their rays may meet the primitive at
//! (`PacketCones::ball_beyond`, `PacketCones::polygon_beyond`; `Redecide::attach_to`), and
//! a tile none of whose packets may exceed walks as `--precision f32` does. Through the
//! BVH or without acceleration a finished strip is scanned against the least trusted distance,
//! and only the pixels beyond it look their limits up (`check.rs`). A re-decision walks that
//! pixel's candidates in f64.

use crate::accel::bvh::{trace_bvh_x1, trace_bvh_x4d};
use crate::accel::{Bvh, Tiles};
use crate::camera::{Camera, RayTables};
use crate::kernel::wide64::{Hit4d, dir_x4d};
use crate::kernel::{Family, Sphere};
use crate::par::prelude::*;
use crate::scene::{Scene, Shape};
use crate::soa::trace::ranges_x4d;
use crate::soa::trace::trace_x1;
use crate::soa::{Columns, Packed, Records, SceneRecords, Stored, for_each_family};
use std::any::Any;
use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use wide::f64x4;

mod bounds;
mod check;
mod verify;
pub use bounds::TOLERANCE;
use bounds::{BUDGET, Bounds, Trusted, is_sharp};
use verify::Oracle;

/// What `--precision auto` needs beside the packet kernel's setup.
pub struct Redecide<'s> {
    scene: &'s Scene,
    camera_eye: glam::DVec3,
    /// Per scene id: the distances `[lo, hi]` between which an f32 hit on that primitive is
    /// trusted (the bounds above solved for `t` once per primitive; f32, rounded inward), as
    /// the bits of both in one cell ([`unpack`]): written at each primitive's id on all
    /// threads, read with relaxed loads (plain loads).
    limits: Vec<AtomicU64>,
    /// A distance up to which a hit on any primitive is trusted (the least `hi`; -inf where
    /// one needs `lo`): the strip scan looks up only the pixels beyond it.
    safe: f32,
    /// Per scene id, the index of that sphere in the packed sphere store (`u32::MAX`: not a
    /// sphere; empty when the scene has none), and per packed sphere, its centre and radius
    /// as the scene holds them: a suspect's sphere is read from a store in screen order, not
    /// from the scene's shapes in file order (a cache miss per suspect on 65,536 spheres).
    sphere_at: Vec<u32>,
    spheres: Vec<(glam::DVec3, f64)>,
    /// The measurement's constants of the polygons whose hits may pass their trusted
    /// distances (those `Tiles::attach` marks; [`Redecide::attach_to`]), per packed triangle
    /// and quad (empty until attached; all zeros for the others). A suspect's plane is read
    /// from here, asked for by its packed index as its packet is traced, rather than computed
    /// from the scene's shape: a miss on three cache lines (and often the page table) on
    /// 65,536 triangles. Kept compact: `plane_at` gives, per packed triangle and quad, the
    /// index of its plane here (`u32::MAX`: not marked; 4 bytes a polygon rather than 40).
    planes: [Vec<verify::Plane>; 2],
    plane_at: [Vec<u32>; 2],
    /// The oracle's f64 ray tables, padded to whole 4x2 blocks (`dir_x1` is the oracle's ray).
    tables: RayTables<f64>,
    /// What the last frame's tile path did ([`Work`]): packets walked, those that carried
    /// the trusted distance, hits measured.
    work: [AtomicUsize; 3],
}

/// The per-primitive buffers of a finished [`Redecide`], emptied, for the next view of the
/// same scene to fill rather than fresh memory ([`Redecide::new_in`], [`Redecide::into_spare`]).
#[derive(Debug, Default)]
pub(crate) struct Spare {
    limits: Vec<AtomicU64>,
    plane_at: [Vec<u32>; 2],
}

/// `[lo, hi]` from their bits in one cell of `Redecide::limits` (`lo` low, `hi` high).
#[inline(always)]
fn pack([lo, hi]: [f32; 2]) -> u64 {
    u64::from(lo.to_bits()) | u64::from(hi.to_bits()) << 32
}

/// The `[lo, hi]` a cell of `Redecide::limits` holds ([`pack`]).
#[inline(always)]
fn unpack(c: &AtomicU64) -> [f32; 2] {
    let c = c.load(Ordering::Relaxed);
    [f32::from_bits(c as u32), f32::from_bits((c >> 32) as u32)]
}

/// What `--precision auto` did on the tile path in a renderer's last frame
/// (`Renderer::auto_work`): how many 4x2 packets were walked, how many of them carried each
/// lane's trusted distance (the rest walked as `--precision f32` does), and how many hits were
/// measured against the oracle's distance for their own primitive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Work {
    /// 4x2 packets walked through the tiles.
    pub packets: usize,
    /// Of those, the packets that carried each lane's trusted distance.
    pub carrying: usize,
    /// Hits beyond their trusted distance, measured against the oracle's.
    pub measured: usize,
}

impl Redecide<'_> {
    /// Clears the counts of [`Work`] (at the start of a frame).
    pub(crate) fn reset_work(&self) {
        self.work.iter().for_each(|w| w.store(0, Ordering::Relaxed));
    }

    /// Adds a strip's counts to the frame's.
    pub(crate) fn add_work(&self, w: Work) {
        for (a, v) in self.work.iter().zip([w.packets, w.carrying, w.measured]) {
            a.fetch_add(v, Ordering::Relaxed);
        }
    }

    /// The last frame's counts.
    pub(crate) fn work(&self) -> Work {
        let [packets, carrying, measured] = self.work.each_ref().map(|a| a.load(Ordering::Relaxed));
        Work {
            packets,
            carrying,
            measured,
        }
    }
}

/// The trusted distance a lane won by a primitive with limits `[lo, hi]` carries: its `hi`, or
/// -inf when it has a `lo` too (the lane's limits are then looked up).
fn carry([lo, hi]: [f32; 2]) -> f32 {
    if lo > 0.0 { f32::NEG_INFINITY } else { hi }
}

/// Where a strip's re-decisions walk: the packet kernel's structure, over f64 records of its
/// stores computed when first reached and kept in a small cache (neighbouring re-decided pixels
/// mostly meet the same primitives).
pub(crate) struct Walk<'a> {
    records: Cached<'a>,
    /// The oracle's constants of the primitives measured so far ([`Redecide::oracle`]):
    /// direct-mapped, slot `id % ORACLE_SLOTS` keyed by `id + 1` (0: empty), allocated on the
    /// first measurement. A primitive's suspect pixels come back packet after packet along
    /// a strip, with other primitives' between them.
    oracles: RefCell<Vec<(usize, Option<Oracle>)>>,
    tiles: Option<&'a Tiles>,
    bvh: Option<&'a Bvh>,
}

/// From this many untrusted lanes in a packet on, its rows are decided again in f64x4 lanes
/// rather than one ray at a time.
const ROW_MIN: u32 = 2;

/// Slots of a strip's cache of the oracle's measurement constants (direct-mapped by id).
const ORACLE_SLOTS: usize = 64;

/// Slots per kind in a strip's record cache (direct-mapped by index).
const CACHE_SLOTS: usize = 256;

/// [`SceneRecords`] with a direct-mapped cache per kind: slot `i % CACHE_SLOTS` holds the
/// record of index `i` when its key is `i + 1`. Each kind's slots (a `Slots` of its family's
/// records) are allocated on its first use, so a strip with nothing to re-decide allocates
/// nothing. Spheres are not cached: their constants cost less to compute than to cache.
struct Cached<'a> {
    inner: SceneRecords<'a>,
    slots: [RefCell<Option<Box<dyn Any>>>; 3],
}

type Slots<K> = Vec<(usize, Option<(K, i32)>)>;

impl Records<f64> for Cached<'_> {
    fn counts(&self) -> [usize; 3] {
        self.inner.counts()
    }
    #[inline(always)]
    fn record<F: Stored>(&self, i: usize) -> Option<(F::K<f64>, i32)> {
        if F::KIND == Sphere::KIND {
            return self.inner.record::<F>(i);
        }
        let mut cell = self.slots[F::KIND].borrow_mut();
        let slots = cell
            .get_or_insert_with(|| {
                let fresh: Slots<F::K<f64>> = vec![(0, None); CACHE_SLOTS];
                Box::new(fresh)
            })
            .downcast_mut::<Slots<F::K<f64>>>()
            .expect("one family per kind");
        let slot = &mut slots[i % CACHE_SLOTS];
        if slot.0 != i + 1 {
            *slot = (i + 1, self.inner.record::<F>(i));
        }
        slot.1
    }
}

impl<'s> Redecide<'s> {
    /// The trusted distances of every primitive of `packed` (which `scene` seen by `camera`
    /// was packed into), and the camera's f64 ray tables.
    #[cfg(test)]
    pub(crate) fn new(scene: &'s Scene, camera: &Camera, packed: &Packed) -> Redecide<'s> {
        Redecide::new_in(scene, camera, packed, Spare::default())
    }

    /// `Redecide::new`, the per-primitive buffers written into `spare`'s.
    pub(crate) fn new_in(
        scene: &'s Scene,
        camera: &Camera,
        packed: &Packed,
        spare: Spare,
    ) -> Redecide<'s> {
        let Spare {
            mut limits,
            plane_at,
        } = spare;
        let sharp_sine = crate::kernel::f32_edge_band(camera) / camera.id_band();
        let bounds = Bounds::new(camera.direction_error(), sharp_sine);
        let s = &packed.spheres;
        // each primitive's limits written at its id, on all threads (the ids of the stores
        // are distinct: each cell is written once at most)
        limits.clear();
        limits.par_extend(
            (0..scene.shapes.len())
                .into_par_iter()
                .map(|_| AtomicU64::new(pack([0.0, f32::INFINITY]))),
        );
        let put = |id: f32, l: [f32; 2]| limits[id as usize].store(pack(l), Ordering::Relaxed);
        // each family's through the bound of its outline class
        for_each_family!(F => {
            let columns = F::columns(packed);
            let ids = Columns::<F>::ids(columns);
            let outline = |i: usize| F::outline(&Columns::<F>::get(columns, i));
            Trusted::each(&bounds, ids.len(), outline, |i, l| put(ids[i], l));
        });
        // the least `hi` over the scene (-inf if any primitive needs `lo`): a pixel nearer
        // needs no lookup (the strip scan: the BVH and no acceleration; tiles carry each lane's)
        let safe = (packed.ids().into_iter())
            .map(|v| {
                (v.par_iter())
                    .map(|&id| carry(unpack(&limits[id as usize])))
                    .reduce(|| f32::INFINITY, f32::min)
            })
            .fold(f32::INFINITY, f32::min);
        let mut sphere_at = vec![u32::MAX; if s.id.is_empty() { 0 } else { limits.len() }];
        for (i, &id) in s.id.iter().enumerate() {
            sphere_at[id as usize] = i as u32;
        }
        let spheres =
            s.id.par_iter()
                .map(|&id| match scene.shapes.get(id as usize) {
                    Shape::Sphere { center, radius } => (center, radius),
                    // not reached (the packed spheres are the scene's); NaN never verifies
                    _ => (glam::DVec3::NAN, f64::NAN),
                })
                .collect();
        Redecide {
            sphere_at,
            spheres,
            planes: [Vec::new(), Vec::new()],
            plane_at: plane_at.map(|mut v| {
                v.clear();
                v
            }),
            scene,
            camera_eye: camera.eye,
            limits,
            safe,
            tables: camera.tables(4, 2),
            work: Default::default(),
        }
    }

    /// The per-primitive buffers, for the next view's [`Redecide::new_in`].
    pub(crate) fn into_spare(self) -> Spare {
        Spare {
            limits: self.limits,
            plane_at: self.plane_at,
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
                slots: Default::default(),
            },
            oracles: RefCell::new(Vec::new()),
            tiles,
            bvh,
        }
    }

    /// Attaches to each primitive of `tiles` (built over `packed` for `camera`) the trusted
    /// distance a lane it wins carries ([`carry`]): the tile entries hand it to the packet walk
    /// with the lanes their primitive takes. Up to a trusted distance the f32 distances err by
    /// at most [`BUDGET`] against the oracle's (first order; [`TOLERANCE`] with the rest), so
    /// the tiles mark the packets that may exceed it by the exact hits their rays may have, and
    /// the others walk without carrying. The marked polygons' planes are computed here, once
    /// (`planes`).
    pub(crate) fn attach_to(&mut self, tiles: &mut Tiles, packed: &Packed, camera: &Camera) {
        let ids = packed.ids();
        let marked = tiles.attach(packed, camera, TOLERANCE, |kind, i| {
            carry(unpack(&self.limits[ids[kind][i] as usize]))
        });
        let polygons: Vec<_> = marked.into_iter().filter(|&(kind, _)| kind > 0).collect();
        if polygons.is_empty() {
            return;
        }
        let found: Vec<_> = polygons
            .par_iter()
            .map(|&(kind, i)| self.plane(self.scene.shapes.get(ids[kind][i] as usize)))
            .collect();
        // filled by the pool's threads, each first touching its own part (4 bytes a polygon:
        // 13 MB for 3.3M triangles), rather than by one
        let lens = [ids[1].len(), ids[2].len()];
        for (v, n) in self.plane_at.iter_mut().zip(lens) {
            v.clear();
            v.par_extend(crate::par::repeat_n(u32::MAX, n));
        }
        for (&(kind, i), plane) in polygons.iter().zip(found) {
            // (a polygon's shape is always one; a sharp one's plane is left all zeros: its hits
            // are decided again, `Redecide::make_oracle`)
            let sharp = is_sharp(unpack(&self.limits[ids[kind][i] as usize]));
            self.plane_at[kind - 1][i] = self.planes[kind - 1].len() as u32;
            self.planes[kind - 1].push(plane.filter(|_| !sharp).unwrap_or_default());
        }
    }

    /// Where the measurement's constants of the winner a packet's walk found, `(kind, index)`
    /// in the packed stores, are kept.
    #[inline(always)]
    fn known(&self, (kind, i): (usize, usize)) -> verify::Known {
        match kind {
            0 => verify::Known::Sphere(i as u32),
            _ => match self.plane_at[kind - 1].get(i) {
                Some(&at) if at != u32::MAX => verify::Known::Polygon(kind as u8, at),
                _ => verify::Known::Unknown,
            },
        }
    }

    /// The centre and radius of primitive `id` when it is a sphere.
    #[inline(always)]
    fn sphere(&self, id: usize) -> Option<(glam::DVec3, f64)> {
        match self.sphere_at.get(id) {
            Some(&at) if at != u32::MAX => Some(self.spheres[at as usize]),
            _ => None,
        }
    }

    /// The oracle's hits for the pixels `x0..x0 + 4` of row `y` in the lanes of `lanes` (bits),
    /// in f64x4 lanes (`kernel::wide64`, each lane the oracle's scalar answer bit for
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

//! Brute-force drivers for the lab's intersection methods ([`crate::method::Method`]): every ray
//! against every primitive, one thread, one method. Their loops are separate from lanecast's
//! renderer (which has acceleration structures), so the lab measures the intersection methods
//! alone.
//!
//! A [`Kit`] holds one method's constants for one scene and the camera's ray tables: for each
//! of lanecast's families, in kind order ([`FamilyList`] over lanecast's list of families), each
//! primitive's constants and id, for the method's own kernel of that family ([`Kernels::Own`],
//! `methods/`) or else lanecast's ([`Family::setup`], [`Family::cast`], [`Family::hit_x1`],
//! [`Family::hit_lanes`]); the families are traced in kind order, as lanecast's loops trace
//! them, so ties resolve alike. A family added to lanecast needs nothing here: every method
//! runs it through lanecast's kernel. [`Kit::render_x8`]
//! traces 4x2 pixel blocks as 8-lane packets (lanes past the image border masked, as in the
//! main renderer) and [`Kit::render_x1`] one ray at a time in f32 with the same method.
//! [`Oracle`] is the f64 scalar oracle. The f64x4 packet form of the default methods, which
//! takes the accelerations and every thread, is lanecast's `render::wide64::Kit64`
//! (`--precision f64`).

use crate::methods::{
    Direction, MtOwn, NaiveOwn, Own, PlaneOwn, Rays, WoopOwn, WoopRays, WorldOwn,
};
use glam::DVec3;
use lanecast::experimental::camera::RayTables;
use lanecast::experimental::kernel::packet::block_rays;
use lanecast::experimental::kernel::{Family, Hit, Hit8, LANES};
use lanecast::experimental::real::V3;
use lanecast::experimental::soa::Families;
use lanecast::experimental::soa::Prepared;
use lanecast::experimental::soa::trace::trace_x1;
use lanecast::scene::{Scene, Shape};
use lanecast::{Camera, Frame};
use wide::f32x8;

/// Pixel block of one packet, as in the main renderer: 4 wide, 2 high.
pub const BW: usize = 4;
/// Pixel block height: `LANES / BW` = 2 rows.
pub const BH: usize = LANES / BW;

/// A lab method as the drivers run it: the families it re-implements and the per-ray data
/// their kernels share.
pub trait Kernels: 'static {
    /// The per-ray data of its own kernels.
    type Rays: Rays;
    /// Its own kernels, one per family it re-implements ([`Own`], a tuple of up to three).
    type Own: OwnList<Self::Rays>;
}

/// lanecast's kernels for every family, with eye-relative f64 setup: the default methods.
pub struct Product;
impl Kernels for Product {
    type Rays = Direction;
    type Own = ();
}

/// Möller–Trumbore (`methods::mt`), lanecast's kernels for the other families.
pub struct Mt;
impl Kernels for Mt {
    type Rays = Direction;
    type Own = MtOwn;
}

/// Woop–Benthin–Wald watertight (`methods::woop`), lanecast's kernels for the other families.
pub struct Watertight;
impl Kernels for Watertight {
    type Rays = WoopRays;
    type Own = WoopOwn;
}

/// The seed's plane + determinants (`methods::plane`), lanecast's kernels for the other
/// families.
pub struct Plane;
impl Kernels for Plane {
    type Rays = Direction;
    type Own = PlaneOwn;
}

/// The textbook sphere (`methods::sphere_naive`), lanecast's kernels for the other families.
pub struct Naive;
impl Kernels for Naive {
    type Rays = Direction;
    type Own = NaiveOwn;
}

/// lanecast's kernels with f32 world-space setup (`methods::world`) for the families it
/// computes, eye-relative f64 setup for the others.
pub struct WorldF32;
impl Kernels for WorldF32 {
    type Rays = Direction;
    type Own = WorldOwn;
}

/// A list of families, `(F, (G, ... ()))` in kind order, with the stores a method's [`Kit`]
/// keeps for them: one [`FamilyStore`] each, traced one after the other, every loop
/// monomorphic.
pub trait FamilyList: 'static {
    /// The stores of the list's families for method `M`.
    type Stores<M: Kernels>: Send + Sync;
    /// Empty stores.
    fn stores<M: Kernels>() -> Self::Stores<M>;
    /// Adds `shape` with its id to its family's store, unless it covers no pixel from `eye`.
    fn push<M: Kernels>(s: &mut Self::Stores<M>, shape: Shape, id: f32, eye: DVec3);
    /// The eight rays `d` against every store, in list order, nearest hits folded into `hit`;
    /// `r` holds the method's per-packet data once an own kernel has computed it.
    fn x8<M: Kernels>(
        s: &Self::Stores<M>,
        d: &[f32x8; 3],
        r: &mut Option<<M::Rays as Rays>::R8>,
        hit: &mut Hit8,
    );
    /// The ray `d` against every store, in list order; `r` as in [`FamilyList::x8`].
    fn x1<M: Kernels>(
        s: &Self::Stores<M>,
        d: V3<f32>,
        r: &mut Option<<M::Rays as Rays>::R1>,
        hit: &mut Hit<f32>,
    );
}

impl FamilyList for () {
    type Stores<M: Kernels> = ();
    fn stores<M: Kernels>() {}
    fn push<M: Kernels>(_: &mut (), _: Shape, _: f32, _: DVec3) {}
    #[inline(always)]
    fn x8<M: Kernels>(_: &(), _: &[f32x8; 3], _: &mut Option<<M::Rays as Rays>::R8>, _: &mut Hit8) {
    }
    #[inline(always)]
    fn x1<M: Kernels>(_: &(), _: V3<f32>, _: &mut Option<<M::Rays as Rays>::R1>, _: &mut Hit<f32>) {
    }
}

impl<F: Family, Rest: FamilyList> FamilyList for (F, Rest) {
    type Stores<M: Kernels> = (FamilyStore<F, M>, Rest::Stores<M>);
    fn stores<M: Kernels>() -> Self::Stores<M> {
        let own = M::Own::stores();
        (
            FamilyStore {
                product: Vec::new(),
                own,
            },
            Rest::stores::<M>(),
        )
    }
    fn push<M: Kernels>(s: &mut Self::Stores<M>, shape: Shape, id: f32, eye: DVec3) {
        if shape.kind() != F::KIND {
            Rest::push::<M>(&mut s.1, shape, id, eye);
        } else if !M::Own::push::<F>(&mut s.0.own, shape, id, eye)
            && let Some(k) = F::geometry(shape).and_then(|g| F::setup(&g, eye))
        {
            s.0.product.push((F::cast(&k), id));
        }
    }
    #[inline(always)]
    fn x8<M: Kernels>(
        s: &Self::Stores<M>,
        d: &[f32x8; 3],
        r: &mut Option<<M::Rays as Rays>::R8>,
        hit: &mut Hit8,
    ) {
        if M::Own::owns::<F>() {
            M::Own::x8::<F>(&s.0.own, d, r, hit);
        } else {
            for (k, id) in &s.0.product {
                if let Some((m, t)) = F::hit_lanes(k, d) {
                    hit.update(m, t, *id);
                }
            }
        }
        Rest::x8::<M>(&s.1, d, r, hit);
    }
    #[inline(always)]
    fn x1<M: Kernels>(
        s: &Self::Stores<M>,
        d: V3<f32>,
        r: &mut Option<<M::Rays as Rays>::R1>,
        hit: &mut Hit<f32>,
    ) {
        if M::Own::owns::<F>() {
            M::Own::x1::<F>(&s.0.own, d, r, hit);
        } else {
            for (k, id) in &s.0.product {
                if let Some(t) = F::hit_x1(k, d) {
                    hit.update(t, *id as i32);
                }
            }
        }
        Rest::x1::<M>(&s.1, d, r, hit);
    }
}

/// Family `F`'s primitives for method `M`: lanecast's constants rounded to f32 with their ids
/// (`product`), or, when `M` re-implements `F`, the constants of its own kernel for `F`, kept
/// in `own` (which holds one list per own kernel of `M`, the others empty).
pub struct FamilyStore<F: Family, M: Kernels> {
    product: Vec<(F::K<f32>, f32)>,
    own: <M::Own as OwnList<M::Rays>>::Stores,
}

/// A method's own kernels ([`Kernels::Own`]): a tuple of [`Own`] kernels sharing per-ray data
/// `R`, each for a different family, and their primitives' constants with ids.
pub trait OwnList<R: Rays>: 'static {
    /// One list of constants and ids per kernel.
    type Stores: Send + Sync;
    /// Empty lists.
    fn stores() -> Self::Stores;
    /// Whether a kernel of the list re-implements family `F`.
    fn owns<F: Family>() -> bool;
    /// Adds `shape` (of family `F`) with its id to the list of the kernel re-implementing `F`,
    /// unless it covers no pixel from `eye`; false when no kernel re-implements `F`.
    fn push<F: Family>(s: &mut Self::Stores, shape: Shape, id: f32, eye: DVec3) -> bool;
    /// The eight rays `d` against the primitives of the kernel re-implementing `F`, computing
    /// the per-packet data `r` if it is not yet.
    fn x8<F: Family>(s: &Self::Stores, d: &[f32x8; 3], r: &mut Option<R::R8>, hit: &mut Hit8);
    /// The ray `d` against the primitives of the kernel re-implementing `F`.
    fn x1<F: Family>(s: &Self::Stores, d: V3<f32>, r: &mut Option<R::R1>, hit: &mut Hit<f32>);
}

/// [`OwnList`] for tuples of up to three kernels: the first whose family is `F`.
macro_rules! own_list {
    ($($o:ident $i:tt),*) => {
        impl<R: Rays, $($o: Own<Rays = R>),*> OwnList<R> for ($($o,)*) {
            type Stores = ($(Vec<($o::K, f32)>,)*);
            fn stores() -> Self::Stores {
                Default::default()
            }
            #[inline(always)]
            fn owns<F: Family>() -> bool {
                false $(|| $o::Family::KIND == F::KIND)*
            }
            #[allow(unused_variables)]
            fn push<F: Family>(s: &mut Self::Stores, shape: Shape, id: f32, eye: DVec3) -> bool {
                $(
                    if $o::Family::KIND == F::KIND {
                        let g = <$o::Family as Family>::geometry(shape);
                        if let Some(k) = g.and_then(|g| $o::setup(&g, eye)) {
                            s.$i.push((k, id));
                        }
                        return true;
                    }
                )*
                false
            }
            #[inline(always)]
            #[allow(unused_variables)]
            fn x8<F: Family>(s: &Self::Stores, d: &[f32x8; 3], r: &mut Option<R::R8>, hit: &mut Hit8) {
                $(
                    if $o::Family::KIND == F::KIND {
                        if s.$i.is_empty() {
                            return;
                        }
                        let r = r.get_or_insert_with(|| R::ray8(d));
                        for (k, id) in &s.$i {
                            if let Some((m, t)) = $o::x8(k, r) {
                                hit.update(m, t, *id);
                            }
                        }
                        return;
                    }
                )*
            }
            #[allow(unused_variables)]
            fn x1<F: Family>(s: &Self::Stores, d: V3<f32>, r: &mut Option<R::R1>, hit: &mut Hit<f32>) {
                $(
                    if $o::Family::KIND == F::KIND {
                        let r = r.get_or_insert_with(|| R::ray1(d));
                        for (k, id) in &s.$i {
                            if let Some(t) = $o::x1(k, r) {
                                hit.update(t, *id as i32);
                            }
                        }
                        return;
                    }
                )*
            }
        }
    };
}
own_list!();
own_list!(A 0);
own_list!(A 0, B 1);
own_list!(A 0, B 1, C 2);

/// One method's constants for one scene, with the camera's f32 ray tables.
pub struct Kit<M: Kernels> {
    /// Each of lanecast's families, in kind order: its primitives' constants and ids, in file
    /// order (those the kernel drops are left out).
    stores: <Families as FamilyList>::Stores<M>,
    /// The camera's f32 ray tables, padded to whole 4x2 blocks.
    pub tables: RayTables<f32>,
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
}

impl<M: Kernels> Kit<M> {
    /// The method's constants for every shape of `scene` seen by `camera` (the setup phase).
    pub fn new(scene: &Scene, camera: &Camera) -> Self {
        let eye = camera.eye;
        let mut stores = Families::stores::<M>();
        for (id, shape) in scene.shapes.iter().enumerate() {
            Families::push::<M>(&mut stores, shape, id as f32, eye);
        }
        Kit {
            stores,
            tables: camera.tables(BW as u32, BH as u32),
            width: camera.width as usize,
            height: camera.height as usize,
        }
    }

    /// Nearest hits of eight rays, folded into `hit`.
    #[inline]
    pub fn trace_x8(&self, d: &[f32x8; 3], hit: &mut Hit8) {
        Families::x8::<M>(&self.stores, d, &mut None, hit);
    }

    /// Nearest hit of one ray.
    pub fn trace_x1(&self, d: V3<f32>) -> Hit<f32> {
        let mut hit = Hit::NONE;
        Families::x1::<M>(&self.stores, d, &mut None, &mut hit);
        hit
    }

    /// The image in 4x2 packets, on the calling thread.
    pub fn render_x8(&self) -> Frame<f64> {
        let (w, h) = (self.width, self.height);
        let mut f = Frame::new(w as u32, h as u32, f64::INFINITY);
        for by in (0..h).step_by(BH) {
            for bx in (0..w).step_by(BW) {
                let (d, active) = block_rays::<BW>(&self.tables, bx, by, w, h);
                let mut hit = Hit8::new(active);
                self.trace_x8(&d, &mut hit);
                let (t, id) = (hit.t.to_array(), hit.id.to_array());
                for lane in 0..LANES {
                    let (x, y) = (bx + lane % BW, by + lane / BW);
                    if x < w && y < h {
                        f.ids[y * w + x] = id[lane] as i32;
                        f.depth[y * w + x] = t[lane] as f64;
                    }
                }
            }
        }
        f
    }

    /// The image one ray at a time (f32, same method).
    pub fn render_x1(&self) -> Frame<f64> {
        let (w, h) = (self.width, self.height);
        let mut f = Frame::new(w as u32, h as u32, f64::INFINITY);
        for y in 0..h {
            for x in 0..w {
                let hit = self.trace_x1(self.tables.dir_x1(x, y));
                f.ids[y * w + x] = hit.id;
                f.depth[y * w + x] = hit.t as f64;
            }
        }
        f
    }
}

/// The f64 scalar oracle, exactly as `lanecast --kernel scalar` computes it (`soa::Prepared<f64>`
/// and `soa::trace::trace_x1`), one ray at a time on the calling thread.
pub struct Oracle {
    /// Every primitive's f64 constants.
    pub prepared: Prepared<f64>,
    /// The camera's f64 ray tables, one entry per column and row.
    pub tables: RayTables<f64>,
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
}

impl Oracle {
    /// The f64 constants and ray tables of `scene` seen by `camera` (the setup phase).
    pub fn new(scene: &Scene, camera: &Camera) -> Oracle {
        Oracle {
            prepared: Prepared::new(scene, camera.eye),
            tables: camera.tables(1, 1),
            width: camera.width as usize,
            height: camera.height as usize,
        }
    }

    /// Nearest hit along unit direction `d` from the eye, in f64.
    pub fn trace(&self, d: V3<f64>) -> Hit<f64> {
        trace_x1(&self.prepared, d)
    }

    /// The image one ray at a time, on the calling thread.
    pub fn render(&self) -> Frame<f64> {
        let (w, h) = (self.width, self.height);
        let mut f = Frame::new(w as u32, h as u32, f64::INFINITY);
        for y in 0..h {
            for x in 0..w {
                let hit = self.trace(self.tables.dir_x1(x, y));
                f.ids[y * w + x] = hit.id;
                f.depth[y * w + x] = hit.t;
            }
        }
        f
    }
}

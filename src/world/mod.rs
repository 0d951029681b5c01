//! The world engine (`--accel world`): a scene prepared once, independent of any camera, then
//! rendered from any number of cameras at a cost that follows what each view sees.
//!
//! [`World::new`] (once per scene) gathers every primitive into flat, camera-independent arrays,
//! one store per family, kept as the family's class draws it (`kernel::family::Class`): for a
//! family of convex polygons (triangles, quads: `Polygon`), the vertices once (a mesh's shared
//! vertices stay shared) and each polygon as vertex indices with its id; for any other family
//! (spheres: `Bounded`), each primitive with its bounding sphere and id. It owns its arrays (it
//! borrows nothing from the scene), so it is `Send + Sync` and shared in an `Arc` by any number
//! of threads, views and fronts. Nothing here names a family: each one's code is written once
//! per class, over the families `soa::for_each_family!` and `soa::with_family!` list.
//!
//! A view ([`World::render`]) works in object order, as a rasteriser does, in four passes:
//! 1. every vertex made eye-relative (`V - eye` in f64, rounded to f32 once: a vertex shared by
//!    several polygons is the same f32 vector in each) and projected to pixel coordinates;
//! 2. each cluster of up to 64 polygons (`clusters.rs`) and each primitive of a bounded family
//!    (a sphere) binned into bands of [`BAND`] rows by its bounding sphere's pixel box; a cluster whose polygons all face away
//!    from the eye (by its normal cone) is *deferred*;
//! 3. each band (on its own thread) takes its clusters' polygons one by one: the pixel centres
//!    inside its projected outline (a 2D test in pixel coordinates, with a margin wider than
//!    every error of the projection and of the edge tolerance, so it only leaves out pixels
//!    the exact test would reject), then its f32 setup (`setup.rs`: edge planes through the
//!    eye, the plane, and a written bound on their error) and the exact test at those pixels,
//!    keeping the nearest hit per pixel. Front clusters go nearest first; a polygon facing
//!    away from the eye waits until every polygon facing it is drawn, and is then passed over
//!    where every pixel it may cover already holds a trusted hit nearer than its nearest point
//!    (on a closed mesh, the back faces); so is a whole cluster, front or deferred, whose box
//!    is covered so (`raster::band` says why this cannot change an answer);
//! 4. the pixels the f32 answer cannot be trusted at (the bound, below) are decided again in f64
//!    with the oracle's own constants and kernels (each family's `Family::setup` and
//!    `Family::hit_x1`), among every primitive binned there: the oracle's answer there, bit for
//!    bit.
//!
//! What is trusted: a primitive is *tight* when its f32 distance is within [`T_TIGHT`] relative
//! of the exact one and its edge planes within [`EDGE_TIGHT`] radians (`setup.rs` derives both
//! from the primitive's distance to its plane). Two tight primitives that f32 orders wrongly are
//! within 1e-5 relative in f64 (a tie), a tight depth is within 1e-5, and a tight edge errs
//! inside the documented boundary band. A pixel where a loose primitive's widened test passes
//! and its distance could beat the winner's is re-decided; so is every pixel a primitive of a
//! bounded family (a sphere) may cover.
//! With `Precision::F64` every pixel is decided in f64 (the oracle); with `Precision::F32`
//! none is.
//!
//! A pixel's result depends only on the scene, the camera, the size and the precision: the
//! nearest-hit rule (smaller t, then lower id) and the re-decision rule (a minimum over every
//! candidate) do not depend on the order primitives arrive in, nor on the thread count.

mod clusters;
mod raster;
mod setup;

use crate::camera::Camera;
use crate::frame::Frame;
use crate::kernel::Family;
use crate::kernel::family::{Bounded, Class, Polygon};
use crate::par::prelude::*;
use crate::scene::{KINDS, Mesh, PartRef, Scene, Shape};
use crate::soa::{Stored, Visit, for_each_family, visit};
use clusters::{Cluster, Morton, Renumber};
use glam::DVec3;

/// Rows per band: the unit of binning and of parallel work. A cluster's box is about as tall
/// as 16 rows on a dense scan at 1080p; at 32 it reaches into fewer bands (a quarter fewer
/// polygon visits than at 16) while a 1080p view still has 34 bands to share out.
pub const BAND: usize = 32;

/// Relative distance error below which an f32 hit is trusted (`setup.rs`): twice it stays
/// under the 1e-5 tie tolerance and it is under the 1e-5 depth guarantee.
pub const T_TIGHT: f64 = 0.4e-5;

/// Edge-plane error (radians) below which a polygon's f32 inside test is trusted: inside the
/// id band `compare` excuses (`Camera::id_band`) of every view `--precision auto` draws in f32
/// (`kernel::f32_resolves`: its id band is at least twice the f32 kernels' 1.1e-6).
pub const EDGE_TIGHT: f64 = 1.5e-6;

/// How a view is decided: the product's one [`Precision`](crate::Precision).
pub use crate::precision::Precision;

/// A scene prepared once for any camera: see the module comment.
#[derive(Debug)]
pub struct World {
    /// Every polygon vertex, f64, world space.
    verts: Vec<DVec3>,
    /// Each family's primitives, by kind (`scene::KINDS` order).
    stores: Vec<Store>,
    /// The items (clusters, bounded primitives) are numbered kind by kind: `first[k]` is kind
    /// `k`'s first, `first[KINDS.len()]` their number.
    first: [usize; KINDS.len() + 1],
}

/// One family's primitives, kept as its class draws them ([`Family::class`]).
#[derive(Debug)]
pub(crate) enum Store {
    /// A family of convex polygons ([`Polygon`]).
    Polygons(Polys),
    /// A family drawn through bounding spheres ([`Bounded`]).
    Bounded(Others),
}

/// A polygon family's polygons, in the spatial order of `clusters::order`.
#[derive(Debug, Default)]
pub(crate) struct Polys {
    /// Vertex indices into `World::verts`: the family's edge count `N` of them per polygon.
    idx: Vec<u32>,
    /// Ids.
    ids: Vec<i32>,
    /// Each polygon's shape factor (`setup::shape`).
    shape: Vec<f32>,
    /// Clusters of consecutive polygons (`clusters.rs`).
    clusters: Vec<Cluster>,
}

impl Polys {
    /// Polygon `i`'s vertex indices, `N` being its family's edge count.
    #[inline(always)]
    fn vertices<const N: usize>(&self, i: usize) -> [u32; N] {
        let v = &self.idx[i * N..i * N + N];
        std::array::from_fn(|k| v[k])
    }
}

/// A bounded family's primitives, in file order.
#[derive(Debug, Default)]
pub(crate) struct Others {
    /// Each primitive as the scene gives it.
    shapes: Vec<Shape>,
    /// Its bounding sphere ([`Bounded::bound`]): centre and radius.
    bounds: Vec<(DVec3, f64)>,
    /// Ids.
    ids: Vec<i32>,
}

impl Others {
    /// Primitive `j`'s geometry, `F` being the store's family.
    #[inline(always)]
    fn geometry<F: Family>(&self, j: usize) -> F::Geometry {
        F::geometry(self.shapes[j]).expect("a family's store holds shapes of that family")
    }
}

/// A view's working buffers, reused from view to view ([`World::render_with`]).
#[derive(Debug, Default)]
pub struct Scratch {
    /// Each vertex relative to the eye, rounded to f32.
    rel: Vec<[f32; 3]>,
    /// Each vertex's pixel coordinates and the cosine of its angle to the view axis.
    proj: Vec<[f32; 3]>,
    /// Per chunk of items, per band: the items binned there, front first (`false`) or
    /// deferred (`true`: a cluster facing away from the eye).
    bins: Vec<Vec<Vec<(u32, bool)>>>,
    /// Each band's per-pixel state.
    bands: Vec<raster::Band>,
}

/// Items (clusters, bounded primitives) per binning chunk.
const CHUNK: usize = 1 << 10;

/// One unit of binning, with its family's kind and its index among that family's items.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Item<'w> {
    /// A cluster of polygons.
    Cluster(usize, usize, &'w Cluster),
    /// A primitive of a bounded family, with its bounding sphere (centre, radius).
    Bounded(usize, usize, DVec3, f64),
}

/// An empty store for a family of each class.
struct Empty;

impl<F: Family> Class<F> for Empty {
    type Out = Store;
    fn polygon<const N: usize>(self) -> Store
    where
        F: Polygon<N>,
    {
        Store::Polygons(Polys::default())
    }
    fn bounded(self) -> Store
    where
        F: Bounded,
    {
        Store::Bounded(Others::default())
    }
}

/// Appends a loose shape, `g` as its family's geometry, to its family's store (a polygon's
/// vertices to `verts`).
struct AddShape<'w, F: Family> {
    g: F::Geometry,
    shape: Shape,
    id: usize,
    verts: &'w mut Vec<DVec3>,
    stores: &'w mut [Store],
}

impl<F: Family> Class<F> for AddShape<'_, F> {
    type Out = ();
    fn polygon<const N: usize>(self)
    where
        F: Polygon<N>,
    {
        let Store::Polygons(p) = &mut self.stores[F::KIND] else {
            unreachable!("a polygon family's store")
        };
        let b = self.verts.len() as u32;
        self.verts.extend_from_slice(&self.g);
        p.idx.extend((0..N as u32).map(|k| b + k));
        p.ids.push(self.id as i32);
    }
    fn bounded(self)
    where
        F: Bounded,
    {
        let Store::Bounded(o) = &mut self.stores[F::KIND] else {
            unreachable!("a bounded family's store")
        };
        o.shapes.push(self.shape);
        o.bounds.push(F::bound(&self.g));
        o.ids.push(self.id as i32);
    }
}

/// [`AddShape`] for the family of a shape ([`visit`]).
struct AddLoose<'w> {
    shape: Shape,
    id: usize,
    verts: &'w mut Vec<DVec3>,
    stores: &'w mut [Store],
}

impl Visit<()> for AddLoose<'_> {
    fn visit<F: Stored>(self, g: F::Geometry) {
        F::class(AddShape::<F> {
            g,
            shape: self.shape,
            id: self.id,
            verts: self.verts,
            stores: self.stores,
        })
    }
}

/// Appends a mesh's faces, whose ids start at `first`, to the store of their family (the
/// family [`visit`] gives its first face), its vertices to `verts` (shared vertices stay
/// shared).
struct AddMesh<'w> {
    mesh: &'w Mesh,
    first: usize,
    verts: &'w mut Vec<DVec3>,
    stores: &'w mut [Store],
}

impl Visit<()> for AddMesh<'_> {
    fn visit<F: Stored>(self, _: F::Geometry) {
        F::class(self)
    }
}

impl<F: Family> Class<F> for AddMesh<'_> {
    type Out = ();
    fn polygon<const N: usize>(self)
    where
        F: Polygon<N>,
    {
        let Store::Polygons(p) = &mut self.stores[F::KIND] else {
            unreachable!("a polygon family's store")
        };
        let faces = self.mesh.faces.as_flattened();
        assert_eq!(
            faces.len(),
            self.mesh.len() * N,
            "a mesh's faces have N vertices"
        );
        let base = self.verts.len() as u32;
        self.verts.extend_from_slice(&self.mesh.vertices);
        p.idx.par_extend(faces.par_iter().map(|&v| v + base));
        let first = self.first;
        p.ids.par_extend(
            (0..self.mesh.len())
                .into_par_iter()
                .map(|f| (first + f) as i32),
        );
    }
    fn bounded(self)
    where
        F: Bounded,
    {
        unreachable!("a mesh's faces are polygons")
    }
}

/// A polygon family's store made ready for views: its polygons in spatial order
/// (`clusters::order`), their shape factors and clusters, then their vertex indices
/// renumbered (`clusters::Renumber`; the vertices themselves are reordered once every family
/// has been).
struct Ready<'w> {
    store: &'w mut Store,
    verts: &'w [DVec3],
    morton: &'w Morton,
    renumber: &'w mut Renumber,
}

impl<F: Family> Class<F> for Ready<'_> {
    type Out = ();
    fn polygon<const N: usize>(self)
    where
        F: Polygon<N>,
    {
        let Store::Polygons(p) = self.store else {
            unreachable!("a polygon family's store")
        };
        let verts = self.verts;
        clusters::order::<N>(&mut p.idx, &mut p.ids, verts, self.morton);
        p.shape = (p.idx.as_chunks::<N>().0.par_iter())
            .map(|v| setup::shape::<F, N>(&v.map(|i| verts[i as usize])))
            .collect();
        p.clusters = clusters::build::<F, N>(verts, &p.idx);
        self.renumber.polygons(&mut p.idx);
    }
    fn bounded(self)
    where
        F: Bounded,
    {
    }
}

impl World {
    /// Prepares `scene` for any camera (in parallel on the current rayon pool).
    pub fn new(scene: &Scene) -> World {
        let mut verts = Vec::new();
        let mut stores = Vec::with_capacity(KINDS.len());
        for_each_family!(F => {
            debug_assert_eq!(stores.len(), F::KIND);
            stores.push(F::class(Empty));
        });
        let mut id = 0usize;
        for part in scene.shapes.parts() {
            match part {
                PartRef::Mesh(mesh) => {
                    if !mesh.is_empty() {
                        let (verts, stores) = (&mut verts, &mut stores[..]);
                        let add = AddMesh {
                            mesh,
                            first: id,
                            verts,
                            stores,
                        };
                        visit(scene.shapes.get(id), add);
                    }
                    id += mesh.len();
                }
                PartRef::Loose(shapes) => {
                    for &shape in shapes {
                        let (verts, stores) = (&mut verts, &mut stores[..]);
                        visit(
                            shape,
                            AddLoose {
                                shape,
                                id,
                                verts,
                                stores,
                            },
                        );
                        id += 1;
                    }
                }
            }
        }
        debug_assert_eq!(id, scene.shapes.len());
        let morton = Morton::new(&verts);
        let mut renumber = Renumber::new(verts.len());
        for_each_family!(F => F::class(Ready {
            store: &mut stores[F::KIND],
            verts: &verts,
            morton: &morton,
            renumber: &mut renumber,
        }));
        let verts = renumber.vertices(&verts);
        let mut first = [0; KINDS.len() + 1];
        for (k, store) in stores.iter().enumerate() {
            first[k + 1] = first[k]
                + match store {
                    Store::Polygons(p) => p.clusters.len(),
                    Store::Bounded(o) => o.ids.len(),
                };
        }
        World {
            verts,
            stores,
            first,
        }
    }

    /// Bytes held by the prepared arrays.
    pub fn bytes(&self) -> usize {
        let store = |s: &Store| match s {
            Store::Polygons(p) => {
                (p.idx.len() + p.ids.len() + p.shape.len()) * 4
                    + p.clusters.len() * std::mem::size_of::<Cluster>()
            }
            Store::Bounded(o) => o.ids.len() * (std::mem::size_of::<(Shape, (DVec3, f64), i32)>()),
        };
        self.verts.len() * 24 + self.stores.iter().map(store).sum::<usize>()
    }

    /// Renders one view with fresh working buffers.
    pub fn render(&self, camera: &Camera, precision: Precision) -> Frame<f32> {
        self.render_with(camera, precision, &mut Scratch::default())
    }

    /// Renders one view, reusing `scratch` (any earlier view's): the same frame as
    /// [`World::render`].
    pub fn render_with(
        &self,
        camera: &Camera,
        precision: Precision,
        scratch: &mut Scratch,
    ) -> Frame<f32> {
        self.render_marking(camera, precision, scratch, None).0
    }

    /// [`World::render_with`], also giving the pixels decided in f64 (row-major, ascending),
    /// and filling `spare`'s buffers when it has the camera's size.
    pub fn render_marking(
        &self,
        camera: &Camera,
        precision: Precision,
        scratch: &mut Scratch,
        spare: Option<Frame<f32>>,
    ) -> (Frame<f32>, Vec<usize>) {
        let precision = match precision {
            // a telephoto view: the f32 kernels' edge band is a sizeable part of a pixel
            Precision::Auto if !crate::kernel::f32_resolves(camera) => Precision::F64,
            p => p,
        };
        let view = raster::View::new(camera);
        self.project(&view, scratch);
        self.bin(&view, scratch);
        let mut frame = Frame::reuse(spare, camera.width, camera.height, f32::INFINITY);
        let redone = raster::bands(self, &view, scratch, precision, &mut frame);
        (frame, redone)
    }

    /// Pass 1: every vertex relative to the eye (f32) and its pixel position.
    fn project(&self, view: &raster::View, s: &mut Scratch) {
        let eye = view.eye;
        s.rel.clear();
        s.rel.par_extend(self.verts.par_iter().map(|v| {
            let r = *v - eye;
            [r.x as f32, r.y as f32, r.z as f32]
        }));
        s.proj.clear();
        s.proj
            .par_extend(s.rel.par_iter().map(|r| view.project(*r)));
    }

    /// Item `i`: the items of each kind in turn, a polygon family's clusters or a bounded
    /// family's primitives.
    #[inline]
    pub(crate) fn item(&self, i: usize) -> Item<'_> {
        let kind = self.first[1..].partition_point(|&end| end <= i);
        let j = i - self.first[kind];
        match &self.stores[kind] {
            Store::Polygons(p) => Item::Cluster(kind, j, &p.clusters[j]),
            Store::Bounded(o) => {
                let (c, r) = o.bounds[j];
                Item::Bounded(kind, j, c, r)
            }
        }
    }

    /// The store of the polygon family of kind `kind`.
    #[inline(always)]
    pub(crate) fn polys(&self, kind: usize) -> &Polys {
        match &self.stores[kind] {
            Store::Polygons(p) => p,
            Store::Bounded(_) => unreachable!("a polygon family's store"),
        }
    }

    /// The store of the bounded family of kind `kind`.
    #[inline(always)]
    pub(crate) fn others(&self, kind: usize) -> &Others {
        match &self.stores[kind] {
            Store::Bounded(o) => o,
            Store::Polygons(_) => unreachable!("a bounded family's store"),
        }
    }

    /// Pass 2: each item's pixel box (its bounding sphere's), binned into bands, chunk by
    /// chunk; clusters facing away from the eye binned as deferred.
    fn bin(&self, view: &raster::View, s: &mut Scratch) {
        let total = self.first[KINDS.len()];
        let chunks = total.div_ceil(CHUNK);
        let bands = view.bands();
        s.bins.resize_with(chunks, Vec::new);
        s.bins.truncate(chunks);
        s.bins.par_iter_mut().enumerate().for_each(|(c, bins)| {
            bins.resize_with(bands, Vec::new);
            bins.truncate(bands);
            bins.iter_mut().for_each(Vec::clear);
            for i in c * CHUNK..((c + 1) * CHUNK).min(total) {
                let (b, deferred) = match self.item(i) {
                    Item::Cluster(_, _, k) => {
                        (view.ball_box(k.centre, k.radius), k.faces_away(view.eye))
                    }
                    Item::Bounded(_, _, c, r) => (view.ball_box(c, r), false),
                };
                if let Some(b) = b {
                    let bands = b[2] as usize / BAND..=b[3] as usize / BAND;
                    for list in &mut bins[bands] {
                        list.push((i as u32, deferred));
                    }
                }
            }
        });
    }
}

#[cfg(test)]
mod tests;

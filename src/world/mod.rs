//! The world engine (`--accel world`): a scene prepared once, independent of any camera, then
//! rendered from any number of cameras at a cost that follows what each view sees.
//!
//! [`World::new`] (once per scene) gathers every primitive into flat, camera-independent arrays:
//! the polygons' vertices once (a mesh's shared vertices stay shared), each triangle and quad as
//! vertex indices with its id, the spheres. It owns its arrays (it borrows nothing from the
//! scene), so it is `Send + Sync` and shared in an `Arc` by any number of threads, views and
//! fronts.
//!
//! A view ([`World::render`]) works in object order, as a rasteriser does, in four passes:
//! 1. every vertex made eye-relative (`V - eye` in f64, rounded to f32 once: a vertex shared by
//!    several polygons is the same f32 vector in each) and projected to pixel coordinates;
//! 2. each cluster of up to 64 polygons (`clusters.rs`) and each sphere binned into bands of
//!    [`BAND`] rows by its bounding sphere's pixel box; a cluster whose polygons all face away
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
//!    with the oracle's own constants and kernels (`kernel::polygon`, `kernel::sphere`), among
//!    every primitive binned there: the oracle's answer there, bit for bit.
//!
//! What is trusted: a primitive is *tight* when its f32 distance is within [`T_TIGHT`] relative
//! of the exact one and its edge planes within [`EDGE_TIGHT`] radians (`setup.rs` derives both
//! from the primitive's distance to its plane). Two tight primitives that f32 orders wrongly are
//! within 1e-5 relative in f64 (a tie), a tight depth is within 1e-5, and a tight edge errs
//! inside the documented boundary band. A pixel where a loose primitive's widened test passes
//! and its distance could beat the winner's is re-decided; so is every pixel a sphere may cover.
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
use crate::par::prelude::*;
use crate::scene::{Scene, Shape};
use clusters::Cluster;
use glam::DVec3;

/// Rows per band: the unit of binning and of parallel work. A cluster's box is about as tall
/// as 16 rows on a dense scan at 1080p; at 32 it reaches into fewer bands (a quarter fewer
/// polygon visits than at 16) while a 1080p view still has 34 bands to share out.
pub const BAND: usize = 32;

/// Relative distance error below which an f32 hit is trusted (`setup.rs`): twice it stays
/// under the 1e-5 tie tolerance and it is under the 1e-5 depth guarantee.
pub const T_TIGHT: f64 = 0.4e-5;

/// Edge-plane error (radians) below which a polygon's f32 inside test is trusted: inside the
/// boundary band `compare` excuses (`compare::EDGE_BAND`).
pub const EDGE_TIGHT: f64 = 1.5e-6;

/// How a view is decided: the product's one [`Precision`](crate::Precision).
pub use crate::precision::Precision;

/// A scene prepared once for any camera: see the module comment.
#[derive(Debug)]
pub struct World {
    /// Every polygon vertex, f64, world space.
    verts: Vec<DVec3>,
    /// Triangles: vertex indices and ids.
    tris: Vec<[u32; 3]>,
    tri_ids: Vec<i32>,
    /// Quads: vertex indices and ids.
    quads: Vec<[u32; 4]>,
    quad_ids: Vec<i32>,
    /// Spheres: centre, radius, id.
    spheres: Vec<(DVec3, f64, i32)>,
    /// Each polygon's shape factor (`setup::shape`), parallel to `tris` and `quads`.
    tri_shape: Vec<f32>,
    quad_shape: Vec<f32>,
    /// Clusters of consecutive triangles, then of quads (`clusters.rs`).
    tri_clusters: Vec<Cluster>,
    quad_clusters: Vec<Cluster>,
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

/// Items (clusters, spheres) per binning chunk.
const CHUNK: usize = 1 << 10;

/// One unit of binning: a cluster of triangles or quads, or a sphere.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Item {
    Tris(Cluster),
    Quads(Cluster),
    Sphere(DVec3, f64, i32),
}

impl World {
    /// Prepares `scene` for any camera (in parallel on the current rayon pool).
    pub fn new(scene: &Scene) -> World {
        let mut verts = Vec::new();
        let (mut tris, mut tri_ids) = (Vec::new(), Vec::new());
        let (mut quads, mut quad_ids) = (Vec::new(), Vec::new());
        let mut spheres = Vec::new();
        let mut id = 0usize;
        for part in scene.shapes.parts() {
            match part {
                crate::scene::PartRef::Mesh(mesh) => {
                    let base = verts.len() as u32;
                    verts.extend_from_slice(&mesh.vertices);
                    tris.par_extend(mesh.faces.par_iter().map(|f| f.map(|v| v + base)));
                    let first = id;
                    tri_ids.par_extend(
                        (0..mesh.faces.len())
                            .into_par_iter()
                            .map(|f| (first + f) as i32),
                    );
                    id += mesh.faces.len();
                }
                crate::scene::PartRef::Loose(shapes) => {
                    for shape in shapes {
                        match *shape {
                            Shape::Sphere { center, radius } => {
                                spheres.push((center, radius, id as i32))
                            }
                            Shape::Triangle(v) => {
                                let b = verts.len() as u32;
                                verts.extend_from_slice(&v);
                                tris.push([b, b + 1, b + 2]);
                                tri_ids.push(id as i32);
                            }
                            Shape::Quad(v) => {
                                let b = verts.len() as u32;
                                verts.extend_from_slice(&v);
                                quads.push([b, b + 1, b + 2, b + 3]);
                                quad_ids.push(id as i32);
                            }
                        }
                        id += 1;
                    }
                }
            }
        }
        debug_assert_eq!(id, scene.shapes.len());
        clusters::sort(
            &mut verts,
            &mut tris,
            &mut tri_ids,
            &mut quads,
            &mut quad_ids,
        );
        let shape = |v: &[u32]| -> [DVec3; 4] {
            std::array::from_fn(|i| verts[v[i.min(v.len() - 1)] as usize])
        };
        let tri_shape = (tris.par_iter())
            .map(|t| {
                let v = shape(t);
                setup::shape(&[v[0], v[1], v[2]])
            })
            .collect();
        let quad_shape = quads.par_iter().map(|q| setup::shape(&shape(q))).collect();
        let tri_clusters = clusters::build(&verts, &tris);
        let quad_clusters = clusters::build(&verts, &quads);
        World {
            verts,
            tris,
            tri_ids,
            quads,
            quad_ids,
            spheres,
            tri_shape,
            quad_shape,
            tri_clusters,
            quad_clusters,
        }
    }

    /// Bytes held by the prepared arrays.
    pub fn bytes(&self) -> usize {
        self.verts.len() * 24
            + self.tris.len() * 20
            + self.quads.len() * 24
            + self.spheres.len() * std::mem::size_of::<(DVec3, f64, i32)>()
            + (self.tri_clusters.len() + self.quad_clusters.len()) * std::mem::size_of::<Cluster>()
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

    fn items(&self) -> usize {
        self.tri_clusters.len() + self.quad_clusters.len() + self.spheres.len()
    }

    /// Item `i`: triangle clusters, then quad clusters, then spheres.
    #[inline]
    pub(crate) fn item(&self, i: usize) -> Item {
        let (ct, cq) = (self.tri_clusters.len(), self.quad_clusters.len());
        if i < ct {
            Item::Tris(self.tri_clusters[i])
        } else if i < ct + cq {
            Item::Quads(self.quad_clusters[i - ct])
        } else {
            let (c, r, id) = self.spheres[i - ct - cq];
            Item::Sphere(c, r, id)
        }
    }

    /// Pass 2: each item's pixel box (its bounding sphere's), binned into bands, chunk by
    /// chunk; clusters facing away from the eye binned as deferred.
    fn bin(&self, view: &raster::View, s: &mut Scratch) {
        let total = self.items();
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
                    Item::Tris(k) | Item::Quads(k) => {
                        (view.sphere_box(k.centre, k.radius), k.faces_away(view.eye))
                    }
                    Item::Sphere(c, r, _) => (view.sphere_box(c, r), false),
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

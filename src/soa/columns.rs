//! The f32 structure-of-arrays stores the 8-lane kernels read ([`Packed`]): one column per
//! constant, one store per type, built straight from the scene on all threads and rearranged
//! as an acceleration structure asks (`super::Order`).

use super::{Columns, Group, IdSet, Order, Prepared, gather};
use crate::kernel::Family;
use crate::kernel::polygon::{PolyK, QuadK, TriangleK};
use crate::kernel::sphere::{Sphere, SphereK};
use crate::kernel::triangle_setup::triangles_x4;
use crate::par::prelude::*;
use crate::scene::{Scene, Shape};
use glam::DVec3;

/// Spheres as f32 columns.
#[derive(Debug, Clone, Default)]
pub struct Spheres {
    /// Centre minus eye, x.
    pub ocx: Vec<f32>,
    /// Centre minus eye, y.
    pub ocy: Vec<f32>,
    /// Centre minus eye, z.
    pub ocz: Vec<f32>,
    /// Radius squared.
    pub r2: Vec<f32>,
    /// |centre - eye|^2 - radius^2, computed in f64 and rounded.
    pub c: Vec<f32>,
    /// Eye inside or on the sphere (c <= 0).
    pub inside: Vec<bool>,
    /// Primitive ids as f32 (exact below 2^24 = `limits::MAX_PRIMITIVES`).
    pub id: Vec<f32>,
}

impl Spheres {
    fn new(g: &Group<SphereK<f64>>) -> Spheres {
        let k: Vec<SphereK<f32>> = g.k.iter().map(|k| k.cast()).collect();
        Spheres {
            ocx: k.iter().map(|k| k.oc[0]).collect(),
            ocy: k.iter().map(|k| k.oc[1]).collect(),
            ocz: k.iter().map(|k| k.oc[2]).collect(),
            r2: k.iter().map(|k| k.r2).collect(),
            c: k.iter().map(|k| k.c).collect(),
            inside: k.iter().map(|k| k.inside).collect(),
            id: g.id.iter().map(|&i| i as f32).collect(),
        }
    }

    /// The f32 columns (all but `inside`).
    fn floats(&mut self) -> [&mut Vec<f32>; 6] {
        let Spheres {
            ocx,
            ocy,
            ocz,
            r2,
            c,
            id,
            ..
        } = self;
        [ocx, ocy, ocz, r2, c, id]
    }

    /// Every column emptied, its allocation kept.
    fn clear(&mut self) {
        self.floats().into_iter().for_each(Vec::clear);
        self.inside.clear();
    }

    /// Number of spheres.
    pub fn len(&self) -> usize {
        self.id.len()
    }

    /// True when there is no sphere.
    pub fn is_empty(&self) -> bool {
        self.id.is_empty()
    }

    /// Appends one sphere's constants.
    fn push(&mut self, k: &SphereK<f32>, id: f32) {
        self.ocx.push(k.oc[0]);
        self.ocy.push(k.oc[1]);
        self.ocz.push(k.oc[2]);
        self.r2.push(k.r2);
        self.c.push(k.c);
        self.inside.push(k.inside);
        self.id.push(id);
    }

    /// Room for exactly `n` more spheres in every column.
    fn reserve(&mut self, n: usize) {
        self.floats()
            .into_iter()
            .for_each(|col| col.reserve_exact(n));
        self.inside.reserve_exact(n);
    }

    /// Appends every sphere of `other`.
    fn append(&mut self, o: &Spheres) {
        self.ocx.extend_from_slice(&o.ocx);
        self.ocy.extend_from_slice(&o.ocy);
        self.ocz.extend_from_slice(&o.ocz);
        self.r2.extend_from_slice(&o.r2);
        self.c.extend_from_slice(&o.c);
        self.inside.extend_from_slice(&o.inside);
        self.id.extend_from_slice(&o.id);
    }

    /// Rearranged to `order` ([`Order`]), or kept with `None`.
    fn permute(&mut self, order: Option<&Vec<u32>>) {
        let Some(order) = order else { return };
        gather(self.floats(), order);
        gather([&mut self.inside], order);
    }

    /// Sphere `i`'s constants, gathered from the columns.
    #[inline(always)]
    pub fn get(&self, i: usize) -> SphereK<f32> {
        SphereK {
            oc: [self.ocx[i], self.ocy[i], self.ocz[i]],
            r2: self.r2[i],
            c: self.c[i],
            inside: self.inside[i],
        }
    }
}

/// Convex polygons with `N` edges (triangles: 3, quads: 4) as f32 columns: the x, y and z
/// column of each edge normal, of the plane normal, and the plane distance.
#[derive(Debug, Clone)]
pub struct Polygons<const N: usize> {
    /// Unit edge plane normals: `n[e][c]` is component c (x, y, z) of edge e's normal.
    pub n: [[Vec<f32>; 3]; N],
    /// Unit plane normal, pointing away from the eye: x, y and z columns.
    pub nrm: [Vec<f32>; 3],
    /// Distance from the eye to the polygon's plane (> 0).
    pub p: Vec<f32>,
    /// Primitive ids as f32 (exact below 2^24).
    pub id: Vec<f32>,
}

impl<const N: usize> Default for Polygons<N> {
    fn default() -> Self {
        Polygons {
            n: std::array::from_fn(|_| Default::default()),
            nrm: Default::default(),
            p: Vec::new(),
            id: Vec::new(),
        }
    }
}

impl<const N: usize> Polygons<N> {
    fn new(g: &Group<PolyK<f64, N>>) -> Polygons<N> {
        let k: Vec<PolyK<f32, N>> = g.k.iter().map(|k| k.cast()).collect();
        let col = |f: &dyn Fn(&PolyK<f32, N>) -> f32| k.iter().map(f).collect::<Vec<f32>>();
        Polygons {
            n: std::array::from_fn(|e| std::array::from_fn(|c| col(&|k| k.n[e][c]))),
            nrm: std::array::from_fn(|c| col(&|k| k.nrm[c])),
            p: col(&|k| k.p),
            id: g.id.iter().map(|&i| i as f32).collect(),
        }
    }

    /// Every column: the edge normals', the plane normal's, `p` and `id`.
    fn columns(&mut self) -> impl Iterator<Item = &mut Vec<f32>> {
        let cols = self.n.iter_mut().flatten().chain(&mut self.nrm);
        cols.chain([&mut self.p, &mut self.id])
    }

    /// Every column emptied, its allocation kept.
    fn clear(&mut self) {
        self.columns().for_each(Vec::clear);
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.id.len()
    }

    /// True when there is no polygon.
    pub fn is_empty(&self) -> bool {
        self.id.is_empty()
    }

    /// Appends one polygon's constants.
    fn push(&mut self, k: &PolyK<f32, N>, id: f32) {
        for (col, n) in self.n.iter_mut().zip(&k.n) {
            (0..3).for_each(|c| col[c].push(n[c]));
        }
        (0..3).for_each(|c| self.nrm[c].push(k.nrm[c]));
        self.p.push(k.p);
        self.id.push(id);
    }

    /// Room for exactly `n` more polygons in every column.
    fn reserve(&mut self, n: usize) {
        self.columns().for_each(|col| col.reserve_exact(n));
    }

    /// Appends every polygon of `other`.
    fn append(&mut self, other: &Polygons<N>) {
        for (col, o) in self.n.iter_mut().zip(&other.n) {
            (0..3).for_each(|c| col[c].extend_from_slice(&o[c]));
        }
        (0..3).for_each(|c| self.nrm[c].extend_from_slice(&other.nrm[c]));
        self.p.extend_from_slice(&other.p);
        self.id.extend_from_slice(&other.id);
    }

    /// Rearranged to `order` ([`Order`]), or kept with `None`.
    fn permute(&mut self, order: Option<&Vec<u32>>) {
        let Some(order) = order else { return };
        gather(self.columns(), order);
    }

    /// Polygon `i`'s constants, gathered from the columns.
    #[inline(always)]
    pub fn get(&self, i: usize) -> PolyK<f32, N> {
        PolyK {
            n: std::array::from_fn(|e| [self.n[e][0][i], self.n[e][1][i], self.n[e][2][i]]),
            nrm: [self.nrm[0][i], self.nrm[1][i], self.nrm[2][i]],
            p: self.p[i],
        }
    }
}

impl Columns<Sphere> for Spheres {
    #[inline(always)]
    fn get(&self, i: usize) -> SphereK<f32> {
        Spheres::get(self, i)
    }
    #[inline(always)]
    fn id(&self, i: usize) -> f32 {
        self.id[i]
    }
    #[inline(always)]
    fn len(&self) -> usize {
        Spheres::len(self)
    }
}

/// Triangles (`N` = 3) and quads (`N` = 4) alike: any family whose constants are an `N`-edge
/// polygon's.
impl<F: Family<K<f32> = PolyK<f32, N>>, const N: usize> Columns<F> for Polygons<N> {
    #[inline(always)]
    fn get(&self, i: usize) -> PolyK<f32, N> {
        Polygons::get(self, i)
    }
    #[inline(always)]
    fn id(&self, i: usize) -> f32 {
        self.id[i]
    }
    #[inline(always)]
    fn len(&self) -> usize {
        Polygons::len(self)
    }
}

/// Up to four triangles waiting for [`triangles_x4`], with their ids.
#[derive(Default)]
struct Four {
    v: [[DVec3; 3]; 4],
    id: [f32; 4],
    n: usize,
}

impl Four {
    /// Adds one triangle; with four, their constants go to `store`.
    #[inline]
    fn add(&mut self, v: [DVec3; 3], id: f32, store: &mut Polygons<3>, eye: DVec3) {
        (self.v[self.n], self.id[self.n]) = (v, id);
        self.n += 1;
        if self.n == 4 {
            self.flush(store, eye);
        }
    }

    /// The constants of the triangles waiting, in their order, to `store`.
    fn flush(&mut self, store: &mut Polygons<3>, eye: DVec3) {
        if self.n == 0 {
            return;
        }
        // (unused lanes repeat the first triangle, and are dropped)
        for k in self.n..4 {
            self.v[k] = self.v[0];
        }
        let ks = triangles_x4(&self.v, eye);
        for (k, id) in ks.iter().zip(self.id).take(self.n) {
            if let Some(k) = k {
                store.push(&k.cast(), id);
            }
        }
        self.n = 0;
    }
}

/// All primitives as f32 structure-of-arrays stores, one per type.
#[derive(Debug, Clone, Default)]
pub struct Packed {
    /// Sphere columns.
    pub spheres: Spheres,
    /// Triangle columns (3 edge planes).
    pub triangles: Polygons<3>,
    /// Quad columns (4 edge planes).
    pub quads: Polygons<4>,
}

impl Packed {
    /// The scene ids of each kind's primitives, in store order: spheres, triangles, quads
    /// (the kinds numbered 0, 1, 2, as the tiles number them).
    #[inline]
    pub fn ids(&self) -> [&[f32]; 3] {
        [&self.spheres.id, &self.triangles.id, &self.quads.id]
    }

    /// The stores of `scene` seen from `eye`, built straight from the shapes on all threads,
    /// with no f64 copy kept: chunks of shapes are prepared in parallel (the same
    /// `SphereK::new`/`PolyK` constructors and f32 rounding as [`Prepared::new`] and
    /// [`Packed::new`], so the columns are identical), then joined in file order.
    pub fn from_scene(scene: &Scene, eye: DVec3) -> Packed {
        Packed::from_scene_in(scene, eye, Packed::default(), None)
    }

    /// [`Packed::from_scene`] written into `out`'s columns, emptied first: their allocations
    /// are kept, so stores rebuilt for another eye of the same scene (a view of many) fill
    /// memory already in use rather than fresh pages. The columns are those `from_scene` gives.
    /// The primitives of `left_out` are not stored.
    pub fn from_scene_in(
        scene: &Scene,
        eye: DVec3,
        mut out: Packed,
        left_out: Option<&IdSet>,
    ) -> Packed {
        const CHUNK: usize = 1 << 14;
        // Batches of a few chunks per thread: the parts of one batch are joined (and freed)
        // before the next is prepared, so the stores exist about once at any time, not twice.
        // The columns are allocated once, for every shape of their type (edge-on polygons,
        // left out, are rare), so they never move or grow.
        let batch_len = CHUNK * (4 * crate::par::current_num_threads()).max(16);
        // (the primitives left out need no room)
        let most = scene.shapes.len() - left_out.map_or(0, IdSet::len);
        let [spheres, triangles, quads] = scene.counts();
        let (spheres, triangles, quads) = (spheres.min(most), triangles.min(most), quads.min(most));
        out.spheres.clear();
        out.triangles.clear();
        out.quads.clear();
        out.spheres.reserve(spheres);
        out.triangles.reserve(triangles);
        out.quads.reserve(quads);
        for batch in (0..scene.shapes.len()).step_by(batch_len) {
            let ids = batch..(batch + batch_len).min(scene.shapes.len());
            let parts: Vec<Packed> = (scene.shapes.par_chunks(ids, CHUNK))
                .map(|(first, shapes)| {
                    let mut part = Packed::default();
                    // triangles four at a time (`triangles_x4`: the same constants), the
                    // others one by one; each store keeps its shapes' order
                    let mut four = Four::default();
                    let mut add = |id: usize, shape: Shape| match shape {
                        Shape::Triangle(v) => four.add(v, id as f32, &mut part.triangles, eye),
                        other => part.push(other, id as f32, eye),
                    };
                    match left_out {
                        None => shapes.enumerate().for_each(|(j, s)| add(first + j, s)),
                        // only the runs of ids kept are read
                        Some(set) => {
                            for run in set.gaps(first..first + shapes.len()) {
                                let at = run.start;
                                let kept = scene.shapes.range(run).enumerate();
                                kept.for_each(|(j, s)| add(at + j, s));
                            }
                        }
                    }
                    four.flush(&mut part.triangles, eye);
                    part
                })
                .collect();
            for part in &parts {
                out.spheres.append(&part.spheres);
                out.triangles.append(&part.triangles);
                out.quads.append(&part.quads);
            }
        }
        out
    }

    /// Appends `shape`'s constants seen from `eye` with id `id`, unless it is a polygon seen
    /// edge-on (or, as the kernels' constructors refuse, has an edge too short to resolve).
    #[inline]
    fn push(&mut self, shape: Shape, id: f32, eye: DVec3) {
        match shape {
            Shape::Sphere { center, radius } => self
                .spheres
                .push(&SphereK::new(center, radius, eye).cast(), id),
            Shape::Triangle(v) => {
                if let Some(k) = TriangleK::triangle(&v, eye) {
                    self.triangles.push(&k.cast(), id)
                }
            }
            Shape::Quad(v) => {
                if let Some(k) = QuadK::quad(&v, eye) {
                    self.quads.push(&k.cast(), id)
                }
            }
        }
    }

    /// Every column's memory beyond its length given back (the next view's columns grow
    /// again where they need to).
    pub(crate) fn shrink_to_fit(&mut self) {
        self.spheres
            .floats()
            .into_iter()
            .for_each(Vec::shrink_to_fit);
        self.spheres.inside.shrink_to_fit();
        self.triangles.columns().for_each(Vec::shrink_to_fit);
        self.quads.columns().for_each(Vec::shrink_to_fit);
    }

    /// Rearranged to `order`.
    pub fn permute(&mut self, order: &Order) {
        self.spheres.permute(order[0].as_ref());
        self.triangles.permute(order[1].as_ref());
        self.quads.permute(order[2].as_ref());
    }

    /// The stores of prepared f64 constants, rounded to f32.
    pub fn new(p: &Prepared<f64>) -> Packed {
        Packed {
            spheres: Spheres::new(&p.spheres),
            triangles: Polygons::new(&p.triangles),
            quads: Polygons::new(&p.quads),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{CameraSpec, Mesh, Shapes};

    #[test]
    fn packed_columns_round_trip_the_f32_records() {
        let scene = Scene {
            source: "t.sc".into(),
            camera: CameraSpec {
                eye: DVec3::new(0.0, 0.0, 5.0),
                look: DVec3::ZERO,
                up: DVec3::Y,
                lens: None,
            },
            shapes: vec![
                Shape::Triangle([DVec3::X, DVec3::Y, DVec3::ZERO]),
                Shape::Sphere {
                    center: DVec3::ONE,
                    radius: 0.5,
                },
                Shape::Quad([
                    DVec3::new(0.0, 0.0, 0.0),
                    DVec3::new(1.0, 0.0, 0.0),
                    DVec3::new(1.0, 1.0, 0.0),
                    DVec3::new(0.0, 1.0, 0.0),
                ]),
                // edge-on from the eye: left out
                Shape::Triangle([DVec3::ZERO, DVec3::Z, DVec3::X]),
            ]
            .into(),
            warnings: Vec::new(),
        };
        let p = Prepared::new(&scene, scene.camera.eye);
        let f = p.cast::<f32>();
        let packed = Packed::new(&p);
        assert_eq!(f.spheres.id, vec![1]);
        assert_eq!(f.triangles.id, vec![0]);
        assert_eq!(f.quads.id, vec![2]);
        assert_eq!(packed.spheres.get(0), f.spheres.k[0]);
        assert_eq!(packed.triangles.get(0), f.triangles.k[0]);
        assert_eq!(packed.quads.get(0), f.quads.k[0]);
        assert_eq!(packed.quads.id, vec![2.0]);
        // The parallel path, over several chunks, gives the same columns, with the triangles
        // loose or in a mesh.
        let mut big = scene.clone();
        let loose: Vec<Shape> = scene.shapes.iter().collect();
        big.shapes = loose.repeat(10_000).into();
        let direct = Packed::from_scene(&big, big.camera.eye);
        let serial = Packed::new(&Prepared::new(&big, big.camera.eye));
        assert_eq!(direct.triangles.len(), 10_000);
        assert_eq!(format!("{direct:?}"), format!("{serial:?}"));
        let mut mesh = Mesh::default();
        for shape in &loose {
            if let Shape::Triangle(v) = shape {
                let n = mesh.vertices.len() as u32;
                mesh.vertices.extend(v);
                mesh.faces.push([n, n + 1, n + 2]);
            }
        }
        let mut meshed = Shapes::new();
        for _ in 0..10_000 {
            meshed.push(loose[1], 2);
            meshed.push_mesh(mesh.clone(), 1);
            meshed.push(loose[2], 3);
        }
        big.shapes = meshed;
        let direct = Packed::from_scene(&big, big.camera.eye);
        let serial = Packed::new(&Prepared::new(&big, big.camera.eye));
        assert_eq!(direct.triangles.len(), 10_000);
        assert_eq!(direct.triangles.id[1], 5.0);
        assert_eq!(format!("{direct:?}"), format!("{serial:?}"));
    }
}

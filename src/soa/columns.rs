//! The f32 structure-of-arrays stores the 8-lane kernels read ([`Packed`]): one column per
//! constant, one store per type, built straight from the scene on all threads and rearranged
//! as an acceleration structure asks (`super::Order`).

use super::{Columns, IdSet, Order, Packed, Prepared, Stored, Visit, gather};
use crate::kernel::Family;
use crate::kernel::polygon::PolyK;
use crate::kernel::sphere::{Sphere, SphereK};
use crate::par::prelude::*;
use crate::scene::{KINDS, Scene, Shape};
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
    fn ids(&self) -> &[f32] {
        &self.id
    }
    #[inline]
    fn push(&mut self, k: &SphereK<f32>, id: f32) {
        Spheres::push(self, k, id)
    }
    fn clear(&mut self) {
        Spheres::clear(self)
    }
    fn reserve(&mut self, n: usize) {
        Spheres::reserve(self, n)
    }
    fn append(&mut self, other: &Spheres) {
        Spheres::append(self, other)
    }
    fn permute(&mut self, order: Option<&Vec<u32>>) {
        Spheres::permute(self, order)
    }
    fn shrink_to_fit(&mut self) {
        self.floats().into_iter().for_each(Vec::shrink_to_fit);
        self.inside.shrink_to_fit();
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
    fn ids(&self) -> &[f32] {
        &self.id
    }
    #[inline]
    fn push(&mut self, k: &PolyK<f32, N>, id: f32) {
        Polygons::push(self, k, id)
    }
    fn clear(&mut self) {
        Polygons::clear(self)
    }
    fn reserve(&mut self, n: usize) {
        Polygons::reserve(self, n)
    }
    fn append(&mut self, other: &Polygons<N>) {
        Polygons::append(self, other)
    }
    fn permute(&mut self, order: Option<&Vec<u32>>) {
        Polygons::permute(self, order)
    }
    fn shrink_to_fit(&mut self) {
        self.columns().for_each(Vec::shrink_to_fit);
    }
}

/// Up to four shapes of one kind waiting for their family's [`Family::setup_x4`], with their
/// ids: one per kind while a part of the stores is built.
#[derive(Clone, Copy)]
struct Four {
    shapes: [Shape; 4],
    id: [f32; 4],
    n: usize,
}

impl Default for Four {
    fn default() -> Four {
        Four {
            shapes: [Shape::Triangle([DVec3::ZERO; 3]); 4],
            id: [0.0; 4],
            n: 0,
        }
    }
}

/// `shape` (with its id) added to the four waiting of its family; with four, their constants
/// go to `part`.
struct Wait<'a> {
    four: &'a mut Four,
    shape: Shape,
    id: f32,
    part: &'a mut Packed,
    eye: DVec3,
}

impl Visit<()> for Wait<'_> {
    #[inline]
    fn visit<F: Stored>(self, _: F::Geometry) {
        let four = self.four;
        (four.shapes[four.n], four.id[four.n]) = (self.shape, self.id);
        four.n += 1;
        if four.n == 4 {
            flush::<F>(four, self.part, self.eye);
        }
    }
}

/// The constants of the shapes waiting in `four` (all of family `F`), in their order, to
/// `part`'s columns of `F`, rounded to f32: a polygon seen edge-on from `eye` (or, as the
/// kernels' constructors refuse, with an edge too short to resolve) is left out.
fn flush<F: Stored>(four: &mut Four, part: &mut Packed, eye: DVec3) {
    if four.n == 0 {
        return;
    }
    // (unused lanes repeat the first shape, and are dropped)
    let g = std::array::from_fn(|k| {
        let shape = four.shapes[if k < four.n { k } else { 0 }];
        F::geometry(shape).expect("a family's four hold its own shapes")
    });
    let ks = F::setup_x4(&g, eye);
    let columns = F::columns_mut(part);
    for (k, &id) in ks.iter().zip(&four.id).take(four.n) {
        if let Some(k) = k {
            Columns::<F>::push(columns, &F::cast(k), id);
        }
    }
    four.n = 0;
}

impl Packed {
    /// The scene ids of each kind's primitives, in store order (`scene::KINDS` order, as the
    /// tiles number the kinds).
    #[inline]
    pub fn ids(&self) -> [&[f32]; KINDS.len()] {
        let mut ids: [&[f32]; KINDS.len()] = [&[]; KINDS.len()];
        for_each_family!(F => ids[F::KIND] = Columns::<F>::ids(F::columns(self)));
        ids
    }

    /// The stores of `scene` seen from `eye`, built straight from the shapes on all threads,
    /// with no f64 copy kept: chunks of shapes are prepared in parallel (each family's
    /// `Family::setup_x4`, bit for bit its `setup`, and the same f32 rounding as
    /// [`Prepared::new`] and [`Packed::new`], so the columns are identical), then joined in
    /// file order.
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
        // The columns are allocated once, for every shape of their kind (edge-on polygons,
        // left out, are rare), so they never move or grow.
        let batch_len = CHUNK * (4 * crate::par::current_num_threads()).max(16);
        // (the primitives left out need no room)
        let most = scene.shapes.len() - left_out.map_or(0, IdSet::len);
        let counts = scene.counts();
        for_each_family!(F => {
            let columns = F::columns_mut(&mut out);
            Columns::<F>::clear(columns);
            Columns::<F>::reserve(columns, counts[F::KIND].min(most));
        });
        for batch in (0..scene.shapes.len()).step_by(batch_len) {
            let ids = batch..(batch + batch_len).min(scene.shapes.len());
            let parts: Vec<Packed> = (scene.shapes.par_chunks(ids, CHUNK))
                .map(|(first, shapes)| {
                    let mut part = Packed::default();
                    // each family's shapes four at a time (`Family::setup_x4`), each store
                    // keeping its shapes' order
                    let mut four = [Four::default(); KINDS.len()];
                    let mut add = |id: usize, shape: Shape| {
                        let wait = Wait {
                            four: &mut four[shape.kind()],
                            shape,
                            id: id as f32,
                            part: &mut part,
                            eye,
                        };
                        super::visit(shape, wait)
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
                    for_each_family!(F => flush::<F>(&mut four[F::KIND], &mut part, eye));
                    part
                })
                .collect();
            for part in &parts {
                for_each_family!(F => Columns::<F>::append(F::columns_mut(&mut out), F::columns(part)));
            }
        }
        out
    }

    /// Every column's memory beyond its length given back (the next view's columns grow
    /// again where they need to).
    pub(crate) fn shrink_to_fit(&mut self) {
        for_each_family!(F => Columns::<F>::shrink_to_fit(F::columns_mut(self)));
    }

    /// Rearranged to `order`.
    pub fn permute(&mut self, order: &Order) {
        for_each_family!(F => Columns::<F>::permute(F::columns_mut(self), order[F::KIND].as_ref()));
    }

    /// The stores of prepared f64 constants, rounded to f32.
    pub fn new(p: &Prepared<f64>) -> Packed {
        let mut out = Packed::default();
        for_each_family!(F => {
            let (group, columns) = (F::group(p), F::columns_mut(&mut out));
            for (k, &id) in group.k.iter().zip(&group.id) {
                Columns::<F>::push(columns, &F::cast(k), id as f32);
            }
        });
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{CameraSpec, Mesh, Shapes};

    #[test]
    fn packed_columns_round_trip_the_f32_records() {
        let scene = Scene {
            camera_at: None,
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

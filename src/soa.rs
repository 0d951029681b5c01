//! Primitives prepared for the kernels: eye-relative constants computed once per render setup.
//!
//! [`Prepared`] holds each type's constants as records, in f64 as computed (the oracle's input)
//! or rounded to f32 (the scalar f32 path's input). [`Packed`] (`soa/columns.rs`) holds the
//! same f32 values as structure-of-arrays columns, one store per type, for the 8-lane kernels:
//! the packet loop broadcasts one primitive's values to the eight lanes, walking the columns
//! front to back (no acceleration) or in the order its structure lists them.
//! A type the scene does not contain has empty columns, and its loop is never entered.

use crate::kernel::Family;
use crate::kernel::polygon::{Quad, QuadK, Triangle, TriangleK};
use crate::kernel::sphere::{Sphere, SphereK};
use crate::par::prelude::*;
use crate::real::Real;
use crate::scene::{KINDS, Scene, Shape, Shapes};
use glam::DVec3;

/// One type's prepared primitives and their ids: in file order, or in the order an acceleration
/// structure rearranged them to (the BVH's leaves, the tiles' screen order).
#[derive(Debug, Clone, PartialEq)]
pub struct Group<K> {
    /// Each primitive's constants record.
    pub k: Vec<K>,
    /// The scene's shape index of each record, parallel to `k`.
    pub id: Vec<i32>,
}

impl<K> Default for Group<K> {
    fn default() -> Self {
        Group {
            k: Vec::new(),
            id: Vec::new(),
        }
    }
}

impl<K> Group<K> {
    fn push(&mut self, k: K, id: usize) {
        self.k.push(k);
        self.id.push(id as i32);
    }

    /// Number of primitives.
    pub fn len(&self) -> usize {
        self.k.len()
    }

    /// True when the group holds no primitive.
    pub fn is_empty(&self) -> bool {
        self.k.is_empty()
    }

    /// Appends element `i` of `other`.
    pub(crate) fn push_from(&mut self, other: &Group<K>, i: usize)
    where
        K: Clone,
    {
        self.k.push(other.k[i].clone());
        self.id.push(other.id[i]);
    }

    /// Rearranged to `order` (new position -> old index; [`Order`]), or kept with `None`.
    pub fn permute(&mut self, order: Option<&Vec<u32>>)
    where
        K: Clone + Send + Sync,
    {
        if let Some(order) = order {
            gather([&mut self.k], order);
            gather([&mut self.id], order);
        }
    }

    fn map<L>(&self, f: impl Fn(&K) -> L) -> Group<L> {
        Group {
            k: self.k.iter().map(f).collect(),
            id: self.id.clone(),
        }
    }
}

/// A rearrangement of the stores, per kind (spheres, triangles, quads): element `j` of a kind's
/// list is the old index of the primitive that moves to index `j`; `None` keeps the kind as it
/// is. The tiles order the stores the way the render reaches them (`accel::tiles`).
pub type Order = [Option<Vec<u32>>; KINDS.len()];

/// Each of `cols` (columns of one length) rearranged so that its element `j` is its old
/// element `order[j]`, gathered on all threads through one scratch buffer that each column's
/// old storage becomes in turn: one allocation (and one first touch of its pages) for all, and
/// only one column exists twice at any time.
pub(crate) fn gather<'c, T: Clone + Send + Sync + 'c>(
    cols: impl IntoIterator<Item = &'c mut Vec<T>>,
    order: &[u32],
) {
    let mut scratch: Vec<T> = Vec::with_capacity(order.len());
    for col in cols {
        scratch.clear();
        scratch.par_extend(order.par_iter().map(|&i| col[i as usize].clone()));
        std::mem::swap(col, &mut scratch);
    }
}

/// Every primitive's eye-relative constants, by type. Polygons seen exactly edge-on from the eye
/// are left out (they cover no pixel; see `kernel::polygon`).
#[derive(Debug, Clone, PartialEq)]
pub struct Prepared<T> {
    /// Sphere constants.
    pub spheres: Group<SphereK<T>>,
    /// Triangle constants (3 edge planes).
    pub triangles: Group<TriangleK<T>>,
    /// Quad constants (4 edge planes).
    pub quads: Group<QuadK<T>>,
}

impl<T> Default for Prepared<T> {
    fn default() -> Self {
        Prepared {
            spheres: Group::default(),
            triangles: Group::default(),
            quads: Group::default(),
        }
    }
}

impl Prepared<f64> {
    /// Constants of every shape of `scene` seen from `eye`, in f64.
    pub fn new(scene: &Scene, eye: DVec3) -> Prepared<f64> {
        /// Appends a primitive's constants from `eye` with its id, unless it covers no pixel
        /// from there ([`Family::setup`]).
        struct Add<'p>(&'p mut Prepared<f64>, usize, DVec3);
        impl Visit<()> for Add<'_> {
            fn visit<F: Stored>(self, g: F::Geometry) {
                if let Some(k) = F::setup(&g, self.2) {
                    F::group_mut(self.0).push(k, self.1);
                }
            }
        }
        let mut p = Prepared::default();
        for (id, shape) in scene.shapes.iter().enumerate() {
            visit(shape, Add(&mut p, id, eye));
        }
        p
    }

    /// Rearranged to `order`.
    pub fn permute(&mut self, order: &Order) {
        for_each_family!(F => F::group_mut(self).permute(order[F::KIND].as_ref()));
    }

    /// The same constants rounded to `T`.
    pub fn cast<T: Real>(&self) -> Prepared<T> {
        let mut out = Prepared::default();
        for_each_family!(F => *F::group_mut(&mut out) = F::group(self).map(F::cast));
        out
    }
}

/// Where the scalar kernels read primitive `i` of each family (the index the acceleration
/// structures and the packed stores use) with its scene id: a store of records ([`Prepared`]),
/// or records computed when asked ([`SceneRecords`]).
pub trait Records<T: Real> {
    /// How many primitives of each kind (`scene::KINDS` order).
    fn counts(&self) -> [usize; KINDS.len()];
    /// Primitive `i` of family `F`: its constants and id (`None`: it covers no pixel).
    fn record<F: Stored>(&self, i: usize) -> Option<(F::K<T>, i32)>;
}

impl<T: Real> Records<T> for Prepared<T> {
    #[inline(always)]
    fn counts(&self) -> [usize; KINDS.len()] {
        let mut n = [0; KINDS.len()];
        for_each_family!(F => n[F::KIND] = F::group(self).len());
        n
    }
    #[inline(always)]
    fn record<F: Stored>(&self, i: usize) -> Option<(F::K<T>, i32)> {
        let g = F::group(self);
        Some((g.k[i], g.id[i]))
    }
}

/// The registration of the families with the stores: each family's index among the kinds
/// (spheres 0, triangles 1, quads 2, as [`Order`], `counts` and the tiles number them) and
/// where its records ([`Prepared`]) and columns ([`Packed`]) are kept.
pub trait Stored: Family + Sized {
    /// Its f32 columns.
    type Columns: Columns<Self>;
    /// Its records in `p`.
    fn group<T: Real>(p: &Prepared<T>) -> &Group<Self::K<T>>;
    /// Its records in `p`, to fill.
    fn group_mut<T: Real>(p: &mut Prepared<T>) -> &mut Group<Self::K<T>>;
    /// Its columns in `p`.
    fn columns(p: &Packed) -> &Self::Columns;
    /// Its columns in `p`, to fill.
    fn columns_mut(p: &mut Packed) -> &mut Self::Columns;
}

/// A family's f32 columns as the packet loops read them, and as [`Packed`] builds, joins and
/// rearranges them.
pub trait Columns<F: Family>: Default {
    /// Primitive `i`'s constants, gathered from the columns.
    fn get(&self, i: usize) -> F::K<f32>;
    /// Primitive `i`'s scene id, as f32 (exact below 2^24 = `limits::MAX_PRIMITIVES`).
    fn id(&self, i: usize) -> f32;
    /// How many primitives.
    fn len(&self) -> usize;
    /// Every primitive's scene id, in store order.
    fn ids(&self) -> &[f32];
    /// Appends one primitive's constants with its id.
    fn push(&mut self, k: &F::K<f32>, id: f32);
    /// Every column emptied, its allocation kept.
    fn clear(&mut self);
    /// Room for exactly `n` more primitives in every column.
    fn reserve(&mut self, n: usize);
    /// Appends every primitive of `other`.
    fn append(&mut self, other: &Self);
    /// Rearranged to `order` ([`Order`]), or kept with `None`.
    fn permute(&mut self, order: Option<&Vec<u32>>);
    /// Every column's memory beyond its length given back.
    fn shrink_to_fit(&mut self);
}

/// The registration's one list of families, in kind order: `for_each_family!(F => expr)`
/// evaluates `expr` once per family with `F` naming it (a type), so a loop over the families is
/// as monomorphic as the three calls it stands for.
macro_rules! for_each_family {
    ($f:ident => $body:expr) => {{
        {
            type $f = $crate::kernel::Sphere;
            $body;
        }
        {
            type $f = $crate::kernel::Triangle;
            $body;
        }
        {
            type $f = $crate::kernel::Quad;
            $body;
        }
    }};
}
pub(crate) use for_each_family;

/// The registration's families in kind order as one type, the list `(F, (G, ... ()))`: for
/// loops written over a type outside the crate (the lab's drivers), which `for_each_family!`
/// cannot reach. Kept in the order of `for_each_family!`.
pub type Families = (Sphere, (Triangle, (Quad, ())));

/// The registration's families by kind at run time: `with_family!(kind, F => expr)` evaluates
/// `expr` with `F` naming the family whose `Family::KIND` is `kind` (a kind tag read from a
/// structure: the BVH's leaves, the tiles' entries). Kinds past the last are the last.
#[allow(unused_macros)]
macro_rules! with_family {
    ($kind:expr, $f:ident => $body:expr) => {
        match $kind {
            0 => {
                type $f = $crate::kernel::Sphere;
                $body
            }
            1 => {
                type $f = $crate::kernel::Triangle;
                $body
            }
            _ => {
                type $f = $crate::kernel::Quad;
                $body
            }
        }
    };
}
#[allow(unused_imports)]
pub(crate) use with_family;

/// Something done to one primitive whatever its family: [`visit`] calls it with the family of
/// a scene shape.
pub trait Visit<R> {
    /// Done to the geometry `g` of a primitive of family `F`.
    fn visit<F: Stored>(self, g: F::Geometry) -> R;
}

/// `v` done to `shape` as a primitive of its family: the registration of the scene's shapes.
#[inline(always)]
pub fn visit<R>(shape: Shape, v: impl Visit<R>) -> R {
    match shape {
        Shape::Sphere { center, radius } => v.visit::<Sphere>((center, radius)),
        Shape::Triangle(t) => v.visit::<Triangle>(t),
        Shape::Quad(q) => v.visit::<Quad>(q),
    }
}

impl Stored for Sphere {
    type Columns = Spheres;
    #[inline(always)]
    fn group<T: Real>(p: &Prepared<T>) -> &Group<SphereK<T>> {
        &p.spheres
    }
    #[inline(always)]
    fn group_mut<T: Real>(p: &mut Prepared<T>) -> &mut Group<SphereK<T>> {
        &mut p.spheres
    }
    #[inline(always)]
    fn columns(p: &Packed) -> &Spheres {
        &p.spheres
    }
    #[inline(always)]
    fn columns_mut(p: &mut Packed) -> &mut Spheres {
        &mut p.spheres
    }
}

impl Stored for Triangle {
    type Columns = Polygons<3>;
    #[inline(always)]
    fn group<T: Real>(p: &Prepared<T>) -> &Group<TriangleK<T>> {
        &p.triangles
    }
    #[inline(always)]
    fn group_mut<T: Real>(p: &mut Prepared<T>) -> &mut Group<TriangleK<T>> {
        &mut p.triangles
    }
    #[inline(always)]
    fn columns(p: &Packed) -> &Polygons<3> {
        &p.triangles
    }
    #[inline(always)]
    fn columns_mut(p: &mut Packed) -> &mut Polygons<3> {
        &mut p.triangles
    }
}

impl Stored for Quad {
    type Columns = Polygons<4>;
    #[inline(always)]
    fn group<T: Real>(p: &Prepared<T>) -> &Group<QuadK<T>> {
        &p.quads
    }
    #[inline(always)]
    fn group_mut<T: Real>(p: &mut Prepared<T>) -> &mut Group<QuadK<T>> {
        &mut p.quads
    }
    #[inline(always)]
    fn columns(p: &Packed) -> &Polygons<4> {
        &p.quads
    }
    #[inline(always)]
    fn columns_mut(p: &mut Packed) -> &mut Polygons<4> {
        &mut p.quads
    }
}

/// The f64 records of the primitives of a [`Packed`] store, computed from the scene's shapes
/// when asked, with the constructors [`Prepared::new`] uses (so bit for bit the oracle's
/// constants): the f64 re-decisions of `--precision auto` read a few primitives per pixel and
/// keep no f64 copy of the scene.
#[derive(Debug, Clone, Copy)]
pub struct SceneRecords<'a> {
    shapes: &'a Shapes,
    ids: [&'a [f32]; KINDS.len()],
    eye: DVec3,
}

impl<'a> SceneRecords<'a> {
    /// The records of `packed`'s primitives, which `scene` seen from `eye` was packed from.
    pub fn new(scene: &'a Scene, packed: &'a Packed, eye: DVec3) -> SceneRecords<'a> {
        SceneRecords {
            shapes: &scene.shapes,
            ids: packed.ids(),
            eye,
        }
    }

    #[inline(always)]
    fn shape(&self, kind: usize, i: usize) -> (Shape, i32) {
        let id = self.ids[kind][i] as i32;
        (self.shapes.get(id as usize), id)
    }
}

impl Records<f64> for SceneRecords<'_> {
    fn counts(&self) -> [usize; KINDS.len()] {
        self.ids.map(|ids| ids.len())
    }
    #[inline(always)]
    fn record<F: Stored>(&self, i: usize) -> Option<(F::K<f64>, i32)> {
        let (shape, id) = self.shape(F::KIND, i);
        F::setup(&F::geometry(shape)?, self.eye).map(|k| (k, id))
    }
}

/// All primitives as f32 structure-of-arrays stores, one per family (`soa/columns.rs`).
#[derive(Debug, Clone, Default)]
pub struct Packed {
    /// Sphere columns.
    pub spheres: Spheres,
    /// Triangle columns (3 edge planes).
    pub triangles: Polygons<3>,
    /// Quad columns (4 edge planes).
    pub quads: Polygons<4>,
}

mod columns;
pub mod trace;
pub use columns::{Polygons, Spheres};

/// A set of primitive ids, one bit each: the primitives a view leaves out of its stores
/// (`render::cull`: those it has shown it cannot see).
#[derive(Debug, Clone, Default)]
pub struct IdSet {
    bits: Vec<u64>,
}

impl IdSet {
    /// The empty set over ids `0..n`, in `spare`'s buffer.
    pub fn empty_in(n: usize, mut spare: IdSet) -> IdSet {
        spare.bits.clear();
        spare.bits.resize(n.div_ceil(64), 0);
        spare
    }

    /// The set of every id `0..n`, in `spare`'s buffer.
    pub fn full_in(n: usize, spare: IdSet) -> IdSet {
        let mut set = IdSet::empty_in(n, spare);
        set.bits.fill(u64::MAX);
        if !n.is_multiple_of(64) {
            *set.bits.last_mut().expect("n > 0") = (1 << (n % 64)) - 1;
        }
        set
    }

    /// Removes `id`.
    #[inline]
    pub fn remove(&mut self, id: usize) {
        self.bits[id / 64] &= !(1 << (id % 64));
    }

    /// Adds `id` (below the `n` the set was made for).
    #[inline]
    pub fn insert(&mut self, id: usize) {
        self.bits[id / 64] |= 1 << (id % 64);
    }

    /// Whether `id` is in the set.
    #[inline]
    pub fn contains(&self, id: usize) -> bool {
        self.bits
            .get(id / 64)
            .is_some_and(|w| w >> (id % 64) & 1 == 1)
    }

    /// The maximal runs of ids in `ids` that the set does not hold, in order (a word of 64
    /// ids the set holds whole is passed over at once).
    pub fn gaps(
        &self,
        ids: std::ops::Range<usize>,
    ) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
        let mut at = ids.start;
        std::iter::from_fn(move || {
            // the next id not in the set, then the next one in it
            while at < ids.end && self.contains(at) {
                let word = self.bits.get(at / 64).copied().unwrap_or(0);
                at = if at.is_multiple_of(64) && word == u64::MAX {
                    at + 64
                } else {
                    at + 1
                };
            }
            if at >= ids.end {
                return None;
            }
            let start = at;
            while at < ids.end && !self.contains(at) {
                let word = self.bits.get(at / 64).copied().unwrap_or(0);
                at = if at.is_multiple_of(64) && word == 0 {
                    at + 64
                } else {
                    at + 1
                };
            }
            let end = at.min(ids.end);
            at = end;
            Some(start..end)
        })
    }

    /// How many ids the set holds.
    pub fn len(&self) -> usize {
        self.bits.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.bits.iter().all(|&w| w == 0)
    }
}

#[cfg(test)]
mod tests {
    use super::IdSet;
    use crate::test_rng::Rng;

    /// Over random sets (sparse, dense, in runs of whole words and of single ids), random
    /// ranges: the gaps are exactly the ids of the range the set does not hold, in maximal
    /// runs; and the counts, the full set and removal agree with a list of booleans.
    #[test]
    fn gaps_are_the_maximal_runs_outside_the_set() {
        let mut rng = Rng(0x1D_5E7);
        for case in 0..400 {
            let n = 1 + rng.below(700) as usize;
            let mut set = if case % 5 == 0 {
                IdSet::full_in(n, IdSet::default())
            } else {
                IdSet::empty_in(n, IdSet::default())
            };
            let mut want = vec![case % 5 == 0; n];
            let density = rng.unit();
            let mut id = 0;
            while id < n {
                let run = if rng.unit() < 0.3 {
                    64
                } else {
                    1 + rng.below(5) as usize
                };
                let into = rng.unit() < density;
                for (i, w) in want.iter_mut().enumerate().take((id + run).min(n)).skip(id) {
                    if into {
                        set.insert(i);
                    } else {
                        set.remove(i);
                    }
                    *w = into;
                }
                id += run;
            }
            assert_eq!(
                set.len(),
                want.iter().filter(|&&b| b).count(),
                "case {case}"
            );
            assert_eq!(set.is_empty(), !want.contains(&true), "case {case}");
            let a = rng.below(n as u32 + 1) as usize;
            let b = a + rng.below((n - a) as u32 + 1) as usize;
            let gaps: Vec<_> = set.gaps(a..b).collect();
            let mut expect = Vec::new();
            let mut i = a;
            while i < b {
                if want[i] {
                    i += 1;
                    continue;
                }
                let start = i;
                while i < b && !want[i] {
                    i += 1;
                }
                expect.push(start..i);
            }
            assert_eq!(gaps, expect, "case {case}: {a}..{b} of {n}");
        }
    }
}

//! A primitive family: what the engine asks of every sphere, triangle or quad, as one type.
//!
//! Each family is a type implementing [`Family`] in its kernel's file (`sphere.rs`: `Sphere`;
//! `polygon.rs`: `Triangle` and `Quad`, which share the edge-plane kernel): where it is read
//! from a scene shape, its eye-relative constants computed in f64 and rounded to the kernel's
//! precision, its one-lane and lane-generic kernels (f32x8 packets, f64x4 for
//! `--precision f64`), and the normal shading reads at a hit. The stores and their loops
//! (`soa`) are written over families; `soa::Stored` registers each family's store.

use crate::kernel::lanes::Lanes;
use crate::real::{Real, V3};
use crate::scene::{KINDS, Shape};
use glam::DVec3;
use std::fmt::Debug;

/// One primitive family (see the module comment). Each kernel states its formula, precision
/// and failure modes beside its own code; this trait only names them.
pub trait Family: 'static {
    /// The family's kind: its index in `scene::KINDS`, the order of every per-kind list.
    const KIND: usize;
    /// The family's keyword in the scene format.
    const NAME: &'static str = KINDS[Self::KIND].0;
    /// Its plural, as counts are printed.
    const PLURAL: &'static str = KINDS[Self::KIND].1;
    /// What the scene holds of one primitive of the family.
    type Geometry: Copy;
    /// One primitive's eye-relative constants in precision `T`.
    type K<T: Real>: Copy + Debug + PartialEq + Send + Sync;

    /// The family's part of `shape`, or `None` when `shape` is of another family.
    fn geometry(shape: Shape) -> Option<Self::Geometry>;

    /// The constants of `g` seen from `eye`, in f64; `None` when it covers no pixel from there
    /// (a polygon seen exactly edge-on).
    fn setup(g: &Self::Geometry, eye: DVec3) -> Option<Self::K<f64>>;

    /// [`Family::setup`] of four primitives at once, bit for bit the same; a family whose
    /// setup has a four-lane form (triangles: `triangle_setup::triangles_x4`) gives it here.
    /// The stores are built through it.
    #[inline(always)]
    fn setup_x4(g: &[Self::Geometry; 4], eye: DVec3) -> [Option<Self::K<f64>>; 4] {
        std::array::from_fn(|i| Self::setup(&g[i], eye))
    }

    /// The f64 constants rounded to `T`, once each.
    fn cast<T: Real>(k: &Self::K<f64>) -> Self::K<T>;

    /// Distance along the unit direction `d` from the eye to the hit, when it is ahead.
    fn hit_x1<T: Real>(k: &Self::K<T>, d: V3<T>) -> Option<T>;

    /// [`Family::hit_x1`] in the lanes of `L` with the same operations in the same order:
    /// `None` when no lane can hit, else the mask of lanes that may and their distances (the
    /// caller keeps those with 0 < t).
    fn hit_lanes<L: Lanes>(k: &Self::K<L::Scalar>, d: &[L; 3]) -> Option<(L, L)>;

    /// [`Family::hit_x1`] in f64 with the primitive's boundary moved outward by `slack`
    /// radians as seen from `eye` (inward when negative): how `compare` tells a ray that passes
    /// within a band of an edge or silhouette from a clear mismatch.
    fn hit_with_slack(g: &Self::Geometry, eye: DVec3, d: V3<f64>, slack: f64) -> Option<f64>;

    /// Whether the unit direction `d` from `eye` passes within `band` radians of the
    /// primitive's boundary as seen from `eye` (its true outline on the sphere of directions):
    /// the rays `compare` excuses at an edge. By default, where [`Family::hit_with_slack`]
    /// with the boundary moved out by `band` and in by `band` disagree, which is that distance
    /// for an outline without corners (a sphere's silhouette); a polygon measures its distance
    /// to each edge's arc, since moving its edges out moves a sharp corner much further.
    fn near_boundary(g: &Self::Geometry, eye: DVec3, d: V3<f64>, band: f64) -> bool {
        Self::hit_with_slack(g, eye, d, band).is_some()
            != Self::hit_with_slack(g, eye, d, -band).is_some()
    }

    /// The plane of a flat primitive seen from `eye`, as its f64 constants hold it (unit normal
    /// pointing away from the eye, distance from the eye), bit for bit; `None` for a curved
    /// one. `--precision auto` measures a polygon's f32 hit against its plane alone.
    fn plane(g: &Self::Geometry, eye: DVec3) -> Option<(V3<f64>, f64)>;

    /// The unit f64 normal facing the eye at the hit `point` of `g` seen from `eye`, and
    /// whether it is the same for every hit of that primitive (a flat one).
    fn normal(g: &Self::Geometry, eye: DVec3, point: DVec3) -> (DVec3, bool);

    // For the world engine (`--accel world`), which draws a family of convex polygons from
    // their vertices and any other family through a bounding sphere.

    /// `class.polygon()` when the family is a [`Polygon`] (with its edge count), else
    /// `class.bounded()` ([`Bounded`]): which of the world engine's two ways draws it.
    fn class<C: Class<Self>>(class: C) -> C::Out
    where
        Self: Sized;

    // What the acceleration structures (`accel`: the tiles, the BVH) ask of a family: the
    // outline class its primitives are bounded by, and the packet kernel without early exit.

    /// The outline class the acceleration structures bound the family's primitives by, from
    /// their f32 constants: a [`Ball`], or a convex polygon of `N` edges (`polygon::PolyK`,
    /// f32). `accel` writes its bounds once per class, not per family.
    type Outline: Copy;

    /// The outline of the primitive of f32 constants `k`: the same f32 values, bit for bit.
    fn outline(k: &Self::K<f32>) -> Self::Outline;

    /// For a family bounded by a [`Ball`]: the ball's centre minus `eye` (one f64 subtraction
    /// per axis) and its radius, exactly as the scene gives them (`g`), which the tiles'
    /// pixel rectangle of a ball is computed from. `None` (the default) for other outlines.
    fn ball(g: &Self::Geometry, eye: DVec3) -> Option<(DVec3, f64)> {
        let _ = (g, eye);
        None
    }

    /// [`Family::hit_lanes`] with no early exit: the distance computed in every lane, the mask
    /// possibly empty, the same bits where it is set (the tiles' per-packet walk, whose
    /// outcomes a branch cannot predict).
    fn hit_lanes_all<L: Lanes>(k: &Self::K<L::Scalar>, d: &[L; 3]) -> (L, L);
}

/// A ball seen from the eye, by its f32 constants: the outline class (`Family::Outline`) of a
/// primitive that every ray a kernel accepts passes near the centre of, with the distances of
/// the sphere kernel's near root (`accel::reach` derives the bounds from them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ball {
    /// Centre minus eye.
    pub oc: [f32; 3],
    /// Radius squared.
    pub r2: f32,
    /// `|oc|^2 - r^2`, computed in f64 and rounded.
    pub c: f32,
    /// The eye inside or on the ball (`c <= 0`).
    pub inside: bool,
}

/// `n` normalised and turned to face the eye, from which a point of the plane lies at `rel`.
pub(crate) fn facing(n: DVec3, rel: DVec3) -> DVec3 {
    let n = n.normalize_or_zero();
    if n.dot(rel) > 0.0 { -n } else { n }
}

// For the world engine (`--accel world`): the two classes of family it draws, and how it
// learns a family's ([`Family::class`]).

/// Something done to a family as the member of its class ([`Family::class`] calls the one
/// method that applies): a polygon family with its edge count, or a bounded one.
pub trait Class<F: Family> {
    /// What either method returns.
    type Out;
    /// Done to `F`, a convex polygon family of `N` edges.
    fn polygon<const N: usize>(self) -> Self::Out
    where
        F: Polygon<N>;
    /// Done to `F`, a family drawn through a bounding sphere.
    fn bounded(self) -> Self::Out
    where
        F: Bounded;
}

/// A family of convex polygons with `N` edges, each given by its vertices in perimeter order:
/// the world engine (`--accel world`) projects the vertices, bins and clusters the polygons,
/// and computes their f32 edge planes itself, then decides again in f64 with
/// [`Family::setup`] and [`Family::hit_x1`].
pub trait Polygon<const N: usize>: Family<Geometry = [DVec3; N]> {
    /// `[a, b, c, d]`: the family's raw normal (any length, either orientation) is
    /// `(V_a - V_b) x (V_c - V_d)`, as its kernel computes it: the world's f32 setup, its
    /// shape factor, its clusters' normal cones and its 2D outlines take the same two vectors.
    const NORMAL: [usize; 4];
}

/// A family the world engine (`--accel world`) draws through a bounding sphere: binned by the
/// sphere's pixel box, tested in f32 with [`Family::hit_x1`] at every pixel of that box, and
/// decided again in f64 ([`Family::setup`], [`Family::hit_x1`]) wherever it may cover.
pub trait Bounded: Family {
    /// A sphere holding every point of `g`: centre and radius, f64.
    fn bound(g: &Self::Geometry) -> (DVec3, f64);
}

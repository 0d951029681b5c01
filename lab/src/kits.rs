//! Brute-force drivers for the lab's intersection methods ([`crate::method::Method`]): every ray
//! against every primitive, one thread, one method. Their loops are separate from lanecast's
//! renderer (which has acceleration structures), so the lab measures the intersection methods
//! alone.
//!
//! A [`Kit`] holds one method's constants for one scene (spheres, triangles, quads, each with
//! its id) and the camera's ray tables; [`Kit::render_x8`] traces 4x2 pixel blocks as 8-lane
//! packets (lanes past the image border masked, as in the main renderer) and
//! [`Kit::render_x1`] one ray at a time in f32 with the same method. [`Oracle`] is the f64
//! scalar oracle. The f64x4 packet form of the default methods, which takes the accelerations
//! and every thread, is lanecast's `render::wide64::Kit64` (`--precision f64`).

use crate::methods::mt::{MtK, mt_x1, mt_x8};
use crate::methods::plane::{PlaneK, plane_x1, plane_x8};
use crate::methods::sphere_naive::{NaiveK, naive_x1, naive_x8};
use crate::methods::woop::{WoopK, WoopRay, WoopRay8, woop_ray, woop_x1, woop_x8};
use crate::methods::{quad_split, world};
use glam::DVec3;
use lanecast::experimental::camera::RayTables;
use lanecast::experimental::kernel::packet::block_rays;
use lanecast::experimental::kernel::polygon::{QuadK, TriangleK, polygon_x1, polygon_x8};
use lanecast::experimental::kernel::sphere::{SphereK, sphere_x1, sphere_x8};
use lanecast::experimental::kernel::{Hit, Hit8, LANES};
use lanecast::experimental::real::V3;
use lanecast::experimental::soa::Prepared;
use lanecast::experimental::soa::trace::trace_x1;
use lanecast::scene::{Scene, Shape};
use lanecast::{Camera, Frame};
use std::marker::PhantomData;
use wide::f32x8;

/// Pixel block of one packet, as in the main renderer: 4 wide, 2 high.
pub const BW: usize = 4;
/// Pixel block height: `LANES / BW` = 2 rows.
pub const BH: usize = LANES / BW;

/// A sphere method: constants and its 1- and 8-lane forms.
pub trait SphereFamily {
    /// One sphere's constants, in f32, as the method's kernels read them.
    type K: Copy + Send + Sync;
    /// The constants of the sphere (`center`, `radius`) seen from `eye`.
    fn make(center: DVec3, radius: f64, eye: DVec3) -> Self::K;
    /// Distance along unit direction `d` from the eye to the hit, when ahead of the eye.
    fn x1(k: &Self::K, d: V3<f32>) -> Option<f32>;
    /// [`SphereFamily::x1`] for eight directions: `None` when no lane can hit, else the lane
    /// mask and distances (the caller keeps the lanes with 0 < t).
    fn x8(k: &Self::K, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)>;
}

/// A triangle/quad method: constants (`None`: the primitive covers no pixel), the per-ray and
/// per-packet data it shares over primitives, and its 1- and 8-lane forms.
pub trait PolyFamily {
    /// One triangle's constants, in f32.
    type T: Copy + Send + Sync;
    /// One quad's constants, in f32 (two triangles' for the triangle-only methods).
    type Q: Copy + Send + Sync;
    /// Per-ray data shared over primitives: the unit direction, or a method's ray transform.
    type R1;
    /// [`PolyFamily::R1`] for eight rays.
    type R8;
    /// The constants of triangle `v` (A, B, C) seen from `eye`; `None`: it covers no pixel.
    fn tri(v: &[DVec3; 3], eye: DVec3) -> Option<Self::T>;
    /// The constants of quad `v` (perimeter order) seen from `eye`; `None`: it covers no pixel.
    fn quad(v: &[DVec3; 4], eye: DVec3) -> Option<Self::Q>;
    /// The per-ray data of unit direction `d`.
    fn ray1(d: V3<f32>) -> Self::R1;
    /// The per-packet data of eight unit directions `d`.
    fn ray8(d: &[f32x8; 3]) -> Self::R8;
    /// Distance to the triangle along ray `r`, when it is hit ahead of the eye.
    fn tri_x1(k: &Self::T, r: &Self::R1) -> Option<f32>;
    /// [`PolyFamily::tri_x1`] for eight rays: `None` when no lane hits, else the lane mask and
    /// distances (the caller keeps the lanes with 0 < t).
    fn tri_x8(k: &Self::T, r: &Self::R8) -> Option<(f32x8, f32x8)>;
    /// Distance to the quad along ray `r`, when it is hit ahead of the eye.
    fn quad_x1(k: &Self::Q, r: &Self::R1) -> Option<f32>;
    /// [`PolyFamily::quad_x1`] for eight rays, as [`PolyFamily::tri_x8`].
    fn quad_x8(k: &Self::Q, r: &Self::R8) -> Option<(f32x8, f32x8)>;
}

/// The nearer of two optional positive distances (the quad of two triangles).
#[inline(always)]
fn nearer(a: Option<f32>, b: Option<f32>) -> Option<f32> {
    match (a, b) {
        (Some(a), Some(b)) => Some(if b < a { b } else { a }),
        (a, None) => a,
        (None, b) => b,
    }
}

/// [`nearer`] lane by lane.
#[inline(always)]
fn nearer8(a: Option<(f32x8, f32x8)>, b: Option<(f32x8, f32x8)>) -> Option<(f32x8, f32x8)> {
    let zero = f32x8::ZERO;
    let inf = f32x8::splat(f32::INFINITY);
    let keep = |(m, t): (f32x8, f32x8)| m & t.simd_gt(zero) & t.simd_lt(inf);
    match (a, b) {
        (Some(a), Some(b)) => {
            let (ma, mb) = (keep(a), keep(b));
            let take_b = mb & (!ma | b.1.simd_lt(a.1));
            Some((ma | mb, take_b.select(b.1, a.1)))
        }
        (a, None) => a,
        (None, b) => b,
    }
}

/// The stable sphere (`kernel::sphere`), eye-relative f64 setup.
pub struct Stable;
impl SphereFamily for Stable {
    type K = SphereK<f32>;
    fn make(c: DVec3, r: f64, eye: DVec3) -> Self::K {
        SphereK::new(c, r, eye).cast()
    }
    fn x1(k: &Self::K, d: V3<f32>) -> Option<f32> {
        sphere_x1(k, d)
    }
    #[inline(always)]
    fn x8(k: &Self::K, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
        sphere_x8(k, d)
    }
}

/// The stable sphere with f32 world-space setup (`methods::world`).
pub struct StableWorld;
impl SphereFamily for StableWorld {
    type K = SphereK<f32>;
    fn make(c: DVec3, r: f64, eye: DVec3) -> Self::K {
        world::sphere(c, r, eye)
    }
    fn x1(k: &Self::K, d: V3<f32>) -> Option<f32> {
        sphere_x1(k, d)
    }
    #[inline(always)]
    fn x8(k: &Self::K, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
        sphere_x8(k, d)
    }
}

/// The textbook sphere (`methods::sphere_naive`).
pub struct Naive;
impl SphereFamily for Naive {
    type K = NaiveK<f32>;
    fn make(c: DVec3, r: f64, eye: DVec3) -> Self::K {
        NaiveK::new(c, r, eye).cast()
    }
    fn x1(k: &Self::K, d: V3<f32>) -> Option<f32> {
        naive_x1(k, d)
    }
    #[inline(always)]
    fn x8(k: &Self::K, d: &[f32x8; 3]) -> Option<(f32x8, f32x8)> {
        naive_x8(k, d)
    }
}

/// The default edge-plane polygons (`kernel::polygon`): a quad is one four-edge polygon.
pub struct EPlane;
impl PolyFamily for EPlane {
    type T = TriangleK<f32>;
    type Q = QuadK<f32>;
    type R1 = V3<f32>;
    type R8 = [f32x8; 3];
    fn tri(v: &[DVec3; 3], eye: DVec3) -> Option<Self::T> {
        Some(TriangleK::triangle(v, eye)?.cast())
    }
    fn quad(v: &[DVec3; 4], eye: DVec3) -> Option<Self::Q> {
        Some(QuadK::quad(v, eye)?.cast())
    }
    fn ray1(d: V3<f32>) -> Self::R1 {
        d
    }
    fn ray8(d: &[f32x8; 3]) -> Self::R8 {
        *d
    }
    fn tri_x1(k: &Self::T, d: &Self::R1) -> Option<f32> {
        polygon_x1(k, *d)
    }
    #[inline(always)]
    fn tri_x8(k: &Self::T, d: &Self::R8) -> Option<(f32x8, f32x8)> {
        polygon_x8(k, d)
    }
    fn quad_x1(k: &Self::Q, d: &Self::R1) -> Option<f32> {
        polygon_x1(k, *d)
    }
    #[inline(always)]
    fn quad_x8(k: &Self::Q, d: &Self::R8) -> Option<(f32x8, f32x8)> {
        polygon_x8(k, d)
    }
}

/// Edge planes with f32 world-space setup (`methods::world`).
pub struct EPlaneWorld;
impl PolyFamily for EPlaneWorld {
    type T = TriangleK<f32>;
    type Q = QuadK<f32>;
    type R1 = V3<f32>;
    type R8 = [f32x8; 3];
    fn tri(v: &[DVec3; 3], eye: DVec3) -> Option<Self::T> {
        world::polygon(v, eye)
    }
    fn quad(v: &[DVec3; 4], eye: DVec3) -> Option<Self::Q> {
        world::polygon(v, eye)
    }
    fn ray1(d: V3<f32>) -> Self::R1 {
        d
    }
    fn ray8(d: &[f32x8; 3]) -> Self::R8 {
        *d
    }
    fn tri_x1(k: &Self::T, d: &Self::R1) -> Option<f32> {
        polygon_x1(k, *d)
    }
    #[inline(always)]
    fn tri_x8(k: &Self::T, d: &Self::R8) -> Option<(f32x8, f32x8)> {
        polygon_x8(k, d)
    }
    fn quad_x1(k: &Self::Q, d: &Self::R1) -> Option<f32> {
        polygon_x1(k, *d)
    }
    #[inline(always)]
    fn quad_x8(k: &Self::Q, d: &Self::R8) -> Option<(f32x8, f32x8)> {
        polygon_x8(k, d)
    }
}

/// Implements [`PolyFamily`] for a triangle-only method whose quads are two triangles.
macro_rules! two_triangle_family {
    ($fam:ident, $k:ident, $r1:ty, $r8:ty, $ray1:expr, $ray8:expr, $x1:ident, $x8:ident) => {
        impl PolyFamily for $fam {
            type T = $k<f32>;
            type Q = [$k<f32>; 2];
            type R1 = $r1;
            type R8 = $r8;
            fn tri(v: &[DVec3; 3], eye: DVec3) -> Option<Self::T> {
                Some($k::new(v, eye).cast())
            }
            fn quad(v: &[DVec3; 4], eye: DVec3) -> Option<Self::Q> {
                Some(quad_split(v).map(|t| $k::new(&t, eye).cast()))
            }
            fn ray1(d: V3<f32>) -> Self::R1 {
                $ray1(d)
            }
            fn ray8(d: &[f32x8; 3]) -> Self::R8 {
                $ray8(d)
            }
            fn tri_x1(k: &Self::T, r: &Self::R1) -> Option<f32> {
                $x1(k, r)
            }
            #[inline(always)]
            fn tri_x8(k: &Self::T, r: &Self::R8) -> Option<(f32x8, f32x8)> {
                $x8(k, r)
            }
            fn quad_x1(k: &Self::Q, r: &Self::R1) -> Option<f32> {
                nearer($x1(&k[0], r), $x1(&k[1], r))
            }
            #[inline(always)]
            fn quad_x8(k: &Self::Q, r: &Self::R8) -> Option<(f32x8, f32x8)> {
                nearer8($x8(&k[0], r), $x8(&k[1], r))
            }
        }
    };
}

/// Möller–Trumbore (`methods::mt`).
pub struct Mt;
fn mt1(k: &MtK<f32>, d: &V3<f32>) -> Option<f32> {
    mt_x1(k, *d)
}
two_triangle_family!(
    Mt,
    MtK,
    V3<f32>,
    [f32x8; 3],
    |d| d,
    |d: &[f32x8; 3]| *d,
    mt1,
    mt_x8
);

/// Woop–Benthin–Wald watertight (`methods::woop`).
pub struct Watertight;
two_triangle_family!(
    Watertight,
    WoopK,
    WoopRay<f32>,
    WoopRay8,
    woop_ray,
    WoopRay8::new,
    woop_x1,
    woop_x8
);

/// The seed's plane + determinants (`methods::plane`).
pub struct Plane;
fn plane1(k: &PlaneK<f32>, d: &V3<f32>) -> Option<f32> {
    plane_x1(k, *d)
}
two_triangle_family!(
    Plane,
    PlaneK,
    V3<f32>,
    [f32x8; 3],
    |d| d,
    |d: &[f32x8; 3]| *d,
    plane1,
    plane_x8
);

/// One method's constants for one scene, with the camera's f32 ray tables.
pub struct Kit<S: SphereFamily, P: PolyFamily> {
    /// Each sphere's constants and its id as f32, in file order.
    pub spheres: Vec<(S::K, f32)>,
    /// Each triangle's constants and id (those the method drops are left out).
    pub triangles: Vec<(P::T, f32)>,
    /// Each quad's constants and id (those the method drops are left out).
    pub quads: Vec<(P::Q, f32)>,
    /// The camera's f32 ray tables, padded to whole 4x2 blocks.
    pub tables: RayTables<f32>,
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
    _m: PhantomData<fn() -> (S, P)>,
}

impl<S: SphereFamily, P: PolyFamily> Kit<S, P> {
    /// The method's constants for every shape of `scene` seen by `camera` (the setup phase).
    pub fn new(scene: &Scene, camera: &Camera) -> Self {
        let eye = camera.eye;
        let mut kit = Kit {
            spheres: Vec::new(),
            triangles: Vec::new(),
            quads: Vec::new(),
            tables: camera.tables(BW as u32, BH as u32),
            width: camera.width as usize,
            height: camera.height as usize,
            _m: PhantomData,
        };
        for (id, shape) in scene.shapes.iter().enumerate() {
            let id = id as f32;
            match shape {
                Shape::Sphere { center, radius } => {
                    kit.spheres.push((S::make(center, radius, eye), id))
                }
                Shape::Triangle(v) => {
                    if let Some(k) = P::tri(&v, eye) {
                        kit.triangles.push((k, id))
                    }
                }
                Shape::Quad(v) => {
                    if let Some(k) = P::quad(&v, eye) {
                        kit.quads.push((k, id))
                    }
                }
            }
        }
        kit
    }

    /// Nearest hits of eight rays, folded into `hit`.
    #[inline]
    pub fn trace_x8(&self, d: &[f32x8; 3], hit: &mut Hit8) {
        for (k, id) in &self.spheres {
            if let Some((m, t)) = S::x8(k, d) {
                hit.update(m, t, *id);
            }
        }
        if self.triangles.is_empty() && self.quads.is_empty() {
            return;
        }
        let r = P::ray8(d);
        for (k, id) in &self.triangles {
            if let Some((m, t)) = P::tri_x8(k, &r) {
                hit.update(m, t, *id);
            }
        }
        for (k, id) in &self.quads {
            if let Some((m, t)) = P::quad_x8(k, &r) {
                hit.update(m, t, *id);
            }
        }
    }

    /// Nearest hit of one ray.
    pub fn trace_x1(&self, d: V3<f32>) -> Hit<f32> {
        let mut hit = Hit::NONE;
        for (k, id) in &self.spheres {
            if let Some(t) = S::x1(k, d) {
                hit.update(t, *id as i32);
            }
        }
        let r = P::ray1(d);
        for (k, id) in &self.triangles {
            if let Some(t) = P::tri_x1(k, &r) {
                hit.update(t, *id as i32);
            }
        }
        for (k, id) in &self.quads {
            if let Some(t) = P::quad_x1(k, &r) {
                hit.update(t, *id as i32);
            }
        }
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

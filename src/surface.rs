//! What a frame says about the surfaces it hit, beyond ids and distances: depth along the
//! optical axis ([`Frame::z_depth`]) and each hit's surface normal ([`Frame::normals`]), as
//! dataset users ask for them (the command line's `--zdepth` and `--normals`, Python's
//! `zdepth=True` and `normals=True`), and the headlight `|n . d|` that `-cm shade` lights a hit
//! by ([`Frame::headlight`]). All are computed per pixel from the frame, the camera and the
//! scene's primitives, after the render; the render itself is unchanged.
//!
//! Formulas (f64, rounded to f32 once):
//! - z-depth: `t (d . f)`, with `t` the pixel's distance along its unit ray `d` (the camera's
//!   f64 ray, `RayTables::dir_x1`) and `f` the unit forward axis. Relative error a few units
//!   of f32 rounding (`t` is the f32 depth): `t` itself is the only rounded input, so against
//!   the exact hit the error is the depth's (within 1e-5 relative of the oracle's).
//! - Normals (each family's `Family::normal`), world coordinates, unit length, turned to face
//!   the eye (`n . (eye - P) > 0` for a polygon, so both sides of a sheet read as seen):
//!   - a triangle: `(B - A) x (C - A)`, a quad: `(C - A) x (D - B)` (its diagonals), the
//!     plane normals the kernels use (`kernel::polygon`), normalised; exact to f64 rounding
//!     whatever the distance, since only the vertices enter;
//!   - a sphere: `P - C` normalised, at the hit `P = eye + t d`, turned to face the eye when
//!     the eye is inside. `P` carries the f32 depth's error, at most `48u / cos(theta)` relative
//!     (u = 2^-24, theta the angle of incidence; the bound tests/agreement/ holds the kernels
//!     to), along the ray; that turns the normal by at most `48u t / (r cos(theta))` radians:
//!     about 5e-5 face-on on a sphere 16 radii away, more towards its silhouette, where the
//!     distance itself is ill-conditioned.
//! - Background: z-depth +inf, normal (0, 0, 0).
//!
//! Known to fail: none beyond the precision above; a pixel's normal is that of the primitive
//! the render reports, so where two primitives tie the id's primitive gives it.
//! Tested in `tests/surface.rs`: a picked scene (a floor, a wall wound backwards, a sphere),
//! and the exact hit along the same f64 ray over random scenes, cameras, scales and eyes
//! inside spheres; `tests/cli/surface_outputs.rs`: the command line's files against each
//! primitive's f64 normal and exact z-depth, with every `--accel`.

use crate::Frame;
use crate::camera::Camera;
use crate::par::prelude::*;
use crate::scene::Scene;
use crate::soa::{Stored, Visit, visit};
use glam::DVec3;

impl Frame<f32> {
    /// Depth along the camera's optical axis per pixel (+inf for background): [`Frame::depth`]
    /// is the distance along each pixel's ray, this is that distance projected onto the
    /// forward axis, as z-buffers and depth cameras report it. `camera` is the one the frame
    /// was rendered with.
    pub fn z_depth(&self, camera: &Camera) -> Vec<f32> {
        let tables = camera.tables::<f64>(1, 1);
        let f = camera.f;
        let w = self.width as usize;
        let mut z = Vec::with_capacity(self.depth.len());
        z.par_extend(self.depth.par_iter().enumerate().map(|(i, &t)| {
            let d = tables.dir_x1(i % w, i / w);
            (f64::from(t) * DVec3::from_array(d).dot(f)) as f32
        }));
        z
    }

    /// The unit surface normal of each pixel's hit in world coordinates, facing the eye, as
    /// `[x, y, z]` rows, row-major like [`Frame::ids`]; `[0, 0, 0]` for background. `scene` and
    /// `camera` are those the frame was rendered from (module comment: formulas, precision).
    pub fn normals(&self, scene: &Scene, camera: &Camera) -> Vec<[f32; 3]> {
        Surfaces::new(self, scene, camera).map([0.0; 3], |n, _| n.as_vec3().to_array())
    }

    /// The headlight term of each pixel, `|n . d|` in `[0, 1]`: the cosine between its hit's
    /// f64 normal (as [`Frame::normals`] gives it, before rounding to f32) and its unit f64
    /// ray, 1 face-on and 0 at grazing incidence; 0 for background. What `-cm shade` lights a
    /// surface by ([`crate::shade`]); rounded to f32 once.
    pub fn headlight(&self, scene: &Scene, camera: &Camera) -> Vec<f32> {
        Surfaces::new(self, scene, camera).map(0.0, |n, d| n.dot(d).abs().min(1.0) as f32)
    }
}

/// What the per-pixel surface functions share: the frame, its scene, its camera's f64 rays.
struct Surfaces<'a> {
    frame: &'a Frame<f32>,
    scene: &'a Scene,
    tables: crate::camera::RayTables<f64>,
    eye: DVec3,
}

impl<'a> Surfaces<'a> {
    fn new(frame: &'a Frame<f32>, scene: &'a Scene, camera: &Camera) -> Self {
        Surfaces {
            frame,
            scene,
            tables: camera.tables::<f64>(1, 1),
            eye: camera.eye,
        }
    }

    /// `f(n, d)` for every pixel that hit, `background` for the others, row-major: `n` the
    /// hit's unit f64 normal facing the eye (the one formula of the module comment), `d` its
    /// unit f64 ray. Rows run in parallel; along a row, a polygon's normal, which depends on its
    /// id alone, is computed once per run of pixels that show it.
    fn map<T: Copy + Send + Sync>(
        &self,
        background: T,
        f: impl Fn(DVec3, DVec3) -> T + Sync + Send,
    ) -> Vec<T> {
        let (ids, w) = (&self.frame.ids, self.frame.width as usize);
        let mut out = vec![background; ids.len()];
        if ids.is_empty() {
            return out;
        }
        out.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
            let mut last: Option<(i32, DVec3)> = None;
            for (x, o) in row.iter_mut().enumerate() {
                let id = ids[y * w + x];
                if id < 0 || id as usize >= self.scene.shapes.len() {
                    continue;
                }
                let d = DVec3::from_array(self.tables.dir_x1(x, y));
                let n = match last {
                    Some((lid, n)) if lid == id => n,
                    _ => {
                        let (n, polygon) = self.normal(id, d, self.frame.depth[y * w + x]);
                        last = polygon.then_some((id, n));
                        n
                    }
                };
                *o = f(n, d);
            }
        });
        out
    }

    /// The unit f64 normal facing the eye of primitive `id`, hit at distance `t` along the unit
    /// ray `d`, and whether it is a flat one's (the same for every ray that hits it): its
    /// family's normal ([`Family::normal`](crate::kernel::Family::normal)).
    fn normal(&self, id: i32, d: DVec3, t: f32) -> (DVec3, bool) {
        struct At(DVec3, DVec3);
        impl Visit<(DVec3, bool)> for At {
            fn visit<F: Stored>(self, g: F::Geometry) -> (DVec3, bool) {
                F::normal(&g, self.0, self.1)
            }
        }
        let point = self.eye + d * f64::from(t);
        visit(self.scene.shapes.get(id as usize), At(self.eye, point))
    }
}

//! The pinhole camera: the one place where pixels become ray directions.
//!
//! Formula (the format's contract, so any other tool can reproduce a pixel):
//! ```text
//! f = normalize(look - eye); r = normalize(cross(f, up)); u = cross(r, f)
//! half_w = tan(fov/2); half_h = half_w * H / W          (fov horizontal)
//! pixel (x, y), y = 0 is the TOP row:
//!   sx = (2*(x + 0.5)/W - 1) * half_w
//!   sy = (1 - 2*(y + 0.5)/H) * half_h
//!   dir = normalize(f + sx*r + sy*u), origin = eye
//! ```
//! The basis, `half_w` and `half_h` are computed once in f64 and rounded to the kernel's
//! precision. `sx` and `sy` depend on one coordinate each, so they are tabulated per column and
//! per row ([`RayTables`]); the direction is then evaluated in the kernel's precision, in the
//! order written, with no fused multiply-add. [`RayTables::dir_x1`] and [`RayTables::dir_x8`]
//! perform the same operations in the same order, so in f32 they give bit-identical rays.

use crate::error::{Error, Result};
use crate::real::{Real, V3, dot, v3};
use crate::scene::{CameraSpec, Scene};
use glam::DVec3;
use wide::f32x8;

/// The orthonormal camera frame (forward, right, up), or `None` when `look == eye` or `up` is
/// parallel to the view direction (the cross product has no usable length).
pub fn basis(eye: DVec3, look: DVec3, up: DVec3) -> Option<[DVec3; 3]> {
    let f = (look - eye).try_normalize()?;
    let r = f.cross(up).try_normalize()?;
    let u = r.cross(f);
    Some([f, r, u])
}

/// A camera fixed to one image size.
#[derive(Debug, Clone, Copy)]
pub struct Camera {
    /// Ray origin for every pixel, in world coordinates.
    pub eye: DVec3,
    /// Forward: unit vector from the eye towards `look`.
    pub f: DVec3,
    /// Right: unit vector, normalize(f x up).
    pub r: DVec3,
    /// Camera up: unit vector, r x f.
    pub u: DVec3,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// tan(fov / 2), fov horizontal: the screen half-width at distance 1.
    pub half_w: f64,
    /// half_w * height / width: the screen half-height at distance 1.
    pub half_h: f64,
}

/// Horizontal field of view, in degrees, when neither the caller nor the scene gives one.
pub const DEFAULT_FOV: f64 = 60.0;

impl Camera {
    /// The camera of `scene` for a `width` x `height` image, with horizontal field of view
    /// `fov_deg` when given, else the scene's, else [`DEFAULT_FOV`]. Fails on a size outside
    /// `1..=limits::MAX_SIDE` per side or past `limits::MAX_PIXELS`, or a field of view outside
    /// (0, 180) degrees.
    pub fn for_scene(
        scene: &Scene,
        width: u32,
        height: u32,
        fov_deg: Option<f64>,
    ) -> Result<Camera> {
        let spec = CameraSpec {
            fov_deg: fov_deg.or(scene.camera.fov_deg),
            ..scene.camera
        };
        Camera::look_at(&spec, width, height)
    }

    /// The camera `spec` describes (eye, look, up and its fov, else [`DEFAULT_FOV`]) for a
    /// `width` x `height` image: a view of a scene other than its own `camera` line. Fails,
    /// naming what is wrong, on a spec `scene::validate::camera` refuses (eye on look, up
    /// parallel to the view, non-finite values), a size outside `1..=limits::MAX_SIDE` per side
    /// or past `limits::MAX_PIXELS`, or a field of view outside (0, 180) degrees.
    pub fn look_at(spec: &CameraSpec, width: u32, height: u32) -> Result<Camera> {
        crate::limits::check_size(width as u64, height as u64)
            .map_err(|why| Error::usage(format!("image size {width}x{height}: {why}")))?;
        let finite = [spec.eye, spec.look, spec.up].iter().all(|v| v.is_finite());
        if !finite {
            return Err(Error::usage(
                "camera: eye, look and up must be finite".to_string(),
            ));
        }
        crate::scene::validate::camera(spec).map_err(|m| Error::usage(format!("camera: {m}")))?;
        let fov = spec.fov_deg.unwrap_or(DEFAULT_FOV);
        crate::scene::validate::fov(fov)
            .map_err(|m| Error::usage(format!("field of view {fov}: {m}")))?;
        Ok(Camera::new(spec, fov, width, height))
    }

    /// The camera of a validated spec (`scene::validate::camera` has accepted it) with a
    /// horizontal field of view in degrees, 0 < fov < 180.
    pub fn new(spec: &CameraSpec, fov_deg: f64, width: u32, height: u32) -> Camera {
        let [f, r, u] = basis(spec.eye, spec.look, spec.up)
            .expect("camera spec is validated before a Camera is made");
        let half_w = (fov_deg.to_radians() / 2.0).tan();
        let half_h = half_w * height as f64 / width as f64;
        Camera {
            eye: spec.eye,
            f,
            r,
            u,
            width,
            height,
            half_w,
            half_h,
        }
    }

    /// Screen coordinate of column `x`: sx = (2*(x + 0.5)/W - 1) * half_w, evaluated in `T`.
    #[inline]
    pub fn sx<T: Real>(&self, x: u32) -> T {
        let w = T::from_f64(self.width as f64);
        (T::TWO * (T::from_f64(x as f64) + T::HALF) / w - T::ONE) * T::from_f64(self.half_w)
    }

    /// Screen coordinate of row `y` (0 = top): sy = (1 - 2*(y + 0.5)/H) * half_h, in `T`.
    #[inline]
    pub fn sy<T: Real>(&self, y: u32) -> T {
        let h = T::from_f64(self.height as f64);
        (T::ONE - T::TWO * (T::from_f64(y as f64) + T::HALF) / h) * T::from_f64(self.half_h)
    }

    /// A bound, in radians, on the angle between any pixel's f32 ray direction and its f64 one
    /// ([`RayTables::dir_x1`] in each precision), to first order in u = 2^-24.
    ///
    /// With `v = f + sx r + sy u` (|v| = sqrt(1 + sx^2 + sy^2) >= 1, the basis orthonormal):
    /// - the f32 tables' own rounding: the basis vectors moved by `Δf`, `Δr`, `Δu` move `v` by
    ///   at most `|Δf| + |sx||Δr| + |sy||Δu| <= sqrt(|Δf|^2 + |Δr|^2 + |Δu|^2) |v|`
    ///   (Cauchy-Schwarz), and the screen tables' `Δsx`, `Δsy` (computed in f32,
    ///   [`Camera::sx`]) by `|Δsx| + |Δsy| <= (|Δsx| + |Δsy|) |v|`; both are measured here,
    ///   exactly, against the f64 tables (whose own rounding is ~1e-16);
    /// - the arithmetic `(f + sx r) + sy u`, two products and two sums per component,
    ///   rounded: component i errs by at most `u (2|f_i| + 3|sx r_i| + 2|sy u_i|)`, so the vector
    ///   by `u (2 + 3|sx| + 2|sy|) <= u sqrt(17) |v|`;
    /// - the normalisation: the length's rounding scales every component alike (no turn),
    ///   and the three divisions, each rounded, turn it by at most u.
    ///
    /// An error `e` turns `v` by at most `|e| / |v|`. So the angle is at most
    /// `(sqrt(17) + 1) u + max |Δsx| + max |Δsy| + sqrt(|Δf|^2 + |Δr|^2 + |Δu|^2)`: about 6u to
    /// 8u for fields of view up to 90 degrees (the screen tables' part grows with `half_w`).
    /// The f32 direction's length differs from 1 by at most 3.5u (the sum of three squares:
    /// 3u, halved by the square root, plus its rounding and the division's); that scales the
    /// ray without turning it. `render::redecide` builds its trust rule on both, and its tests
    /// check the rule against the kernels; `accel::reach` the tiles' and BVH's culling.
    pub fn direction_error(&self) -> f64 {
        let (t32, t64) = (self.tables::<f32>(1, 1), self.tables::<f64>(1, 1));
        let worst = |a: &[f32], b: &[f64]| {
            a.iter()
                .zip(b)
                .map(|(&a, &b)| (a as f64 - b).abs())
                .fold(0.0, f64::max)
        };
        let moved =
            |a: V3<f32>, b: V3<f64>| (0..3).map(|i| (a[i] as f64 - b[i]).powi(2)).sum::<f64>();
        let basis = (moved(t32.f, t64.f) + moved(t32.r, t64.r) + moved(t32.u, t64.u)).sqrt();
        let u = crate::real::U32;
        (17f64.sqrt() + 1.0) * u + worst(&t32.sx, &t64.sx) + worst(&t32.sy, &t64.sy) + basis
    }

    /// Per-column and per-row screen coordinates and the rounded basis, in `T`. Tables are
    /// padded to a multiple of `pad_x` columns and `pad_y` rows by repeating the last entry, so
    /// packet blocks at the image border read valid (masked) values.
    pub fn tables<T: Real>(&self, pad_x: u32, pad_y: u32) -> RayTables<T> {
        let cols = self.width.div_ceil(pad_x) * pad_x;
        let rows = self.height.div_ceil(pad_y) * pad_y;
        RayTables {
            sx: (0..cols).map(|x| self.sx(x.min(self.width - 1))).collect(),
            sy: (0..rows).map(|y| self.sy(y.min(self.height - 1))).collect(),
            f: v3(self.f),
            r: v3(self.r),
            u: v3(self.u),
        }
    }
}

/// What the kernels need to make any pixel's ray: see the module comment.
#[derive(Debug, Clone)]
pub struct RayTables<T> {
    /// Screen x of each column ([`Camera::sx`]), padded by repeating the last column.
    pub sx: Vec<T>,
    /// Screen y of each row ([`Camera::sy`], row 0 at the top), padded likewise.
    pub sy: Vec<T>,
    /// Forward basis vector, rounded to `T`.
    pub f: V3<T>,
    /// Right basis vector, rounded to `T`.
    pub r: V3<T>,
    /// Up basis vector, rounded to `T`.
    pub u: V3<T>,
}

impl<T: Real> RayTables<T> {
    /// Unit direction of pixel (x, y): normalize(f + sx*r + sy*u).
    #[inline]
    pub fn dir_x1(&self, x: usize, y: usize) -> V3<T> {
        let (sx, sy) = (self.sx[x], self.sy[y]);
        let (f, r, u) = (self.f, self.r, self.u);
        let d = [
            f[0] + sx * r[0] + sy * u[0],
            f[1] + sx * r[1] + sy * u[1],
            f[2] + sx * r[2] + sy * u[2],
        ];
        let len = dot(d, d).sqrt();
        [d[0] / len, d[1] / len, d[2] / len]
    }
}

impl RayTables<f32> {
    /// Eight directions at once, lane by lane the same operations as [`Self::dir_x1`].
    #[inline(always)]
    pub fn dir_x8(&self, sx: f32x8, sy: f32x8) -> [f32x8; 3] {
        let (f, r, u) = (self.f, self.r, self.u);
        let c = |i: usize| f32x8::splat(f[i]) + sx * f32x8::splat(r[i]) + sy * f32x8::splat(u[i]);
        let d = [c(0), c(1), c(2)];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        [d[0] / len, d[1] / len, d[2] / len]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> CameraSpec {
        CameraSpec {
            eye: DVec3::new(0.0, 0.0, 5.0),
            look: DVec3::ZERO,
            up: DVec3::Y,
            fov_deg: None,
        }
    }

    #[test]
    fn basis_is_right_handed_and_orthonormal() {
        let [f, r, u] = basis(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(-4.0, 0.5, 2.0),
            DVec3::Y,
        )
        .unwrap();
        for v in [f, r, u] {
            assert!((v.length() - 1.0).abs() < 1e-15);
        }
        assert!(f.dot(r).abs() < 1e-15 && f.dot(u).abs() < 1e-15 && r.dot(u).abs() < 1e-15);
        assert!(
            (r.cross(u) - (-f)).length() < 1e-15,
            "r x u = -f: camera looks down -z of (r,u)"
        );
    }

    #[test]
    fn degenerate_bases_are_refused() {
        assert!(basis(DVec3::ONE, DVec3::ONE, DVec3::Y).is_none());
        assert!(basis(DVec3::ZERO, DVec3::Y, DVec3::Y).is_none());
    }

    #[test]
    fn centre_pixel_of_odd_image_looks_at_look_and_row_zero_is_top() {
        let cam = Camera::new(&spec(), 90.0, 3, 3);
        let t = cam.tables::<f64>(1, 1);
        let d = t.dir_x1(1, 1);
        assert_eq!(d, [0.0, 0.0, -1.0]);
        // Top-left pixel points up (+y) and left (-x) for a camera looking down -z with up +y.
        let d = t.dir_x1(0, 0);
        assert!(d[0] < 0.0 && d[1] > 0.0);
        // fov 90: half_w = 1; column 0's sx = (2*0.5/3 - 1) = -2/3.
        assert!((t.sx[0] + 2.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn x8_directions_equal_x1_bit_for_bit() {
        let cam = Camera::new(&spec(), 73.0, 37, 11);
        let t = cam.tables::<f32>(4, 2);
        for y in 0..11 {
            for x0 in (0..37).step_by(8) {
                let xs: [usize; 8] = std::array::from_fn(|i| (x0 + i).min(36));
                let sx = f32x8::new(xs.map(|x| t.sx[x]));
                let d8 = t.dir_x8(sx, f32x8::splat(t.sy[y]));
                for (lane, &x) in xs.iter().enumerate() {
                    let d1 = t.dir_x1(x, y);
                    for k in 0..3 {
                        assert_eq!(d8[k].to_array()[lane].to_bits(), d1[k].to_bits());
                    }
                }
            }
        }
    }

    /// Every pixel's f32 ray direction lies within [`Camera::direction_error`] of its f64 one,
    /// and its length within 3.5u of 1, for cameras turned off the axes with narrow to wide
    /// fields of view; and the bound is not loose by more than a few times.
    #[test]
    fn f32_directions_stay_within_the_stated_error() {
        let u = crate::real::U32;
        let specs = [
            (
                DVec3::new(0.3, -1.7, 5.2),
                DVec3::new(-0.4, 0.9, -2.0),
                DVec3::Y,
            ),
            (
                DVec3::new(1e3, 2e3, -3e3),
                DVec3::new(1e3 + 1.0, 2e3 - 0.3, -3e3 + 0.7),
                DVec3::Z,
            ),
            (DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), DVec3::Y),
        ];
        let mut worst_ratio: f64 = 0.0;
        for (eye, look, up) in specs {
            let spec = CameraSpec {
                eye,
                look,
                up,
                fov_deg: None,
            };
            for (fov, w, h) in [
                (20.0, 160, 90),
                (60.0, 211, 117),
                (90.0, 128, 128),
                (150.0, 97, 61),
            ] {
                let cam = Camera::new(&spec, fov, w, h);
                let bound = cam.direction_error();
                let (t32, t64) = (cam.tables::<f32>(1, 1), cam.tables::<f64>(1, 1));
                for y in 0..h as usize {
                    for x in 0..w as usize {
                        let (a, b) = (t32.dir_x1(x, y).map(f64::from), t64.dir_x1(x, y));
                        let len = dot(a, a).sqrt();
                        assert!((len - 1.0).abs() <= 3.5 * u, "length {len} at ({x}, {y})");
                        let cross = [
                            a[1] * b[2] - a[2] * b[1],
                            a[2] * b[0] - a[0] * b[2],
                            a[0] * b[1] - a[1] * b[0],
                        ];
                        let angle = dot(cross, cross).sqrt() / len;
                        assert!(
                            angle <= bound,
                            "{angle:e} > {bound:e} at ({x}, {y}), fov {fov}"
                        );
                        worst_ratio = worst_ratio.max(angle / bound);
                    }
                }
            }
        }
        eprintln!("largest angle / direction_error {worst_ratio:.2}");
        assert!(
            worst_ratio > 0.2,
            "the bound is {:.1} times the worst angle",
            1.0 / worst_ratio
        );
    }
}

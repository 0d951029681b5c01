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
        crate::limits::check_size(width as u64, height as u64)
            .map_err(|why| Error::usage(format!("image size {width}x{height}: {why}")))?;
        let fov = fov_deg.or(scene.camera.fov_deg).unwrap_or(DEFAULT_FOV);
        crate::scene::validate::fov(fov)
            .map_err(|m| Error::usage(format!("field of view {fov}: {m}")))?;
        Ok(Camera::new(&scene.camera, fov, width, height))
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
}

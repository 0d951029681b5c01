//! The pinhole camera: the one place where pixels become ray directions.
//!
//! Formula (the format's contract, so any other tool can reproduce a pixel):
//! ```text
//! f = normalize(look - eye); r = normalize(cross(f, up)); u = cross(r, f)      (basis.rs)
//! intrinsics fx, fy, cx, cy in pixels (skew 0); a horizontal field of view is
//!   fx = fy = W / (2 tan(fov/2)), cx = W/2, cy = H/2
//! pixel (x, y), y = 0 is the TOP row, its centre at (x + 0.5, y + 0.5):
//!   sx = (x + 0.5 - cx) / fx
//!   sy = (cy - (y + 0.5)) / fy
//!   dir = normalize(f + sx*r + sy*u), origin = eye
//! ```
//! In OpenCV's axes (x right = r, y down = -u, z forward = f) that is `K^-1 (x + 0.5, y + 0.5,
//! 1)`, `K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]`: pixel x spans `[x, x + 1)` of K's image
//! coordinates, as in Open3D's `create_rays_pinhole` (OpenCV's own convention puts pixel x's
//! centre at `x`: add 0.5 to its cx and cy). The camera is [`Camera::world_to_camera`] and
//! [`Camera::k`].
//!
//! Evaluation. The camera holds `half_w = W / (2 fx)` and `half_h = H / (2 fy)` (the screen's
//! half-extents at distance 1) and the principal point, and evaluates, in the kernel's
//! precision, in this order, with no fused multiply-add:
//! ```text
//!   sx = (2*(x + 0.5)/W - 2cx/W) * half_w        sy = (2cy/H - 2*(y + 0.5)/H) * half_h
//! ```
//! (the formula above, rearranged), `2cx/W` and `2cy/H` rounded from f64. A field of view
//! sets `half_w = tan(fov/2)` and `half_h = half_w * H / W` directly, and its `2cx/W = 2cy/H =
//! 1` exactly, so its screen tables and rays are bit for bit those of the centred formula
//! `sx = (2*(x + 0.5)/W - 1) * tan(fov/2)` this camera had before intrinsics (tested below):
//! every existing comparison, and the byte identity of wasm and native, stands. For
//! intrinsics, `half_w` rounds `W / (2 fx)`, so an f64 ray lies within a few units of 1e-16
//! (relative to `1 + |sx| + |sy|`) of the formula evaluated directly (tested at random K,
//! principal points far off the centre and `fx != fy`).
//!
//! The basis, `half_w`, `half_h` and the principal point are computed once in f64 and rounded
//! to the kernel's precision. `sx` and `sy` depend on one coordinate each, so they are
//! tabulated per column and per row ([`RayTables`]); the direction is then evaluated in the
//! kernel's precision, in the order written. [`RayTables::dir_x1`] and [`RayTables::dir_x8`]
//! perform the same operations in the same order, so in f32 they give bit-identical rays.

use crate::basis::basis;
use crate::error::{Error, Result};
use crate::real::{Real, V3, dot, v3};
use crate::scene::{CameraSpec, Intrinsics, Lens, Scene};
use glam::DVec3;
use wide::f32x8;

/// The intrinsics of a 3x3 matrix `K = [[fx, s, cx], [0, fy, cy], [0, 0, 1]]` as calibrations
/// give it (module comment: pixel x spans `[x, x + 1)`), or why not, as an [`Error::Usage`]
/// (the caller's argument): a non-finite entry, a second or third row other than
/// `[0, fy, cy]` and `[0, 0, 1]`, a skew `s` beyond `1e-9 fx` (the pinhole has none), a focal
/// length that is not positive (`scene::validate::intrinsics`).
pub fn intrinsics_of_matrix(k: &[[f64; 3]; 3]) -> Result<Intrinsics> {
    intrinsics_of(k).map_err(Error::Usage)
}

fn intrinsics_of(k: &[[f64; 3]; 3]) -> std::result::Result<Intrinsics, String> {
    if !k.iter().flatten().all(|x| x.is_finite()) {
        return Err("K must be finite".into());
    }
    if k[1][0] != 0.0 || k[2] != [0.0, 0.0, 1.0] {
        return Err(format!(
            "K must be [[fx, 0, cx], [0, fy, cy], [0, 0, 1]], got {k:?}"
        ));
    }
    let i = Intrinsics {
        fx: k[0][0],
        fy: k[1][1],
        cx: k[0][2],
        cy: k[1][2],
    };
    crate::scene::validate::intrinsics(&i).map_err(|m| format!("K: {m}"))?;
    if k[0][1].abs() > 1e-9 * i.fx {
        return Err(format!(
            "K: skew {} is not 0 (lanecast's pinhole has none)",
            k[0][1]
        ));
    }
    Ok(i)
}

/// The camera spec of a rig: intrinsics `k` (3x3, [`intrinsics_of_matrix`]) and a 4x4
/// world-to-camera matrix in OpenCV's axes (`scene::pose::from_world_to_camera`), or why not,
/// as an [`Error::Usage`], so that `?` lifts it into [`crate::Result`] as any other call's.
/// [`Camera::look_at`] then checks it against an image size.
///
/// ```
/// use lanecast::{Camera, CameraSpec, DVec3, Lens};
///
/// fn rig() -> lanecast::Result<(CameraSpec, Camera)> {
///     let k = [[525.0, 0.0, 319.5], [0.0, 525.0, 239.5], [0.0, 0.0, 1.0]];
///     let pose = [
///         [1.0, 0.0, 0.0, 0.0],
///         [0.0, -1.0, 0.0, 0.0],
///         [0.0, 0.0, -1.0, 9.0],
///         [0.0, 0.0, 0.0, 1.0],
///     ];
///     let spec = lanecast::spec_from_matrices(&k, &pose)?;
///     Ok((spec, Camera::look_at(&spec, 640, 480)?))
/// }
/// let (spec, camera) = rig()?;
/// assert_eq!(spec.eye, DVec3::new(0.0, 0.0, 9.0)); // lanecast::DVec3 is glam's
/// assert!(matches!(spec.lens, Some(Lens::Pinhole(_))));
/// assert_eq!(camera.k.fx, 525.0);
/// let skewed = [[525.0, 3.0, 319.5], [0.0, 525.0, 239.5], [0.0, 0.0, 1.0]];
/// let e = lanecast::spec_from_matrices(&skewed, &[[0.0; 4]; 4]).unwrap_err();
/// assert_eq!(e.exit_code(), 2);
/// # Ok::<(), lanecast::Error>(())
/// ```
pub fn spec_from_matrices(
    k: &[[f64; 3]; 3],
    world_to_camera: &[[f64; 4]; 4],
) -> Result<CameraSpec> {
    let k = intrinsics_of_matrix(k)?;
    let spec = crate::scene::pose::from_world_to_camera(world_to_camera).map_err(Error::Usage)?;
    Ok(CameraSpec {
        lens: Some(Lens::Pinhole(k)),
        ..spec
    })
}

/// The image-size rule ([`crate::limits::check_size`]) as a camera states it.
fn check_image(width: u32, height: u32) -> Result<()> {
    crate::limits::check_size(width as u64, height as u64)
        .map_err(|why| Error::usage(format!("image size {width}x{height}: {why}")))
}

/// A field of view's screen and intrinsics for a `width` x `height` image: `half_w =
/// tan(fov/2)`, `half_h = half_w H / W` (what the rays use), and `fx = W / (2 half_w)`, computed
/// once and used for `fy` too (the pixels are square), `cx = W/2`, `cy = H/2`.
fn fov_screen(fov_deg: f64, width: u32, height: u32) -> (f64, f64, Intrinsics) {
    let half_w = (fov_deg.to_radians() / 2.0).tan();
    let (w, h) = (width as f64, height as f64);
    let half_h = half_w * h / w;
    let fx = w / (2.0 * half_w);
    let k = Intrinsics {
        fx,
        fy: fx,
        cx: w / 2.0,
        cy: h / 2.0,
    };
    (half_w, half_h, k)
}

/// The size-dependent rule of a lens, one for both kinds: its intrinsics (a field of view's
/// are [`fov_screen`]'s) within [`crate::limits::check_lens`] for a `width` x `height` image.
/// A field of view's refusal says which fields of view the size allows. The lens's own rules
/// (`scene::validate::camera`) are checked before.
pub(crate) fn check_lens(lens: &Lens, width: u32, height: u32) -> std::result::Result<(), String> {
    use crate::limits::{MAX_SCREEN, MIN_SCREEN};
    match *lens {
        Lens::Pinhole(k) => crate::limits::check_lens(k.fx, k.fy, k.cx, k.cy, width, height),
        Lens::Fov(deg) => {
            let (_, _, k) = fov_screen(deg, width, height);
            crate::limits::check_lens(k.fx, k.fy, k.cx, k.cy, width, height).map_err(|_| {
                // the screen's width 2 tan(fov/2) = W / fx, and H / fy = that times H / W
                let aspect = height as f64 / width as f64;
                let lo = MIN_SCREEN.max(MIN_SCREEN / aspect);
                let hi = MAX_SCREEN.min(MAX_SCREEN / aspect);
                let deg_of = |screen: f64| 2.0 * (screen / 2.0).atan().to_degrees();
                format!(
                    "a field of view of {} degrees gives a screen {:.3e} wide at distance 1 \
                     (W / fx) for a {width}x{height} image; W / fx and H / fy must span \
                     {MIN_SCREEN:e} to {MAX_SCREEN:e}, as for intrinsics, so at this size the \
                     field of view must lie within {:.4e} and {:.9} degrees",
                    crate::scene::cameras::num(deg),
                    width as f64 / k.fx,
                    deg_of(lo),
                    deg_of(hi),
                )
            })
        }
    }
}

/// The id band's width in pixels ([`Camera::id_band`]): an eighth of the smallest pixel.
pub const ID_BAND_PIXELS: f64 = 0.125;

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
    /// W / (2 fx): the screen's half-width at distance 1 (tan(fov / 2) for a field of view).
    pub half_w: f64,
    /// H / (2 fy): the screen's half-height at distance 1 (half_w * H / W for a field of view).
    pub half_h: f64,
    /// The intrinsics in pixels: as given, or those of the field of view (fx = W / (2 half_w),
    /// fy = H / (2 half_h), cx = W/2, cy = H/2).
    pub k: Intrinsics,
}

/// Horizontal field of view, in degrees, when neither the caller nor the scene gives one.
pub const DEFAULT_FOV: f64 = 60.0;

impl Camera {
    /// The camera of `scene` for a `width` x `height` image, with horizontal field of view
    /// `fov_deg` when given (in place of the scene's lens), else the scene's lens (a field of
    /// view or intrinsics), else [`DEFAULT_FOV`]. Fails as [`Camera::look_at`].
    /// An error about the scene's own camera (its lens for this size) names the scene's
    /// `camera` line, `FILE:LINE:COL`, as a views file's line would be named.
    pub fn for_scene(
        scene: &Scene,
        width: u32,
        height: u32,
        fov_deg: Option<f64>,
    ) -> Result<Camera> {
        check_image(width, height)?;
        let spec = CameraSpec {
            lens: fov_deg.map(Lens::Fov).or(scene.camera.lens),
            ..scene.camera
        };
        Camera::look_at(&spec, width, height).map_err(|e| match scene.camera_at {
            // the caller's fov is the caller's to answer for; the rest is the scene's line
            Some((line, col)) if fov_deg.is_none() => {
                Error::input(&scene.source, line, col, e.to_string())
            }
            _ => e,
        })
    }

    /// The camera `spec` describes (eye, look, up and its lens, else [`DEFAULT_FOV`]) for a
    /// `width` x `height` image: a view of a scene other than its own `camera` line. Fails,
    /// naming what is wrong, on a spec `scene::validate::camera` refuses (eye on look, up
    /// parallel to the view, non-finite values, a field of view outside (0, 180) degrees, a
    /// focal length that is not positive), a size outside `1..=limits::MAX_SIDE` per side or
    /// past `limits::MAX_PIXELS`, or intrinsics outside `limits::check_lens` for that size.
    pub fn look_at(spec: &CameraSpec, width: u32, height: u32) -> Result<Camera> {
        check_image(width, height)?;
        let finite = [spec.eye, spec.look, spec.up].iter().all(|v| v.is_finite());
        if !finite {
            return Err(Error::usage(
                "camera: eye, look and up must be finite".to_string(),
            ));
        }
        crate::scene::validate::camera(spec).map_err(|m| Error::usage(format!("camera: {m}")))?;
        let lens = spec.lens.unwrap_or(Lens::Fov(DEFAULT_FOV));
        check_lens(&lens, width, height).map_err(|m| Error::usage(format!("camera: {m}")))?;
        match lens {
            Lens::Pinhole(k) => Ok(Camera::pinhole(spec, &k, width, height)),
            Lens::Fov(fov) => Ok(Camera::new(spec, fov, width, height)),
        }
    }

    /// The camera of a validated spec (`scene::validate::camera` has accepted it) with a
    /// horizontal field of view in degrees, 0 < fov < 180 (the spec's own lens is not read).
    pub fn new(spec: &CameraSpec, fov_deg: f64, width: u32, height: u32) -> Camera {
        let (half_w, half_h, k) = fov_screen(fov_deg, width, height);
        Camera::with_screen(spec, half_w, half_h, k, width, height)
    }

    /// The camera of a validated spec with intrinsics `k` that `limits::check_lens` accepts
    /// for this size (the spec's own lens is not read).
    pub fn pinhole(spec: &CameraSpec, k: &Intrinsics, width: u32, height: u32) -> Camera {
        let half_w = width as f64 / (2.0 * k.fx);
        let half_h = height as f64 / (2.0 * k.fy);
        Camera::with_screen(spec, half_w, half_h, *k, width, height)
    }

    fn with_screen(
        spec: &CameraSpec,
        half_w: f64,
        half_h: f64,
        k: Intrinsics,
        width: u32,
        height: u32,
    ) -> Camera {
        let [f, r, u] = basis(spec.eye, spec.look, spec.up)
            .expect("camera spec is validated before a Camera is made");
        Camera {
            eye: spec.eye,
            f,
            r,
            u,
            width,
            height,
            half_w,
            half_h,
            k,
        }
    }

    /// The principal point in units of the half image, `(2cx/W, 2cy/H)`: (1, 1) exactly for a
    /// field of view.
    #[inline]
    pub fn principal(&self) -> (f64, f64) {
        (
            2.0 * self.k.cx / self.width as f64,
            2.0 * self.k.cy / self.height as f64,
        )
    }

    /// The image's edges in screen coordinates: `[left, right, bottom, top]`, `sx` of pixel
    /// coordinates 0 and W, `sy` of H and 0 (`[-half_w, half_w, -half_h, half_h]` exactly for
    /// a field of view). Every pixel centre's exact `(sx, sy)` lies inside, half a pixel in.
    pub fn screen(&self) -> [f64; 4] {
        let (px, py) = self.principal();
        [
            -px * self.half_w,
            (2.0 - px) * self.half_w,
            (py - 2.0) * self.half_h,
            py * self.half_h,
        ]
    }

    /// The largest `|sx|` and `|sy|` over the image ([`Camera::screen`]).
    pub fn screen_reach(&self) -> (f64, f64) {
        let [l, r, b, t] = self.screen();
        (l.abs().max(r.abs()), b.abs().max(t.abs()))
    }

    /// Screen coordinate of column `x`: sx = (2*(x + 0.5)/W - 2cx/W) * half_w, evaluated in `T`.
    #[inline]
    pub fn sx<T: Real>(&self, x: u32) -> T {
        let w = T::from_f64(self.width as f64);
        let px = T::from_f64(self.principal().0);
        (T::TWO * (T::from_f64(x as f64) + T::HALF) / w - px) * T::from_f64(self.half_w)
    }

    /// Screen coordinate of row `y` (0 = top): sy = (2cy/H - 2*(y + 0.5)/H) * half_h, in `T`.
    #[inline]
    pub fn sy<T: Real>(&self, y: u32) -> T {
        let h = T::from_f64(self.height as f64);
        let py = T::from_f64(self.principal().1);
        (py - T::TWO * (T::from_f64(y as f64) + T::HALF) / h) * T::from_f64(self.half_h)
    }

    /// The 3x3 intrinsic matrix `[[fx, 0, cx], [0, fy, cy], [0, 0, 1]]` (module comment).
    pub fn k_matrix(&self) -> [[f64; 3]; 3] {
        let k = self.k;
        [[k.fx, 0.0, k.cx], [0.0, k.fy, k.cy], [0.0, 0.0, 1.0]]
    }

    /// The 4x4 world-to-camera matrix in OpenCV's axes (x right, y down, z forward), row-major:
    /// rotation rows `r`, `-u`, `f`, translation `-R eye`, last row `0 0 0 1`.
    pub fn world_to_camera(&self) -> [[f64; 4]; 4] {
        let rows = [self.r, -self.u, self.f];
        let mut m = [[0.0; 4]; 4];
        for (i, a) in rows.iter().enumerate() {
            m[i] = [a.x, a.y, a.z, -a.dot(self.eye)];
        }
        m[3] = [0.0, 0.0, 0.0, 1.0];
        m
    }

    /// The smallest angle, in radians, between the rays of two neighbouring pixel centres
    /// anywhere in the image: a screen step `s` (`2 half_w / W` across, `2 half_h / H` down) at
    /// screen radius `rho` turns the ray by at least `s / (1 + rho^2)` (the radial step; a
    /// tangential one turns it by `s / sqrt(1 + rho^2)`), and `rho` is largest at a corner.
    pub fn pixel_angle(&self) -> f64 {
        let step =
            (2.0 * self.half_w / self.width as f64).min(2.0 * self.half_h / self.height as f64);
        let (rx, ry) = self.screen_reach();
        step / (1.0 + rx * rx + ry * ry)
    }

    /// The id band of this view, in radians: a pixel whose ray passes within this angle of a
    /// primitive's boundary (its true boundary, measured on the sphere of directions) may take
    /// a neighbour's id in any precision other than f64, and `compare` excuses it there. It is
    /// [`ID_BAND_PIXELS`] of [`Camera::pixel_angle`], so it scales with the view: a telephoto
    /// camera's band is as many pixels wide as a wide-angle one's. `--precision auto` trusts
    /// the f32 kernels only where their own error stays inside it (`render::redecide`).
    pub fn id_band(&self) -> f64 {
        ID_BAND_PIXELS * self.pixel_angle()
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
            lens: None,
        }
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
    /// fields of view, and pinholes of those focal lengths with `fy != fx` and the principal
    /// point off the image; and the bound is not loose by more than a few times.
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
                lens: None,
            };
            for (fov, w, h) in [
                (20.0f64, 160, 90),
                (60.0, 211, 117),
                (90.0, 128, 128),
                (150.0, 97, 61),
            ] {
                let fx = w as f64 / (2.0 * (fov.to_radians() / 2.0).tan());
                let off = Intrinsics {
                    fx,
                    fy: 1.3 * fx,
                    cx: 0.2 * w as f64 - 3.0,
                    cy: 1.7 * h as f64,
                };
                for cam in [
                    Camera::new(&spec, fov, w, h),
                    Camera::pinhole(&spec, &off, w, h),
                ] {
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
        }
        eprintln!("largest angle / direction_error {worst_ratio:.2}");
        assert!(
            worst_ratio > 0.2,
            "the bound is {:.1} times the worst angle",
            1.0 / worst_ratio
        );
    }

    /// Today's fov cameras are the centred special case bit for bit: every screen table entry,
    /// in f32 and f64, equals the formula before intrinsics, `sx = (2*(x + 0.5)/W - 1) *
    /// tan(fov/2)`, `sy = (1 - 2*(y + 0.5)/H) * half_w * H / W`, evaluated in the table's
    /// precision; and the camera's K is that of the field of view.
    #[test]
    fn fov_cameras_keep_the_centred_formula_bit_for_bit() {
        fn old<T: Real>(cam: &Camera, fov: f64) -> (Vec<T>, Vec<T>) {
            let half_w = (fov.to_radians() / 2.0).tan();
            let half_h = half_w * cam.height as f64 / cam.width as f64;
            let (w, h) = (
                T::from_f64(cam.width as f64),
                T::from_f64(cam.height as f64),
            );
            let sx = (0..cam.width)
                .map(|x| {
                    (T::TWO * (T::from_f64(x as f64) + T::HALF) / w - T::ONE) * T::from_f64(half_w)
                })
                .collect();
            let sy = (0..cam.height)
                .map(|y| {
                    (T::ONE - T::TWO * (T::from_f64(y as f64) + T::HALF) / h) * T::from_f64(half_h)
                })
                .collect();
            (sx, sy)
        }
        let mut rng = crate::test_rng::Rng(38);
        for _ in 0..300 {
            let fov = rng.log(-4.0, 179.9f64.log10());
            let w = rng.log(0.0, 65536f64.log10()).round().max(1.0) as u32;
            let h = rng.log(0.0, 4096f64.log10()).round().max(1.0) as u32;
            let cam = Camera::new(&spec(), fov, w, h);
            assert_eq!(cam.principal(), (1.0, 1.0));
            let (t32, t64) = (cam.tables::<f32>(1, 1), cam.tables::<f64>(1, 1));
            let (sx32, sy32) = old::<f32>(&cam, fov);
            let (sx64, sy64) = old::<f64>(&cam, fov);
            let bits32 = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let bits64 = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits32(&t32.sx), bits32(&sx32), "fov {fov}, {w}x{h}");
            assert_eq!(bits32(&t32.sy), bits32(&sy32), "fov {fov}, {w}x{h}");
            assert_eq!(bits64(&t64.sx), bits64(&sx64), "fov {fov}, {w}x{h}");
            assert_eq!(bits64(&t64.sy), bits64(&sy64), "fov {fov}, {w}x{h}");
            let hw = (fov.to_radians() / 2.0).tan();
            assert_eq!(cam.screen(), [-hw, hw, -cam.half_h, cam.half_h]);
            assert_eq!(cam.k.cx, w as f64 / 2.0);
            assert!((cam.k.fx / (w as f64 / (2.0 * hw)) - 1.0).abs() < 1e-15);
            assert_eq!(cam.k.fy, cam.k.fx, "square pixels: fy is fx");
        }
    }

    /// A pinhole's f64 rays equal the reference formula evaluated directly,
    /// `normalize(f + (x + 0.5 - cx)/fx r + (cy - y - 0.5)/fy u)`, at random K: focal lengths
    /// 1e-3 to 1e3 times the size, `fy` 0.1 to 10 times `fx`, principal points up to 50 image
    /// sizes off the centre; within 8 units of 1e-16, relative to the terms summed.
    #[test]
    fn pinhole_rays_equal_the_reference_formula() {
        let mut rng = crate::test_rng::Rng(7);
        let mut worst: f64 = 0.0;
        for _ in 0..300 {
            let w = rng.log(0.0, 3.0).round().max(1.0) as u32;
            let h = rng.log(0.0, 3.0).round().max(1.0) as u32;
            let fx = w as f64 * rng.log(-3.0, 3.0);
            let far = if rng.unit() < 0.3 { 50.0 } else { 1.0 };
            let k = Intrinsics {
                fx,
                fy: fx * rng.log(-1.0, 1.0),
                cx: w as f64 * (0.5 + rng.range(-far, far)),
                cy: h as f64 * (0.5 + rng.range(-far, far)),
            };
            let spec = CameraSpec {
                eye: rng.point(10.0),
                look: rng.point(10.0),
                up: rng.direction(),
                lens: Some(Lens::Pinhole(k)),
            };
            let Ok(cam) = Camera::look_at(&spec, w, h) else {
                continue;
            };
            let t = cam.tables::<f64>(1, 1);
            for _ in 0..50 {
                let (x, y) = (rng.below(w), rng.below(h));
                let sx = (x as f64 + 0.5 - k.cx) / k.fx;
                let sy = (k.cy - (y as f64 + 0.5)) / k.fy;
                let q = cam.f + sx * cam.r + sy * cam.u;
                let d = t.dir_x1(x as usize, y as usize);
                let err = (DVec3::from_array(d) - q.normalize()).length();
                // the tables' rounding: a few u of each term, over |q|
                let scale = (1.0
                    + sx.abs()
                    + sy.abs()
                    + (x as f64 + 0.5).abs() / k.fx
                    + k.cx.abs() / k.fx
                    + (y as f64 + 0.5).abs() / k.fy
                    + k.cy.abs() / k.fy)
                    / q.length();
                let rel = err / (scale * f64::EPSILON / 2.0);
                assert!(rel <= 8.0, "{rel} u at ({x}, {y}) of {w}x{h}, {k:?}");
                worst = worst.max(rel);
            }
        }
        eprintln!("largest error / (u * scale): {worst:.2}");
    }

    /// K and the world-to-camera matrix project a point on pixel (x, y)'s ray back to
    /// `(x + 0.5, y + 0.5)` (OpenCV: `(u, v, 1) z = K (R X + t)`), the matrix is a rotation
    /// (OpenCV axes: x right, y down, z forward) and maps the eye to the origin.
    #[test]
    fn k_and_world_to_camera_project_a_pixel_back_onto_it() {
        let mut rng = crate::test_rng::Rng(11);
        for i in 0..200 {
            let (w, h) = (rng.below(900) + 1, rng.below(700) + 1);
            let lens = if i % 2 == 0 {
                Lens::Fov(rng.range(1.0, 170.0))
            } else {
                let fx = w as f64 * rng.log(-1.0, 1.0);
                Lens::Pinhole(Intrinsics {
                    fx,
                    fy: fx * rng.log(-0.5, 0.5),
                    cx: w as f64 * rng.range(-1.0, 2.0),
                    cy: h as f64 * rng.range(-1.0, 2.0),
                })
            };
            let spec = CameraSpec {
                eye: rng.point(100.0),
                look: rng.point(100.0),
                up: rng.direction(),
                lens: Some(lens),
            };
            let Ok(cam) = Camera::look_at(&spec, w, h) else {
                continue;
            };
            let (k, m) = (cam.k_matrix(), cam.world_to_camera());
            let t = cam.tables::<f64>(1, 1);
            let apply = |p: DVec3| {
                let row = |i: usize| m[i][0] * p.x + m[i][1] * p.y + m[i][2] * p.z + m[i][3];
                DVec3::new(row(0), row(1), row(2))
            };
            assert!(apply(cam.eye).length() < 1e-12 * (1.0 + cam.eye.length()));
            assert_eq!(m[3], [0.0, 0.0, 0.0, 1.0]);
            let (x, y) = (rng.below(w), rng.below(h));
            let p = cam.eye + DVec3::from_array(t.dir_x1(x as usize, y as usize)) * 7.0;
            let c = apply(p);
            let u = (k[0][0] * c.x + k[0][1] * c.y + k[0][2] * c.z) / c.z;
            let v = (k[1][0] * c.x + k[1][1] * c.y + k[1][2] * c.z) / c.z;
            let tol = 1e-9 * (1.0 + (u - k[0][2]).abs() + (v - k[1][2]).abs());
            assert!(
                (u - (x as f64 + 0.5)).abs() < tol && (v - (y as f64 + 0.5)).abs() < tol,
                "({u}, {v}) for pixel ({x}, {y}) of {w}x{h}, {lens:?}"
            );
        }
    }

    /// Intrinsics `look_at` refuses for the image size, with the reason.
    #[test]
    fn pinholes_outside_the_limits_are_refused() {
        let k = |fx: f64, fy: f64, cx: f64, cy: f64| CameraSpec {
            lens: Some(Lens::Pinhole(Intrinsics { fx, fy, cx, cy })),
            ..spec()
        };
        let e = |s: CameraSpec| Camera::look_at(&s, 640, 480).unwrap_err().to_string();
        assert!(e(k(0.0, 500.0, 320.0, 240.0)).contains("fx = 0 pixels"));
        assert!(e(k(500.0, -1.0, 320.0, 240.0)).contains("fy = -1 pixels"));
        assert!(e(k(500.0, 500.0, f64::NAN, 240.0)).contains("cx"));
        assert!(e(k(1e-8, 500.0, 320.0, 240.0)).contains("W / fx"));
        assert!(e(k(500.0, 1e13, 320.0, 240.0)).contains("H / fy"));
        assert!(e(k(500.0, 500.0, 320.0 + 640e3 + 1.0, 240.0)).contains("principal point cx"));
        assert!(Camera::look_at(&k(500.0, 700.0, 319.5, -2000.0), 640, 480).is_ok());
    }
}

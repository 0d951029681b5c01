//! Intersection kernels. Each primitive family has its own file (`sphere.rs`; `polygon.rs` for
//! triangles and quads) holding its formula, its per-primitive constants and its 1-lane
//! (`*_x1`, generic over f32/f64) and 8-lane (`*_x8`, `wide::f32x8`) forms side by side, and
//! its [`Family`] type (`family.rs`): what the engine asks of it. `packet.rs` is the packet's
//! pixel block and its rays; `wide64.rs` the f64x4 lanes of `--precision f64`. The loops that
//! drive the kernels over a store's primitives sit above the stores (`soa/trace.rs`). The other
//! intersection methods the accuracy lab measures live in the lab crate (`lab/src/methods/`).
//!
//! Every kernel works in eye-relative coordinates: all primary rays share the eye as origin, so
//! each primitive's constants are computed once, in f64, relative to the eye, and only then
//! rounded to the kernel's precision. A scene far from the world origin loses nothing.
//!
//! Nearest-hit rule, identical in every driver ([`closer`] and [`Hit8::update`]): a hit counts
//! when 0 < t; it replaces the current one when t is smaller, or when t is exactly equal and its
//! primitive id is lower (exact ties go to the lower id).

pub mod family;
pub mod lanes;
pub mod packet;
pub mod polygon;
pub mod sphere;
pub mod wide64;

pub use family::Family;
pub use lanes::HitLanes;
pub use polygon::{Quad, Triangle};
pub use sphere::Sphere;

use crate::real::Real;
use wide::f32x8;

/// Rays per packet.
pub const LANES: usize = 8;

/// Edge tolerance of the triangle and quad tests, in radians of angle between the ray and an
/// edge's plane (the edge normals are unit vectors, the ray direction is a unit vector).
/// Evaluating `dot(d, n)` for unit `d` and a rounded unit `n` errs by at most about 4u
/// (u = unit roundoff: one rounding of `n`, plus the gamma_3 bound of a 3-term dot product), so
/// 8u is twice the error bound: a ray that exactly grazes a shared edge is accepted by both
/// triangles' tests rather than by neither. See `polygon.rs` for the watertightness argument.
#[inline]
pub fn edge_eps<T: Real>() -> T {
    T::from_f64(8.0) * T::UNIT_ROUNDOFF
}

/// How far, in radians, the f32 kernels may move a polygon's outline or a sphere's silhouette
/// across its edge against the f64 oracle's in `camera`'s view: `12u + a` (8u of
/// [`edge_eps`], 4u of the rounded dot product and normal, and `a`, the angle between a
/// pixel's f32 and f64 rays, `Camera::direction_error`). Derivation and use:
/// `render::redecide`'s bounds ("Ids").
pub fn f32_edge_band(camera: &crate::camera::Camera) -> f64 {
    12.0 * crate::real::U32 + camera.direction_error()
}

/// Whether the f32 kernels resolve `camera`'s pixels: their edge band ([`f32_edge_band`])
/// within half the view's id band (`Camera::id_band`, an eighth of a pixel). `--precision
/// auto` draws a view that fails this in f64 alone, through every engine (a telephoto view:
/// under about 0.65 degrees of field of view at 640 pixels wide, 1.9 at 1920).
pub fn f32_resolves(camera: &crate::camera::Camera) -> bool {
    2.0 * f32_edge_band(camera) <= camera.id_band()
}

/// The nearest hit of one ray so far: `id == -1` and `t == inf` when there is none.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit<T> {
    /// Distance along the unit ray from the eye (inf: no hit).
    pub t: T,
    /// Primitive id (-1: no hit).
    pub id: i32,
}

impl<T: Real> Hit<T> {
    /// No hit: `t = inf`, `id = -1`.
    pub const NONE: Hit<T> = Hit {
        t: T::INFINITY,
        id: -1,
    };

    /// Applies the nearest-hit rule to a candidate.
    #[inline]
    pub fn update(&mut self, t: T, id: i32) {
        if closer(t, id, self.t, self.id) {
            *self = Hit { t, id };
        }
    }
}

/// The nearest-hit rule: `t` is a hit (0 < t < inf) and beats the current best (smaller t, or
/// equal t and lower id). With `best_id == -1` an equal t never wins, so `t == inf` never counts.
#[inline]
pub fn closer<T: Real>(t: T, id: i32, best_t: T, best_id: i32) -> bool {
    t > T::ZERO && (t < best_t || (t == best_t && id < best_id))
}

/// The nearest hits of eight rays, ids as f32 (see [`HitLanes`]).
pub type Hit8 = HitLanes<f32x8>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tie_goes_to_lower_id_in_both_forms() {
        let mut h = Hit::<f32>::NONE;
        h.update(2.0, 5);
        h.update(2.0, 3);
        h.update(2.0, 4);
        assert_eq!(h, Hit { t: 2.0, id: 3 });

        let mut h8 = Hit8::new(f32x8::splat(-1.0).simd_lt(f32x8::ZERO));
        let all = f32x8::splat(1.0).simd_gt(f32x8::ZERO);
        h8.update(all, f32x8::splat(2.0), 5.0);
        h8.update(all, f32x8::splat(2.0), 3.0);
        h8.update(all, f32x8::splat(2.0), 4.0);
        assert_eq!(h8.id.to_array(), [3.0; 8]);
    }

    #[test]
    fn non_positive_and_infinite_t_never_count() {
        let mut h = Hit::<f64>::NONE;
        h.update(0.0, 0);
        h.update(-1.0, 0);
        h.update(f64::INFINITY, 0);
        h.update(f64::NAN, 0);
        assert_eq!(h.id, -1);
    }

    #[test]
    fn inactive_lanes_come_back_unchanged() {
        let active = f32x8::new([1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0]).simd_gt(f32x8::ZERO);
        let mut h8 = Hit8::new(active);
        let before = h8;
        let all = f32x8::splat(1.0).simd_gt(f32x8::ZERO);
        h8.update(all, f32x8::splat(1e-30), 0.0);
        for lane in 4..8 {
            assert_eq!(h8.t.to_array()[lane], before.t.to_array()[lane]);
            assert_eq!(h8.id.to_array()[lane], -1.0);
        }
        assert_eq!(h8.id.to_array()[0], 0.0);
    }

    /// The thresholds docs/precision.md and README quote: f32 resolves a 640-wide view from
    /// about 0.65 degrees of field of view up, a 1920-wide one from about 1.9.
    #[test]
    fn f32_resolves_from_the_quoted_fields_of_view() {
        use crate::scene::{CameraSpec, Lens};
        let at = |fov: f64, w: u32, h: u32| {
            let spec = CameraSpec {
                eye: glam::DVec3::new(0.3, 0.2, 5.0),
                look: glam::DVec3::ZERO,
                up: glam::DVec3::Y,
                lens: Some(Lens::Fov(fov)),
            };
            f32_resolves(&crate::camera::Camera::look_at(&spec, w, h).unwrap())
        };
        assert!(!at(0.6, 640, 480) && at(0.7, 640, 480));
        assert!(!at(1.8, 1920, 1080) && at(2.0, 1920, 1080));
        assert!(at(60.0, 640, 480) && !at(0.0802, 640, 480));
    }
}

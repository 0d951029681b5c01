//! Where a whole cluster of triangles can be hit from a view, and how near: one bound for 64
//! faces at a time (`scene::range_clusters` builds the clusters once per scene), by which a
//! view leaves out clusters its rays cannot reach (off screen, behind the eye) or that what is
//! already drawn hides (`render::cull`).
//!
//! A face's own screen region can be a strip across the image (a sliver seen edge-on,
//! `accel::reach`), so a box around a cluster's vertices does not hold its faces' pixels in
//! general. It does once widened, when the eye is off every face's plane. Derivation,
//! u = 2^-24, `u64` = 2^-53:
//!
//! - The cluster's vertices lie in a box (`Gap`: about `c`, in the frame of the cluster's
//!   normal axis); from the eye, every face's exact plane is at least `h > 0` away and every
//!   vertex at most `reach` (from the cluster's cone of normals). `kappa = h / reach`.
//! - Every ray a kernel accepts on a face has `n . d >= -E` for each edge plane of its stored
//!   f32 normals `n` (`accel::reach`, `d` the pixel's exact ray). A stored normal lies within
//!   `beta = 32 u64 / s + 2u` of the exact plane through the eye and the edge (its f64 cross
//!   product of two eye-relative vectors turns by a few `u64` over the sine `s` the edge
//!   subtends, and rounding to f32 by `u`), with `s >= l h / reach^2` (`l` the shortest edge:
//!   the edge's line lies in the face's plane, at least `h` from the eye). So `n* . d >= -E'`
//!   for the exact edge planes, `E' = E + beta`.
//! - The plane through the eye and an edge meets the face's plane at an angle whose sine is
//!   `p / dist(eye, edge line) >= h / reach = kappa`. So where an accepted ray meets the face's
//!   plane, at distance `t`, the point is at most `E' t / kappa` outside each edge's line: in
//!   the face widened by `w = E' t / kappa` on every edge, which is the face scaled about its
//!   incentre by `1 + w / r`, within `Q w` of the face (`Q`, the cluster's quality: the
//!   farthest vertex from the incentre over the inradius). With `g = Q E' / kappa < 1`, the
//!   point lies within `g t` of a face, so `t <= reach + g t`, `t <= t_max = reach / (1 - g)`,
//!   and the point lies in the box widened by `g t_max` on every side (the slab the ray meets:
//!   [`Slab`]). (The accepted directions form a convex cone whose cut by the plane is bounded,
//!   so none runs parallel to it.)
//! - The pixels: those whose rays meet the widened box, within the projection of its corners
//!   (`footprint::Screen::rect`): none when it is off screen or wholly behind the eye, the whole
//!   image when a corner is not in front.
//! - `near`: the ray meets the exact plane at `t*` no nearer than the widened box, `t* >= L`
//!   (`L` the eye's distance from the box, less its rounding, `4 u64 reach`). The kernel
//!   returns `fl(p32 / c32)` with `c32 <= N . d + e_c` (`accel::reach`), the stored `N` within
//!   `delta + 2u` of the exact normal (`Gap::delta`), `p32 >= (p* - reach (delta + 4 u64))
//!   (1 - u)`, and `N* . d = p* / t*` with `p* >= h`: so every distance a kernel returns is at
//!   least `L (1 - reach (delta + 4 u64) / h) (1 - 2u) / (1 + (e_c + delta + 2u)
//!   t_max / h)`; the f64 kernels' distances lie closer to `t*` still.
//!
//! Precision assumed: the f32 packet kernels and the f64 ones, fed by eye-relative f64 setup
//! (`soa`), in the limits `scene::range::f32_range` accepts. Known to give nothing (the
//! cluster is kept, never left out): an eye near any face's plane or inside the widened box
//! (the silhouette of a curved cluster; a camera inside the mesh), `g >= 1/2` (slivers seen
//! from far off with a narrow field of view, where `E` grows). Proven by the tests below: over
//! random clusters, cameras (fields of view 1e-3 to 170 degrees) and scales, every pixel a
//! face's kernel accepts lies in the cluster's rectangle, meets its widened box, and is no
//! nearer than its `near`.

use super::footprint::{Screen, near_f32};
use super::reach::SLACK;
use crate::camera::Camera;
use crate::real::{U32, U64};
use crate::scene::range_clusters::{Gap, frame};
use glam::DVec3;

/// Where a cluster's faces can be hit from one view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Reach {
    /// On no pixel: off screen or behind the eye.
    Nowhere,
    /// Only on the pixels of the rectangle `[x0, y0, x1, y1]` (inclusive), at distances no
    /// nearer than `near`; the third value is `g`, how far the faces' box was widened, as
    /// a fraction of their farthest distance (module comment); the fourth, the widened box,
    /// which every pixel's ray the kernels accept meets.
    Pixels([u16; 4], f32, f64, Slab),
    /// Not bounded from this view.
    Unbounded,
}

/// A cluster's box widened as the module comment says, seen from the eye: every ray a kernel
/// accepts on one of its faces meets it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Slab {
    /// The box's frame, and the eye in the box's coordinates.
    frame: [DVec3; 3],
    eye: DVec3,
    /// The least and greatest coordinates, widened.
    lo: DVec3,
    hi: DVec3,
}

impl Slab {
    /// Whether the ray from the eye along `q` (any length; a pixel's exact ray
    /// `f + sx r + sy u`) meets the box (the slab test in the box's frame, in f64: the box
    /// carries a margin far beyond this test's rounding).
    pub(crate) fn meets(&self, q: DVec3) -> bool {
        let d = DVec3::new(
            q.dot(self.frame[0]),
            q.dot(self.frame[1]),
            q.dot(self.frame[2]),
        );
        let (mut enter, mut leave) = (0f64, f64::INFINITY);
        for i in 0..3 {
            let (lo, hi, o, d) = (self.lo[i], self.hi[i], self.eye[i], d[i]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return false;
                }
                continue;
            }
            let (a, b) = ((lo - o) / d, (hi - o) / d);
            enter = enter.max(a.min(b));
            leave = leave.min(a.max(b));
        }
        // (a NaN, from an infinite coordinate, meets)
        enter.is_nan() || leave.is_nan() || enter <= leave
    }
}

/// A camera's screen, for bounding clusters.
pub(crate) struct ClusterScreen {
    screen: Screen,
}

impl ClusterScreen {
    /// The screen of `camera`.
    pub(crate) fn new(camera: &Camera) -> ClusterScreen {
        ClusterScreen {
            screen: Screen::new(camera),
        }
    }

    /// Where the cluster of `gap` (seen from this camera's eye) can be hit (module comment).
    pub(crate) fn reach(&self, gap: &Gap) -> Reach {
        let v = &self.screen.view;
        let Gap {
            centre,
            axis,
            lo,
            hi,
            quality,
            shortest,
            delta,
            h,
            reach,
            ..
        } = *gap;
        let kappa = h / reach;
        let beta = 32.0 * U64 * reach * reach / (shortest * h) + 2.0 * U32;
        let edge = (v.edge + beta) * (1.0 + SLACK);
        let g = quality * edge / kappa * (1.0 + SLACK);
        if g.is_nan() || g >= 0.5 {
            return Reach::Unbounded;
        }
        let t_max = reach / (1.0 - g) * (1.0 + SLACK);
        // the box widened by `g t_max`, and by 1e-9 of the farthest distance for the
        // rounding of its coordinates and of the slab test
        let m = DVec3::splat((g * t_max + 2e-9 * reach) * (1.0 + SLACK));
        let (lo, hi) = (lo - m, hi + m);
        let f = frame(axis);
        let oc = centre - v.eye;
        let corners = (0..8).map(|i| {
            let pick = |bit: usize| if i >> bit & 1 == 1 { hi } else { lo };
            oc + f[0] * pick(0).x + f[1] * pick(1).y + f[2] * pick(2).z
        });
        let Some(rect) = self.screen.rect(corners) else {
            return Reach::Nowhere;
        };
        // the eye's distance from the box, in its frame
        let e = -DVec3::new(oc.dot(f[0]), oc.dot(f[1]), oc.dot(f[2]));
        let gap = (lo - e).max(e - hi).max(DVec3::ZERO).length() - 4.0 * U64 * reach;
        let plane = 1.0 - reach * (delta + 4.0 * U64) / h;
        let cosine = 1.0 + (v.cosine + delta + 2.0 * U32) * t_max / h;
        let near = gap * plane * (1.0 - 2.0 * U32) / cosine * (1.0 - SLACK);
        if near.is_nan() || near <= 0.0 || plane <= 0.0 {
            return Reach::Unbounded;
        }
        let slab = Slab {
            frame: f,
            eye: e,
            lo,
            hi,
        };
        Reach::Pixels(rect, near_f32(near), g, slab)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::polygon::{TriangleK, polygon_x1, polygon_x8};
    use crate::scene::range::f32_range_from;
    use crate::scene::range_clusters::RangeClusters;
    use crate::scene::range_clusters::tests::sheet;
    use crate::scene::{CameraSpec, Shape, Shapes};
    use crate::test_rng::Rng;
    use std::path::Path;
    use wide::f32x8;

    /// Over random bumpy sheets (slivers among them: stretched up to 1000 times), sizes 1e-3
    /// to 1e3, far from the origin, seen through fields of view from 1e-3 to 170 degrees from
    /// inside the sheet's span out to ten times the distance that fills the view: every ray
    /// the f32 packet kernel or the f64 kernel accepts on a face of a cluster with a bounded
    /// reach lies in the cluster's rectangle, at a distance no nearer than its `near`, and a
    /// cluster on no pixel is hit nowhere. The bound is not vacuous: most clusters are
    /// bounded, and some are on no pixel.
    #[test]
    fn every_accepted_ray_lies_in_its_cluster_rectangle_beyond_near() {
        let mut rng = Rng(0xC1_0057);
        let (w, h) = (40u32, 30u32);
        let (mut bounded, mut nowhere, mut all, mut hits) = (0, 0, 0, 0);
        for case in 0..240 {
            let size = rng.log(-3.0, 3.0);
            let origin = rng.direction() * size * rng.log(0.0, 4.0);
            let mut mesh = sheet(&mut rng, 12, size, origin);
            let stretch = if case % 3 == 0 {
                rng.log(-3.0, 0.0)
            } else {
                1.0
            };
            for v in &mut mesh.vertices {
                v.x = origin.x + (v.x - origin.x) * stretch;
            }
            let n = mesh.vertices.len() as f64;
            let mid = mesh.vertices.iter().copied().sum::<DVec3>() / n;
            let extent = (mesh.vertices.iter())
                .map(|v| (*v - mid).length())
                .fold(0.0, f64::max);
            let text = "camera eye 0 0 0 look 0 0 -1 up 0 1 0\n";
            let mut scene = crate::parse_scene(text, Path::new("c.sc")).unwrap();
            scene.shapes = Shapes::new();
            scene.shapes.push_mesh(mesh, 1);
            let fov = rng.log(-3.0, 170f64.log10());
            let fill = extent / (fov.to_radians() / 2.0).tan();
            let eye = mid + rng.direction() * fill * rng.log(-1.5, 1.0);
            let spec = CameraSpec {
                eye,
                look: mid + rng.direction() * extent * rng.range(0.0, 0.7),
                up: rng.direction(),
                lens: Some(crate::scene::Lens::Fov(fov)),
            };
            let Ok(camera) = Camera::look_at(&spec, w, h) else {
                continue;
            };
            if f32_range_from(&scene, eye).is_err() {
                continue;
            }
            let clusters = RangeClusters::new(&scene);
            let screen = ClusterScreen::new(&camera);
            let (t32, t64) = (camera.tables::<f32>(1, 1), camera.tables::<f64>(1, 1));
            for k in 0..clusters.len() {
                all += 1;
                let Some(gap) = clusters.gap(k, eye) else {
                    continue;
                };
                let reach = screen.reach(&gap);
                match reach {
                    Reach::Unbounded => continue,
                    Reach::Nowhere => nowhere += 1,
                    Reach::Pixels(..) => bounded += 1,
                }
                for &id in clusters.cluster(k) {
                    let Shape::Triangle(v) = scene.shapes.get(id as usize) else {
                        unreachable!("a sheet holds triangles")
                    };
                    let Some(k64) = TriangleK::triangle(&v, eye) else {
                        continue;
                    };
                    let k32 = k64.cast::<f32>();
                    for y in 0..h as usize {
                        for x in 0..w as usize {
                            let d = t32.dir_x1(x, y).map(f32x8::splat);
                            let f32_hit = polygon_x8(&k32, &d)
                                .filter(|(m, _)| m.to_array()[0] != 0.0)
                                .map(|(_, t)| f64::from(t.to_array()[0]));
                            let f64_hit = polygon_x1(&k64, t64.dir_x1(x, y));
                            for t in [f32_hit, f64_hit].into_iter().flatten() {
                                if t.is_nan() || t <= 0.0 {
                                    continue;
                                }
                                hits += 1;
                                let Reach::Pixels([x0, y0, x1, y1], near, _, slab) = reach else {
                                    panic!(
                                        "case {case}: cluster {k} on no pixel, hit at ({x}, {y})"
                                    );
                                };
                                let inside = (x0 as usize..=x1 as usize).contains(&x)
                                    && (y0 as usize..=y1 as usize).contains(&y);
                                assert!(
                                    inside,
                                    "case {case}: ({x}, {y}) outside {x0} {y0} {x1} {y1}"
                                );
                                assert!(t >= f64::from(near), "case {case}: t {t} < near {near}");
                                let q = camera.f
                                    + camera.r * camera.sx::<f64>(x as u32)
                                    + camera.u * camera.sy::<f64>(y as u32);
                                assert!(slab.meets(q), "case {case}: ({x}, {y}) misses the box");
                            }
                        }
                    }
                }
            }
        }
        assert!(
            bounded > all / 2 && nowhere > 10 && hits > 100_000,
            "{bounded} bounded, {nowhere} on no pixel of {all}; {hits} hits"
        );
    }
}

//! The bounds of `accel::reach` against the kernels themselves, over random cameras (fields of
//! view from 1e-4 to 179.9 degrees, images up to `limits::MAX_SIDE` wide, up vectors near the
//! view direction), scales (primitives of 1e-4 to 1e4 units, 1 to 1e4 sizes away, up to 1e6
//! units from the origin, each case scaled by 1e-10 to 1e10: within `scene::validate`'s limits,
//! which the cases are checked against) and shapes (slivers seen nearly edge-on among them). Each test also reports how close the kernels come to the
//! bound, and asserts that they come within a few times of it (the bound is not vacuous).

use super::*;
use crate::kernel::polygon::{PolyK, polygon_x1};
use crate::kernel::sphere::{SphereK, sphere_x1};
use crate::real::{V3, dot, v3};
use crate::scene::{CameraSpec, Scene, Shape};
use crate::test_rng::Rng;

/// A random camera at `eye` looking at `look`: fov log-uniform in [1e-4, 179.9] degrees,
/// width and height from 1 to `limits::MAX_SIDE` (within `limits::MAX_PIXELS`), up vector
/// random or within 1e-8 to 1e-2 rad of the view direction; a third of them pinholes of that
/// horizontal focal length with `fy` 0.5 to 2 times `fx` and the principal point up to two
/// image sizes off the centre.
fn camera(rng: &mut Rng, eye: DVec3, look: DVec3) -> Camera {
    let fov = rng.log(-4.0, 179.9f64.log10());
    camera_with(rng, eye, look, |_| fov)
}

/// [`camera`] with the fov `fov(width)` degrees.
fn camera_with(rng: &mut Rng, eye: DVec3, look: DVec3, fov: impl Fn(u32) -> f64) -> Camera {
    let side = |rng: &mut Rng| rng.log(0.0, 65536f64.log10()).round().max(1.0) as u32;
    let (w, mut h) = (side(rng), side(rng));
    let fov = fov(w);
    while w as u64 * h as u64 > crate::limits::MAX_PIXELS {
        h /= 2;
    }
    let f = (look - eye).normalize();
    let up = if rng.unit() < 0.3 {
        f + f.any_orthonormal_vector() * rng.log(-8.0, -2.0)
    } else {
        rng.direction()
    };
    let spec = CameraSpec {
        eye,
        look,
        up,
        lens: Some(crate::scene::Lens::Fov(fov)),
    };
    if rng.unit() < 1.0 / 3.0 {
        let fx = w as f64 / (2.0 * (fov.to_radians() / 2.0).tan());
        let k = crate::scene::Intrinsics {
            fx,
            fy: fx * rng.log(-0.3, 0.3),
            cx: w as f64 * (0.5 + rng.range(-2.0, 2.0)),
            cy: h as f64 * (0.5 + rng.range(-2.0, 2.0)),
        };
        if crate::limits::check_lens(k.fx, k.fy, k.cx, k.cy, w, h).is_ok() {
            return Camera::pinhole(&spec, &k, w, h);
        }
    }
    Camera::new(&spec, fov, w, h)
}

/// A pixel of `cam`: a random one, or one of the image's corners (where the rays err most).
fn pixel(rng: &mut Rng, cam: &Camera) -> (usize, usize) {
    let (w, h) = (cam.width, cam.height);
    let (x, y) = match rng.below(4) {
        0 => (
            [0, w - 1][rng.below(2) as usize],
            [0, h - 1][rng.below(2) as usize],
        ),
        _ => (rng.below(w), rng.below(h)),
    };
    (x as usize, y as usize)
}

fn d64(v: V3<f32>) -> DVec3 {
    DVec3::new(v[0].into(), v[1].into(), v[2].into())
}

/// Every ray the f32 or f64 edge test accepts lies within `E` of the edge's plane, exact ray
/// against the stored f32 normal: over pixels of random cameras and normals tilted from
/// -40u to +20u off each pixel's ray.
#[test]
fn accepted_rays_lie_within_the_edge_bound() {
    let mut rng = Rng(0x5EED_0001);
    let eps32 = crate::kernel::edge_eps::<f32>();
    let eps64 = crate::kernel::edge_eps::<f64>();
    let (mut worst, mut accepted) = (0.0f64, 0);
    for _ in 0..300 {
        let look = rng.direction();
        let cam = camera(&mut rng, DVec3::ZERO, look);
        let view = View::new(&cam);
        let (t32, t64) = (cam.tables::<f32>(1, 1), cam.tables::<f64>(1, 1));
        for _ in 0..200 {
            let (x, y) = pixel(&mut rng, &cam);
            let d = DVec3::from(t64.dir_x1(x, y));
            // a unit normal turned about the ray, tilted off it by -40u to +20u
            let tilt = rng.range(-40.0, 20.0) * U32;
            let a = rng.range(0.0, std::f64::consts::TAU);
            let p = d.any_orthonormal_vector();
            let n64 = (p * a.cos() + d.cross(p) * a.sin() + d * tilt).normalize();
            let n32: V3<f32> = v3(n64);
            let in32 = dot(t32.dir_x1(x, y), n32) >= -eps32;
            let in64 = dot(t64.dir_x1(x, y), v3::<f64>(n64)) >= -eps64;
            if in32 || in64 {
                let off = -d64(n32).dot(d);
                assert!(
                    off <= view.edge,
                    "{off:e} > E {:e}: {:?}, {}x{}, ({x}, {y})",
                    view.edge,
                    cam.k,
                    cam.width,
                    cam.height
                );
                worst = worst.max(off / view.edge);
                accepted += 1;
            }
        }
    }
    eprintln!("{accepted} accepted; largest offset / E {worst:.2}");
    assert!(accepted > 10_000 && worst > 0.2, "{accepted}, {worst}");
}

/// The f32 kernel's `fl(N . d32)` exceeds `N . d` (exact ray, stored f32 normal) by at most
/// `e_c`, over pixels of random cameras and random normals.
#[test]
fn the_kernels_cosine_errs_within_its_bound() {
    let mut rng = Rng(0x5EED_0002);
    let mut worst = 0.0f64;
    for _ in 0..300 {
        let look = rng.direction();
        let cam = camera(&mut rng, DVec3::ZERO, look);
        let view = View::new(&cam);
        let (t32, t64) = (cam.tables::<f32>(1, 1), cam.tables::<f64>(1, 1));
        for _ in 0..200 {
            let (x, y) = pixel(&mut rng, &cam);
            let nrm: V3<f32> = v3(rng.direction());
            let over =
                f64::from(dot(t32.dir_x1(x, y), nrm)) - d64(nrm).dot(t64.dir_x1(x, y).into());
            assert!(over <= view.cosine, "{over:e} > {:e}", view.cosine);
            worst = worst.max(over / view.cosine);
        }
    }
    eprintln!("largest excess / e_c {worst:.2}");
    assert!(worst > 0.1, "{worst}");
}

/// The pixels around the centre of `cam` (where a case's primitive is seen): up to 33 x 33.
fn window(cam: &Camera) -> impl Iterator<Item = (usize, usize)> {
    let (w, h) = (cam.width as usize, cam.height as usize);
    let span = |n: usize| n.saturating_sub(n / 2 + 17)..(n / 2 + 17).min(n);
    span(h).flat_map(move |y| span(w).map(move |x| (x, y)))
}

/// A scene of one shape seen by `eye` looking at `look`.
fn one_shape(shape: Shape, eye: DVec3, look: DVec3) -> Scene {
    Scene {
        camera_at: None,
        source: "reach.sc".into(),
        camera: CameraSpec {
            eye,
            look,
            up: DVec3::Y,
            lens: None,
        },
        shapes: vec![shape].into(),
        warnings: Vec::new(),
    }
}

/// What a case's kernels did over its window, for the claims' tightness.
#[derive(Default)]
struct Seen {
    /// Pixels some kernel accepted.
    accepted: usize,
    /// Of those, pixels the f32 and f64 kernels disagree on (the f32 kernel's band at work).
    widened: usize,
    /// The smallest distance a kernel returned over `near` (1 at best).
    closest: f64,
}

/// A BVH of one leaf, the box `(min, max)` (rounded outward to f32, as `Bvh::new` rounds),
/// over the one primitive of `p`.
fn one_box(p: &crate::soa::Prepared<f64>, (min, max): (DVec3, DVec3)) -> crate::accel::Bvh {
    use crate::real::{f32_down, f32_up};
    let one = [p.spheres.len(), p.triangles.len(), p.quads.len()].map(|n| (0, n as u32));
    crate::accel::Bvh {
        nodes: vec![crate::accel::bvh::Node {
            min: min.to_array().map(f32_down),
            max: max.to_array().map(f32_up),
            index: 0,
            meta: crate::accel::bvh::LEAF,
        }],
        leaves: vec![one],
    }
}

/// Checks one primitive (`shape`, its f64 and f32 constants by `hits`) through `cam`: every
/// pixel of the window a kernel accepts lies in `region` (when given) and in `rect`, every
/// distance is at least `near`, and the BVH built over the shape alone finds the same hits
/// (f32 and f64, one ray and eight), as does a BVH of each box of `boxes` alone (each must
/// serve the traversal by itself).
fn check_pixels(
    cam: &Camera,
    scene: &Scene,
    (region, rect, near): (Option<&Region>, Option<[u16; 4]>, f64),
    hits: impl Fn(V3<f32>, V3<f64>) -> (Option<f32>, Option<f64>),
    boxes: &[(DVec3, DVec3)],
    seen: &mut Seen,
) {
    use crate::accel::bvh::{trace_bvh_x1, trace_bvh_x4d, trace_bvh_x8};
    use crate::kernel::wide64::Hit4d;
    use crate::soa::trace::trace_x1;
    let (t32, t64) = (cam.tables::<f32>(1, 1), cam.tables::<f64>(1, 1));
    let prepared = crate::soa::Prepared::new(scene, cam.eye);
    let (bvh, reordered) = crate::accel::Bvh::new(&prepared, scene, cam);
    let (p32, packed) = (reordered.cast::<f32>(), crate::soa::Packed::new(&reordered));
    let alone: Vec<_> = boxes.iter().map(|&b| one_box(&prepared, b)).collect();
    let packed_alone = crate::soa::Packed::new(&prepared);
    for (x, y) in window(cam) {
        let (d32, d) = (t32.dir_x1(x, y), t64.dir_x1(x, y));
        let (h32, h64) = hits(d32, d);
        let at = format!("({x}, {y}) of {}x{}, {:?}", cam.width, cam.height, cam.k);
        for t in [h32.map(f64::from), h64].into_iter().flatten() {
            if let Some(region) = region {
                assert!(
                    region.contains([t64.sx[x], t64.sy[y]]),
                    "{at}: not in the region"
                );
            }
            let [x0, y0, x1, y1] = rect.unwrap_or_else(|| panic!("{at}: hit, no rectangle"));
            let inside = (x0 as usize..=x1 as usize).contains(&x)
                && (y0 as usize..=y1 as usize).contains(&y);
            assert!(inside, "{at}: outside the rectangle {:?}", [x0, y0, x1, y1]);
            assert!(t >= near, "{at}: t {t:e} below near {near:e}");
            seen.closest = seen.closest.min(t / near);
        }
        seen.accepted += usize::from(h32.is_some() || h64.is_some());
        seen.widened += usize::from(h32.is_some() != h64.is_some());
        // the BVH over the shape alone, against the kernels
        assert_eq!(
            trace_bvh_x1(&p32, &bvh, d32),
            trace_x1(&p32, d32),
            "{at}: bvh f32"
        );
        assert_eq!(
            trace_bvh_x1(&reordered, &bvh, d),
            trace_x1(&reordered, d),
            "{at}: bvh f64"
        );
        // a tie at the kernel's own distance, held by another primitive (of a higher id): the
        // traversal must still reach this one, entering every box no later than its hit
        let tie = |bvh: &crate::accel::Bvh, packed: &crate::soa::Packed, p64, what: &str| {
            use wide::{f32x8, f64x4};
            if let Some(t) = h32 {
                let mut hit = crate::kernel::Hit8::new(f32x8::splat(1.0).simd_gt(f32x8::ZERO));
                (hit.t, hit.id) = (f32x8::splat(t), f32x8::splat(1e9));
                trace_bvh_x8(packed, bvh, &d32.map(f32x8::splat), &mut hit);
                assert_eq!(hit.id.to_array()[0], 0.0, "{at}: {what}, f32 at {t:e}");
            }
            if let Some(t) = h64 {
                let mut hit = Hit4d::new(f64x4::splat(1.0).simd_gt(f64x4::ZERO));
                (hit.t, hit.id) = (f64x4::splat(t), f64x4::splat(1e9));
                trace_bvh_x4d(p64, bvh, &d.map(f64x4::splat), &mut hit);
                assert_eq!(hit.id.to_array()[0], 0.0, "{at}: {what}, f64 at {t:e}");
            }
        };
        tie(&bvh, &packed, &reordered, "bvh");
        for b in &alone {
            tie(b, &packed_alone, &prepared, "one box");
        }
        let mut hit = crate::kernel::Hit8::new(wide::f32x8::splat(1.0).simd_gt(wide::f32x8::ZERO));
        trace_bvh_x8(&packed, &bvh, &d32.map(wide::f32x8::splat), &mut hit);
        let (t8, id8) = (hit.t.to_array()[0], hit.id.to_array()[0]);
        let one = trace_x1(&p32, d32);
        assert_eq!(
            (t8.to_bits(), id8 as i32),
            (one.t.to_bits(), one.id),
            "{at}: bvh x8"
        );
    }
}

/// Triangles and quads of every size and shape, slivers seen nearly edge-on among them: every
/// pixel the f32 or f64 kernel accepts lies in the polygon's screen region and its tile
/// rectangle, at no less than its `near`, and the BVH finds it.
#[test]
fn polygon_regions_hold_every_accepted_ray() {
    use crate::accel::footprint::{Screen, polygon_footprint};
    let mut rng = Rng(0x5EED_0003);
    let mut seen = Seen {
        closest: f64::INFINITY,
        ..Seen::default()
    };
    let mut cases = 0;
    while cases < 1500 {
        // (the whole case scaled by 1e-10 to 1e10: eyes up to `limits::MAX_EYE_DISTANCE` away)
        let scale = rng.log(-10.0, 10.0);
        let size = rng.log(-4.0, 4.0) * scale;
        let centre = rng.direction() * rng.log(-3.0, 6.0) * scale;
        // along the axes one time in three (where the BVH's boxes are as tight as they get)
        let (e1, e2) = if rng.unit() < 0.3 {
            let axes = [DVec3::X, DVec3::Y, DVec3::Z];
            let i = rng.below(3) as usize;
            (axes[i], axes[(i + 1 + rng.below(2) as usize) % 3])
        } else {
            let e1 = rng.direction();
            (e1, e1.cross(rng.direction()).normalize())
        };
        // a sliver one time in two: its third vertex within 1e-6 to 1 of the first edge
        let thin = if rng.unit() < 0.5 {
            rng.log(-6.0, 0.0)
        } else {
            rng.range(0.2, 1.0)
        };
        let a = centre;
        let b = a + e1 * size;
        let c = a + (e1 * rng.range(-0.5, 1.5) + e2 * thin) * size;
        let quad = rng.unit() < 0.3;
        let shape = if quad {
            Shape::Quad([a, b, b + e2 * thin * size, a + e2 * thin * size])
        } else {
            Shape::Triangle([a, b, c])
        };
        // the eye 1 to 1e4 sizes away, half the time within 1e-9 to 0.1 rad of the plane, one
        // time in six face-on
        let nrm = e1.cross(e2);
        let elev = match rng.below(6) {
            0..=2 => rng.log(-9.0, -1.0),
            3 => std::f64::consts::FRAC_PI_2,
            _ => rng.range(0.1, 1.5),
        };
        let side = e1.rotate_axis(nrm, rng.range(0.0, std::f64::consts::TAU));
        let up_or_down = if rng.unit() < 0.5 { 1.0 } else { -1.0 };
        let dir = side * elev.cos() + nrm * elev.sin() * up_or_down;
        let eye = a + (b - a) * rng.unit() + dir * size * rng.log(0.0, 4.0);
        let look = match shape {
            Shape::Triangle([a, b, c]) => {
                a + (b - a) * rng.unit() * 0.5 + (c - a) * rng.unit() * 0.5
            }
            Shape::Quad([a, b, _, d]) => a + (b - a) * rng.unit() + (d - a) * rng.unit(),
            Shape::Sphere { .. } => unreachable!(),
        };
        let scene = one_shape(shape, eye, look);
        if crate::scene::range::f32_range(&scene).is_err() {
            continue;
        }
        let cam = camera(&mut rng, eye, look);
        let screen = Screen::new(&cam);
        match shape {
            Shape::Triangle(v) => {
                let Some(k64) = PolyK::<f64, 3>::triangle(&v, eye) else {
                    continue;
                };
                polygon_case(&cam, &scene, &screen, k64, &mut seen, polygon_footprint);
            }
            Shape::Quad(v) => {
                let Some(k64) = PolyK::<f64, 4>::quad(&v, eye) else {
                    continue;
                };
                polygon_case(&cam, &scene, &screen, k64, &mut seen, polygon_footprint);
            }
            Shape::Sphere { .. } => unreachable!(),
        }
        cases += 1;
    }
    eprintln!(
        "{cases} polygons: {} pixels accepted, {} by one precision alone; nearest hit {:.3} times near",
        seen.accepted, seen.widened, seen.closest
    );
    assert!(
        seen.accepted > 20_000 && seen.widened > 500,
        "{} {}",
        seen.accepted,
        seen.widened
    );
    assert!(seen.closest < 1.01, "{}", seen.closest);
}

/// One polygon case of [`polygon_regions_hold_every_accepted_ray`].
fn polygon_case<const N: usize>(
    cam: &Camera,
    scene: &Scene,
    screen: &crate::accel::footprint::Screen,
    k64: PolyK<f64, N>,
    seen: &mut Seen,
    footprint: impl Fn(&crate::accel::footprint::Screen, &PolyK<f32, N>) -> (Option<[u16; 4]>, f64),
) {
    let k32 = k64.cast::<f32>();
    let region = screen.view.polygon_region(&k32.n, k32.nrm);
    let (rect, near) = footprint(screen, &k32);
    let hits = |d32, d| (polygon_x1(&k32, d32), polygon_x1(&k64, d));
    let view = &screen.view;
    let boxes = [
        view.polygon_slice(&region, near),
        view.polygon_cut(&region, k32.nrm, k32.p),
    ];
    let boxes: Vec<_> = boxes.into_iter().flatten().collect();
    check_pixels(cam, scene, (Some(&region), rect, near), hits, &boxes, seen);
}

/// Spheres of radius 1e-4 to 1e4, seen from 1 to 1e4 radii away, from just outside (1e-9 of
/// the radius) and from inside: every pixel the f32 or f64 kernel accepts lies in the tile
/// rectangle, within `r'` of the centre, at no less than `near`, and the BVH finds it.
#[test]
fn sphere_reach_holds_every_accepted_ray() {
    use crate::accel::footprint::{Screen, ball_footprint};
    let mut rng = Rng(0x5EED_0004);
    let mut seen = Seen {
        closest: f64::INFINITY,
        ..Seen::default()
    };
    let mut cases = 0;
    while cases < 1000 {
        let scale = rng.log(-10.0, 10.0);
        let r = rng.log(-4.0, 4.0) * scale;
        let centre = rng.direction() * rng.log(-3.0, 6.0) * scale;
        let l = match rng.below(4) {
            0 => r * (1.0 + rng.log(-9.0, -1.0)),
            1 => r * rng.range(0.0, 0.99),
            _ => r * rng.log(0.0, 4.0),
        };
        let eye = centre + rng.direction() * l;
        // half the time along the silhouette (from outside), where the f32 kernel widens
        let oc = centre - eye;
        let tangent = oc
            .normalize()
            .any_orthonormal_vector()
            .rotate_axis(oc.normalize(), rng.range(0.0, 7.0));
        let silhouette = l > r && rng.unit() < 0.5;
        let look = if silhouette {
            // (far along the ray: look - eye keeps its direction to 1e-16 far from the origin)
            let far = l.max(eye.length());
            eye + (oc * (l * l - r * r).sqrt() / l + tangent * r).normalize() * far
        } else {
            centre + rng.direction() * r * rng.unit()
        };
        let shape = Shape::Sphere {
            center: centre,
            radius: r,
        };
        let scene = one_shape(shape, eye, look);
        if crate::scene::range::f32_range(&scene).is_err() || look == eye {
            continue;
        }
        let cam = if silhouette {
            // pixels 0.1u to 100u apart: the f32 silhouette's band spans a few
            let apart = rng.log(-1.0, 2.0) * U32;
            camera_with(&mut rng, eye, look, |w| {
                (apart * w as f64).min(3.0).to_degrees()
            })
        } else {
            camera(&mut rng, eye, look)
        };
        let screen = Screen::new(&cam);
        let k64 = SphereK::new(centre, r, eye);
        let k32 = k64.cast::<f32>();
        let oc = centre - screen.view.eye;
        let (rect, near) = ball_footprint(&screen, (oc, r), (k32.oc, k32.r2, k32.c));
        let reach = screen.view.ball_reach(centre - eye, r);
        let hits = |d32: V3<f32>, d: V3<f64>| {
            let (h32, h64) = (sphere_x1(&k32, d32), sphere_x1(&k64, d));
            if h32.is_some() || h64.is_some() {
                let off = (centre - eye).cross(DVec3::from(d)).length();
                assert!(off <= reach, "{off:e} from the centre, beyond {reach:e}");
            }
            (h32, h64)
        };
        let cap = [ball_cap(k32.oc, k32.r2, k32.c)];
        check_pixels(&cam, &scene, (None, rect, near), hits, &cap, &mut seen);
        cases += 1;
    }
    eprintln!(
        "{cases} spheres: {} pixels accepted, {} by one precision alone; nearest hit {:.3} times near",
        seen.accepted, seen.widened, seen.closest
    );
    assert!(
        seen.accepted > 20_000 && seen.widened > 1000,
        "{} {}",
        seen.accepted,
        seen.widened
    );
    assert!(seen.closest < 1.01, "{}", seen.closest);
}

/// [`arc_max`] bounds `n . d` over every point of the arc, and is the largest of them, within
/// rounding (or within its short-arc bound below 1e-6 rad): arcs from 1e-9 rad to most of a
/// half turn, `n` anywhere, 2,000 points of each arc sampled (its ends among them); the
/// largest lies inside the arc for hundreds of them.
#[test]
fn arc_max_is_the_largest_over_the_arc() {
    let mut rng = Rng(0x5EED_0005);
    let (mut peaks, mut short) = (0, 0);
    for _ in 0..3000 {
        let a = rng.direction();
        let w = if rng.unit() < 0.5 {
            rng.log(-9.0, 3f64.log10())
        } else {
            rng.range(0.01, 3.0)
        };
        let b = a.rotate_axis(a.any_orthonormal_vector(), w);
        let n = rng.direction() * rng.range(0.5, 1.5);
        let bound = arc_max((a, n.dot(a)), (b, n.dot(b)), n);
        let axis = a.cross(b).normalize();
        let sampled = (0..=2000)
            .map(|i| a.rotate_axis(axis, w * i as f64 / 2000.0).dot(n))
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(bound >= sampled - 1e-14, "w {w:e}: {bound} < {sampled}");
        let step = w / 2000.0;
        // (the sampled largest is within a step's curvature of the true one)
        let slack = if w < 1e-6 {
            n.length() * w
        } else {
            1e-12 + n.length() * step * step
        };
        assert!(
            bound <= sampled + slack,
            "w {w:e}: {bound} > {sampled} + {slack:e}"
        );
        peaks += usize::from(sampled > n.dot(a).max(n.dot(b)) + 1e-15);
        short += usize::from(w < 1e-6);
    }
    assert!(
        peaks > 100 && short > 300,
        "{peaks} peaks inside, {short} short arcs"
    );
}

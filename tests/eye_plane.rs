//! An eye near a polygon's plane: the polygon is drawn wherever the pixel rays meet it steeply,
//! by every precision, kernel and acceleration, the oracle included. A polygon is dropped as
//! "seen edge-on" only when every point of it lies within `kernel::polygon::EDGE_ON_SINE` of
//! the eye's horizon of its plane; judging it by the line of sight to one vertex once dropped a
//! floor seen from 1e-12 above (and a 1e13 ground quad seen from 2 above), in the oracle too.
//!
//! Each case is held to an independent f64 computation, not to lanecast's kernels: the ray
//! meets the polygon's plane at `t = (r_0 . n) / (d . n)` (`r_i` the eye-relative vertices),
//! and the point `t d` is inside when it lies on the inner side of every edge line in the
//! plane. Only clear pixels are judged: a ray whose point lies farther than twice the view's id
//! band (`Camera::id_band`) from every edge, seen from the eye, and which meets the plane at
//! more than 1e-3 of a right angle (rays nearer the plane are within the kernels' bound of it,
//! and are decided per ray by `--precision auto`'s re-decision).

mod common;

use common::*;
use glam::DVec3;
use lanecast::scene::{Scene, Shape};
use lanecast::{Accel, Precision};

const W: u32 = 48;
const H: u32 = 32;

/// What the independent computation says of one pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Truth {
    /// The polygon, at this distance, known to within the second value: the vertices'
    /// rounding (u |V|, `u` = 2^-53) moves the plane by a few times that, and the hit along
    /// the ray by that over the cosine of incidence.
    Hit(f64, f64),
    /// Not the polygon.
    Miss,
    /// Too near an edge or too grazing to judge.
    Unclear,
}

/// The independent answer for the f64 ray `d` from `eye` against the convex polygon `v`.
fn truth(v: &[DVec3], eye: DVec3, d: DVec3, band: f64) -> Truth {
    let r: Vec<DVec3> = v.iter().map(|p| *p - eye).collect();
    let n = (r[1] - r[0]).cross(r[2] - r[0]).normalize();
    let dn = d.dot(n);
    if dn.abs() < 1e-3 {
        return Truth::Unclear;
    }
    let t = r[0].dot(n) / dn;
    if t <= 0.0 {
        return Truth::Miss;
    }
    let q = d * t;
    // signed distances to the edge lines, positive inside (the winding of n)
    let margin = (0..r.len())
        .map(|i| {
            let (a, b) = (r[i], r[(i + 1) % r.len()]);
            (b - a).cross(q - a).dot(n) / (b - a).length()
        })
        .fold(f64::INFINITY, f64::min);
    // an in-plane distance m seen from t away at this incidence subtends at least m |d.n| / t
    let angle = margin.abs() * dn.abs() / t;
    if angle <= 2.0 * band {
        Truth::Unclear
    } else if margin > 0.0 {
        let reach = v
            .iter()
            .map(|p| p.abs().max_element())
            .fold(eye.abs().max_element(), f64::max);
        Truth::Hit(t, 8.0 * f64::EPSILON * reach / dn.abs())
    } else {
        Truth::Miss
    }
}

/// The scene's one polygon (id 0), with a sphere beneath it (id 1) that must not show through.
struct Case {
    scene: Scene,
    polygon: Vec<DVec3>,
    what: String,
    /// The eye within 1e-10 of the polygon's size over its interior.
    near: bool,
}

fn case(rng: &mut Rng, k: usize) -> Case {
    // size up to the coordinate limit, the eye 1e-15 to 1e-3 sizes from the plane, and a
    // centre up to ten sizes out (within 1e16), but not so far that the eye's height is below
    // 1e-8 of the coordinates' size: their rounding would move the plane by more than 1e-8 of
    // it, and no computation could then say where the plane is to 1e-5
    let size = 10f64.powf(rng.range(-2.0, 16.0));
    let height = size * 10f64.powf(rng.range(-15.0, -3.0));
    let centre = rng.in_box(DVec3::ZERO, (10.0 * size).min(1e16).min(1e8 * height));
    let n = rng.direction();
    let e1 = n.any_orthonormal_vector();
    let e2 = n.cross(e1);
    let at = |a: f64| centre + (e1 * a.cos() + e2 * a.sin()) * size;
    let a0 = rng.range(0.0, std::f64::consts::TAU);
    let quad = k % 2 == 1;
    let polygon: Vec<DVec3> = if quad {
        // a rectangle: planar and convex after rounding
        let (u, w) = (e1 * size, e2 * size * rng.range(0.3, 1.0));
        vec![
            centre - u - w,
            centre + u - w,
            centre + u + w,
            centre - u + w,
        ]
    } else {
        (0..3)
            .map(|i| at(a0 + i as f64 * 2.1 + rng.range(-0.3, 0.3)))
            .collect()
    };
    // the eye's foot on the plane: inside the polygon, or outside near it
    let inside = rng.unit() < 0.6;
    let foot = if inside {
        centre + (e1 * rng.range(-0.2, 0.2) + e2 * rng.range(-0.2, 0.2)) * size
    } else {
        at(rng.range(0.0, std::f64::consts::TAU)) + (at(a0) - centre) * rng.range(0.2, 2.0)
    };
    let side = if rng.unit() < 0.5 { 1.0 } else { -1.0 };
    let eye = foot + n * side * height;
    // looking down at the plane, from straight down to 80 degrees off the normal
    let tilt = rng.range(0.0, 80f64.to_radians());
    let dir = -n * side * tilt.cos() + e1 * tilt.sin();
    let look = eye + dir * size;
    let up = dir.any_orthonormal_vector();
    let sphere = Shape::Sphere {
        center: foot - n * side * size * 0.5,
        radius: size * 0.3,
    };
    let shape = if quad {
        Shape::Quad([polygon[0], polygon[1], polygon[2], polygon[3]])
    } else {
        Shape::Triangle([polygon[0], polygon[1], polygon[2]])
    };
    let what = format!(
        "case {k}: {} of size {size:.1e} at {centre:?}, eye {height:.1e} {} the plane ({}), tilt {:.0} deg",
        if quad { "quad" } else { "triangle" },
        if side > 0.0 { "above" } else { "below" },
        if inside {
            "over its interior"
        } else {
            "beside it"
        },
        tilt.to_degrees()
    );
    let scene = build_scene("eye_plane.sc", spec(eye, look, up, 60.0), &[shape, sphere]);
    Case {
        scene,
        polygon,
        what,
        near: inside && height < 1e-10 * size,
    }
}

/// Every clear pixel of every method agrees with the independent computation; depths within
/// 1e-5 relative (f32 alone: 1e-4; the coordinates' rounding moves the plane by up to 1e-8).
#[test]
fn polygons_seen_from_near_their_plane_are_drawn_by_every_method() {
    let mut rng = Rng::new(0x0E7E_01A4_E5EE_D001);
    let (mut hits, mut near_hits) = (0usize, 0usize);
    for k in 0..160 {
        let c = case(&mut rng, k);
        let camera = camera_of(&c.scene, W, H);
        let t64 = camera.tables::<f64>(1, 1);
        let band = camera.id_band();
        let truths: Vec<Truth> = (0..(W * H) as usize)
            .map(|i| {
                let d = DVec3::from_array(t64.dir_x1(i % W as usize, i / W as usize));
                truth(&c.polygon, camera.eye, d, band)
            })
            .collect();
        let clear_hits = truths
            .iter()
            .filter(|t| matches!(t, Truth::Hit(..)))
            .count();
        hits += clear_hits;
        if c.near {
            near_hits += clear_hits;
        }
        let oracle = lanecast::compare::oracle(&c.scene, &camera);
        let mut frames: Vec<(String, Vec<i32>, Vec<f64>, f64)> = vec![(
            "the scalar oracle".into(),
            oracle.ids.clone(),
            oracle.depth.clone(),
            1e-5,
        )];
        for precision in Precision::ALL {
            for accel in [Accel::None, Accel::Tiles, Accel::Bvh, Accel::World] {
                let f = render_packets(&c.scene, &camera, precision, accel);
                let tol = if precision == Precision::F32 {
                    1e-4
                } else {
                    1e-5
                };
                frames.push((
                    format!("{} {}", precision.name(), accel.name()),
                    f.ids,
                    f.depth.iter().map(|&x| x as f64).collect(),
                    tol,
                ));
            }
        }
        for (name, ids, depth, tol) in &frames {
            for (i, truth) in truths.iter().enumerate() {
                let (x, y) = (i % W as usize, i / W as usize);
                match *truth {
                    Truth::Hit(t, known) => {
                        assert!(
                            ids[i] == 0 && (depth[i] - t).abs() <= *tol * t + known,
                            "{}: {name} at ({x}, {y}) has id {} at {:.6e}, the polygon is at {t:.6e}",
                            c.what,
                            ids[i],
                            depth[i]
                        );
                    }
                    Truth::Miss => assert!(
                        ids[i] != 0,
                        "{}: {name} at ({x}, {y}) hits the polygon where the ray misses it",
                        c.what
                    ),
                    Truth::Unclear => {}
                }
            }
        }
    }
    // the cases judge many pixels, and many with the eye 1e-10 of a size or nearer above the
    // polygon's interior (the views an edge-on rule by one vertex dropped)
    assert!(hits > 50_000, "{hits} clear hits");
    assert!(
        near_hits > 5_000,
        "{near_hits} clear hits from within 1e-10 of a plane"
    );
}

/// The new user's two scenes, as they typed them: the floor seen from 1e-12 above covers every
/// pixel (the sphere beneath it never shows), and a ground quad of half-size 1e13 to 1e17 seen
/// from 2 above covers the lower part of the view, with every method.
#[test]
fn the_reported_floor_and_ground_are_drawn() {
    let floor = lanecast::parse_scene(
        "camera eye 0.3 1e-12 0.2 look 0.3 0 0.2 up 0 0 -1 fov 60\n\
         triangle -1 0 -1  1 0 -1  0 0 1\n\
         sphere 0.3 -1 0.2 0.5\n",
        std::path::Path::new("t.sc"),
    )
    .unwrap();
    let camera = camera_of(&floor, 64, 48);
    for precision in Precision::ALL {
        for accel in [
            Accel::Auto,
            Accel::None,
            Accel::Tiles,
            Accel::Bvh,
            Accel::World,
        ] {
            let f = render_packets(&floor, &camera, precision, accel);
            assert!(
                f.ids.iter().all(|&i| i == 0),
                "{} {}: {} of {} pixels are not the floor",
                precision.name(),
                accel.name(),
                f.ids.iter().filter(|&&i| i != 0).count(),
                f.ids.len()
            );
        }
    }
    for half in [1e12, 1e13, 1e15, 1e17] {
        let ground = lanecast::parse_scene(
            &format!(
                "camera eye 0 2 8 look 0 0 0 up 0 1 0 fov 60\n\
                 quad -{half} 0 -{half}  {half} 0 -{half}  {half} 0 {half}  -{half} 0 {half}\n"
            ),
            std::path::Path::new("g.sc"),
        )
        .unwrap();
        let camera = camera_of(&ground, 64, 48);
        let oracle = lanecast::compare::oracle(&ground, &camera);
        let drawn = oracle.ids.iter().filter(|&&i| i == 0).count();
        // below the horizon: the lower 3/4 of the view at this pitch, or so
        assert!(drawn > 64 * 48 / 2, "half-size {half}: {drawn} pixels");
        for precision in Precision::ALL {
            for accel in [Accel::Auto, Accel::Tiles, Accel::Bvh, Accel::World] {
                let f = render_packets(&ground, &camera, precision, accel);
                let differ = (f.ids.iter().zip(&oracle.ids))
                    .filter(|(a, b)| a != b)
                    .count();
                // at most the pixels along the horizon
                assert!(
                    differ <= 64,
                    "half-size {half}, {} {}: {differ} pixels differ from the oracle",
                    precision.name(),
                    accel.name()
                );
            }
        }
    }
}

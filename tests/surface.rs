//! `Frame::normals` and `Frame::z_depth` (src/surface.rs): on a picked scene (a floor, a wall
//! wound backwards and a sphere) each pixel's normal is the one its primitive should have; over
//! random scenes of every type, random cameras, scales from 1e-3 to 1e4 and offsets far from
//! the origin, a sphere's normal is within its stated error (`48u t / (r cos)`) of the exact
//! normal at the exact hit along the same f64 ray and a polygon's is its plane's. In both,
//! every pixel passes `checked_hits`: background zero, a hit's normal unit length and facing
//! the eye, z-depth the depth times the ray's cosine with the forward axis, to f32 rounding.

mod common;

use common::*;
use glam::DVec3;
use lanecast::scene::{Scene, Shape};
use lanecast::{Camera, Frame, Options, Renderer};
use std::path::Path;

const U: f64 = f32::EPSILON as f64 / 2.0;

/// A pixel that hit: its primitive, normal, unit f64 ray and f32 depth.
struct Hit {
    pixel: usize,
    id: i32,
    n: DVec3,
    d: DVec3,
    t: f64,
}

/// Renders `scene` from `camera` and checks what every pixel of every scene must satisfy:
/// background has normal zero and z-depth +inf; a hit's normal is unit length and faces the
/// eye, and its z-depth is its depth times its ray's cosine with the forward axis, to f32
/// rounding, and no more than its depth. Returns the frame and its hits.
fn checked_hits(scene: &Scene, camera: &Camera, case: &str) -> (Frame<f32>, Vec<Hit>) {
    let frame = Renderer::new(scene, camera, &Options::default())
        .unwrap()
        .render();
    let normals = frame.normals(scene, camera);
    let z = frame.z_depth(camera);
    let tables = camera.tables::<f64>(1, 1);
    let w = frame.width as usize;
    let mut hits = Vec::new();
    for (i, n) in normals.iter().enumerate() {
        let n = DVec3::from_array(n.map(f64::from));
        let d = DVec3::from_array(tables.dir_x1(i % w, i / w));
        let id = frame.ids[i];
        if id < 0 {
            assert_eq!(n, DVec3::ZERO, "{case} pixel {i}: background");
            assert_eq!(z[i], f32::INFINITY, "{case} pixel {i}: background");
            continue;
        }
        let t = f64::from(frame.depth[i]);
        assert!((n.length() - 1.0).abs() < 1e-6, "{case} pixel {i}: |n| {n}");
        assert!(n.dot(d) < 1e-6, "{case} pixel {i}: {n} faces away");
        let expected_z = t * d.dot(camera.f);
        assert!(
            (f64::from(z[i]) - expected_z).abs() <= 2.0 * U * expected_z.abs(),
            "{case} pixel {i}: z {} against {expected_z}",
            z[i]
        );
        assert!(z[i] <= frame.depth[i], "{case} pixel {i}");
        hits.push(Hit {
            pixel: i,
            id,
            n,
            d,
            t,
        });
    }
    (frame, hits)
}

/// A floor, a wall (a quad wound either way) and a sphere: each pixel's normal is the floor's
/// +y, the wall's +z towards the eye, or the sphere's outward normal at the hit.
#[test]
fn normals_of_a_floor_a_wall_and_a_sphere() {
    let text = "camera eye 0 2 8 look 0 1 0 up 0 1 0 fov 60\n\
                sphere 0 1 0 1\n\
                quad -4 0 -4  -4 0 4  4 0 4  4 0 -4\n\
                triangle -4 0 -3  0 4 -3  4 0 -3\n";
    let scene = lanecast::parse_scene(text, Path::new("n.sc")).unwrap();
    let camera = Camera::for_scene(&scene, 80, 60, None).unwrap();
    let (frame, hits) = checked_hits(&scene, &camera, "picked");
    for Hit { pixel, id, n, d, t } in hits {
        match id {
            0 => {
                let p = camera.eye + d * t;
                assert!((n - (p - DVec3::Y)).length() < 1e-5, "{pixel}: {n}");
                assert!(n.dot(d) < 0.0, "{pixel}: faces the eye");
            }
            1 => assert!((n - DVec3::Y).length() < 1e-7, "{pixel}: {n}"),
            2 => assert!((n - DVec3::Z).length() < 1e-7, "{pixel}: {n}"),
            id => panic!("id {id}"),
        }
    }
    let mut seen = [0; 4];
    for id in &frame.ids {
        seen[(id + 1) as usize] += 1;
    }
    assert!(seen.iter().all(|&k| k > 50), "{seen:?}");
}

/// The exact distance along unit ray `d` from `eye` to the sphere (`c`, `r`), the near root
/// (the far one with the eye inside).
fn sphere_t(eye: DVec3, d: DVec3, c: DVec3, r: f64) -> Option<f64> {
    let oc = c - eye;
    let b = oc.dot(d);
    let perp2 = (oc - d * b).length_squared();
    let h2 = r * r - perp2;
    (h2 >= 0.0).then(|| {
        let h = h2.sqrt();
        if b - h > 0.0 { b - h } else { b + h }
    })
}

#[test]
fn normals_face_the_eye_and_match_the_exact_hit_at_every_scale() {
    let mut rng = Rng::new(0x5EED_0A0A);
    let mut checked = [0usize; 3];
    for case in 0..36 {
        let scale = [1e-3, 1.0, 1e4][case % 3];
        let offset = if case % 2 == 0 {
            DVec3::ZERO
        } else {
            rng.direction() * 1e3 * scale
        };
        let mut shapes = random_spheres(&mut rng, 6);
        shapes.extend(random_triangles(&mut rng, 6));
        shapes.extend(random_quads(&mut rng, 6));
        let moved: Vec<Shape> = shapes
            .iter()
            .map(|s| match *s {
                Shape::Sphere { center, radius } => Shape::Sphere {
                    center: center * scale + offset,
                    radius: radius * scale,
                },
                Shape::Triangle(v) => Shape::Triangle(v.map(|p| p * scale + offset)),
                Shape::Quad(v) => Shape::Quad(v.map(|p| p * scale + offset)),
            })
            .collect();
        let mut cam = random_camera(&mut rng);
        // one case in four from inside a sphere
        if case % 4 == 3
            && let Shape::Sphere { center, radius } = shapes[0]
        {
            cam.eye = center + rng.direction() * radius * 0.5;
        }
        cam.eye = cam.eye * scale + offset;
        cam.look = cam.look * scale + offset;
        let scene = build_scene("surface.sc", cam, &moved);
        let camera = Camera::new(&scene.camera, cam.fov_deg().unwrap(), 97, 61);
        let (_, hits) = checked_hits(&scene, &camera, &format!("case {case}"));
        for Hit {
            pixel: i,
            id,
            n,
            d,
            t,
        } in hits
        {
            match scene.shapes.get(id as usize) {
                Shape::Sphere { center, radius } => {
                    let Some(t64) = sphere_t(camera.eye, d, center, radius) else {
                        continue; // a silhouette pixel the f64 ray just misses
                    };
                    let inside = (camera.eye - center).length() < radius;
                    let exact = (camera.eye + d * t64 - center).normalize();
                    let exact = if inside { -exact } else { exact };
                    // the stated error: the f32 depth's own, at most 48u / cos of the
                    // incidence relative (tests/agreement/main.rs, COND_BOUND_U), moves the hit
                    // along the ray, turning the normal by up to that distance over r; and
                    // the f32 rounding of the normal
                    let cos = exact.dot(d).abs();
                    let bound = 48.0 * U * t / (radius * cos) + 1e-6;
                    let angle = n.cross(exact).length();
                    assert!(
                        n.dot(exact) > 0.0 && angle <= bound,
                        "case {case} pixel {i}: angle {angle:e} > {bound:e}"
                    );
                    checked[0] += 1;
                }
                Shape::Triangle(v) => {
                    let raw = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
                    assert!(n.cross(raw).length() < 1e-6, "case {case} pixel {i}");
                    checked[1] += 1;
                }
                Shape::Quad(v) => {
                    let raw = (v[2] - v[0]).cross(v[3] - v[1]).normalize();
                    assert!(n.cross(raw).length() < 1e-6, "case {case} pixel {i}");
                    checked[2] += 1;
                }
            }
        }
    }
    assert!(checked.iter().all(|&k| k > 2000), "{checked:?}");
}

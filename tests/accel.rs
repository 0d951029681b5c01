//! Accelerations agree: every kernel and precision (the packet kernel, f64x4 packets, the
//! scalar f64 oracle and scalar-f32) with `--accel bvh` and with `--accel tiles` returns
//! exactly the ids and depths of `--accel none` (the nearest-hit rule is order-independent, the
//! BVH's padded boxes never cull a primitive a ray hits, and the tiles' rectangles and near
//! bounds are conservative), on the seed scenes, random scenes of every type, dense random
//! scenes, closed meshes, a scene far from the origin, primitives crossing the eye's plane, the
//! eye inside a sphere, and primitives cut by the image border.

mod common;

use common::*;
use glam::DVec3;
use lanecast::Accel;
use lanecast::experimental::render::wide64::Kit64;
use lanecast::experimental::render::{Frame, PacketScene, Plain, Setup, f32_depth, render_packet};
use lanecast::scene::{Scene, Shape};

fn same_bits(what: &str, w: u32, a: &Frame<f32>, b: &Frame<f32>) {
    for i in 0..a.ids.len() {
        assert_eq!(
            (a.ids[i], a.depth[i].to_bits()),
            (b.ids[i], b.depth[i].to_bits()),
            "{what}: pixel ({}, {})",
            i % w as usize,
            i / w as usize
        );
    }
}

fn frames_equal(name: &str, scene: &Scene, w: u32, h: u32) {
    let camera = camera_of(scene, w, h);
    // The scalar kernels (the f64 oracle and scalar-f32) through each structure, against
    // themselves testing every primitive.
    let (wu, hu) = (w as usize, h as usize);
    for kernel in [Plain::ScalarF64, Plain::ScalarF32] {
        let none = Setup::with_accel(kernel, Accel::None, scene, &camera);
        assert_eq!(none.accel(), Accel::None);
        let a = none.render(wu, hu);
        for accel in [Accel::Tiles, Accel::Bvh] {
            let other = Setup::with_accel(kernel, accel, scene, &camera);
            assert_eq!(other.accel(), accel);
            let b = other.render(wu, hu);
            same_bits(&format!("{name}, {kernel:?} {}", accel.name()), w, &a, &b);
        }
    }
    // f64x4 packets (`--precision f64`) through each structure, f64 depths bit for bit;
    // without acceleration they are the oracle.
    let f64x4 = |accel: Accel| Kit64::with_accel(scene, &camera, accel);
    let a = f64x4(Accel::None).render();
    let oracle = Setup::with_accel(Plain::ScalarF64, Accel::None, scene, &camera);
    same_bits(
        &format!("{name}, f64x4 = oracle"),
        w,
        &oracle.render(wu, hu),
        &f32_depth(a.clone()),
    );
    for accel in [Accel::Tiles, Accel::Bvh] {
        let m = f64x4(accel);
        assert_eq!(m.accel(), accel);
        let b = m.render();
        for i in 0..a.ids.len() {
            assert_eq!(
                (a.ids[i], a.depth[i].to_bits()),
                (b.ids[i], b.depth[i].to_bits()),
                "{name}, f64x4 {}: pixel ({}, {})",
                accel.name(),
                i % wu,
                i / wu
            );
        }
    }
    let tables = camera.tables::<f32>(4, 2);
    let none = PacketScene::new(scene, &camera, Accel::None);
    assert_eq!(none.accel(), Accel::None);
    let a = render_packet(&none, &tables, w as usize, h as usize);
    let hits = a.ids.iter().filter(|&&i| i >= 0).count();
    assert!(hits > 0, "{name}: the test scene must hit something");
    for accel in [Accel::Bvh, Accel::Tiles] {
        let other = PacketScene::new(scene, &camera, accel);
        assert_eq!(other.accel(), accel);
        let b = render_packet(&other, &tables, w as usize, h as usize);
        same_bits(&format!("{name}, {}", accel.name()), w, &a, &b);
    }
}

#[test]
fn bvh_equals_brute_force_on_seed_scenes() {
    for (name, scene) in seed_scenes() {
        frames_equal(&name, &scene, 320, 240);
    }
}

#[test]
fn bvh_equals_brute_force_on_random_scenes() {
    let mut rng = Rng::new(0xACCE1);
    for round in 0..6 {
        let mut shapes: Vec<Shape> = Vec::new();
        shapes.extend(random_spheres(&mut rng, 40));
        shapes.extend(random_triangles(&mut rng, 60));
        shapes.extend(random_quads(&mut rng, 30));
        let cam = random_camera(&mut rng);
        let scene = build_scene("mixed.sc", cam, &shapes);
        frames_equal(&format!("mixed {round}"), &scene, 160, 120);
    }
}

/// Fields of view near 180 degrees in a wide image, where the f32 screen tables' rounding
/// (which grows with the screen's half width) dominates the rays' error: the tiles' margin
/// grows with `Camera::direction_error`, and the tiles still equal testing every primitive.
#[test]
fn tiles_equal_brute_force_at_the_widest_fields_of_view() {
    let mut rng = Rng::new(0x71DE);
    for (round, fov) in [170.0, 178.0].into_iter().enumerate() {
        let mut shapes: Vec<Shape> = Vec::new();
        shapes.extend(random_spheres(&mut rng, 30));
        shapes.extend(random_triangles(&mut rng, 60));
        shapes.extend(random_quads(&mut rng, 20));
        let mut cam = random_camera(&mut rng);
        cam.lens = Some(lanecast::Lens::Fov(fov));
        let scene = build_scene("wide.sc", cam, &shapes);
        frames_equal(&format!("wide {round}, fov {fov}"), &scene, 8192, 6);
    }
}

#[test]
fn bvh_equals_brute_force_on_dense_tiny_triangles() {
    // 3000 small triangles: deep tree, many leaves per ray.
    let mut rng = Rng::new(7);
    let shapes: Vec<Shape> = (0..3000)
        .map(|_| {
            let c = rng.in_box(DVec3::ZERO, 3.0);
            Shape::Triangle([c, c + rng.direction() * 0.3, c + rng.direction() * 0.3])
        })
        .filter(|s| match s {
            Shape::Triangle(v) => (v[1] - v[0]).cross(v[2] - v[0]).length() > 1e-3,
            _ => false,
        })
        .collect();
    let scene = build_scene(
        "dense.sc",
        spec(DVec3::new(0.0, 0.0, 9.0), DVec3::ZERO, DVec3::Y, 50.0),
        &shapes,
    );
    frames_equal("dense", &scene, 200, 150);
}

#[test]
fn bvh_equals_brute_force_on_closed_meshes_and_far_scenes() {
    let mut shapes: Vec<Shape> = Vec::new();
    shapes.extend(
        icosphere(DVec3::new(-1.5, 0.0, 0.0), 1.2, 2)
            .into_iter()
            .map(Shape::Triangle),
    );
    shapes.extend(
        cube(DVec3::new(1.5, 0.0, 0.0), 1.0)
            .into_iter()
            .map(Shape::Triangle),
    );
    let cam = spec(DVec3::new(0.3, 2.0, 7.0), DVec3::ZERO, DVec3::Y, 60.0);
    let scene = build_scene("meshes.sc", cam, &shapes);
    frames_equal("meshes", &scene, 240, 180);
    let far = translated(&scene, DVec3::new(1e5, -1e5, 1e5));
    frames_equal("meshes at 1e5", &far, 240, 180);
}

#[test]
fn tiles_equal_brute_force_across_the_eye_plane_and_inside_a_sphere() {
    let eye = DVec3::new(0.0, 0.5, 4.0);
    let cam = spec(eye, DVec3::ZERO, DVec3::Y, 70.0);
    let shapes = vec![
        // a floor that runs under and behind the eye: crosses the eye's plane
        Shape::Quad([
            DVec3::new(-20.0, -1.0, -20.0),
            DVec3::new(20.0, -1.0, -20.0),
            DVec3::new(20.0, -1.0, 20.0),
            DVec3::new(-20.0, -1.0, 20.0),
        ]),
        // a triangle with one vertex behind the eye
        Shape::Triangle([
            DVec3::new(-2.0, 1.5, -3.0),
            DVec3::new(2.0, 1.2, -3.0),
            DVec3::new(0.5, 2.0, 6.0),
        ]),
        // a sphere that reaches behind the eye's plane, off to the side
        Shape::Sphere {
            center: DVec3::new(3.0, 0.5, 4.5),
            radius: 2.0,
        },
        // a wall entirely behind the eye (never hit)
        Shape::Quad([
            DVec3::new(-5.0, -5.0, 9.0),
            DVec3::new(5.0, -5.0, 9.0),
            DVec3::new(5.0, 5.0, 9.0),
            DVec3::new(-5.0, 5.0, 9.0),
        ]),
        // small spheres cut by the image border and in the middle
        Shape::Sphere {
            center: DVec3::new(-2.55, 0.2, 0.0),
            radius: 0.4,
        },
        Shape::Sphere {
            center: DVec3::new(0.0, -0.3, -1.0),
            radius: 0.5,
        },
    ];
    frames_equal(
        "eye plane",
        &build_scene("plane.sc", cam, &shapes),
        203,
        117,
    );
    // the eye inside a big sphere, with things inside it too
    let mut inside = shapes.clone();
    inside.push(Shape::Sphere {
        center: DVec3::new(0.2, 0.0, 1.0),
        radius: 30.0,
    });
    frames_equal("inside", &build_scene("inside.sc", cam, &inside), 203, 117);
}

#[test]
fn auto_picks_tiles_from_the_threshold() {
    assert_eq!(
        Accel::Auto.resolve(lanecast::experimental::accel::AUTO_MIN - 1),
        Accel::None
    );
    assert_eq!(
        Accel::Auto.resolve(lanecast::experimental::accel::AUTO_MIN),
        Accel::Tiles
    );
    assert_eq!(Accel::None.resolve(1_000_000), Accel::None);
}

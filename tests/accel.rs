//! Accelerations agree: the packet kernel with `--accel bvh` returns exactly the ids and depths
//! of `--accel none` (the nearest-hit rule is order-independent, and the BVH's padded boxes
//! never cull a primitive a ray hits), on the seed scenes, random scenes of every type, dense
//! random scenes, closed meshes, and a scene far from the origin.

mod common;

use common::*;
use glam::DVec3;
use lanecast::accel::Accel;
use lanecast::render::{PacketScene, render_packet};
use lanecast::scene::{Scene, Shape};

fn frames_equal(name: &str, scene: &Scene, w: u32, h: u32) {
    let camera = camera_of(scene, w, h);
    let tables = camera.tables::<f32>(4, 2);
    let none = PacketScene::new(scene, camera.eye, Accel::None);
    let bvh = PacketScene::new(scene, camera.eye, Accel::Bvh);
    assert_eq!(none.accel(), Accel::None);
    assert_eq!(bvh.accel(), Accel::Bvh);
    let a = render_packet(&none, &tables, w as usize, h as usize);
    let b = render_packet(&bvh, &tables, w as usize, h as usize);
    let hits = a.ids.iter().filter(|&&i| i >= 0).count();
    assert!(hits > 0, "{name}: the test scene must hit something");
    for i in 0..a.ids.len() {
        assert_eq!(
            (a.ids[i], a.depth[i].to_bits()),
            (b.ids[i], b.depth[i].to_bits()),
            "{name}: pixel ({}, {})",
            i % w as usize,
            i / w as usize
        );
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
fn auto_picks_bvh_from_the_threshold() {
    assert_eq!(
        Accel::Auto.resolve(lanecast::accel::AUTO_BVH_MIN - 1),
        Accel::None
    );
    assert_eq!(
        Accel::Auto.resolve(lanecast::accel::AUTO_BVH_MIN),
        Accel::Bvh
    );
    assert_eq!(Accel::None.resolve(1_000_000), Accel::None);
}

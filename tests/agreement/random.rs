//! Random scenes.

use super::*;

const RANDOM_W: u32 = 160;
const RANDOM_H: u32 = 120;

fn random_scene(seed: u64, make: impl Fn(&mut Rng) -> Vec<Shape>) -> Scene {
    let mut rng = Rng::new(seed);
    let camera = random_camera(&mut rng);
    let shapes = make(&mut rng);
    build_scene(&format!("random{seed}.sc"), camera, &shapes)
}

fn random_cases(kind: &str, make: impl Fn(&mut Rng) -> Vec<Shape>, far: bool) {
    for seed in 1..=6 {
        let kind_hash = kind.bytes().fold(0u64, |h, b| h * 31 + b as u64);
        let scene = random_scene(seed * 7919 + kind_hash, &make);
        let name = format!("random {kind} #{seed}");
        if far {
            check(
                &format!("{name} far"),
                &translated(&scene, FAR),
                RANDOM_W,
                RANDOM_H,
                Mesh::Loose,
                0.05,
            );
        } else {
            check(&name, &scene, RANDOM_W, RANDOM_H, Mesh::Loose, 0.05);
        }
    }
}

fn spheres(rng: &mut Rng) -> Vec<Shape> {
    random_spheres(rng, 30)
}

fn tris(rng: &mut Rng) -> Vec<Shape> {
    random_triangles(rng, 30)
}

fn quads(rng: &mut Rng) -> Vec<Shape> {
    random_quads(rng, 30)
}

fn mixed(rng: &mut Rng) -> Vec<Shape> {
    let mut s = random_spheres(rng, 10);
    s.extend(random_triangles(rng, 10));
    s.extend(random_quads(rng, 10));
    s
}

#[test]
fn random_spheres_agree() {
    random_cases("spheres", spheres, false);
}

#[test]
fn random_spheres_far_from_the_origin_agree() {
    random_cases("spheres", spheres, true);
}

#[test]
fn random_triangles_agree() {
    random_cases("triangles", tris, false);
}

#[test]
fn random_triangles_far_from_the_origin_agree() {
    random_cases("triangles", tris, true);
}

#[test]
fn random_quads_agree() {
    random_cases("quads", quads, false);
}

#[test]
fn random_quads_far_from_the_origin_agree() {
    random_cases("quads", quads, true);
}

/// Cameras as rigs give them (`K`: `fy != fx`, the principal point off the centre), mixed
/// scenes near the origin and far from it.
#[test]
fn random_pinhole_cameras_agree() {
    for seed in 1..=6u64 {
        let mut rng = Rng::new(seed * 31_337);
        let spec = random_camera(&mut rng);
        let spec = random_pinhole(&mut rng, spec, RANDOM_W, RANDOM_H);
        let shapes = mixed(&mut rng);
        let scene = build_scene(&format!("pinhole{seed}.sc"), spec, &shapes);
        let name = format!("random pinhole #{seed}");
        check(&name, &scene, RANDOM_W, RANDOM_H, Mesh::Loose, 0.02);
        let far = translated(&scene, FAR);
        check(
            &format!("{name} far"),
            &far,
            RANDOM_W,
            RANDOM_H,
            Mesh::Loose,
            0.02,
        );
    }
}

#[test]
fn random_mixed_scenes_agree() {
    random_cases("mixed", mixed, false);
    random_cases("mixed", mixed, true);
}

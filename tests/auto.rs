//! `--precision auto`, the guarantee (docs/precision.md, `render::redecide`): with every
//! acceleration, every pixel's depth is within 1e-5 relative of the f64 oracle's for the same
//! primitive, and ids differ from the oracle's only near a primitive's boundary or at genuine
//! ties (both hit within 1e-5 relative). The band derived for "near" is `12u + a` of an edge
//! plane (1.1e-6 rad at 60 degrees); these tests hold ids to the stricter 1e-6 rad. Checked on
//! the lab's stress scenes, the seed scenes, and scenes written here for each class where f32
//! alone fails: rotated grazing quads, rotated grazing corridors, a huge sphere near its horizon
//! (with and without the horizon in view), and tiny far triangles. Each failure class is also
//! checked to fail with `--precision f32`, so the scenes do test what they claim.

mod common;

use common::*;
use glam::{DMat3, DVec3};
use lanecast::Accel;
use lanecast::compare::{UNEXCUSED, classify_within};
use lanecast::experimental::render::{Frame, Options, Renderer};
use lanecast::scene::{Scene, Shape};
use lanecast::{Kernel, Precision};
use std::path::Path;

const DEPTH_REL: f64 = 1e-5;
const EDGE_BAND: f64 = 1e-6;

/// The worst failure of a frame against the oracle: unexcused id mismatches, and the largest
/// relative depth error over pixels with the oracle's id.
#[derive(Debug, Default)]
struct Failures {
    unexcused: Vec<(usize, usize, i32, i32)>,
    depth_rel_max: f64,
}

fn judge(scene: &Scene, w: u32, h: u32, oracle: &Frame<f64>, got: &Frame<f32>) -> Failures {
    let camera = camera_of(scene, w, h);
    let tables = camera.tables::<f64>(1, 1);
    let mut f = Failures::default();
    for i in 0..oracle.ids.len() {
        let (a, b) = (oracle.ids[i], got.ids[i]);
        let (x, y) = (i % w as usize, i / w as usize);
        if a == b {
            if a >= 0 {
                let rel = (got.depth[i] as f64 - oracle.depth[i]).abs() / oracle.depth[i];
                f.depth_rel_max = f.depth_rel_max.max(rel);
            }
        } else if classify_within(scene, &camera, tables.dir_x1(x, y), a, b, EDGE_BAND) == UNEXCUSED
        {
            f.unexcused.push((x, y, a, b));
        }
    }
    f
}

fn render(
    scene: &Scene,
    w: u32,
    h: u32,
    precision: Precision,
    accel: Accel,
) -> (Frame<f32>, usize) {
    let camera = camera_of(scene, w, h);
    let options = Options {
        precision,
        accel,
        kernel: Kernel::Packet,
    };
    let r = Renderer::new(scene, &camera, &options).unwrap();
    let (frame, redone) = r.render_marking(None);
    (frame, redone.len())
}

/// Asserts the guarantee for `--precision auto` with every acceleration; returns the f32
/// failures, for the scenes that must show them.
fn holds(name: &str, scene: &Scene, w: u32, h: u32) -> Failures {
    let oracle = lanecast::compare::oracle(scene, &camera_of(scene, w, h));
    assert!(
        oracle.ids.iter().any(|&i| i >= 0),
        "{name}: the scene must hit something"
    );
    for accel in [Accel::None, Accel::Tiles, Accel::Bvh] {
        let (frame, redone) = render(scene, w, h, Precision::Auto, accel);
        let f = judge(scene, w, h, &oracle, &frame);
        assert!(
            f.unexcused.is_empty() && f.depth_rel_max <= DEPTH_REL,
            "{name}, auto, accel {}: {} unexcused (first {:?}), depth rel max {:.3e}, {redone} re-decided",
            accel.name(),
            f.unexcused.len(),
            f.unexcused.first(),
            f.depth_rel_max
        );
    }
    let (f32_frame, _) = render(scene, w, h, Precision::F32, Accel::Auto);
    judge(scene, w, h, &oracle, &f32_frame)
}

fn fails(f: &Failures) -> bool {
    !f.unexcused.is_empty() || f.depth_rel_max > DEPTH_REL
}

#[test]
fn auto_holds_on_the_stress_scenes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/stress");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "sc"))
        .collect();
    names.sort();
    assert!(names.len() >= 12, "{} stress scenes", names.len());
    let mut f32_failed = Vec::new();
    for p in names {
        let scene = lanecast::load_scene(&p).unwrap();
        let name = p.file_stem().unwrap().to_string_lossy().into_owned();
        if fails(&holds(&name, &scene, 256, 192)) {
            f32_failed.push(name);
        }
    }
    // f32 alone fails the huge sphere (`ground`): auto made the difference there. (The lab's
    // `grazing` is axis-aligned, where `d . N` has one non-zero term and f32 stays exact; the
    // rotated grazing scenes below are the ones f32 fails.)
    assert!(f32_failed.iter().any(|n| n == "ground"), "{f32_failed:?}");
}

#[test]
fn auto_holds_on_the_seed_scenes() {
    for (name, scene) in seed_scenes() {
        holds(&name, &scene, 320, 240);
    }
}

/// Images whose sides are not whole tiles or packets: the last strip is three rows, the last
/// tile column five pixels, and suspect packets there reach past the image (a packet's row
/// beyond the last strip once made the strip check index past its rows).
#[test]
fn auto_holds_on_images_off_the_tile_grid() {
    for (name, scene) in seed_scenes() {
        holds(&name, &scene, 333, 211);
    }
}

/// A rotation off every axis.
fn tilt() -> DMat3 {
    DMat3::from_rotation_y(0.37) * DMat3::from_rotation_x(0.21) * DMat3::from_rotation_z(0.53)
}

/// A rectangle in the plane through `c` spanned by unit `e1`, `e2`: corners at
/// `c + a e1 + b e2`, `a` in `[-w, w]`, `b` in `[b0, b1]`.
fn rect(c: DVec3, e1: DVec3, e2: DVec3, w: f64, (b0, b1): (f64, f64)) -> Shape {
    Shape::Quad([
        c - w * e1 + b0 * e2,
        c + w * e1 + b0 * e2,
        c + w * e1 + b1 * e2,
        c - w * e1 + b1 * e2,
    ])
}

#[test]
fn auto_holds_on_rotated_grazing_quads() {
    // Quads whose planes pass 0.01 to 0.03 from the eye, reaching 200 units along the view:
    // incidence down to 5e-5 rad, rotated off the axes, with a wall behind them.
    let m = tilt();
    let fwd = m * DVec3::NEG_Z;
    let side = m * DVec3::X;
    let up = m * DVec3::Y;
    let mut shapes = Vec::new();
    for (k, off) in [0.01, 0.02, 0.03].iter().enumerate() {
        let n = up * (k as f64 - 1.0).signum().max(0.0) * 2.0 - up; // below, below, above
        let e1 = (side + 0.02 * k as f64 * fwd).normalize();
        let e2 = n.cross(e1).normalize();
        let e2 = if e2.dot(fwd) < 0.0 { -e2 } else { e2 };
        shapes.push(rect(n * *off, e1, e2, 3.0, (0.5, 200.0)));
    }
    shapes.push(rect(fwd * 300.0, side, up, 400.0, (-400.0, 400.0)));
    let scene = build_scene(
        "grazing_quads.sc",
        spec(DVec3::ZERO, fwd + 0.002 * up, up, 50.0),
        &shapes,
    );
    let f = holds("grazing_quads", &scene, 256, 192);
    assert!(fails(&f), "f32 alone must fail here: {f:?}");
}

#[test]
fn auto_holds_in_a_rotated_grazing_corridor() {
    // A corridor 1 wide and 1,000 long, the eye inside near one end, looking along it: walls,
    // floor and ceiling at grazing angles far down, rotated off the axes, shifted off the origin.
    let m = tilt();
    let (x, y, z) = (m * DVec3::X, m * DVec3::Y, m * DVec3::NEG_Z);
    let base = DVec3::new(120.0, -40.0, 75.0);
    let len = (0.0, 1000.0);
    let shapes = vec![
        rect(base - 0.5 * y, x, z, 0.5, len),
        rect(base + 0.5 * y, x, z, 0.5, len),
        rect(base - 0.5 * x, y, z, 0.5, len),
        rect(base + 0.5 * x, y, z, 0.5, len),
        rect(base + 1000.0 * z, x, y, 0.5, (-0.5, 0.5)),
    ];
    let eye = base + 0.13 * x - 0.07 * y + 2.0 * z;
    let scene = build_scene("corridor.sc", spec(eye, eye + z, y, 70.0), &shapes);
    let f = holds("corridor", &scene, 256, 192);
    assert!(fails(&f), "f32 alone must fail here: {f:?}");
}

#[test]
fn auto_holds_on_a_huge_sphere_near_its_horizon() {
    // Radius 1e4, the eye just above it: the horizon in view, then looking down past it.
    let ground = Shape::Sphere {
        center: DVec3::new(0.0, -1e4, 0.0),
        radius: 1e4,
    };
    let ball = Shape::Sphere {
        center: DVec3::new(0.3, 0.2, -6.0),
        radius: 0.2,
    };
    let eye = DVec3::new(0.0, 0.5, 0.0);
    for (name, look, must_fail) in [
        ("horizon", DVec3::new(0.0, 0.45, -10.0), true),
        ("below_horizon", DVec3::new(0.0, -2.0, -10.0), false),
    ] {
        let scene = build_scene(name, spec(eye, look, DVec3::Y, 60.0), &[ground, ball]);
        let f = holds(name, &scene, 256, 192);
        if must_fail {
            assert!(fails(&f), "{name}: f32 alone must fail here: {f:?}");
        }
    }
}

#[test]
fn auto_holds_on_tiny_far_triangles() {
    // 400 triangles of 1e-3 seen from about 1e4 (1e-7 rad: far below the f32 edge tolerance),
    // in front of a wall.
    let mut rng = Rng::new(11);
    let mut shapes = Vec::new();
    for _ in 0..400 {
        let c = DVec3::new(rng.range(-3e3, 3e3), rng.range(-2e3, 2e3), -1e4);
        let a = rng.direction() * 1e-3;
        let b = rng.direction() * 1e-3;
        shapes.push(Shape::Triangle([c, c + a, c + b]));
    }
    shapes.push(rect(
        DVec3::new(0.0, 0.0, -1.2e4),
        DVec3::X,
        DVec3::Y,
        1e4,
        (-1e4, 1e4),
    ));
    let scene = build_scene(
        "tiny_far.sc",
        spec(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y, 40.0),
        &shapes,
    );
    holds("tiny_far_triangles", &scene, 256, 192);
}

/// `Renderer::auto_work` counts the last frame's tile path: every packet of the image walked,
/// some carrying the trusted distance and not all, at least as many hits measured as pixels
/// re-decided; nothing counted through the BVH, and no counts for `--precision f32`.
#[test]
fn auto_work_counts_the_last_frames_packets_and_measurements() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/stress/ground.sc");
    let scene = lanecast::load_scene(&path).unwrap();
    let (w, h) = (203, 101);
    let camera = camera_of(&scene, w, h);
    let renderer = |precision, accel| {
        let options = Options {
            precision,
            accel,
            kernel: Kernel::Packet,
        };
        Renderer::new(&scene, &camera, &options).unwrap()
    };
    let tiles = renderer(Precision::Auto, Accel::Tiles);
    for _ in 0..2 {
        let (_, redone) = tiles.render_marking(None);
        let work = tiles.auto_work().expect("auto counts its work");
        let packets = (w as usize).div_ceil(4) * (h as usize).div_ceil(2);
        assert_eq!(work.packets, packets, "every packet, once per frame");
        assert!(work.carrying > 0 && work.carrying < packets, "{work:?}");
        assert!(
            work.measured >= redone.len() && work.measured > 0,
            "{work:?}"
        );
    }
    let bvh = renderer(Precision::Auto, Accel::Bvh);
    bvh.render_marking(None);
    assert_eq!(bvh.auto_work(), Some(Default::default()));
    assert_eq!(renderer(Precision::F32, Accel::Tiles).auto_work(), None);
}

use super::*;
use crate::camera::Camera;
use crate::kernel::polygon::{TriangleK, polygon_x1};
use crate::kernel::sphere::sphere_x1;
use crate::scene::Scene;
use crate::scene::{CameraSpec, Shapes};
use crate::soa::Packed;

/// Scene 7's far-reaching triangle (grazing far away) and a sphere far larger than its
/// distance to the eye, seen near its horizon, through a 64x48 camera.
fn grazing_scene() -> (Scene, Camera) {
    let mut shapes = Shapes::new();
    let v = |x, y, z| DVec3::new(x, y, z);
    shapes.push(
        Shape::Triangle([
            v(0.0, -0.15, -0.48),
            v(-42.0, 24.0, -80.0),
            v(42.0, 24.0, -80.0),
        ]),
        1,
    );
    shapes.push(
        Shape::Sphere {
            center: v(0.0, -1.0e4 - 1.5, -20.0),
            radius: 1.0e4,
        },
        2,
    );
    let scene = Scene {
        camera_at: None,
        source: "t.sc".into(),
        camera: CameraSpec {
            eye: DVec3::ZERO,
            look: v(0.0, 0.0, -1.0),
            up: DVec3::Y,
            lens: None,
        },
        shapes,
        warnings: Vec::new(),
    };
    let camera = Camera::new(&scene.camera, 60.0, 64, 48);
    (scene, camera)
}

/// The oracle's distance to primitive `id` along pixel `(x, y)`'s f64 ray, with the oracle's
/// own kernel and constants (spheres and triangles: the shapes of [`grazing_scene`]).
fn oracle_t(scene: &Scene, r: &Redecide, (x, y): (usize, usize), id: usize) -> Option<f64> {
    let d = r.tables.dir_x1(x, y);
    match scene.shapes.get(id) {
        Shape::Sphere { center, radius } => {
            sphere_x1(&SphereK::new(center, radius, r.camera_eye), d)
        }
        Shape::Triangle(v) => TriangleK::triangle(&v, r.camera_eye).and_then(|k| polygon_x1(&k, d)),
        Shape::Quad(_) => None,
    }
}

/// A hit beyond its primitive's limits is kept exactly when its distance is within
/// `BUDGET` of the oracle's for that primitive, measured one lane alone and by groups of four, on one primitive or two.
#[test]
fn measured_hits_are_kept_only_within_the_budget() {
    let (scene, camera) = grazing_scene();
    let packed = Packed::from_scene(&scene, camera.eye);
    let r = Redecide::new(&scene, &camera, &packed);
    let walk = r.walk(&packed, None, None);
    let (mut kept, mut refused, mut mixed) = (0, 0, 0);
    for y in 0..48 {
        for x0 in (0..64).step_by(4) {
            // the oracle's distance of each lane for each primitive, with the oracle's own
            // kernel and constants
            let t64: [[Option<f64>; 4]; 2] = std::array::from_fn(|id| {
                std::array::from_fn(|i| oracle_t(&scene, &r, (x0 + i, y), id))
            });
            // each primitive alone, then the two alternating lane by lane where both hit
            let choices: [[usize; 4]; 3] = [[0; 4], [1; 4], [0, 1, 0, 1]];
            for pick in choices {
                let lanes: u32 = (0..4)
                    .filter(|&i| t64[pick[i]][i].is_some())
                    .fold(0, |m, i| m | 1 << i);
                if lanes == 0 {
                    continue;
                }
                let id = pick.map(|p| p as f32);
                if (0..4).any(|i| lanes & (1 << i) != 0 && pick[i] == 1)
                    && (0..4).any(|i| lanes & (1 << i) != 0 && pick[i] == 0)
                {
                    mixed += 1;
                }
                // f32 hits at the oracle's distance, and at 2 BUDGET beyond it
                for (scale, want_kept) in [(1.0, true), (1.0 + 2.0 * BUDGET, false)] {
                    let t: [f32; 4] = std::array::from_fn(|i| {
                        t64[pick[i]][i].map_or(f32::INFINITY, |t| (t * scale) as f32)
                    });
                    // the whole group and one lane alone
                    let single = 1 << lanes.trailing_zeros();
                    for mask in [lanes, single] {
                        let left = r.recheck_group(&walk, (x0, y), &t, &id, mask);
                        if want_kept {
                            assert_eq!(left, 0, "{pick:?} at ({x0}, {y}) lanes {mask:04b}");
                            kept += mask.count_ones();
                        } else {
                            assert_eq!(left, mask, "{pick:?} at ({x0}, {y})");
                            refused += mask.count_ones();
                        }
                    }
                }
            }
        }
    }
    assert!(mixed > 5, "{mixed} mixed groups");
    assert!(kept > 500 && refused > 500, "{kept} {refused}");
}

/// Once attached to the tiles, a marked polygon's plane is kept, bit for bit the one the
/// measurement computes from the scene's shape, and a suspect found in its packet
/// (`Known::Polygon`) is measured with it as one looked up by id is: kept at the oracle's
/// distance, refused at 2 `BUDGET` beyond it. The grazing triangle is marked; the scene
/// has no other polygon.
#[test]
fn a_marked_polygons_kept_plane_measures_as_the_oracles() {
    let (scene, camera) = grazing_scene();
    let mut p = crate::render::PacketScene::new(&scene, &camera, crate::accel::Accel::Tiles);
    let mut r = Redecide::new(&scene, &camera, &p.packed);
    let tiles = p.tiles.as_mut().expect("tiles");
    r.attach_to(tiles, &p.packed, &camera);
    let at = p.packed.triangles.id.iter().position(|&id| id == 0.0);
    let at = at.expect("the triangle, packed");
    let Known::Polygon(1, at) = r.known((1, at)) else {
        panic!("the grazing triangle is marked")
    };
    let kept = r.planes[0][at as usize];
    assert!(kept.hi2 > 0.0, "its plane is kept");
    assert_eq!(Some(kept), r.plane(scene.shapes.get(0)));
    let walk = r.walk(&p.packed, p.tiles.as_ref(), None);
    let mut measured = 0;
    for y in 0..48 {
        for x in 0..64 {
            let Some(t64) = oracle_t(&scene, &r, (x, y), 0) else {
                continue;
            };
            for (scale, expected) in [(1.0, 1), (1.0 + 2.0 * BUDGET, 0)] {
                let s = |known| Suspect {
                    x,
                    y,
                    id: 0.0,
                    t: (t64 * scale) as f32,
                    known,
                };
                let found = [s(Known::Polygon(1, at)); 4];
                let by_id = [s(Known::Unknown); 4];
                assert_eq!(r.verified_lanes(&walk, &found, 1), expected, "({x}, {y})");
                assert_eq!(r.verified_lanes(&walk, &by_id, 1), expected, "({x}, {y})");
                measured += 1;
            }
        }
    }
    assert!(measured > 1000, "{measured}");
}

/// Suspects measured four at a time whatever their pixels, rows and primitives (as a strip's
/// pending packets fill the lanes) get each the answer their own oracle distance gives: kept
/// at it, refused at 2 `BUDGET` beyond it, wherever the batch puts them.
#[test]
fn suspects_batched_across_pixels_and_primitives_are_measured_each_alone() {
    let (scene, camera) = grazing_scene();
    let packed = Packed::from_scene(&scene, camera.eye);
    let r = Redecide::new(&scene, &camera, &packed);
    let walk = r.walk(&packed, None, None);
    let mut cases = Vec::new();
    for y in 0..48 {
        for x in 0..64 {
            for id in 0..2 {
                if let Some(t64) = oracle_t(&scene, &r, (x, y), id) {
                    let at = |scale: f64| Suspect {
                        x,
                        y,
                        id: id as f32,
                        t: (t64 * scale) as f32,
                        known: Known::Unknown,
                    };
                    cases.push((at(1.0), true));
                    cases.push((at(1.0 + 2.0 * BUDGET), false));
                }
            }
        }
    }
    // a fixed shuffle: neighbours in a batch come from far apart in the image
    let n = cases.len();
    let order: Vec<usize> = (0..n).map(|i| i * 7919 % n).collect();
    assert!(n % 7919 != 0 && n > 1000, "{n} cases");
    let (mut mixed, mut kept) = (0, 0);
    for four in order.chunks(4) {
        let s = std::array::from_fn(|i| four.get(i).map_or(Suspect::default(), |&c| cases[c].0));
        let lanes = (1 << four.len()) - 1;
        let ok = r.verified_lanes(&walk, &s, lanes);
        for (i, &c) in four.iter().enumerate() {
            assert_eq!(
                ok >> i & 1 == 1,
                cases[c].1,
                "{:?} in a batch of {}",
                cases[c].0,
                four.len()
            );
            kept += u32::from(cases[c].1);
        }
        if four.iter().any(|&c| cases[c].0.id == 0.0) && four.iter().any(|&c| cases[c].0.id == 1.0)
        {
            mixed += 1;
        }
    }
    assert!(
        mixed > 50 && kept > 500,
        "{mixed} mixed batches, {kept} kept"
    );
}

/// Four spheres in four lanes, each along its own pixel's ray, give `sphere_x1`'s answer
/// bit for bit: the same hit or miss, the same distance (eye outside and inside).
#[test]
fn sphere_lanes_of_four_spheres_are_the_oracle_bit_for_bit() {
    let (scene, camera) = grazing_scene();
    let packed = Packed::from_scene(&scene, camera.eye);
    let r = Redecide::new(&scene, &camera, &packed);
    let spheres = [
        SphereK::new(DVec3::new(0.0, -1.0e4 - 1.5, -20.0), 1.0e4, camera.eye),
        SphereK::new(DVec3::new(0.3, 0.1, -3.0), 0.7, camera.eye),
        SphereK::new(DVec3::new(-0.2, 0.05, 0.1), 2.0, camera.eye),
        SphereK::new(DVec3::new(1.0e3, 2.0e2, -4.0e3), 900.0, camera.eye),
    ];
    let (mut hits, mut misses) = (0, 0);
    for y in 0..48 {
        for x0 in (0..64).step_by(4) {
            // lane i: sphere (i + x0 / 4 + y) % 4 along pixel (x0 + i, y)
            let pick = |i: usize| (i + x0 / 4 + y) % 4;
            let mut k = SphereLanes::default();
            (0..4).for_each(|i| k.set(i, &spheres[pick(i)]));
            let sx = f64x4::new(std::array::from_fn(|i| r.tables.sx[x0 + i]));
            let d = dir_x4d(&r.tables, sx, f64x4::splat(r.tables.sy[y]));
            let (hit, t64) = sphere_t64(&k, &d);
            let (hit, t64) = (hit.to_bitmask(), t64.to_array());
            for i in 0..4 {
                let one = sphere_x1(&spheres[pick(i)], r.tables.dir_x1(x0 + i, y));
                match one {
                    Some(t) => {
                        assert!(hit >> i & 1 == 1, "({}, {y}) lane {i}", x0 + i);
                        assert_eq!(t.to_bits(), t64[i].to_bits(), "({}, {y})", x0 + i);
                        hits += 1;
                    }
                    None => {
                        assert!(hit >> i & 1 == 0, "({}, {y}) lane {i}", x0 + i);
                        misses += 1;
                    }
                }
            }
        }
    }
    assert!(hits > 500 && misses > 100, "{hits} hits, {misses} misses");
}

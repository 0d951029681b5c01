//! The tiles' unit tests: binning, footprints and the per-packet split against brute force.

use super::*;
use crate::camera::Camera;
use crate::kernel::packet::{BLOCK_H, BLOCK_W};
use crate::kernel::polygon::polygon_x8;
use crate::kernel::sphere::Sphere;
use crate::kernel::sphere::sphere_x8;
use crate::kernel::{Family, Quad, Triangle};
use crate::real::V3;
use crate::scene::{CameraSpec, Scene, Shape};
use crate::soa::Prepared;
use crate::test_rng::Rng;

/// The entries' kinds (`Family::KIND`).
const SPHERE: u32 = Sphere::KIND as u32;
const TRIANGLE: u32 = Triangle::KIND as u32;
const QUAD: u32 = Quad::KIND as u32;
use glam::DVec3;

/// Primitives of every kind and size around the eye: tiny and large, in front, crossing
/// the eye's plane, behind, and the eye inside one sphere.
fn scene(seed: u64, eye: DVec3, look: DVec3, fov: f64) -> Scene {
    let mut rng = Rng(seed);
    let mut shapes = Vec::new();
    for i in 0..300 {
        let size = [0.01, 0.1, 1.0, 5.0][i % 4];
        let c = rng.point(6.0);
        match i % 3 {
            0 => shapes.push(Shape::Sphere {
                center: c,
                radius: size * (0.2 + rng.unit()),
            }),
            1 => shapes.push(Shape::Triangle([
                c,
                c + rng.point(size),
                c + rng.point(size),
            ])),
            _ => {
                let (a, b) = (rng.point(size), rng.point(size));
                shapes.push(Shape::Quad([c, c + a, c + a + b, c + b]));
            }
        }
    }
    shapes.push(Shape::Sphere {
        center: eye + DVec3::new(0.1, 0.0, 0.0),
        radius: 20.0,
    });
    Scene {
        camera_at: None,
        source: "tiles.sc".into(),
        camera: CameraSpec {
            eye,
            look,
            up: DVec3::Y,
            lens: Some(crate::scene::Lens::Fov(fov)),
        },
        shapes: shapes.into(),
        warnings: Vec::new(),
    }
}

/// The claims the binning rests on, checked ray by ray against the kernels themselves: every
/// pixel whose ray a primitive's f32 kernel accepts has that primitive in its tile's list with
/// the pixel's packet among the entry's packets, and the distance it returns is at least the
/// entry's `near`.
#[test]
fn kernels_accept_rays_only_in_their_packets_and_beyond_near() {
    for (seed, fov) in [(1, 60.0), (2, 150.0), (3, 20.0)] {
        let eye = DVec3::new(0.3, 0.2, 1.0);
        let scene = scene(seed, eye, DVec3::new(0.0, 0.0, -3.0), fov);
        let camera = Camera::new(&scene.camera, fov, 97, 61);
        let mut packed = Packed::new(&Prepared::new(&scene, eye));
        let (tiles, order) = Tiles::new(&scene, &packed, &camera);
        packed.permute(&order);
        let tables = camera.tables::<f32>(1, 1);
        let mut accepted = 0;
        for y in 0..61 {
            for x in 0..97 {
                let d = tables.dir_x1(x, y).map(f32x8::splat);
                let kinds = [
                    (SPHERE, packed.spheres.len()),
                    (TRIANGLE, packed.triangles.len()),
                    (QUAD, packed.quads.len()),
                ];
                for (kind, n) in kinds {
                    for i in 0..n {
                        let found = match kind {
                            SPHERE => sphere_x8(&packed.spheres.get(i), &d),
                            TRIANGLE => polygon_x8(&packed.triangles.get(i), &d),
                            _ => polygon_x8(&packed.quads.get(i), &d),
                        };
                        let Some((mask, t)) = found else { continue };
                        let (m, t) = (mask.to_array()[0], t.to_array()[0]);
                        if m == 0.0 || t.is_nan() || t <= 0.0 {
                            continue;
                        }
                        accepted += 1;
                        let prim = kind << KIND_SHIFT | i as u32;
                        let list = tiles.list(x / TILE_W, y / TILE_H);
                        let e = list.iter().find(|e| e.prim == prim).unwrap_or_else(|| {
                            panic!(
                                "seed {seed}: kind {kind} #{i} hit at ({x}, {y}), not in its tile"
                            )
                        });
                        let k = y % TILE_H / BLOCK_H * (TILE_W / BLOCK_W) + x % TILE_W / BLOCK_W;
                        assert!(
                            e.packets() >> k & 1 == 1,
                            "seed {seed}: kind {kind} #{i} hit at ({x}, {y}), packet {k} not in {:08b}",
                            e.packets()
                        );
                        assert!(t >= e.near, "seed {seed}: t {t} < near {}", e.near);
                    }
                }
            }
        }
        assert!(
            accepted > 1000,
            "seed {seed}: the scene must be seen ({accepted})"
        );
    }
}

/// `split_tile` gives each packet the tile's entries that name it, in the tile's (nearest-first)
/// order, and no packet's list leaves out a primitive that the packet kernel accepts on one of
/// its rays; for every tile, including the partial ones at the right and bottom borders. The
/// packets are not the whole tile: entries listed in a tile leave some of its packets out.
#[test]
fn split_tile_keeps_the_entries_reaching_each_packet() {
    let eye = DVec3::new(0.3, 0.2, 1.0);
    let scene = scene(4, eye, DVec3::new(0.0, 0.0, -3.0), 70.0);
    let (w, h): (usize, usize) = (101, 45);
    let camera = Camera::new(&scene.camera, 70.0, w as u32, h as u32);
    let mut packed = Packed::new(&Prepared::new(&scene, eye));
    let (tiles, order) = Tiles::new(&scene, &packed, &camera);
    packed.permute(&order);
    let tables = camera.tables::<f32>(BLOCK_W as u32, BLOCK_H as u32);
    let mut lists = PacketLists::default();
    let (mut kept, mut listed_missed, mut left_out) = (0, 0, 0);
    let all: Vec<u32> = [
        (SPHERE, packed.spheres.len()),
        (TRIANGLE, packed.triangles.len()),
        (QUAD, packed.quads.len()),
    ]
    .iter()
    .flat_map(|&(kind, n)| (0..n as u32).map(move |i| kind << KIND_SHIFT | i))
    .collect();
    for ty in 0..h.div_ceil(TILE_H) {
        for tx in 0..w.div_ceil(TILE_W) {
            tiles.split_tile((tx, ty), &mut lists);
            let list = tiles.list(tx, ty);
            for k in 0..PACKETS {
                let x0 = tx * TILE_W + k % (TILE_W / BLOCK_W) * BLOCK_W;
                let y0 = ty * TILE_H + k / (TILE_W / BLOCK_W) * BLOCK_H;
                let named: Vec<u32> = (0..list.len() as u32)
                    .filter(|&i| list[i as usize].packets() >> k & 1 == 1)
                    .collect();
                let got = &lists.index[k * lists.stride..][..lists.len[k]];
                assert_eq!(got, &named[..], "tile ({tx}, {ty}) packet {k}");
                left_out += list.len() - named.len();
                if x0 >= w || y0 >= h {
                    continue;
                }
                // the packet's rays, as the kernel takes them
                let dirs: [V3<f32>; 8] = std::array::from_fn(|l| {
                    tables.dir_x1((x0 + l % BLOCK_W).min(w - 1), (y0 + l / BLOCK_W).min(h - 1))
                });
                let d: [f32x8; 3] = std::array::from_fn(|c| f32x8::new(dirs.map(|v| v[c])));
                for &prim in &all {
                    let idx = (prim & INDEX_MASK) as usize;
                    let accepted = match prim >> KIND_SHIFT {
                        TRIANGLE => polygon_x8(&packed.triangles.get(idx), &d),
                        QUAD => polygon_x8(&packed.quads.get(idx), &d),
                        _ => sphere_x8(&packed.spheres.get(idx), &d),
                    }
                    .is_some_and(|(m, t)| (m & t.simd_gt(f32x8::ZERO)).any());
                    let listed = got.iter().any(|&i| list[i as usize].prim == prim);
                    assert!(
                        listed || !accepted,
                        "tile ({tx}, {ty}) packet {k}: kind {} #{idx} accepted, not listed",
                        prim >> KIND_SHIFT
                    );
                    match (listed, accepted) {
                        (true, true) => kept += 1,
                        (true, false) => listed_missed += 1,
                        _ => {}
                    }
                }
            }
        }
    }
    assert!(
        kept > 1000 && listed_missed > 100 && left_out > 100,
        "every case occurs: {kept} accepted, {listed_missed} listed but missed, {left_out} left out"
    );
}

/// The stores come back rearranged: a permutation of the originals per kind, each column
/// moved alike (the order itself: `bin.rs`'s tests; the lists naming the rearranged stores:
/// `kernels_accept_rays_only_in_their_packets_and_beyond_near`).
#[test]
fn stores_are_permuted_column_by_column_alike() {
    let eye = DVec3::new(0.3, 0.2, 1.0);
    let scene = scene(5, eye, DVec3::new(0.0, 0.0, -3.0), 70.0);
    let camera = Camera::new(&scene.camera, 70.0, 83, 57);
    let original = Packed::new(&Prepared::new(&scene, eye));
    let (_, order) = Tiles::new(&scene, &original, &camera);
    let mut packed = original.clone();
    packed.permute(&order);
    let counts = [
        original.spheres.len(),
        original.triangles.len(),
        original.quads.len(),
    ];
    let ids = |p: &Packed| {
        [
            p.spheres.id.clone(),
            p.triangles.id.clone(),
            p.quads.id.clone(),
        ]
    };
    let (before, after) = (ids(&original), ids(&packed));
    for kind in 0..3 {
        let order = order[kind]
            .as_ref()
            .expect("random primitives are out of screen order");
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(
            seen,
            (0..counts[kind] as u32).collect::<Vec<_>>(),
            "kind {kind}"
        );
        for (new, &old) in order.iter().enumerate() {
            assert_eq!(after[kind][new], before[kind][old as usize]);
        }
    }
    let first_triangle = order[1].as_ref().map_or(0, |o| o[0] as usize);
    assert_eq!(
        packed.triangles.get(0),
        original.triangles.get(first_triangle)
    );
}

/// Small triangles already in screen order (a strip across the image, left to right, as a
/// subdivided mesh lists its faces) are kept as they are; the same triangles in a scattered
/// order are rearranged.
#[test]
fn stores_already_in_screen_order_are_kept() {
    let eye = DVec3::ZERO;
    let strip: Vec<Shape> = (0..200)
        .map(|i| {
            let c = DVec3::new(-4.0 + 0.04 * i as f64, 0.0, -5.0);
            Shape::Triangle([
                c,
                c + DVec3::new(0.03, 0.0, 0.0),
                c + DVec3::new(0.0, 0.03, 0.0),
            ])
        })
        .collect();
    // every 37th of 200 (coprime): neighbours in the list lie far apart on screen
    let scattered: Vec<Shape> = (0..200).map(|i| strip[i * 37 % 200]).collect();
    for (shapes, kept) in [(strip, true), (scattered, false)] {
        let scene = Scene {
            camera_at: None,
            source: "strip.sc".into(),
            camera: CameraSpec {
                eye,
                look: DVec3::new(0.0, 0.0, -1.0),
                up: DVec3::Y,
                lens: Some(crate::scene::Lens::Fov(90.0)),
            },
            shapes: shapes.into(),
            warnings: Vec::new(),
        };
        let camera = Camera::new(&scene.camera, 90.0, 640, 64);
        let packed = Packed::new(&Prepared::new(&scene, eye));
        let (_, order) = Tiles::new(&scene, &packed, &camera);
        assert_eq!(
            order[1].is_none(),
            kept,
            "{}",
            if kept { "strip" } else { "scattered" }
        );
    }
}

/// `attach` keeps each entry's packets and stores the value rounded down by less than 2^-14
/// relative (+inf to a finite value above 3.4e38, every value <= 0 to one below -3.4e38), and
/// the packet walk hands each tested entry's value back with the lanes it took: a lane's
/// carried value is that of the primitive that won it.
#[test]
fn attached_values_are_rounded_down_and_follow_the_winner() {
    let eye = DVec3::new(0.3, 0.2, 1.0);
    let scene = scene(4, eye, DVec3::new(0.0, 0.0, -3.0), 60.0);
    let camera = Camera::new(&scene.camera, 60.0, 64, 48);
    let mut packed = Packed::new(&Prepared::new(&scene, eye));
    let (mut tiles, order) = Tiles::new(&scene, &packed, &camera);
    packed.permute(&order);
    let before = tiles.entries.clone();
    // a value per primitive: both infinities, zero, and finite values of many scales, some
    // powers of two (where rounding down crosses an exponent)
    let value = |kind: usize, i: usize| match (kind * 7 + i) % 6 {
        0 => f32::INFINITY,
        1 => f32::NEG_INFINITY,
        2 => 0.0,
        3 => 2f32.powi(i as i32 % 40 - 20),
        _ => (1.0 + i as f32 * 0.123_456_7) * 10f32.powi(i as i32 % 9 - 4),
    };
    let stored = |v: f32, got: f32| match v {
        f32::INFINITY => got > 3.4e38 && got.is_finite(),
        v if v <= 0.0 => got < -3.4e38 && got.is_finite(),
        v => got < v && got >= v * (1.0 - 2f32.powi(-14)),
    };
    tiles.attach(&packed, &camera, 1e-5, value);
    for (e, b) in tiles.entries.iter().zip(&before) {
        assert_eq!(e.packets(), b.packets());
        assert!(stored(f32::INFINITY, b.attached()), "+inf until attached");
        let (kind, i) = e.kind_index();
        let (v, got) = (value(kind as usize, i), e.attached());
        assert!(
            stored(v, got),
            "{v} stored as {got} (packets {:08b})",
            e.packets()
        );
    }
    // each lane's carried value is its winner's, through the packets' own lists
    let tables = camera.tables::<f32>(BLOCK_W as u32, BLOCK_H as u32);
    let ids = packed.ids();
    let (mut lists, mut checked) = (PacketLists::default(), 0);
    for ty in 0..48 / TILE_H {
        for tx in 0..64 / TILE_W {
            tiles.split_tile((tx, ty), &mut lists);
            for k in 0..PACKETS {
                let (x0, y0) = (tx * TILE_W + k % 2 * BLOCK_W, ty * TILE_H + k / 2 * BLOCK_H);
                let d: [f32x8; 3] = std::array::from_fn(|c| {
                    f32x8::new(std::array::from_fn(|l| {
                        tables.dir_x1(x0 + l % BLOCK_W, y0 + l / BLOCK_W)[c]
                    }))
                });
                let mut hit = Hit8::new(f32x8::splat(-1.0).simd_lt(f32x8::ZERO));
                let carried = tiles.trace_packet_x8_carrying(&packed, &lists, k, &d, &mut hit);
                for (l, (&id, &c)) in hit
                    .id
                    .to_array()
                    .iter()
                    .zip(&carried.to_array())
                    .enumerate()
                {
                    if id < 0.0 {
                        assert_eq!(c, f32::INFINITY, "lane {l} without a hit");
                        continue;
                    }
                    let (kind, i) = (0..3)
                        .find_map(|kind| {
                            let i = ids[kind].iter().position(|&v| v == id)?;
                            Some((kind, i))
                        })
                        .expect("the winner is in a store");
                    assert!(
                        stored(value(kind, i), c),
                        "lane {l}: {c} for {}",
                        value(kind, i)
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 1000, "{checked} lanes");
}

/// `attach` marks, per tile, every packet where a pixel's exact ray may meet an entry's
/// primitive beyond the reach `s (1 - 2 error)` of the value `s` stored: checked pixel by pixel with the
/// oracle's f64 kernels along the oracle's rays, for values cutting through each primitive
/// (spheres between their nearest point and their silhouette, polygons at 1.5 to 13 times
/// their plane distance), at three fields of view. The marks must also leave packets out,
/// and the marked ones include hits beyond the reach (the test can tell a mark from none).
#[test]
fn packets_left_unmarked_have_no_exact_hit_beyond_the_reach() {
    use crate::kernel::polygon::polygon_x1;
    use crate::kernel::sphere::sphere_x1;
    use crate::kernel::{Quad, Sphere, Triangle};
    use crate::soa::{Records, SceneRecords};
    const ERROR: f64 = 1e-5;
    for (seed, fov) in [(5, 60.0), (6, 150.0), (7, 20.0)] {
        let eye = DVec3::new(0.3, 0.2, 1.0);
        let scene = scene(seed, eye, DVec3::new(0.0, 0.0, -3.0), fov);
        let (w, h) = (97, 61);
        let camera = Camera::new(&scene.camera, fov, w as u32, h as u32);
        let mut packed = Packed::new(&Prepared::new(&scene, eye));
        let (mut tiles, order) = Tiles::new(&scene, &packed, &camera);
        packed.permute(&order);
        let records = SceneRecords::new(&scene, &packed, eye);
        let frac = |i: usize| [0.3, 0.9, 0.999, 0.999_99][i % 4];
        let value = |kind: usize, i: usize| -> f32 {
            match kind {
                0 => {
                    let k = records.record::<Sphere>(i).expect("a sphere").0;
                    if k.inside {
                        // (every packet would be marked)
                        return f32::INFINITY;
                    }
                    let l = k.oc.iter().map(|v| v * v).sum::<f64>().sqrt();
                    let (near, rim) = (l - k.r2.sqrt(), k.c.max(0.0).sqrt());
                    (near + frac(i) * (rim - near)) as f32
                }
                1 => packed.triangles.p[i] * [1.5, 4.0, 13.0][i % 3],
                _ => packed.quads.p[i] * [1.5, 4.0, 13.0][i % 3],
            }
        };
        tiles.attach(&packed, &camera, ERROR, value);
        let tables = camera.tables::<f64>(1, 1);
        let (mut unmarked, mut marked_beyond) = (0, 0);
        for y in 0..h {
            for x in 0..w {
                let d = tables.dir_x1(x, y);
                let k = y % TILE_H / BLOCK_H * (TILE_W / BLOCK_W) + x % TILE_W / BLOCK_W;
                let t = (y / TILE_H) * tiles.cols + x / TILE_W;
                let range = tiles.start[t] as usize..tiles.start[t + 1] as usize;
                let marked = tiles.carries[t] >> k & 1 == 1;
                for e in &tiles.entries[range] {
                    if e.packets() >> k & 1 == 0 {
                        continue;
                    }
                    let (kind, i) = e.kind_index();
                    let hit = match kind {
                        SPHERE => records
                            .record::<Sphere>(i)
                            .and_then(|(k, _)| sphere_x1(&k, d)),
                        TRIANGLE => records
                            .record::<Triangle>(i)
                            .and_then(|(k, _)| polygon_x1(&k, d)),
                        _ => records
                            .record::<Quad>(i)
                            .and_then(|(k, _)| polygon_x1(&k, d)),
                    };
                    let Some(t64) = hit else { continue };
                    let reach = f64::from(e.attached()) * (1.0 - 2.0 * ERROR);
                    if !marked {
                        assert!(
                            t64 <= reach,
                            "seed {seed}: kind {kind} #{i} at ({x}, {y}): {t64} beyond {reach}, \
                             packet {k} unmarked"
                        );
                        unmarked += 1;
                    } else if t64 > reach {
                        marked_beyond += 1;
                    }
                }
            }
        }
        assert!(
            unmarked > 500,
            "seed {seed}: {unmarked} hits in unmarked packets"
        );
        assert!(
            marked_beyond > 100,
            "seed {seed}: {marked_beyond} hits beyond, marked"
        );
    }
}

/// `winner_in_packet` finds, in a packet's own list, the kind and packed index of the primitive
/// that won a lane, whether sphere or polygon.
#[test]
fn the_winner_of_a_lane_is_found_in_its_packet() {
    let eye = DVec3::new(0.3, 0.2, 1.0);
    let mut found = [0; 3];
    // (seeds whose views show some of every kind: in most, the sphere around the eye and a
    // few spheres and triangles fill the 64x48 view)
    for seed in [1, 2] {
        let scene = scene(seed, eye, DVec3::new(0.0, 0.0, -3.0), 60.0);
        let camera = Camera::new(&scene.camera, 60.0, 64, 48);
        let mut packed = Packed::new(&Prepared::new(&scene, eye));
        let (tiles, order) = Tiles::new(&scene, &packed, &camera);
        packed.permute(&order);
        let tables = camera.tables::<f32>(BLOCK_W as u32, BLOCK_H as u32);
        let mut lists = PacketLists::default();
        for ty in 0..48 / TILE_H {
            for tx in 0..64 / TILE_W {
                tiles.split_tile((tx, ty), &mut lists);
                for k in 0..PACKETS {
                    let (x0, y0) = (tx * TILE_W + k % 2 * BLOCK_W, ty * TILE_H + k / 2 * BLOCK_H);
                    let (d, active) =
                        crate::kernel::packet::block_rays::<BLOCK_W>(&tables, x0, y0, 64, 48);
                    let mut hit = Hit8::new(active);
                    tiles.trace_packet_x8(&packed, &lists, k, &d, &mut hit);
                    for id in hit.id.to_array().into_iter().filter(|&id| id >= 0.0) {
                        let owner = packed
                            .ids()
                            .into_iter()
                            .enumerate()
                            .find_map(|(kind, ids)| {
                                ids.iter().position(|&s| s == id).map(|i| (kind, i))
                            });
                        let (kind, i) = owner.expect("a packed primitive");
                        assert_eq!(
                            tiles.winner_in_packet(&packed, &lists, k, id),
                            Some((kind, i)),
                            "seed {seed}: primitive {id}"
                        );
                        found[kind] += 1;
                    }
                }
            }
        }
    }
    assert!(
        found[0] > 1000 && found[1] > 100 && found[2] > 10,
        "{found:?}"
    );
}

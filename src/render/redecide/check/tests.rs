use super::super::Redecide;
use crate::accel::Accel;
use crate::accel::tiles::{PACKETS, PacketLists};
use crate::accel::{TILE_H, TILE_W};
use crate::camera::Camera;
use crate::kernel::Hit8;
use crate::kernel::packet::{BLOCK_H, BLOCK_W, block_rays};
use crate::render::PacketScene;
use std::path::Path;

/// The packets `Tiles::attach` leaves unmarked walk without carrying: checked against the
/// carrying walk, with the trusted distances auto attaches, on the stress and seed scenes,
/// every unmarked packet has no lane beyond its winner's trusted distance. The marked
/// packets must hold some such lanes (the scenes have suspects to miss), and the unmarked
/// ones some hits.
#[test]
fn packets_left_unmarked_have_no_lane_beyond_its_trusted_distance() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut paths: Vec<_> = std::fs::read_dir(root.join("stress"))
        .expect("scenes/stress")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "sc"))
        .collect();
    paths.extend((1..=7).map(|n| root.join(format!("scene{n}.sc"))));
    paths.sort();
    let (mut unmarked_hits, mut marked_beyond) = (0, 0);
    for path in &paths {
        let scene = crate::scene::load_scene(path).expect("a seed or stress scene");
        let fov = scene.camera.fov_deg().unwrap_or(60.0);
        let (w, h): (usize, usize) = (200, 120);
        let camera = Camera::new(&scene.camera, fov, w as u32, h as u32);
        let mut p = PacketScene::new(&scene, &camera, Accel::Tiles);
        let mut r = Redecide::new(&scene, &camera, &p.packed);
        let tiles = p.tiles.as_mut().expect("tiles");
        r.attach_to(tiles, &p.packed, &camera);
        let tables = camera.tables::<f32>(BLOCK_W as u32, BLOCK_H as u32);
        let mut lists = PacketLists::default();
        for ty in 0..h.div_ceil(TILE_H) {
            for tx in 0..w.div_ceil(TILE_W) {
                tiles.split_tile((tx, ty), &mut lists);
                for k in 0..PACKETS {
                    let (bx, by) = (tx * TILE_W + k % 2 * BLOCK_W, ty * TILE_H + k / 2 * BLOCK_H);
                    if bx >= w || by >= h {
                        continue;
                    }
                    let (d, active) = block_rays::<BLOCK_W>(&tables, bx, by, w, h);
                    let mut hit = Hit8::new(active);
                    let carried =
                        tiles.trace_packet_x8_carrying(&p.packed, &lists, k, &d, &mut hit);
                    let beyond = hit.t.simd_gt(carried).to_bitmask().count_ones();
                    if lists.carries_packet(k) {
                        marked_beyond += beyond;
                    } else {
                        assert_eq!(
                            beyond,
                            0,
                            "{}: tile ({tx}, {ty}), packet {k} unmarked",
                            path.display()
                        );
                        unmarked_hits +=
                            hit.id.simd_ge(wide::f32x8::ZERO).to_bitmask().count_ones();
                    }
                }
            }
        }
    }
    assert!(
        unmarked_hits > 10_000,
        "{unmarked_hits} hits in unmarked tiles"
    );
    assert!(
        marked_beyond > 100,
        "{marked_beyond} lanes beyond, in marked tiles"
    );
}

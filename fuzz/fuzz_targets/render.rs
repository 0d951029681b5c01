//! Parse, then (if the scene is accepted, as `lanecast` itself would: `parse_scene` plus
//! `range::f32_range`) render 16x16 with the packet kernel and the f64 scalar oracle.
//! Asserts: no NaN depth from either kernel, and every id mismatch is excused by
//! `compare` (a tie or within the edge band).
#![no_main]

use lanecast::Camera;
use lanecast::compare::compare;
use lanecast::experimental::render::{Plain, Setup};
use lanecast::experimental::scene::range;
use lanecast::scene::parse_scene;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

const SIZE: u32 = 16;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = parse_scene(text, Path::new("fuzz.sc")) else {
        return;
    };
    // Keep each run fast: the fuzzer's scenes are small anyway.
    if scene.shapes.len() > 64 || range::f32_range(&scene).is_err() {
        return;
    }
    let fov = scene.camera.fov_deg().unwrap_or(60.0);
    let camera = Camera::new(&scene.camera, fov, SIZE, SIZE);
    let n = (SIZE * SIZE) as usize;
    for kernel in [Plain::Packet, Plain::ScalarF64] {
        let frame = Setup::new(kernel, &scene, &camera).render(SIZE as usize, SIZE as usize);
        assert_eq!(frame.ids.len(), n);
        for (i, (&id, &t)) in frame.ids.iter().zip(&frame.depth).enumerate() {
            assert!(!t.is_nan(), "{kernel:?}: NaN depth at pixel {i}");
            assert!(
                id >= -1 && id < scene.shapes.len() as i32,
                "{kernel:?}: id {id}"
            );
            assert_eq!(
                id == -1,
                t == f32::INFINITY,
                "{kernel:?}: pixel {i}: id {id}, t {t}"
            );
        }
    }
    let (report, _) = compare(&scene, &camera);
    assert_eq!(
        report.unexcused, 0,
        "unexcused mismatches: {report:?}\nscene:\n{text}"
    );
});

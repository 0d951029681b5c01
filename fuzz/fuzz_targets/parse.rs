//! The scene parser on arbitrary bytes: valid UTF-8 goes to `parse_scene` directly; anything
//! else goes through a temporary-free path, `String::from_utf8_lossy`, so the parser also sees
//! replacement characters. It must return Ok or Err, never panic, and an accepted scene must
//! satisfy the invariants the renderer relies on.
#![no_main]

use lanecast::scene::{Shape, parse_scene};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(scene) = parse_scene(&text, Path::new("fuzz.sc")) {
        assert_eq!(scene.shapes.len(), scene.shapes.lines().count());
        for s in scene.shapes.iter() {
            match s {
                Shape::Sphere { center, radius } => {
                    assert!(center.is_finite() && radius.is_finite() && radius > 0.0)
                }
                Shape::Triangle(v) => assert!(v.iter().all(|p| p.is_finite())),
                Shape::Quad(v) => assert!(v.iter().all(|p| p.is_finite())),
            }
        }
        let _ = lanecast::experimental::scene::range::f32_range(&scene);
    }
});

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
            let mut numbers = Vec::new();
            s.write_numbers(&mut numbers);
            assert!(numbers.iter().all(|x| x.is_finite()), "{s:?}");
            if let Shape::Sphere { radius, .. } = s {
                assert!(radius > 0.0)
            }
        }
        let _ = lanecast::experimental::scene::range::f32_range(&scene);
    }
});

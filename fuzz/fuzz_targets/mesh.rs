//! The OBJ reader behind `mesh PATH` on arbitrary bytes: Ok or Err, never a panic; every
//! triangle it returns has finite vertices, and the degenerate count never exceeds the total.
#![no_main]

use lanecast::experimental::scene::mesh::parse_obj;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    if let Ok((mesh, degenerate)) = parse_obj(data, Path::new("fuzz.obj"), 1 << 16) {
        assert!(degenerate <= mesh.len());
        assert!((0..mesh.len()).all(|f| mesh.triangle(f).iter().all(|p| p.is_finite())));
    }
});

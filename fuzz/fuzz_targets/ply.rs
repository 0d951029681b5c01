//! The PLY reader behind `mesh PATH.ply` and `-i PATH.ply` (`scene::mesh::parse_ply`) on
//! arbitrary bytes: Ok or Err, never a panic, and no allocation the input cannot back (a header
//! may declare billions of records). An accepted mesh has finite vertices, faces that index
//! them, at most the triangle limit, and no more degenerate triangles than triangles.
#![no_main]

use lanecast::experimental::scene::mesh::parse_ply;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

const MAX_TRIANGLES: usize = 1 << 16;

fuzz_target!(|data: &[u8]| {
    if let Ok((mesh, degenerate)) = parse_ply(data, Path::new("fuzz.ply"), MAX_TRIANGLES) {
        assert!(mesh.len() <= MAX_TRIANGLES);
        assert!(degenerate <= mesh.len());
        assert!(mesh.vertices.iter().all(|v| v.is_finite()));
        let n = mesh.vertices.len();
        assert!(mesh.faces.iter().flatten().all(|&i| (i as usize) < n));
    }
});

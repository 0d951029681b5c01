//! PLY load throughput on a large generated file: scenes/meshes/armadillo.obj (26,002 vertices,
//! 52,000 triangles) repeated COPIES times side by side (default 100: about 99 MB of binary
//! PLY, 5.2 million triangles), written as a binary little-endian, a binary big-endian and an
//! ASCII PLY file (`float` x, y, z; faces `uchar` count, `int` indices, as the Stanford scans
//! are written), and the same mesh as OBJ text for comparison. Run with
//!
//!     cargo run --release --example ply_speed [COPIES]
//!
//! (`RAYON_NUM_THREADS` picks the thread count, printed). Each file is written to a temporary
//! file and loaded with `load_ply` / `load_obj` (read from the page cache, then parsed): MB/s
//! with 1 MB = 1e6 bytes of the file, best of 5; the clock stops when the loader returns.

use lanecast::experimental::scene::mesh::{load_obj, load_ply};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

fn main() {
    let copies: usize = std::env::args()
        .nth(1)
        .map_or(100, |a| a.parse().expect("a whole number of copies"));
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/meshes/armadillo.obj");
    let (mesh, _) = load_obj(&src, usize::MAX).expect("armadillo.obj");
    let (nv, nf) = (mesh.vertices.len(), mesh.faces.len());
    let width = {
        let xs = mesh.vertices.iter().map(|v| v.x);
        xs.clone().fold(f64::NEG_INFINITY, f64::max) - xs.fold(f64::INFINITY, f64::min)
    };
    // copy k moved along x by k widths, its indices by k * nv
    let vertex = |k: usize, i: usize| {
        let v = mesh.vertices[i];
        [(v.x + k as f64 * width) as f32, v.y as f32, v.z as f32]
    };
    let face = |k: usize, f: usize| mesh.faces[f].map(|i| i + (k * nv) as u32);
    let (verts, tris) = (copies * nv, copies * nf);
    println!(
        "threads: {}; {copies} copies of the armadillo: {verts} vertices, {tris} triangles",
        rayon::current_num_threads()
    );
    let dir = std::env::temp_dir();
    let tmp = |ext: &str| dir.join(format!("lanecast-ply-speed-{}.{ext}", std::process::id()));
    for (name, big) in [("binary_little_endian", false), ("binary_big_endian", true)] {
        let mut b = format!(
            "ply\nformat {name} 1.0\ncomment armadillo x{copies}\nelement vertex {verts}\n\
             property float x\nproperty float y\nproperty float z\nelement face {tris}\n\
             property list uchar int vertex_indices\nend_header\n"
        )
        .into_bytes();
        b.reserve(12 * verts + 13 * tris);
        for k in 0..copies {
            for i in 0..nv {
                for c in vertex(k, i) {
                    b.extend(if big {
                        c.to_be_bytes()
                    } else {
                        c.to_le_bytes()
                    });
                }
            }
        }
        for k in 0..copies {
            for f in 0..nf {
                b.push(3);
                for i in face(k, f) {
                    let i = i as i32;
                    b.extend(if big {
                        i.to_be_bytes()
                    } else {
                        i.to_le_bytes()
                    });
                }
            }
        }
        time(&format!("load_ply, {name}:"), &tmp("ply"), &b, tris, |p| {
            load_ply(p, usize::MAX).map(|m| m.0.len())
        });
    }
    let mut ply = format!(
        "ply\nformat ascii 1.0\nelement vertex {verts}\nproperty float x\nproperty float y\n\
         property float z\nelement face {tris}\nproperty list uchar int vertex_indices\n\
         end_header\n"
    );
    let mut obj = String::new();
    for k in 0..copies {
        for i in 0..nv {
            let [x, y, z] = vertex(k, i);
            writeln!(ply, "{x} {y} {z}").unwrap();
            writeln!(obj, "v {x} {y} {z}").unwrap();
        }
    }
    for k in 0..copies {
        for f in 0..nf {
            let [a, b, c] = face(k, f);
            writeln!(ply, "3 {a} {b} {c}").unwrap();
            writeln!(obj, "f {} {} {}", a + 1, b + 1, c + 1).unwrap();
        }
    }
    time("load_ply, ascii:", &tmp("ply"), ply.as_bytes(), tris, |p| {
        load_ply(p, usize::MAX).map(|m| m.0.len())
    });
    time(
        "load_obj, same mesh:",
        &tmp("obj"),
        obj.as_bytes(),
        tris,
        |p| load_obj(p, usize::MAX).map(|m| m.0.len()),
    );
}

/// Writes `bytes` to `path`, loads it 5 times with `load` (which must give `want` triangles),
/// prints the best time and MB/s, and removes the file.
fn time(
    what: &str,
    path: &Path,
    bytes: &[u8],
    want: usize,
    load: impl Fn(&Path) -> lanecast::Result<usize>,
) {
    std::fs::write(path, bytes).unwrap();
    let best = (0..5)
        .map(|_| {
            let t = Instant::now();
            let n = load(path).unwrap_or_else(|e| panic!("{what} {e}"));
            let s = t.elapsed().as_secs_f64();
            assert_eq!(n, want);
            s
        })
        .fold(f64::INFINITY, f64::min);
    let mb = bytes.len() as f64 / 1e6;
    println!(
        "{what:<34} {mb:6.1} MB  {best:.3} s  {:6.0} MB/s",
        mb / best
    );
    let _ = std::fs::remove_file(path);
}

//! Parse throughput (docs/performance.md: "Parsing") on two generated files: a scene of 1e6 spheres, and a
//! Wavefront OBJ grid mesh of 2e6 triangles (1e6 vertices: `v x y z` with 6 decimals, then
//! `f a b c`). Run with
//!
//!     cargo run --release --example parse_speed [SPHERES] [GRID_SIDE]
//!
//! and compare thread counts with `RAYON_NUM_THREADS=1` and `=2` (parsing runs in the current
//! rayon pool, whose size is printed). Each file is written to a temporary file and the parser
//! is timed (`scene::parse`, without the f32 range check that `scene::load_scene` adds):
//! `parse_scene` on the scene text, `load_scene` on the scene file (read + UTF-8 check + parse),
//! `load_obj` on the OBJ file, and `load_scene` on a scene holding the OBJ through a `mesh`
//! line. Prints MB/s (1 MB = 1e6 bytes of the file parsed), best of 5; the clock stops when
//! the loader returns (freeing the result is not timed).

use lanecast::experimental::scene::mesh::load_obj;
use lanecast::experimental::scene::parse::{load_scene, parse_scene};
use lanecast::scene::Scene;
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

/// Seconds of the fastest of 5 runs of `load`, whose result must hold `want` items by `len`.
/// The clock stops when `load` returns: freeing its result is not part of parsing.
fn best<T>(want: usize, load: impl Fn() -> T, len: impl Fn(&T) -> usize) -> f64 {
    (0..5)
        .map(|_| {
            let t = Instant::now();
            let loaded = load();
            let s = t.elapsed().as_secs_f64();
            assert_eq!(len(&loaded), want);
            s
        })
        .fold(f64::INFINITY, f64::min)
}

fn report(what: &str, mb: f64, s: f64) {
    println!("{what:<26} {s:.3} s, {:>5.0} MB/s", mb / s);
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut arg = |default: usize| {
        args.next()
            .map_or(default, |a| a.parse().expect("a whole number"))
    };
    let (n, side) = (arg(1_000_000), arg(1001));
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    println!("threads: {}", rayon::current_num_threads());
    let dir = std::env::temp_dir();
    let tmp = |ext: &str| dir.join(format!("lanecast-parse-speed-{}.{ext}", std::process::id()));

    // a scene of n spheres
    let mut text =
        String::from("# generated: 1e6 spheres\ncamera eye 0 0 50 look 0 0 0 up 0 1 0 fov 60\n");
    for _ in 0..n {
        let (x, y, z, r) = (
            rnd() * 200.0 - 100.0,
            rnd() * 200.0 - 100.0,
            -rnd() * 100.0,
            0.05 + rnd(),
        );
        writeln!(text, "sphere {x:.6} {y:.6} {z:.6} {r:.6}").unwrap();
    }
    let mb = text.len() as f64 / 1e6;
    println!("{n} spheres, {mb:.1} MB of scene text");
    let shapes = |s: &Result<Scene, _>| s.as_ref().unwrap().shapes.len();
    let s = best(n, || parse_scene(&text, Path::new("gen.sc")), shapes);
    report("parse_scene:", mb, s);
    let sc = tmp("sc");
    std::fs::write(&sc, &text).unwrap();
    drop(text);
    let s = best(n, || load_scene(&sc), shapes);
    report("load_scene (page cache):", mb, s);

    // a side x side grid of vertices, two triangles per cell
    let mut obj = String::from("# generated grid\n");
    for i in 0..side {
        for j in 0..side {
            let (x, y) = (i as f64 * 0.2 - 100.0, j as f64 * 0.2 - 100.0);
            let z = rnd() * 0.5 - 10.0;
            writeln!(obj, "v {x:.6} {y:.6} {z:.6}").unwrap();
        }
    }
    for i in 0..side - 1 {
        for j in 0..side - 1 {
            let a = i * side + j + 1;
            let (b, c, d) = (a + 1, a + side, a + side + 1);
            writeln!(obj, "f {a} {b} {d}\nf {a} {d} {c}").unwrap();
        }
    }
    let tris = 2 * (side - 1) * (side - 1);
    let mb = obj.len() as f64 / 1e6;
    println!(
        "{tris} triangles, {} vertices, {mb:.1} MB of OBJ text",
        side * side
    );
    let path = tmp("obj");
    std::fs::write(&path, &obj).unwrap();
    drop(obj);
    let s = best(
        tris,
        || load_obj(&path, usize::MAX),
        |m| m.as_ref().unwrap().0.len(),
    );
    report("load_obj (page cache):", mb, s);
    let name = path.file_name().unwrap().to_string_lossy();
    let mesh_sc = tmp("mesh.sc");
    let scene = format!("camera eye 0 0 50 look 0 0 0 up 0 1 0\nmesh {name}\n");
    std::fs::write(&mesh_sc, scene).unwrap();
    let s = best(tris, || load_scene(&mesh_sc), shapes);
    report("load_scene, mesh line:", mb, s);
    for p in [sc, path, mesh_sc] {
        let _ = std::fs::remove_file(p);
    }
}

//! Parse throughput on a generated scene of 1e6 spheres (README: "Limits"). Run with
//! `cargo run --release --example parse_speed [N]`. The text is generated in memory and
//! written to a temporary file, then timed twice: `parse_scene` on the text, and `load_scene`
//! on the file (read + UTF-8 check + parse). Prints MB/s (1 MB = 1e6 bytes), best of 5.

use lanecast::scene::{load_scene, parse_scene};
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map_or(1_000_000, |a| a.parse().expect("N: a whole number"));
    let mut text =
        String::from("# generated: 1e6 spheres\ncamera eye 0 0 50 look 0 0 0 up 0 1 0 fov 60\n");
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
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

    let best = |f: &dyn Fn() -> usize| {
        (0..5)
            .map(|_| {
                let t = Instant::now();
                assert_eq!(f(), n);
                t.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    };
    let s = best(&|| {
        parse_scene(&text, Path::new("gen.sc"))
            .unwrap()
            .shapes
            .len()
    });
    println!("parse_scene: {:.3} s, {:.0} MB/s", s, mb / s);

    let path = std::env::temp_dir().join(format!("lanecast-parse-speed-{}.sc", std::process::id()));
    std::fs::write(&path, &text).unwrap();
    let s = best(&|| load_scene(&path).unwrap().shapes.len());
    let _ = std::fs::remove_file(&path);
    println!(
        "load_scene:  {:.3} s, {:.0} MB/s (file in page cache)",
        s,
        mb / s
    );
}

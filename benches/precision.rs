//! `--precision auto` against `--precision f32`: render-phase time of the packet kernel with
//! automatic acceleration on one thread, the two renderers alternated frame by frame in one
//! process (so the machine's noise falls on both alike), best and median of `ROUNDS` frames
//! each. Prints a Markdown table: the ratio f32 time / auto time (auto's speed as a fraction of
//! f32's; target at least 0.9) and the fraction of pixels auto re-decided in f64.
//!
//! Scenes: the seven seed scenes at 1920x1080, and the scaling scenes of
//! `../shared/anchors/gen_scenes.py` at 1280x720 where `target/scale/` holds them
//! (`python3 scripts/vs_embree.py` or `scripts/auto_speed.py` writes them).
//!
//! `cargo bench --bench precision`; `LANECAST_BENCH_QUICK=1` for 9 rounds instead of 31;
//! `cargo bench --bench precision -- scene7` for the cases whose name contains `scene7`.

use lanecast::camera::Camera;
use lanecast::render::{Method, Options, Renderer};
use lanecast::scene::{Scene, load_scene};
use std::path::{Path, PathBuf};
use std::time::Instant;

fn cases() -> Vec<(String, PathBuf, u32, u32)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut v: Vec<_> = (1..=7)
        .map(|n| {
            let p = root.join(format!("scenes/scene{n}.sc"));
            (format!("scene{n}"), p, 1920, 1080)
        })
        .collect();
    for kind in ["spheres", "triangles"] {
        for n in [16, 256, 4096, 65536] {
            let p = root.join(format!("target/scale/{kind}_{n}.sc"));
            if p.is_file() {
                v.push((format!("{kind}_{n}"), p, 1280, 720));
            }
        }
    }
    v
}

fn renderer<'s>(scene: &'s Scene, camera: &Camera, method: Method) -> Renderer<'s> {
    let options = Options {
        method,
        ..Options::default()
    };
    Renderer::new(scene, camera, &options).expect("f32 and auto take every scene")
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let rounds = if std::env::var_os("LANECAST_BENCH_QUICK").is_some() {
        9
    } else {
        31
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool");
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    println!("# --precision auto against f32: {cpu}, one thread, {rounds} alternated frames each");
    println!();
    println!(
        "| scene | size | f32 best ms | auto best ms | f32 median ms | auto median ms | auto speed / f32 (medians) | re-decided |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    let mut worst = f64::INFINITY;
    // cargo passes `--bench`; any other argument filters the cases by name
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let wanted = |name: &str| filters.is_empty() || filters.iter().any(|f| name.contains(f));
    for (name, path, w, h) in cases().into_iter().filter(|c| wanted(&c.0)) {
        let scene = match load_scene(&path) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        let camera = Camera::for_scene(&scene, w, h, None).expect("bench sizes are valid");
        let (f32r, auto) = (
            renderer(&scene, &camera, Method::Default),
            renderer(&scene, &camera, Method::Auto),
        );
        let (mut tf, mut ta, mut redone) = (Vec::new(), Vec::new(), 0);
        pool.install(|| {
            for _ in 0..rounds {
                let t = Instant::now();
                std::hint::black_box(f32r.render());
                tf.push(t.elapsed().as_secs_f64() * 1e3);
                let t = Instant::now();
                let (frame, marks) = auto.render_marking(None);
                ta.push(t.elapsed().as_secs_f64() * 1e3);
                std::hint::black_box(frame);
                redone = marks.len();
            }
        });
        let best = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let (bf, ba) = (best(&tf), best(&ta));
        let (mf, ma) = (median(&mut tf), median(&mut ta));
        worst = worst.min(mf / ma);
        println!(
            "| {name} | {w}x{h} | {bf:.2} | {ba:.2} | {mf:.2} | {ma:.2} | {:.3} | {:.4}% |",
            mf / ma,
            redone as f64 * 100.0 / (w * h) as f64
        );
    }
    println!();
    println!(
        "Lowest auto speed / f32: {worst:.3} (target at least 0.9: {}).",
        if worst >= 0.9 { "met" } else { "MISSED" }
    );
}

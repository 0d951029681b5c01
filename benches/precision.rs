//! `--precision auto` against `--precision f32`: render-phase time of the packet kernel with
//! automatic acceleration on one thread, the two renderers alternated frame by frame in one
//! process (so the machine's noise falls on both alike), best and median of `ROUNDS` frames
//! each. Prints a Markdown table: the ratio f32 time / auto time (auto's speed as a fraction of
//! f32's) and the fraction of pixels auto re-decided in f64, then the lowest paired ratio.
//!
//! Two ratios, from the same frames: the ratio of the two medians, and the median of the
//! rounds' own ratios (each round times one frame of each, back to back, which of the two
//! goes first alternating from round to round). A burst of load on this shared machine that
//! lasts a few frames falls on both frames of a round, so it moves the second far less than
//! the first. The last line reads the paired one; `LANECAST_BENCH_NULL=1` times f32
//! against itself, the noise floor of both (docs/precision.md, "Speed"). Each renderer is built
//! twice, first in one half of the rounds and second in the other.
//!
//! Scenes: the seven seed scenes at 1920x1080, and the scaling scenes of
//! `../shared/anchors/gen_scenes.py` at 1280x720 where `target/scale/` holds them
//! (`python3 scripts/vs_embree.py` writes them).
//!
//! `cargo bench --bench precision`; `LANECAST_BENCH_QUICK=1` for 10 rounds instead of 32;
//! `cargo bench --bench precision -- scene7` for the cases whose name contains `scene7`.

use lanecast::Camera;
use lanecast::scene::{Scene, load_scene};
use lanecast::{Options, Precision, Renderer};
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

fn renderer<'s>(scene: &'s Scene, camera: &Camera, precision: Precision) -> Renderer<'s> {
    let options = Options {
        precision,
        ..Options::default()
    };
    Renderer::new(scene, camera, &options).expect("f32 and auto take every scene")
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let rounds: usize = if std::env::var_os("LANECAST_BENCH_QUICK").is_some() {
        10
    } else {
        32
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
    let null = std::env::var_os("LANECAST_BENCH_NULL").is_some();
    let other = if null { "f32 (null)" } else { "auto" };
    println!(
        "# --precision {other} against f32: {cpu}, one thread, {rounds} alternated frames each"
    );
    println!();
    println!(
        "| scene | size | f32 best ms | {other} best ms | f32 median ms | {other} median ms | ratio of medians | median of paired ratios | re-decided |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
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
        // Half the rounds with f32's renderer built first, half with auto's: on
        // triangles_65536 the renderer built second ran 3-5% faster in the null test, which
        // favoured whichever was built second.
        let (mut tf, mut ta, mut redone) = (Vec::new(), Vec::new(), 0);
        let second = if null {
            Precision::F32
        } else {
            Precision::Auto
        };
        for half in 0..2 {
            let (f32r, auto) = if half == 0 {
                let f = renderer(&scene, &camera, Precision::F32);
                (f, renderer(&scene, &camera, second))
            } else {
                let a = renderer(&scene, &camera, second);
                (renderer(&scene, &camera, Precision::F32), a)
            };
            pool.install(|| {
                for round in 0..rounds.div_ceil(2) {
                    // each frame is freed after its time is taken, for both alike
                    let mut f32_frame = || {
                        let t = Instant::now();
                        let (frame, marks) = f32r.render_marking(None);
                        tf.push(t.elapsed().as_secs_f64() * 1e3);
                        std::hint::black_box((frame, marks));
                    };
                    let mut auto_frame = || {
                        let t = Instant::now();
                        let (frame, marks) = auto.render_marking(None);
                        ta.push(t.elapsed().as_secs_f64() * 1e3);
                        redone = marks.len();
                        std::hint::black_box((frame, marks));
                    };
                    if round % 2 == 0 {
                        f32_frame();
                        auto_frame();
                    } else {
                        auto_frame();
                        f32_frame();
                    }
                }
            });
        }
        let best = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let (bf, ba) = (best(&tf), best(&ta));
        let mut paired: Vec<f64> = tf.iter().zip(&ta).map(|(f, a)| f / a).collect();
        let paired = median(&mut paired);
        let (mf, ma) = (median(&mut tf), median(&mut ta));
        worst = worst.min(paired);
        println!(
            "| {name} | {w}x{h} | {bf:.2} | {ba:.2} | {mf:.2} | {ma:.2} | {:.3} | {paired:.3} | {:.4}% |",
            mf / ma,
            redone as f64 * 100.0 / (w * h) as f64
        );
    }
    println!();
    println!("Lowest {other} speed / f32 (median of paired ratios): {worst:.3}.");
}

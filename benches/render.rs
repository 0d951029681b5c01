//! Render-phase throughput of the seed scenes: packet vs scalar f32 vs scalar f64, on one thread
//! and on all threads, at 640x480 and 1920x1080. One criterion group per scene and size, so every
//! ratio in docs/performance.md's packet-against-scalar table comes from one run (`scripts/bench_table.py` prints it).
//!
//! `LANECAST_BENCH_QUICK=1` keeps one size (640x480) and fewer samples, for a fast look.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use lanecast::Accel;
use lanecast::Camera;
use lanecast::DEFAULT_FOV;
use lanecast::experimental::render::{PacketScene, Plain, Setup, render_packet_blocks};
use lanecast::scene::load_scene;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

/// `packet`: the default renderer (automatic acceleration: a BVH here); `packet_none`: the same
/// packet kernel testing every primitive, the like-for-like partner of the scalar kernels,
/// which test every primitive too.
const KERNELS: [(&str, Plain, Accel); 4] = [
    ("packet", Plain::Packet, Accel::Auto),
    ("packet_none", Plain::Packet, Accel::None),
    ("scalar_f32", Plain::ScalarF32, Accel::None),
    ("scalar_f64", Plain::ScalarF64, Accel::None),
];

fn seed_scenes(c: &mut Criterion) {
    let quick = std::env::var_os("LANECAST_BENCH_QUICK").is_some();
    let sizes: &[(u32, u32)] = if quick {
        &[(640, 480)]
    } else {
        &[(640, 480), (1920, 1080)]
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let pools: Vec<(usize, rayon::ThreadPool)> = [1, cores]
        .iter()
        .map(|&n| {
            (
                n,
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .unwrap(),
            )
        })
        .collect();
    for n in 1..=7 {
        let path = format!("{}/scenes/scene{n}.sc", env!("CARGO_MANIFEST_DIR"));
        let scene = load_scene(Path::new(&path)).expect("seed scene parses");
        for &(w, h) in sizes {
            let camera = Camera::new(
                &scene.camera,
                scene.camera.fov_deg().unwrap_or(DEFAULT_FOV),
                w,
                h,
            );
            let mut g = c.benchmark_group(format!("scene{n}/{w}x{h}"));
            g.throughput(Throughput::Elements(w as u64 * h as u64));
            g.sample_size(10);
            g.warm_up_time(Duration::from_millis(if quick { 200 } else { 500 }));
            g.measurement_time(Duration::from_secs(if quick { 1 } else { 2 }));
            for (name, kernel, accel) in KERNELS {
                let setup = Setup::with_accel(kernel, accel, &scene, &camera);
                for (threads, pool) in &pools {
                    let id = BenchmarkId::new(name, format!("t{threads}"));
                    g.bench_function(id, |b| {
                        b.iter(|| pool.install(|| black_box(setup.render(w as usize, h as usize))))
                    });
                }
            }
            g.finish();
        }
    }
}

/// Packet block shape: 4x2 against 8x1 pixels per packet, one thread, at 1920x1080.
fn block_shape(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (w, h) = (1920, 1080);
    for n in [2, 4, 6] {
        let path = format!("{}/scenes/scene{n}.sc", env!("CARGO_MANIFEST_DIR"));
        let scene = load_scene(Path::new(&path)).expect("seed scene parses");
        let camera = Camera::new(
            &scene.camera,
            scene.camera.fov_deg().unwrap_or(DEFAULT_FOV),
            w,
            h,
        );
        let packed = PacketScene::new(&scene, &camera, Accel::None);
        let tables = camera.tables::<f32>(8, 2);
        let mut g = c.benchmark_group(format!("block_shape/scene{n}"));
        g.throughput(Throughput::Elements(w as u64 * h as u64));
        g.sample_size(10);
        g.measurement_time(Duration::from_secs(2));
        let (w, h) = (w as usize, h as usize);
        g.bench_function("4x2", |b| {
            b.iter(|| {
                pool.install(|| black_box(render_packet_blocks::<4>(&packed, &tables, w, h, None)))
            })
        });
        g.bench_function("8x1", |b| {
            b.iter(|| {
                pool.install(|| black_box(render_packet_blocks::<8>(&packed, &tables, w, h, None)))
            })
        });
        g.finish();
    }
}

// No plots: criterion's plotters backend needs system fonts, which a clean machine lacks; the
// numbers (and scripts/bench_table.py) need only the JSON estimates.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = seed_scenes, block_shape
}
criterion_main!(benches);

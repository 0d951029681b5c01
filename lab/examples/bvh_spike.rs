//! The world-space BVH spike on a scan: build once, then every view of a views file through
//! each traversal variant, and optionally the first views held to the f64 oracle.
//!
//! Usage: cargo run --release -p lanecast-lab --example bvh_spike -- SCENE.sc --views FILE
//!        [--size WxH] [--threads T] [--variant packets|frustum|both] [--rounds R] [--check N]
//!
//! Prints `key=value` lines: the build (ms, ns a triangle on the pool's threads, bytes a
//! triangle), then per variant the median ms a view (rays, traversal, frame; over every view
//! of every round), and what a view did on average. `--check N`: the first N views compared
//! with the f64 oracle (`lanecast::compare::compare_frame`: mismatches in ppm as ties, edge
//! band and unexcused, and the largest relative depth error).

use lanecast::Camera;
use lanecast::compare::compare_frame;
use lanecast::scene::cameras::load_views;
use lanecast_lab::bvh_spike::{Bvh, Variant, render};
use std::path::PathBuf;
use std::time::Instant;

struct Args {
    scene: PathBuf,
    views: PathBuf,
    size: (u32, u32),
    threads: usize,
    variants: Vec<Variant>,
    rounds: usize,
    check: usize,
}

fn args() -> Result<Args, String> {
    let mut it = std::env::args().skip(1);
    let mut a = Args {
        scene: PathBuf::new(),
        views: PathBuf::new(),
        size: (1920, 1080),
        threads: 2,
        variants: vec![Variant::Packets, Variant::Frustum],
        rounds: 1,
        check: 0,
    };
    let bad = |flag: &str, v: &str| format!("{flag} {v}: not understood");
    while let Some(arg) = it.next() {
        let mut val = || it.next().ok_or(format!("{arg}: needs a value"));
        match arg.as_str() {
            "--views" => a.views = val()?.into(),
            "--size" => {
                let v = val()?;
                let (w, h) = v.split_once('x').ok_or(bad("--size", &v))?;
                a.size = (
                    w.parse().map_err(|_| bad("--size", &v))?,
                    h.parse().map_err(|_| bad("--size", &v))?,
                );
            }
            "--threads" => {
                let v = val()?;
                a.threads = v.parse().map_err(|_| bad("--threads", &v))?;
            }
            "--rounds" => {
                let v = val()?;
                a.rounds = v.parse().map_err(|_| bad("--rounds", &v))?;
            }
            "--check" => {
                let v = val()?;
                a.check = v.parse().map_err(|_| bad("--check", &v))?;
            }
            "--variant" => {
                let v = val()?;
                a.variants = match v.as_str() {
                    "packets" => vec![Variant::Packets],
                    "frustum" => vec![Variant::Frustum],
                    "both" => vec![Variant::Packets, Variant::Frustum],
                    _ => return Err(bad("--variant", &v)),
                };
            }
            s if !s.starts_with('-') && a.scene.as_os_str().is_empty() => a.scene = s.into(),
            s => return Err(format!("{s}: unknown argument")),
        }
    }
    if a.scene.as_os_str().is_empty() || a.views.as_os_str().is_empty() {
        return Err(
            "usage: bvh_spike SCENE.sc --views FILE [--size WxH] [--threads T] \
                    [--variant packets|frustum|both] [--rounds R] [--check N]"
                .into(),
        );
    }
    Ok(a)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    if let Err(e) = run() {
        eprintln!("bvh_spike: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let a = args()?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads)
        .build()
        .map_err(|e| e.to_string())?;
    let scene = lanecast::load_scene(&a.scene).map_err(|e| e.to_string())?;
    let views = load_views(&a.views).map_err(|e| e.to_string())?;
    let cameras = views
        .iter()
        .map(|v| Camera::look_at(&v.camera, a.size.0, a.size.1))
        .collect::<lanecast::Result<Vec<_>>>()
        .map_err(|e| e.to_string())?;
    pool.install(|| {
        let t0 = Instant::now();
        let bvh = Bvh::build(&scene)?;
        let build = t0.elapsed().as_secs_f64();
        let n = scene.shapes.len();
        let (leaves, depth) = bvh.shape();
        println!(
            "build_ms={:.1} ns_per_tri={:.1} bytes_per_tri={:.1} triangles={n} nodes={} \
             leaves={leaves} depth={depth} threads={}",
            build * 1e3,
            build * 1e9 / n as f64,
            bvh.bytes() as f64 / n as f64,
            bvh.nodes.len(),
            a.threads
        );
        for &variant in &a.variants {
            let mut times = Vec::new();
            let mut sum = lanecast_lab::bvh_spike::traverse::Counts::default();
            for _ in 0..a.rounds {
                for cam in &cameras {
                    let t0 = Instant::now();
                    let (frame, counts) = render(&bvh, cam, variant);
                    times.push(t0.elapsed().as_secs_f64());
                    std::hint::black_box(&frame);
                    sum.tiles += counts.tiles;
                    sum.nodes += counts.nodes;
                    sum.leaves += counts.leaves;
                    sum.setups += counts.setups;
                    sum.tests += counts.tests;
                }
            }
            let per = (a.rounds * cameras.len()) as f64;
            println!(
                "variant={} view_median_ms={:.2} nodes_per_view={:.0} leaves_per_view={:.0} \
                 setups_per_view={:.0} tests8_per_view={:.0} tiles={}",
                variant.name(),
                median(times) * 1e3,
                sum.nodes as f64 / per,
                sum.leaves as f64 / per,
                sum.setups as f64 / per,
                sum.tests as f64 / per,
                sum.tiles as f64 / per
            );
        }
        for (k, cam) in cameras.iter().take(a.check).enumerate() {
            for &variant in &a.variants {
                let (frame, _) = render(&bvh, cam, variant);
                let (r, _) = compare_frame(&scene, cam, &frame);
                let ppm = |c: usize| c as f64 * 1e6 / r.pixels as f64;
                println!(
                    "check view={k} variant={} mismatch_ppm={:.1} ties_ppm={:.1} \
                     edges_ppm={:.1} unexcused_ppm={:.1} depth_rel_max={:.2e} depth_rel_p99={:.2e}",
                    variant.name(),
                    ppm(r.mismatches),
                    ppm(r.ties),
                    ppm(r.edges),
                    ppm(r.unexcused),
                    r.depth_rel_max,
                    r.depth_rel_p99
                );
            }
        }
        Ok(())
    })
}

//! The world engine over an orbit: prepare once, then every view timed, and the first view
//! (or every view with CHECK=all) held to the f64 oracle (`compare::compare_frame`).
//!
//!     RAYON_NUM_THREADS=2 cargo run --release --example world_views -- SCENE WxH VIEWS [auto|f32|f64]
use lanecast::scene::cameras::orbit;
use lanecast::world::{Precision, Scratch, World};
use lanecast::{Camera, load_scene};
use std::sync::Arc;
use std::time::Instant;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let (w, h) = a[2]
        .split_once('x')
        .map(|(w, h)| (w.parse().unwrap(), h.parse().unwrap()))
        .unwrap();
    let n: usize = a[3].parse().unwrap();
    let precision = match a.get(4).map(String::as_str) {
        Some("f32") => Precision::F32,
        Some("f64") => Precision::F64,
        _ => Precision::Auto,
    };
    let t = Instant::now();
    let scene = Arc::new(load_scene(std::path::Path::new(&a[1])).unwrap());
    let load = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let world = World::new(&scene);
    let prep = t.elapsed().as_secs_f64() * 1e3;
    println!(
        "load {load:.1} ms, prepare {prep:.1} ms, {} prims, {} MB prepared",
        scene.shapes.len(),
        world.bytes() >> 20
    );
    let mut scratch = Scratch::default();
    let mut times = Vec::new();
    let check = std::env::var("CHECK").unwrap_or_default();
    for (i, spec) in orbit(&scene.camera, n).iter().enumerate() {
        let cam = Camera::look_at(spec, w, h).unwrap();
        let t = Instant::now();
        let frame = world.render_with(&cam, precision, &mut scratch);
        times.push(t.elapsed().as_secs_f64() * 1e3);
        if (i == 0 && check != "none") || check == "all" {
            let (r, _) = lanecast::compare::compare_frame(&scene, &cam, &frame);
            println!(
                "view {i}: mismatches {} (ties {}, edge band {}, unexcused {}), depth rel max {:.2e}",
                r.mismatches, r.ties, r.edges, r.unexcused, r.depth_rel_max
            );
        }
    }
    let total: f64 = times.iter().sum();
    times.sort_by(f64::total_cmp);
    println!(
        "views {n}: median {:.1} ms, total {:.1} ms",
        times[times.len() / 2],
        total
    );
}

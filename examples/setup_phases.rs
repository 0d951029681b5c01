//! Where a view's time goes in a many-view run: for each camera of an orbit about the scene's
//! camera (`scene::cameras::orbit`, as `--orbit N`), the best of `REPEAT` timings of each stage
//! of the per-view work, run alone, in the current rayon pool (`RAYON_NUM_THREADS`):
//!
//! - `check`: the f32 range check from the view's eye, primitive by primitive
//!   (`range::f32_range_from`, what a one-view run does);
//! - `check clusters`: the same check as many views do it (`Views::check`), settling clusters
//!   of triangles at a time with bounds built once (`scene::range_clusters`; the build's time
//!   and the share of clusters settled are printed too);
//! - `pack`: the eye-relative f32 stores (`Packed::from_scene`);
//! - `setup f32`, `setup auto`: the whole setup, `Renderer::new`, with `--precision f32` (the
//!   stores, then every footprint, the tiles' lists and the screen order: `setup f32 - pack`
//!   is the tiles' part) and `auto` (its extra: each primitive's trusted distances and the
//!   tiles' marks);
//! - `render`: `Renderer::render` of the auto renderer.
//!
//! Usage, printing the median over the views of each stage, ms:
//!
//!     RAYON_NUM_THREADS=2 cargo run --release --example setup_phases -- SCENE WxH VIEWS [REPEAT]
use lanecast::experimental::scene::range::f32_range_from;
use lanecast::experimental::scene::range_clusters::RangeClusters;
use lanecast::experimental::soa::Packed;
use lanecast::scene::cameras::orbit;
use lanecast::{Camera, Options, Precision, Renderer, load_scene};
use std::time::Instant;

fn best<T>(repeat: usize, mut f: impl FnMut() -> T) -> f64 {
    let mut t = f64::INFINITY;
    for _ in 0..repeat {
        let s = Instant::now();
        let r = f();
        t = t.min(s.elapsed().as_secs_f64());
        drop(r);
    }
    t * 1e3
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: setup_phases SCENE WxH VIEWS [REPEAT]";
    let [scene, size, views, rest @ ..] = args.as_slice() else {
        return Err(usage.into());
    };
    let (w, h) = size.split_once('x').ok_or(usage)?;
    let (w, h): (u32, u32) = (w.parse()?, h.parse()?);
    let views: usize = views.parse()?;
    let repeat: usize = rest.first().map_or(Ok(3), |r| r.parse())?;
    let scene = load_scene(std::path::Path::new(scene))?;
    let options = |precision| Options {
        precision,
        ..Options::default()
    };
    let names = [
        "check",
        "check clusters",
        "pack",
        "setup f32",
        "setup auto",
        "render",
    ];
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    let clock = Instant::now();
    let clusters = RangeClusters::new(&scene);
    let build = clock.elapsed().as_secs_f64() * 1e3;
    let mut settled = (0, 0);
    for spec in orbit(&scene.camera, views) {
        let camera = Camera::look_at(&spec, w, h)?;
        let eye = camera.eye;
        times[0].push(best(repeat, || f32_range_from(&scene, eye)));
        times[1].push(best(repeat, || clusters.check(&scene, eye)));
        let (s, n) = clusters.settled(eye);
        settled = (settled.0 + s, settled.1 + n);
        times[2].push(best(repeat, || Packed::from_scene(&scene, eye)));
        let f32_ = options(Precision::F32);
        times[3].push(best(repeat, || Renderer::new(&scene, &camera, &f32_)));
        let auto = options(Precision::Auto);
        times[4].push(best(repeat, || Renderer::new(&scene, &camera, &auto)));
        let r = Renderer::new(&scene, &camera, &auto)?;
        times[5].push(best(repeat, || r.render()));
    }
    println!(
        "{} primitives, {w}x{h}, {views} views, RAYON_NUM_THREADS={}; median over the views \
         of the best of {repeat}, ms:",
        scene.shapes.len(),
        std::env::var("RAYON_NUM_THREADS").unwrap_or_else(|_| "(all cores)".into())
    );
    for (name, t) in names.iter().zip(times) {
        println!("  {name:<14} {:8.1}", median(t));
    }
    println!(
        "  clusters built once in {build:.1} ms; {:.1}% of the views' clusters settled",
        100.0 * settled.0 as f64 / settled.1.max(1) as f64
    );
    Ok(())
}

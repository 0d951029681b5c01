//! Renders one scene's frame a given number of times with the packet kernel, automatic
//! acceleration and one thread, in `--precision f32` or `auto`: the workload that
//! `scripts/icount.py` counts instructions of under valgrind (frames 1 and N, so that the
//! difference is N - 1 frames without the setup). Run with
//!
//!     cargo run --release --example frames -- SCENE f32|auto FRAMES [WIDTHxHEIGHT]
//!
//! It prints the wall time per frame (noisy on a shared machine; the instruction counts are
//! not), the number of pixels `auto` re-decided in the last frame, and what auto did on the
//! tile path (`Renderer::auto_work`): the packets that carried the trusted distance and the
//! hits measured.

use lanecast::{Camera, load_scene};
use lanecast::{Options, Precision, Renderer};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: frames SCENE f32|auto FRAMES [WIDTHxHEIGHT]";
    let [scene, precision, frames, rest @ ..] = args.as_slice() else {
        return Err(usage.into());
    };
    let precision = match precision.as_str() {
        "f32" => Precision::F32,
        "auto" => Precision::Auto,
        _ => return Err(usage.into()),
    };
    let frames: usize = frames.parse().map_err(|_| usage)?;
    let (w, h) = match rest.first() {
        Some(size) => {
            let (w, h) = size.split_once('x').ok_or(usage)?;
            (w.parse()?, h.parse()?)
        }
        None => (1280, 720),
    };
    let scene = load_scene(std::path::Path::new(scene))?;
    let camera = Camera::for_scene(&scene, w, h, None)?;
    let options = Options {
        precision,
        ..Options::default()
    };
    let renderer = Renderer::new(&scene, &camera, &options)?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let (ms, redone) = pool.install(|| {
        let t = Instant::now();
        let mut redone = 0;
        for _ in 0..frames {
            redone = renderer.render_marking(None).1.len();
        }
        (
            t.elapsed().as_secs_f64() * 1e3 / frames.max(1) as f64,
            redone,
        )
    });
    println!(
        "{}: {ms:.3} ms per frame, {redone} pixels re-decided",
        precision.name()
    );
    if let Some(w) = renderer.auto_work() {
        println!(
            "auto, last frame: {} of {} packets carried the trusted distance ({:.1}%), {} hits measured",
            w.carrying,
            w.packets,
            100.0 * w.carrying as f64 / w.packets.max(1) as f64,
            w.measured
        );
    }
    Ok(())
}

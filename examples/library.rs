//! lanecast as a library, without the command line or threads: load a scene, render it, write
//! a PNG and its ids (ids.npy beside the PNG).
//! `cargo run --release --no-default-features --example library -- [SCENE] [OUT.png]`
use lanecast::{Camera, ColorMode, Options, Renderer, Variation};
use std::path::PathBuf;

fn main() -> lanecast::Result<()> {
    let mut args = std::env::args().skip(1).map(PathBuf::from);
    let scene = lanecast::load_scene(&args.next().unwrap_or("scenes/scene1.sc".into()))?;
    let out = args.next().unwrap_or("out.png".into());
    let camera = Camera::for_scene(&scene, 640, 480, None)?; // the scene's fov, else 60 degrees
    let frame = Renderer::new(&scene, &camera, &Options::default())?.render();
    let (mode, variation) = (ColorMode::Random, Variation::Linear); // or -cm shade's look
    frame.write_image(&out, (&scene, &camera), mode, variation, 0)?; // .png or .bmp
    frame.write_ids(&out.with_file_name("ids.npy")) // (height, width) little-endian i32
}

//! The render command, phase by phase: check the outputs, parse, setup, render, shade, write.

use super::load_view;
use crate::camera::Camera;
use crate::cli::RenderSettings;
use crate::error::{Error, Result};
use crate::frame::Frame;
use crate::limits::{BYTES_PER_PIXEL, MAX_PIXELS};
use crate::output::{self, OutputKind, OutputSet};
use crate::progress;
use crate::render::{Options, Renderer};
use crate::scene::Scene;
use crate::stats::{Stats, scene_name, secs};
use std::path::Path;
use std::time::Instant;

/// The outputs the render command writes: (flag, path, kind), the image first.
fn outputs(s: &RenderSettings) -> Vec<(&'static str, &Path, OutputKind)> {
    let mut outs = Vec::new();
    outs.extend(s.image_file().map(|p| ("--output", p, OutputKind::Image)));
    outs.extend(s.ids.as_deref().map(|p| ("--ids", p, OutputKind::Npy)));
    outs.extend(s.depth.as_deref().map(|p| ("--depth", p, OutputKind::Npy)));
    outs.extend(
        s.zdepth
            .as_deref()
            .map(|p| ("--zdepth", p, OutputKind::Npy)),
    );
    outs.extend(
        s.normals
            .as_deref()
            .map(|p| ("--normals", p, OutputKind::Npy)),
    );
    outs.extend(s.stats.as_deref().map(|p| ("--stats", p, OutputKind::Json)));
    outs
}

/// The key of an output in the `--stats` record.
pub(super) fn stats_key(flag: &str) -> &'static str {
    match flag {
        "--output" => "image",
        "--ids" => "ids",
        "--depth" => "depth",
        "--zdepth" => "zdepth",
        "--normals" => "normals",
        _ => "stats",
    }
}

/// Checks the memory a render of `width` x `height` needs against `limits::MAX_PIXELS`.
pub(super) fn check_memory(width: u32, height: u32) -> Result<()> {
    let pixels = width as u64 * height as u64;
    if pixels > MAX_PIXELS {
        return Err(Error::usage(format!(
            "--size {width}x{height}: needs about {} MiB; at most {MAX_PIXELS} pixels per image",
            (pixels * BYTES_PER_PIXEL) >> 20
        )));
    }
    Ok(())
}

/// The record of a render run as the settings give it, before anything has run: version,
/// command line, scene, size, kernel, seed and `outputs` (what, path).
pub(super) fn run_stats(s: &RenderSettings, outputs: Vec<(&'static str, String)>) -> Stats {
    Stats {
        version: env!("CARGO_PKG_VERSION"),
        command: std::env::args_os()
            .map(|a| a.to_string_lossy().into_owned())
            .collect(),
        scene: scene_name(&s.view.input),
        width: s.view.width as usize,
        height: s.view.height as usize,
        kernel: s.kernel.name(),
        seed: s.seed,
        outputs,
        ..Stats::default()
    }
}

/// The frame shaded as `s` asks (`-cm`, `-cv`, `--seed`: [`Frame::rgb`], which lights each
/// hit by its normal in `shade` mode), from the scene and camera it was rendered with.
pub(super) fn shade_frame(
    s: &RenderSettings,
    frame: &Frame<f32>,
    scene: &Scene,
    camera: &Camera,
) -> Vec<u8> {
    frame.rgb(scene, camera, s.color_mode, s.variation, s.seed)
}

/// Writes a frame's outputs that `s` asks for into the temporary files of `set`: the image
/// (`rgb`, unless it goes to standard output), ids, depths, z-depths and normals (the last
/// two from the scene and camera the frame was rendered with: `Frame::z_depth`,
/// `Frame::normals`). The targets change only when the set commits.
pub(super) fn write_frame(
    set: &mut OutputSet,
    s: &RenderSettings,
    (frame, scene, camera): (&Frame<f32>, &Scene, &Camera),
    rgb: &[u8],
) -> Result<()> {
    let (w, h) = (s.view.width as usize, s.view.height as usize);
    if s.image_file().is_some() {
        set.write_image("--output", s.view.width, s.view.height, rgb)?;
    }
    if s.ids.is_some() {
        set.write_npy_i32("--ids", w, h, &frame.ids)?;
    }
    if s.depth.is_some() {
        set.write_npy_f32("--depth", w, h, &frame.depth)?;
    }
    if s.zdepth.is_some() {
        set.write_npy_f32("--zdepth", w, h, &frame.z_depth(camera))?;
    }
    if s.normals.is_some() {
        set.write_npy_f32x3("--normals", w, h, &frame.normals(scene, camera))?;
    }
    Ok(())
}

/// Writes an image to standard output (`-o -`); `Ok(false)` when the reader has closed the
/// pipe (`-o - | head -c 8`): it wants no more, and as with ripgrep that is a quiet end, not an
/// error.
pub(super) fn encode_to_stdout(
    format: output::ImageFormat,
    width: u32,
    height: u32,
    rgb: &[u8],
) -> Result<bool> {
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let written = output::encode_image(&mut out, format, width, height, rgb)
        .and_then(|()| std::io::Write::flush(&mut out));
    match written {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(false),
        other => other
            .map(|()| true)
            .map_err(|e| Error::io("-", "write the image to standard output", e)),
    }
}

/// Runs the render command for one view (many views: `many_views::views_command`). Every output is
/// checked and its temporary file created before the scene is read; the outputs are renamed
/// into place together at the end (`OutputSet`).
pub(crate) fn render_command(s: &RenderSettings) -> Result<()> {
    // Ctrl-C / SIGTERM remove pending temporary files, exit 130.
    output::install_interrupt_cleanup();
    check_memory(s.view.width, s.view.height)?;
    let mut set = OutputSet::create(&outputs(s), &[("the input scene", &s.view.input)])?;
    let outputs = set
        .paths()
        .map(|(f, p)| (stats_key(f), p.display().to_string()));
    let mut stats = run_stats(s, outputs.collect());
    let mut clock = Instant::now();
    let lap = |name, stats: &mut Stats, clock: &mut Instant| {
        stats.phases.push((name, secs(clock.elapsed())));
        *clock = Instant::now();
    };

    let (scene, camera) = load_view(&s.view, &set)?;
    stats.primitives = scene.counts();
    let lens = (s.view.fov.map(crate::scene::Lens::Fov))
        .or(scene.camera.lens)
        .unwrap_or(crate::scene::Lens::Fov(crate::camera::DEFAULT_FOV));
    stats.poses.push(crate::stats::ViewRecord {
        spec: crate::scene::CameraSpec {
            lens: Some(lens),
            ..scene.camera
        },
        camera,
        outputs: (stats.outputs.iter())
            .filter(|(what, _)| *what != "stats")
            .cloned()
            .collect(),
        rendered: None,
        skipped: false,
    });
    lap("parse", &mut stats, &mut clock);

    let options = Options {
        precision: s.view.precision,
        accel: s.view.accel,
        kernel: s.kernel.kernel(),
    };
    // The renderer borrows the scene: `--precision auto` re-decides hits from its shapes.
    let renderer = Renderer::new(&scene, &camera, &options)?;
    stats.accel = renderer.accel().name();
    // Every kernel and precision renders on the pool.
    stats.threads = rayon::current_num_threads();
    stats.precision = s.view.precision.name();
    lap("setup", &mut stats, &mut clock);

    let mut frame = None;
    for _ in 0..s.repeat {
        // the last frame's buffers are handed back for the next to fill: freed, the allocator
        // returned them to the system at some sizes, and each repeat faulted them in again
        if let Some(f) = frame.take() {
            renderer.recycle(f);
        }
        let start = Instant::now();
        let (f, redone) = progress::with_progress(renderer.work_units(), |done| {
            renderer.render_marking(Some(done))
        });
        if renderer.redecides() {
            stats.redecided = Some(redone.len());
        }
        frame = Some(f);
        stats.renders.push(secs(start.elapsed()));
    }
    let frame = frame.expect("--repeat is at least 1");
    stats.phases.push(("render", stats.render_best()));
    clock = Instant::now();

    let rgb = shade_frame(s, &frame, &scene, &camera);
    lap("shade", &mut stats, &mut clock);

    // Into the temporary files; the targets change only in `commit`, all together.
    write_frame(&mut set, s, (&frame, &scene, &camera), &rgb)?;
    lap("write", &mut stats, &mut clock);

    if s.stats.is_some() {
        set.write_bytes("--stats", stats.json().as_bytes())?;
    }
    set.commit()?;
    if let Some(format) = s.stdout_format {
        // `-o -`: after the files, so a failed file leaves nothing half-sent either
        encode_to_stdout(format, s.view.width, s.view.height, &rgb)?;
    }
    if s.time {
        super::say::write(
            super::say::Stream::Stderr,
            "write the -time report",
            &stats.text(),
        )?;
    }
    Ok(())
}

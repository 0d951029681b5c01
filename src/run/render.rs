//! The render command, phase by phase: parse, setup, render, shade, write.

use super::load_view;
use crate::cli::{KernelArg, RenderSettings};
use crate::error::{Error, Result};
use crate::limits::{BYTES_PER_PIXEL, MAX_PIXELS};
use crate::output;
use crate::progress;
use crate::render::{Kernel, Method, Options, Renderer};
use crate::shade::shade;
use crate::stats::{Stats, scene_name, secs};
use std::path::PathBuf;
use std::time::Instant;

impl From<KernelArg> for Kernel {
    fn from(k: KernelArg) -> Kernel {
        match k {
            KernelArg::Simd => Kernel::Packet,
            KernelArg::Scalar => Kernel::ScalarF64,
            KernelArg::ScalarF32 => Kernel::ScalarF32,
        }
    }
}

/// Refuses, before any work, outputs that would overwrite the input or each other, and image
/// paths whose extension names no supported format.
fn check_outputs(s: &RenderSettings) -> Result<()> {
    output::image_format(&s.output)?;
    let mut outs: Vec<(&str, &PathBuf)> = vec![("--output", &s.output)];
    outs.extend(s.ids.as_ref().map(|p| ("--ids", p)));
    outs.extend(s.depth.as_ref().map(|p| ("--depth", p)));
    outs.extend(s.stats.as_ref().map(|p| ("--stats", p)));
    for (i, (flag, path)) in outs.iter().enumerate() {
        if output::same_file(path, &s.view.input) {
            return Err(Error::usage(format!(
                "{flag} {}: is the input scene; refusing to overwrite it",
                path.display()
            )));
        }
        for (other, opath) in &outs[..i] {
            if output::same_file(path, opath) {
                return Err(Error::usage(format!(
                    "{flag} {} and {other} name the same file",
                    path.display()
                )));
            }
        }
    }
    Ok(())
}

/// Checks the memory a render of `width` x `height` needs against `limits::MAX_PIXELS`.
fn check_memory(width: u32, height: u32) -> Result<()> {
    let pixels = width as u64 * height as u64;
    if pixels > MAX_PIXELS {
        return Err(Error::usage(format!(
            "--size {width}x{height}: needs about {} MiB; at most {MAX_PIXELS} pixels per image",
            (pixels * BYTES_PER_PIXEL) >> 20
        )));
    }
    Ok(())
}

/// Runs the render command.
pub(crate) fn render_command(s: &RenderSettings) -> Result<()> {
    // hardening (issue 5): Ctrl-C / SIGTERM remove pending temporary files, exit 130.
    output::install_interrupt_cleanup();
    check_outputs(s)?;
    check_memory(s.view.width, s.view.height)?;
    let mut stats = Stats {
        scene: scene_name(&s.view.input),
        width: s.view.width as usize,
        height: s.view.height as usize,
        kernel: s.kernel.name(),
        ..Stats::default()
    };
    let mut clock = Instant::now();
    let lap = |name, stats: &mut Stats, clock: &mut Instant| {
        stats.phases.push((name, secs(clock.elapsed())));
        *clock = Instant::now();
    };

    let (scene, camera) = load_view(&s.view)?;
    stats.primitives = scene.counts();
    lap("parse", &mut stats, &mut clock);

    let method = s.view.method;
    if method != Method::Default && s.kernel != KernelArg::Simd {
        return Err(Error::usage(format!(
            "--method {}: methods apply to the simd kernel (--kernel {} is the oracle's own)",
            method.name(),
            s.kernel.name()
        )));
    }
    let options = Options {
        kernel: s.kernel.into(),
        accel: s.view.accel,
        method,
    };
    let renderer = Renderer::new(&scene, &camera, &options)?;
    // The renderer holds what it needs; the parsed shapes are not needed past setup.
    drop(scene);
    stats.accel = renderer.accel().name();
    // The default method renders on the pool; the other methods on one thread.
    stats.threads = if renderer.is_parallel() {
        rayon::current_num_threads()
    } else {
        1
    };
    stats.method = method.name();
    lap("setup", &mut stats, &mut clock);

    let (w, h) = (s.view.width as usize, s.view.height as usize);
    let mut frame = None;
    for _ in 0..s.repeat {
        let start = Instant::now();
        frame = Some(progress::with_progress(renderer.work_units(), |done| {
            renderer.render_counting(Some(done))
        }));
        stats.renders.push(secs(start.elapsed()));
    }
    let frame = frame.expect("--repeat is at least 1");
    stats.phases.push(("render", stats.render_best()));
    clock = Instant::now();

    let rgb = shade(
        &frame.ids,
        &frame.depth,
        w,
        s.color_mode,
        s.variation,
        s.seed,
    );
    lap("shade", &mut stats, &mut clock);

    output::write_image(&s.output, s.view.width, s.view.height, &rgb)?;
    if let Some(p) = &s.ids {
        output::write_npy_i32(p, w, h, &frame.ids)?;
    }
    if let Some(p) = &s.depth {
        output::write_npy_f32(p, w, h, &frame.depth)?;
    }
    lap("write", &mut stats, &mut clock);

    if s.time {
        eprint!("{}", stats.text());
    }
    if let Some(p) = &s.stats {
        output::write_atomic(p, stats.json().as_bytes())?;
    }
    Ok(())
}

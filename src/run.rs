//! The render command, phase by phase: parse, setup, render, shade, write.

use crate::camera::Camera;
use crate::cli::{KernelArg, RenderSettings, ViewSettings};
use crate::error::{Error, Result};
use crate::limits::{BYTES_PER_PIXEL, MAX_PIXELS};
use crate::output;
use crate::render::{Kernel, Setup};
use crate::scene::{Scene, load_scene};
use crate::shade::shade;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Field of view when neither the command line nor the scene gives one.
pub const DEFAULT_FOV: f64 = 60.0;

impl From<KernelArg> for Kernel {
    fn from(k: KernelArg) -> Kernel {
        match k {
            KernelArg::Simd => Kernel::Packet,
            KernelArg::Scalar => Kernel::ScalarF64,
            KernelArg::ScalarF32 => Kernel::ScalarF32,
        }
    }
}

/// Loads the scene and makes its camera for the requested view.
pub fn load_view(v: &ViewSettings) -> Result<(Scene, Camera)> {
    let scene = load_scene(&v.input)?;
    // hardening (issue 5): reject primitives the f32 kernels cannot represent from this eye.
    crate::scene::validate::f32_range(&scene)?;
    let fov = v.fov.or(scene.camera.fov_deg).unwrap_or(DEFAULT_FOV);
    let camera = Camera::new(&scene.camera, fov, v.width, v.height);
    Ok((scene, camera))
}

/// A rayon pool of the requested size (all cores when `None`).
pub fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| Error::Failed(format!("cannot start worker threads: {e}")))
}

/// Refuses, before any work, outputs that would overwrite the input or each other, and image
/// paths whose extension names no supported format.
fn check_outputs(s: &RenderSettings) -> Result<()> {
    output::image_format(&s.output)?;
    let mut outs: Vec<(&str, &PathBuf)> = vec![("--output", &s.output)];
    outs.extend(s.ids.as_ref().map(|p| ("--ids", p)));
    outs.extend(s.depth.as_ref().map(|p| ("--depth", p)));
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
pub fn render_command(s: &RenderSettings) -> Result<()> {
    // hardening (issue 5): Ctrl-C / SIGTERM remove pending temporary files, exit 130.
    output::install_interrupt_cleanup();
    check_outputs(s)?;
    check_memory(s.view.width, s.view.height)?;
    let mut phases: Vec<(&str, Duration)> = Vec::new();
    let mut clock = Instant::now();
    let mut lap = |name, phases: &mut Vec<(&str, Duration)>| {
        phases.push((name, clock.elapsed()));
        clock = Instant::now();
    };

    let (scene, camera) = load_view(&s.view)?;
    lap("parse", &mut phases);

    let pool = pool(s.view.threads)?;
    let setup = Setup::with_accel(s.kernel.into(), s.view.accel, &scene, &camera);
    lap("setup", &mut phases);

    let (w, h) = (s.view.width as usize, s.view.height as usize);
    let frame = pool.install(|| setup.render(w, h));
    lap("render", &mut phases);

    let rgb = pool.install(|| {
        shade(
            &frame.ids,
            &frame.depth,
            w,
            s.color_mode,
            s.variation,
            s.seed,
        )
    });
    lap("shade", &mut phases);

    output::write_image(&s.output, s.view.width, s.view.height, &rgb)?;
    if let Some(p) = &s.ids {
        output::write_npy_i32(p, w, h, &frame.ids)?;
    }
    if let Some(p) = &s.depth {
        output::write_npy_f32(p, w, h, &frame.depth)?;
    }
    lap("write", &mut phases);

    if s.time {
        eprint!(
            "{}",
            time_report(
                &s.view.input,
                w * h,
                pool.current_num_threads(),
                setup.accel().name(),
                &phases
            )
        );
    }
    Ok(())
}

/// The `-time` report: one line per phase, then the primary ray rate of the render phase.
fn time_report(
    input: &Path,
    pixels: usize,
    threads: usize,
    accel: &str,
    phases: &[(&str, Duration)],
) -> String {
    let mut out = format!(
        "lanecast: {} ({pixels} primary rays, {threads} threads, accel {accel})\n",
        input.display()
    );
    for (name, d) in phases {
        out += &format!("  {name:<7} {:>10.3} ms\n", d.as_secs_f64() * 1e3);
    }
    let total: Duration = phases.iter().map(|p| p.1).sum();
    out += &format!("  {:<7} {:>10.3} ms\n", "total", total.as_secs_f64() * 1e3);
    if let Some((_, render)) = phases.iter().find(|p| p.0 == "render") {
        let rate = pixels as f64 / render.as_secs_f64().max(1e-9);
        out += &format!("  {:.2} Mrays/s (render phase)\n", rate / 1e6);
    }
    out
}

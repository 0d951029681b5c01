//! The commands behind the command line, phase by phase, and the one place that prints what the
//! library returns (warnings, reports). `render.rs` is the render command, `compare.rs` the
//! `compare` subcommand; both go through the library API (`lanecast::Renderer`, `compare`).

mod compare;
mod many_views;
mod record;
mod render;
mod say;

use crate::camera::Camera;
use crate::cli::{Command, ViewSettings};
use crate::error::{Error, Result};
use crate::output::OutputSet;
use crate::scene::cameras::num;
use crate::scene::{Lens, Scene, load_scene_meshes};
use std::path::PathBuf;

/// Runs a parsed command line.
pub(crate) fn command(cmd: Command) -> Result<()> {
    match cmd {
        Command::Info(text) => {
            // `lanecast --help | head -1`: a closed pipe is a quiet end
            say::write(say::Stream::Stdout, "write the help", &text)?;
            Ok(())
        }
        // Every phase (parse, setup, render, shade) runs on the pool `--threads` asks for.
        Command::Render(s) => pool(s.view.threads)?.install(|| match &s.views {
            Some(source) => many_views::views_command(&s, source),
            None => render::render_command(&s),
        }),
        Command::Compare(s) => pool(s.view.threads)?.install(|| compare::compare_command(&s)),
    }
}

/// Loads the scene (printing its warnings) and makes its camera for the requested view,
/// refusing any output of `set` that names one of the mesh files the scene read (the scene
/// file itself is checked by `OutputSet::create`, before parsing).
fn load_view(v: &ViewSettings, set: &OutputSet) -> Result<(Scene, Camera)> {
    let (scene, meshes) = load_scene_meshes(&v.input)?;
    let reads: Vec<(String, PathBuf)> = meshes
        .into_iter()
        .map(|m| (format!("the mesh {} the scene reads", m.display()), m))
        .collect();
    set.check_reads(&reads)?;
    for w in &scene.warnings {
        say::warn(w)?;
    }
    let mut scene = scene;
    frame_mesh_alone(&mut scene, v, false);
    v.camera.apply(&mut scene.camera)?;
    if v.camera.eye.is_some() {
        // the range rule is relative to the eye (kernels work eye-relative): check it again,
        // a refusal the flag's (the scene passed from its own eye)
        crate::scene::range::f32_range(&scene)
            .map_err(|e| v.camera.blame(format_args!("seen from this eye, {e}")))?;
    }
    if let (Some(typed), Some(Lens::Pinhole(k))) = (&v.fov_typed, scene.camera.lens) {
        let at = scene
            .camera_at
            .map_or(String::new(), |(l, c)| format!(":{l}:{c}"));
        say::note(&format!(
            "{typed} replaces the scene's intrinsics ({}{at}: K {} {} {} {}): a centred camera \
             with square pixels",
            scene.source.display(),
            num(k.fx),
            num(k.fy),
            num(k.cx),
            num(k.cy)
        ))?;
    }
    let camera = Camera::for_scene(&scene, v.width, v.height, v.fov)?;
    Ok((scene, camera))
}

/// A mesh rendered alone (`-i mesh.obj`, `.ply`) stays whole in the image it is rendered
/// to. The loaded scene's camera is every front's default (`scene::parse::framing_camera`:
/// a 5% margin at 640x480, whole up to 16:9, at 60 degrees), kept as it is for those
/// images, so that the command line's frames are the browser's and Python's. A wider image, a
/// narrower `-fov`, or a turntable (`turntable`, `--orbit`) would cross its border: there the
/// camera moves back along its view, no more than the 5% margin needs (README "Camera").
/// `--eye`, `--look`, `--up` apply after.
fn frame_mesh_alone(scene: &mut Scene, v: &ViewSettings, turntable: bool) {
    use crate::scene::parse::{FRAMING_MARGIN, FRAMING_WIDEST, Framing, framing_camera_for};
    if crate::scene::mesh::MeshFormat::of(&v.input).is_none() {
        return;
    }
    let fov_deg = v.fov.unwrap_or(crate::camera::DEFAULT_FOV);
    let (ww, wh) = FRAMING_WIDEST;
    let wider = v.width as u64 * wh as u64 > v.height as u64 * ww as u64;
    if !(wider || turntable || fov_deg < crate::camera::DEFAULT_FOV) {
        return;
    }
    let framing = Framing {
        width: v.width,
        height: v.height,
        fov_deg,
        margin: FRAMING_MARGIN,
        turntable,
    };
    let camera =
        (scene.shapes.meshes().next()).and_then(|(m, _)| framing_camera_for(m, &[framing]));
    // both look at the box's centre along -z: the farther eye keeps the mesh inside in both
    if let Some(camera) = camera
        && camera.look == scene.camera.look
        && camera.eye.z > scene.camera.eye.z
    {
        scene.camera = camera;
    }
}

/// A rayon pool of the requested size (all cores when `None`).
fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| Error::Failed(format!("cannot start worker threads: {e}")))
}

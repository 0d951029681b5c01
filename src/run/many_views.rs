//! The render command with many views (`--views FILE`, `--orbit N`): the scene is loaded once,
//! then each view is prepared for its camera, rendered, shaded and written as its own output
//! set, all-or-nothing (README "Many views").
//!
//! Before anything renders: the views file is parsed and every camera checked (FILE:LINE:COL
//! errors), every view's output names are made from their patterns and checked against each
//! other and against every file the run reads, and every view's eye is checked against the f32
//! range rule (`scene::range::f32_range`, relative to that eye). A bad view stops the run
//! with nothing written.

use super::record;
use super::render::{
    check_memory, encode_to_stdout, run_stats, shade_frame, stats_key, write_frame,
};
use crate::cli::{RenderSettings, ViewSource};
use crate::error::{Error, Result};
use crate::output::{self, Expected, OutputKind, OutputSet, Pattern};
use crate::progress;
use crate::render::{Options, Views};
use crate::scene::cameras::{ViewLine, load_views, orbit};
use crate::scene::{CameraSpec, Lens, Scene, load_scene_meshes};
use crate::stats::{Stats, ViewRecord, ViewTime, ViewTimes, secs};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::time::Instant;

/// One numbered output: its flag, pattern (and its text as given) and kind.
struct Numbered {
    flag: &'static str,
    pattern: Pattern,
    /// The pattern as typed (`frames/view_%05d.png`): what `--stats` records as the run's
    /// output.
    typed: PathBuf,
    kind: OutputKind,
}

/// The numbered outputs of `s`: the image (unless it goes to standard output or none is
/// asked for), ids, depth, z-depth, normals.
fn numbered(s: &RenderSettings) -> Result<Vec<Numbered>> {
    let mut outs = Vec::new();
    let mut add = |flag, path: &Path, kind| -> Result<()> {
        let pattern = Pattern::parse(flag, path)?;
        outs.push(Numbered {
            flag,
            pattern,
            typed: path.to_path_buf(),
            kind,
        });
        Ok(())
    };
    if let Some(p) = s.image_file() {
        add("--output", p, OutputKind::Image)?;
    }
    if let Some(p) = &s.ids {
        add("--ids", p, OutputKind::Npy)?;
    }
    if let Some(p) = &s.depth {
        add("--depth", p, OutputKind::Npy)?;
    }
    if let Some(p) = &s.zdepth {
        add("--zdepth", p, OutputKind::Npy)?;
    }
    if let Some(p) = &s.normals {
        add("--normals", p, OutputKind::Npy)?;
    }
    Ok(outs)
}

/// Every view's output names, checked: extensions, no two names alike (across views and
/// outputs, by the file they would be), none naming a file the run reads (`reads`).
fn names(
    outs: &[Numbered],
    views: usize,
    reads: &[(String, PathBuf)],
) -> Result<Vec<Vec<PathBuf>>> {
    for o in outs {
        o.kind.check_extension(o.flag, &o.pattern.name(0))?;
    }
    let mut seen: HashMap<PathBuf, (usize, &str)> = HashMap::new();
    let mut all = Vec::with_capacity(views);
    for v in 0..views {
        let mut paths = Vec::with_capacity(outs.len());
        for o in outs {
            let path = o.pattern.name(v);
            output::check_not_read(
                o.flag,
                &path,
                reads.iter().map(|(w, p)| (w.as_str(), p.as_path())),
            )?;
            if paths.is_empty() {
                // the view's record, beside its first output
                output::check_not_read(
                    o.flag,
                    &record::path_for(&path),
                    reads.iter().map(|(w, p)| (w.as_str(), p.as_path())),
                )?;
            }
            if let Some((other, flag)) = seen.insert(output::identity(&path), (v, o.flag)) {
                return Err(Error::usage(format!(
                    "{} {}: view {v} and view {other} ({flag}) would both write {}; the \
                     patterns must give every view's outputs distinct names",
                    o.flag,
                    o.pattern_text(),
                    path.display()
                )));
            }
            paths.push(path);
        }
        all.push(paths);
    }
    Ok(all)
}

impl Numbered {
    /// The pattern as given, for messages (view 0's name shows what it makes).
    fn pattern_text(&self) -> String {
        format!("(view 0: {})", self.pattern.name(0).display())
    }
}

/// The cameras of the run, with the lens each uses, one rule for every view: `-fov` when
/// given (replacing every lens), else a views file's line's own (a field of view or
/// intrinsics), else the scene's, else the default; an orbit's from the scene's camera (with
/// `--eye`, `--look`, `--up` applied). Where `-fov` replaces intrinsics, a note on stderr
/// says so, once. Each camera comes with its spec, the lens filled in (the default field of
/// view where none is given): what `--stats` records and `--save-views` writes.
fn cameras(
    s: &RenderSettings,
    source: &ViewSource,
    lines: &[ViewLine],
    scene: &Scene,
) -> Result<Vec<(CameraSpec, crate::Camera)>> {
    let (w, h) = (s.view.width, s.view.height);
    let fallback = scene.camera.lens;
    let lens = s.view.fov.map(Lens::Fov).or(fallback);
    let lens = lens.unwrap_or(Lens::Fov(crate::camera::DEFAULT_FOV));
    if let Some(typed) = &s.view.fov_typed {
        note_replaced_intrinsics(typed, source, lines, scene)?;
    }
    match source {
        ViewSource::File(file) => lines
            .iter()
            .map(|l| {
                let own = s.view.fov.map(Lens::Fov).or(l.camera.lens);
                let spec = CameraSpec {
                    lens: Some(own.unwrap_or(lens)),
                    ..l.camera
                };
                crate::Camera::look_at(&spec, w, h)
                    .map(|c| (spec, c))
                    .map_err(|e| Error::input(file, l.line, l.col, e.to_string()))
            })
            .collect(),
        ViewSource::Orbit(n) => {
            let spec = CameraSpec {
                lens: Some(lens),
                ..scene.camera
            };
            orbit(&spec, *n)
                .into_iter()
                .enumerate()
                .map(|(k, c)| {
                    crate::Camera::look_at(&c, w, h)
                        .map(|cam| (c, cam))
                        .map_err(|e| Error::usage(format!("--orbit {n}: view {k}: {e}")))
                })
                .collect()
        }
    }
}

/// The note that `-fov` (`typed`) replaces the intrinsics some views would have used: a
/// views line's own `K`, or the scene's for a line with no lens and for an orbit.
fn note_replaced_intrinsics(
    typed: &str,
    source: &ViewSource,
    lines: &[ViewLine],
    scene: &Scene,
) -> Result<()> {
    let scene_k = matches!(scene.camera.lens, Some(Lens::Pinhole(_)));
    let at = |line: usize| format!("{}:{line}", scene.source.display());
    let replaced: Vec<usize> = match source {
        ViewSource::File(_) => (lines.iter())
            .filter(|l| match l.camera.lens {
                Some(Lens::Pinhole(_)) => true,
                None => scene_k,
                Some(Lens::Fov(_)) => false,
            })
            .map(|l| l.line)
            .collect(),
        ViewSource::Orbit(_) => Vec::new(),
    };
    let what = match source {
        ViewSource::File(f) if !replaced.is_empty() => format!(
            "the intrinsics of {} (first: {}:{})",
            crate::words::count(replaced.len(), "view", "views"),
            f.display(),
            replaced[0]
        ),
        ViewSource::Orbit(_) if scene_k => format!(
            "the scene's intrinsics ({})",
            at(scene.camera_at.map_or(0, |a| a.0))
        ),
        _ => return Ok(()),
    };
    super::say::note(&format!(
        "{typed} replaces {what}: a centred camera with square pixels"
    ))
}

/// The `--save-views` file's name checked: its extension (`.txt`), against every file the run
/// reads and writes, and, when it exists, its content: only a views file (one that
/// `load_views` reads without error) is replaced, so a mesh, an image or notes are never
/// written over.
fn check_save_views(
    p: &Path,
    reads: &[(&str, &Path)],
    names: &[Vec<PathBuf>],
    stats: Option<&Path>,
) -> Result<()> {
    OutputKind::Views.check_extension("--save-views", p)?;
    output::check_not_read("--save-views", p, reads.iter().copied())?;
    let id = output::identity(p);
    let clash = (names.iter().flatten().map(PathBuf::as_path))
        .chain(stats)
        .find(|n| output::identity(n) == id);
    if let Some(clash) = clash {
        return Err(Error::usage(format!(
            "--save-views {}: the run also writes {} by that name",
            p.display(),
            clash.display()
        )));
    }
    match std::fs::metadata(p) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(Error::io(
            p,
            "read the --save-views file it would replace",
            e,
        )),
        // a folder or another non-file: `OutputSet::create` refuses it
        Ok(m) if !m.is_file() => Ok(()),
        Ok(_) => match load_views(p) {
            Ok(_) => Ok(()),
            Err(e @ Error::Io { .. }) => Err(e),
            Err(e) => Err(Error::usage(format!(
                "--save-views {}: exists and is not a views file ({e}); refusing to replace \
                 it: remove it, or name another file",
                p.display()
            ))),
        },
    }
}

/// Runs the render command over many views.
pub(crate) fn views_command(s: &RenderSettings, source: &ViewSource) -> Result<()> {
    output::install_interrupt_cleanup();
    check_memory(s.view.width, s.view.height)?;
    let start = Instant::now();
    let lines = match source {
        ViewSource::File(f) => load_views(f)?,
        ViewSource::Orbit(_) => Vec::new(),
    };
    let count = match source {
        ViewSource::File(_) => lines.len(),
        ViewSource::Orbit(n) => *n,
    };
    let outs = numbered(s)?;
    let mut reads = vec![("the input scene".to_string(), s.view.input.clone())];
    if let ViewSource::File(f) = source {
        reads.push(("the views file".to_string(), f.clone()));
    }
    if let Some(p) = &s.stats {
        OutputKind::Json.check_extension("--stats", p)?;
    }
    names(&outs, count, &reads)?;

    let (scene, meshes) = load_scene_meshes(&s.view.input)?;
    for m in meshes {
        reads.push((format!("the mesh {} the scene reads", m.display()), m));
    }
    let names = names(&outs, count, &reads)?;
    let stats_reads: Vec<(&str, &Path)> = reads.iter().map(|(w, p)| (w.as_str(), &**p)).collect();
    if let Some(p) = &s.stats {
        // the record's own name against the reads and every view's outputs
        output::check_not_read("--stats", p, stats_reads.iter().copied())?;
        let id = output::identity(p);
        if let Some(clash) = names.iter().flatten().find(|n| output::identity(n) == id) {
            return Err(Error::usage(format!(
                "--stats {}: a view's output {} has the same name",
                p.display(),
                clash.display()
            )));
        }
    }
    if let Some(p) = &s.save_views {
        check_save_views(p, &stats_reads, &names, s.stats.as_deref())?;
    }
    for w in &scene.warnings {
        super::say::warn(w)?;
    }
    let mut scene = scene;
    super::frame_mesh_alone(&mut scene, &s.view, matches!(source, ViewSource::Orbit(_)));
    s.view.camera.apply(&mut scene.camera)?;
    let cameras = cameras(s, source, &lines, &scene)?;

    let options = Options {
        precision: s.view.precision,
        accel: s.view.accel,
        kernel: s.kernel.kernel(),
    };
    let views = Views::new(&scene, &options)?;
    let loaded = secs(start.elapsed());
    // every view's eye against the f32 range rule, before anything renders
    let clock = Instant::now();
    for (k, (_, camera)) in cameras.iter().enumerate() {
        views
            .check(camera)
            .map_err(|e| in_view(source, &lines, k, e))?;
    }
    let checked = secs(clock.elapsed());
    let outputs = outs
        .iter()
        .map(|o| (stats_key(o.flag), o.typed.display().to_string()))
        .chain(s.stats.iter().map(|p| ("stats", p.display().to_string())));
    let mut stats = Stats {
        primitives: scene.counts(),
        precision: s.view.precision.name(),
        ..run_stats(s, outputs.collect())
    };
    if let (Some(p), ViewSource::Orbit(n)) = (&s.save_views, source) {
        let specs: Vec<CameraSpec> = cameras.iter().map(|c| c.0).collect();
        let header = format!(
            "the {n} views of lanecast --orbit {n} ({}x{}): `--views` this file renders them \
             again",
            s.view.width, s.view.height
        );
        let text = crate::scene::cameras::write_views(&specs, &header);
        let mut set = OutputSet::create(&[("--save-views", p, OutputKind::Views)], &stats_reads)?;
        set.write_bytes("--save-views", text.as_bytes())?;
        set.commit()?;
    }
    let keys: Vec<&'static str> = outs.iter().map(|o| stats_key(o.flag)).collect();
    stats.poses = (cameras.iter().zip(&names))
        .map(|(&(spec, camera), paths)| ViewRecord {
            spec,
            camera,
            outputs: (keys.iter().copied())
                .zip(paths.iter().map(|p| p.display().to_string()))
                .collect(),
            rendered: None,
            skipped: false,
        })
        .collect();
    stats.phases.push(("load", loaded));
    stats.phases.push(("check", checked));
    let loop_start = Instant::now();
    let mut times = ViewTimes::default();
    let flags: Vec<(&'static str, OutputKind)> = outs.iter().map(|o| (o.flag, o.kind)).collect();
    // what every view's record holds but its camera and files
    let run_lines = record::run_lines(s, &scene, s.image_file().is_some());
    // the progress line (a terminal only, past a second) counts views
    progress::with_progress(cameras.len(), |done| -> Result<()> {
        for (k, (spec, camera)) in cameras.iter().enumerate() {
            let paths = &names[k];
            let files: Vec<(&'static str, &Path)> = (flags.iter().zip(paths))
                .map(|(&(flag, _), p)| (flag, p.as_path()))
                .collect();
            // beside the first file (none with -o - alone, which --skip-existing refuses)
            let record = paths.first().map(|p| record::path_for(p));
            if s.skip_existing
                && let Some(r) = &record
                && complete(&flags, paths, s)
                && record::matches(r, &run_lines, spec, &files)
            {
                stats.poses[k].skipped = true;
                times.skipped += 1;
                done.fetch_add(1, Ordering::Relaxed);
                continue;
            }
            let mut outputs: Vec<(&'static str, &Path, OutputKind)> = flags
                .iter()
                .zip(paths)
                .map(|(&(flag, kind), p)| (flag, p.as_path(), kind))
                .collect();
            outputs.extend(record.as_deref().map(record::output));
            let mut set = OutputSet::create(&outputs, &[])?;
            let view = views.render_marking(camera)?;
            let mut time = ViewTime {
                setup_s: view.setup_s,
                render_s: view.render_s,
                left_out: view.left_out,
                renders: view.renders,
                ..ViewTime::default()
            };
            let frame = view.frame;
            if view.redecides {
                *stats.redecided.get_or_insert(0) += view.redecided.len();
            }
            stats.accel = view.accel.name();
            stats.threads = crate::par::current_num_threads();
            stats.renders.push(time.render_s);
            let clock = Instant::now();
            // no image asked for (buffers only): nothing to shade
            let rgb = match s.writes_image() {
                true => shade_frame(s, &frame, &scene, camera),
                false => Vec::new(),
            };
            write_frame(&mut set, s, (&frame, &scene, camera), &rgb)?;
            if record.is_some() {
                record::write(&mut set, &run_lines, spec, &files)?;
            }
            set.commit()?;
            views.recycle(frame);
            let sent = match s.stdout_format {
                Some(format) => encode_to_stdout(format, s.view.width, s.view.height, &rgb)?,
                None => true,
            };
            time.output_s = secs(clock.elapsed());
            stats.poses[k].rendered = Some(times.each.len());
            times.each.push(time);
            done.fetch_add(1, Ordering::Relaxed);
            if !sent {
                break; // the reader closed the pipe: it wants no more views
            }
        }
        Ok(())
    })?;
    stats.phases.push(("views", secs(loop_start.elapsed())));
    stats.views = Some(times);
    if let Some(p) = &s.stats {
        let mut set = OutputSet::create(&[("--stats", p, OutputKind::Json)], &stats_reads)?;
        set.write_bytes("--stats", stats.json().as_bytes())?;
        set.commit()?;
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

/// Whether every output of a view (`paths`, one for each of `flags`) is already a whole file
/// of this run's size: a view with a missing, empty, truncated or other-sized output is
/// rendered again by `--skip-existing` (and one whose files are whole, but whose record does
/// not say this run made them: `record::matches`).
fn complete(flags: &[(&'static str, OutputKind)], paths: &[PathBuf], s: &RenderSettings) -> bool {
    flags.iter().zip(paths).all(|(&(flag, kind), path)| {
        let what = match (kind, flag) {
            (OutputKind::Npy, "--ids") => Expected::Npy("<i4", 1),
            (OutputKind::Npy, "--normals") => Expected::Npy("<f4", 3),
            (OutputKind::Npy, _) => Expected::Npy("<f4", 1),
            _ => Expected::Image,
        };
        output::is_complete(path, what, s.view.width, s.view.height)
    })
}

/// An error of view `k`, naming its line in the views file (or its place in the orbit).
fn in_view(source: &ViewSource, lines: &[ViewLine], k: usize, e: Error) -> Error {
    match source {
        ViewSource::File(f) => {
            Error::input(f, lines[k].line, lines[k].col, format!("view {k}: {e}"))
        }
        ViewSource::Orbit(n) => Error::usage(format!("--orbit {n}: view {k}: {e}")),
    }
}

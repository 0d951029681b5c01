//! The accuracy lab: every intersection method ([`methods`], plus lanecast's own kernels and
//! precisions) on the stress scenes (`scenes/stress/`) and the seed scenes, measured against the
//! f64 scalar oracle, with throughput on one thread; writes a chart, a table and error images
//! to `docs/lab/`. Run it with `cargo bench -p lanecast-lab --bench lab` (see [`lab_main`]).
//!
//! The lab is its own crate on top of lanecast: it uses the library's public API (scenes,
//! cameras, `compare`'s mismatch classes) and its inner layers (`lanecast::experimental`:
//! kernels, ray tables, constant records), and nothing in lanecast imports it, so the
//! `lanecast` binary never links the chart's plotting crate nor the lab's methods.
//!
//! - `methods/`: the other intersection methods (Möller–Trumbore, watertight, plane, the
//!   textbook sphere, f32 world-space setup), 1-lane and 8-lane forms side by side;
//! - `kits.rs`: their brute-force drivers, and the f64 scalar oracle;
//! - `method.rs`: [`Method`], one point on the chart, and its driver;
//! - `render.rs`: `lab-render` (`src/bin/lab-render.rs`), one scene with any method against
//!   the oracle, reported as `lanecast compare` reports lanecast's precisions;
//! - `measure.rs`: mismatches (ties, edge band, unexcused), holes, false hits, depth error,
//!   throughput;
//! - `report.rs`: the Markdown table, the chart (plotters), the error images;
//! - `bvh_spike/`: a world-space BVH traversed by pixel tiles, the many-view design measured
//!   against `--accel world` and Embree (`examples/bvh_spike`, `scripts/bvh_spike_table.py`;
//!   docs/architecture.md, "Many views: object order against a world-space BVH").

pub mod bvh_spike;
pub mod kits;
pub mod measure;
pub mod method;
pub mod methods;
pub mod render;
pub mod report;

use lanecast::Camera;
use lanecast::scene::{Scene, load_scene};
use lanecast::{Error, Result};
pub use method::Method;
use std::path::{Path, PathBuf};

/// Per-pixel results of a lab render: the renderer's frame, depth kept in f64.
pub type LabFrame = lanecast::Frame<f64>;

/// Size of the stress scenes unless their `# lab:` line says otherwise; also the seed scenes'.
pub const DEFAULT_SIZE: (u32, u32) = (320, 240);

/// A scene as the lab uses it: the parsed scene, its camera at the lab's size, and which
/// primitives form closed surfaces (where a miss is a hole), from the file's `# lab:` lines:
/// `# lab: size WxH closed A-B closed C-D` (ids inclusive).
#[derive(Debug, Clone)]
pub struct LabScene {
    pub name: String,
    pub path: PathBuf,
    pub scene: Scene,
    pub camera: Camera,
    pub closed: Vec<bool>,
    pub stress: bool,
}

impl LabScene {
    pub fn load(path: &Path, stress: bool) -> Result<LabScene> {
        let scene = load_scene(path)?;
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::Failed(format!("{}: {e}", path.display())))?;
        let mut size = DEFAULT_SIZE;
        let mut closed = vec![false; scene.shapes.len()];
        let bad = |what: &str| Error::Failed(format!("{}: bad '# lab:' {what}", path.display()));
        for line in text.lines().filter_map(|l| l.trim().strip_prefix("# lab:")) {
            let mut it = line.split_whitespace();
            while let Some(key) = it.next() {
                let val = it.next().ok_or_else(|| bad(key))?;
                match key {
                    "size" => {
                        let (w, h) = val.split_once('x').ok_or_else(|| bad(val))?;
                        size = (
                            w.parse().map_err(|_| bad(val))?,
                            h.parse().map_err(|_| bad(val))?,
                        );
                    }
                    "closed" => {
                        let (a, b) = val.split_once('-').ok_or_else(|| bad(val))?;
                        let (a, b): (usize, usize) = (
                            a.parse().map_err(|_| bad(val))?,
                            b.parse().map_err(|_| bad(val))?,
                        );
                        if b >= closed.len() || a > b {
                            return Err(bad(val));
                        }
                        closed[a..=b].iter_mut().for_each(|c| *c = true);
                    }
                    _ => return Err(bad(key)),
                }
            }
        }
        let fov = scene.camera.fov_deg().unwrap_or(60.0);
        let camera = Camera::new(&scene.camera, fov, size.0, size.1);
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        Ok(LabScene {
            name,
            path: path.to_path_buf(),
            scene,
            camera,
            closed,
            stress,
        })
    }
}

/// The stress scenes (sorted by name) and then the seed scenes 1..7, from the crate root.
pub fn load_all(root: &Path) -> Result<Vec<LabScene>> {
    let mut stress: Vec<PathBuf> = std::fs::read_dir(root.join("scenes/stress"))
        .map_err(|e| Error::Failed(format!("scenes/stress: {e}")))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "sc"))
        .collect();
    stress.sort();
    let mut out = Vec::new();
    for p in stress {
        out.push(LabScene::load(&p, true)?);
    }
    for i in 1..=7 {
        out.push(LabScene::load(
            &root.join(format!("scenes/scene{i}.sc")),
            false,
        )?);
    }
    Ok(out)
}

/// Runs the whole lab: `args` may hold `--out DIR` (default `docs/lab`), `--only SCENE` (a
/// scene name, repeatable, for quick runs) and `--method NAME` (repeatable). Writes
/// `speed-vs-accuracy.svg`/`.png`, `table.md` and `err-*.png`, and prints one line per scene
/// and method to stderr.
pub fn lab_main(args: impl IntoIterator<Item = String>) -> Result<()> {
    // The lab crate sits in `lab/` beside the product's `src/`; scenes and docs are the root's.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("lab/ has a parent")
        .to_path_buf();
    let mut out = root.join("docs/lab");
    let mut only: Vec<String> = Vec::new();
    let mut methods: Vec<Method> = Vec::new();
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--out" => {
                out = PathBuf::from(
                    it.next()
                        .ok_or_else(|| Error::usage("--out needs a folder"))?,
                )
            }
            "--only" => only.push(
                it.next()
                    .ok_or_else(|| Error::usage("--only needs a scene"))?,
            ),
            "--method" => {
                let m = it
                    .next()
                    .ok_or_else(|| Error::usage("--method needs a name"))?;
                methods.push(
                    Method::parse(&m).ok_or_else(|| Error::usage(format!("unknown method {m}")))?,
                );
            }
            // cargo bench passes --bench; ignore flags meant for the harness
            "--bench" => {}
            other => return Err(Error::usage(format!("unknown lab argument {other}"))),
        }
    }
    if methods.is_empty() {
        methods = Method::ALL.to_vec();
    }
    let mut scenes = load_all(&root)?;
    if !only.is_empty() {
        scenes.retain(|s| only.contains(&s.name));
    }
    std::fs::create_dir_all(&out).map_err(|e| Error::Failed(format!("{}: {e}", out.display())))?;
    let started = std::time::Instant::now();
    let mut results = Vec::new();
    for s in &scenes {
        let r = measure::run_scene(s, &methods);
        for m in &r.rows {
            eprintln!(
                "{:<14} {:<14} mism {:>7} unexc {:>6} holes {:>6} false {:>6} dmed {:.1e} dp99 {:.1e} {:>7.2} Mrays/s",
                s.name,
                m.method.name(),
                m.mismatches,
                m.unexcused,
                m.holes,
                m.false_hits,
                m.depth_med,
                m.depth_p99,
                m.rays_per_s / 1e6
            );
        }
        results.push(r);
    }
    report::write_all(&out, &scenes, &results, &methods)?;
    eprintln!(
        "lab: {} scenes x {} methods in {:.1} s, written to {}",
        scenes.len(),
        methods.len(),
        started.elapsed().as_secs_f64(),
        out.display()
    );
    Ok(())
}

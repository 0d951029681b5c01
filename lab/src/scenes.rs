//! The scenes the lab measures on: the stress scenes (`scenes/stress/`) and the seed scenes,
//! each with its camera at the lab's size and the primitives that form closed surfaces, read
//! from the file's `# lab:` lines.

use lanecast::Camera;
use lanecast::scene::{Scene, load_scene};
use lanecast::{Error, Result};
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

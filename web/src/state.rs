//! The session: the scene on show, the last frame and its camera, and the files a scene's
//! `mesh` lines may name, with loading, rendering (by the engine `engine::choose` names),
//! shading and picking.

use crate::engine::{self, Engine};
use crate::report::Pick;
use glam::DVec3;
use lanecast::scene::{RangeClusters, parse_mesh_bytes, parse_scene_with};
use lanecast::world::{self, World};
use lanecast::{Camera, CameraSpec, ColorMode, Frame, Options, Renderer, Scene, Variation};
use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, OnceLock};

/// A scene ready for views, with what picking needs beside it. It owns everything: the
/// scene, and what is prepared from it once for every camera (the world engine's prepared
/// scene, the range check's cluster bounds), each built by the first frame that needs it.
pub struct Loaded {
    /// The parsed scene.
    scene: Scene,
    /// `--accel world`'s prepared scene, built by the first frame the world engine renders.
    world: OnceLock<Arc<World>>,
    /// The world engine's working buffers, reused from frame to frame.
    scratch: world::Scratch,
    /// The f32 range check's cluster bounds, built by the first eye other than the scene's.
    range: OnceLock<RangeClusters>,
    /// For each scene line holding a `mesh` (0 for a bare mesh), the id of its first face.
    mesh_first: HashMap<usize, usize>,
    /// The box around every primitive (min, max), for the page to keep its camera near it.
    bounds: [DVec3; 2],
}

impl std::fmt::Debug for Loaded {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Loaded")
            .field("scene", &self.scene().source)
            .finish()
    }
}

impl Loaded {
    fn new(scene: Scene) -> Loaded {
        let mesh_lines: Vec<usize> = scene.shapes.meshes().map(|(_, l)| l).collect();
        let mut mesh_first = HashMap::new();
        if !mesh_lines.is_empty() {
            for (id, line) in scene.shapes.lines().enumerate() {
                if mesh_lines.contains(&line) {
                    mesh_first.entry(line).or_insert(id);
                }
            }
        }
        let bounds = bounds(&scene);
        Loaded {
            scene,
            world: OnceLock::new(),
            scratch: world::Scratch::default(),
            range: OnceLock::new(),
            mesh_first,
            bounds,
        }
    }

    /// The box around every primitive: (min, max) corners.
    pub fn bounds(&self) -> [DVec3; 2] {
        self.bounds
    }

    /// The parsed scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The world engine's prepared scene, once built (by the first frame it renders).
    pub fn world(&self) -> Option<&Arc<World>> {
        self.world.get()
    }

    /// The mesh face index of primitive `id` when it is a mesh triangle.
    pub fn face(&self, id: usize) -> Option<usize> {
        let line = self.scene().shapes.line(id);
        self.mesh_first.get(&line).map(|first| id - first)
    }

    /// The command line's f32 range check of the scene seen from `eye`: the scene's own eye
    /// was checked when it loaded; any other is checked through cluster bounds built once.
    fn check(&self, eye: DVec3) -> lanecast::Result<()> {
        if eye == self.scene.camera.eye {
            return Ok(());
        }
        let range = self.range.get_or_init(|| RangeClusters::new(&self.scene));
        range.check(&self.scene, eye)
    }

    /// The view from `camera` by `engine`, its buffers those of `spare` when it has the size:
    /// the ids and depths `lanecast --accel auto` or `--accel world` gives (precision auto).
    fn render(&mut self, camera: &Camera, engine: Engine, spare: Option<Frame<f32>>) -> Frame<f32> {
        match engine {
            Engine::World => {
                let scene = &self.scene;
                let world = self.world.get_or_init(|| Arc::new(World::new(scene)));
                let precision = world::Precision::Auto;
                (world.render_marking(camera, precision, &mut self.scratch, spare)).0
            }
            Engine::Tiles => {
                // the command line's default: `--accel auto` (tiles from two primitives on)
                let renderer = Renderer::new(&self.scene, camera, &Options::default())
                    .expect("the default options are consistent");
                if let Some(spare) = spare {
                    renderer.recycle(spare);
                }
                renderer.render()
            }
        }
    }
}

/// Everything the module holds between calls.
#[derive(Default)]
pub struct State {
    /// Files that `mesh` lines may name, by the name JS gave them.
    pub files: HashMap<String, Vec<u8>>,
    /// The scene on show.
    pub loaded: Option<Loaded>,
    /// The last frame rendered, and the camera it was rendered from.
    pub frame: Option<(Frame<f32>, Camera)>,
    /// The engine every frame is rendered by, when set (to measure one against the other);
    /// `None`: [`engine::choose`]'s.
    pub force: Option<Engine>,
    /// The engine that rendered the last frame.
    pub engine: Option<Engine>,
    rgba: Vec<u8>,
    npy: Vec<u8>,
    pub(crate) message: String,
}

impl State {
    /// Loads the file `name` (a scene, or a bare mesh by its `.obj`/`.ply` extension); on
    /// failure the previous scene stays and the error is the command line's message.
    pub fn load(&mut self, name: &str, bytes: &[u8]) -> Result<&Loaded, String> {
        let path = Path::new(name);
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let scene = if matches!(ext.as_deref(), Some("obj" | "ply")) {
            parse_mesh_bytes(bytes, path)
        } else {
            let files = &self.files;
            // A file given as `meshes/x.obj` matches the resolved path `scenes/meshes/x.obj`;
            // a dropped file, which knows only its own name, matches by that name. The
            // longest match wins.
            let lookup = |p: &Path| -> Option<Vec<u8>> {
                let found = files.iter().filter(|(k, _)| p.ends_with(k.as_str()));
                found.max_by_key(|(k, _)| k.len()).map(|(_, b)| b.clone())
            };
            parse_scene_with(bytes, path, &lookup)
        }
        .map_err(|e| e.to_string())?;
        let loaded = Loaded::new(scene);
        self.frame = None;
        Ok(self.loaded.insert(loaded))
    }

    /// Renders the loaded scene from `spec` (the scene's camera when `None`) at the given size,
    /// by the engine [`engine::choose`] names for the scene and size (or [`State::force`]'s),
    /// reusing the last frame's buffers.
    pub fn render(
        &mut self,
        width: u32,
        height: u32,
        spec: Option<CameraSpec>,
    ) -> Result<&Frame<f32>, String> {
        let loaded = self.loaded.as_mut().ok_or("no scene loaded")?;
        let own = &loaded.scene().camera;
        // a camera of the caller's (the page's orbit, pan and zoom), not the scene's line
        let theirs = spec.filter(|s| (s.eye, s.look, s.up) != (own.eye, own.look, own.up));
        let camera = match spec {
            Some(spec) => Camera::look_at(&spec, width, height),
            None => Camera::for_scene(loaded.scene(), width, height, None),
        }
        .map_err(|e| e.to_string())?;
        loaded.check(camera.eye).map_err(|e| match (&theirs, e) {
            // the scene's file is not at fault (it loaded): the caller's view is, so the
            // message names the camera and not a scene line
            (Some(c), lanecast::Error::Input { msg, .. }) => {
                let v = |v: DVec3| format!("{} {} {}", v.x, v.y, v.z);
                format!(
                    "this view cannot be rendered (camera eye {} look {}): {msg}",
                    v(c.eye),
                    v(c.look)
                )
            }
            (_, e) => e.to_string(),
        })?;
        let engine = (self.force).unwrap_or_else(|| engine::choose(loaded.scene(), width, height));
        let spare = self.frame.take().map(|(f, _)| f);
        let frame = loaded.render(&camera, engine, spare);
        self.engine = Some(engine);
        Ok(&self.frame.insert((frame, camera)).0)
    }

    /// The last frame as RGBA (`ColorMode`, `Variation` and seed as the command line's
    /// `-cm`, `-cv` and `--seed`), primitives `hover` and `pinned` highlighted.
    pub fn shade(
        &mut self,
        mode: ColorMode,
        variation: Variation,
        seed: u64,
        hover: i32,
        pinned: i32,
    ) -> &[u8] {
        let (Some((frame, camera)), Some(loaded)) = (&self.frame, &self.loaded) else {
            self.rgba.clear();
            return &self.rgba;
        };
        let rgb = frame.rgb(loaded.scene(), camera, mode, variation, seed);
        let (w, h) = (frame.width as usize, frame.height as usize);
        self.rgba.resize(w * h * 4, 255);
        for (o, i) in self.rgba.chunks_exact_mut(4).zip(rgb.chunks_exact(3)) {
            o[..3].copy_from_slice(i);
        }
        for (id, tint) in [(hover, [255u8, 255, 255]), (pinned, [255, 220, 0])] {
            if id >= 0 {
                highlight(&mut self.rgba, &frame.ids, w, h, id, tint);
            }
        }
        &self.rgba
    }

    /// The last frame's ids (`depth` false) or depths as a `.npy` file, byte for byte the
    /// command line's `--ids` or `--depth` file; empty before a frame.
    pub fn npy(&mut self, depth: bool) -> &[u8] {
        self.npy = match &self.frame {
            Some((f, _)) if depth => lanecast::output::npy_f32(f.width, f.height, &f.depth),
            Some((f, _)) => lanecast::output::npy_i32(f.width, f.height, &f.ids),
            None => Vec::new(),
        };
        &self.npy
    }

    /// The length of the `.npy` file [`State::npy`] last made.
    pub fn npy_len(&self) -> usize {
        self.npy.len()
    }

    /// What lies under pixel (x, y) of the last frame: `None` outside the frame or on the
    /// background.
    pub fn pick(&self, x: u32, y: u32) -> Option<Pick> {
        let (frame, camera) = self.frame.as_ref()?;
        let loaded = self.loaded.as_ref()?;
        if x >= frame.width || y >= frame.height {
            return None;
        }
        let at = y as usize * frame.width as usize + x as usize;
        let id = frame.ids[at];
        if id < 0 {
            return None;
        }
        let depth = frame.depth[at];
        // the pixel's ray, as the f64 oracle forms it: f + sx r + sy u, normalised
        let dir = (camera.f + camera.sx::<f64>(x) * camera.r + camera.sy::<f64>(y) * camera.u)
            .normalize();
        let shapes = &loaded.scene().shapes;
        let id_u = id as usize;
        let kind = shapes.get(id_u).keyword();
        Some(Pick {
            id,
            kind,
            line: shapes.line(id_u),
            face: loaded.face(id_u),
            depth,
            point: (camera.eye + dir * depth as f64).to_array(),
        })
    }
}

/// The box around every primitive of `scene` (a sphere by its centre and radius): (min, max).
fn bounds(scene: &Scene) -> [DVec3; 2] {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    if scene.shapes.is_empty() {
        return [scene.camera.look; 2];
    }
    for shape in scene.shapes.iter() {
        let (min, max) = shape.bounds(DVec3::ZERO);
        (lo, hi) = (lo.min(min), hi.max(max));
    }
    [lo, hi]
}

/// How far (in pixels, as a disk) the ring drawn around a highlighted primitive reaches.
pub const RING: i32 = 3;

/// Marks primitive `id` so that it stands out at any density, even where it covers a pixel or
/// two of a dense mesh: its pixels mixed two thirds toward `tint`, and a ring around them
/// `RING` pixels wide (disk-shaped), `tint` nearest the primitive and black outside it, so it
/// shows on light and dark neighbours alike.
fn highlight(rgba: &mut [u8], ids: &[i32], w: usize, h: usize, id: i32, tint: [u8; 3]) {
    // the ring: every pixel within RING of one of the primitive's edge pixels, not its own
    let mut ring: Vec<(usize, u8)> = Vec::new();
    let r2 = RING * RING;
    for y in 0..h {
        for x in 0..w {
            let at = y * w + x;
            if ids[at] != id {
                continue;
            }
            let p = &mut rgba[at * 4..at * 4 + 3];
            for (c, t) in p.iter_mut().zip(tint) {
                *c = ((*c as u16 + 2 * t as u16) / 3) as u8;
            }
            let edge = x == 0
                || y == 0
                || x + 1 == w
                || y + 1 == h
                || ids[at - 1] != id
                || ids[at + 1] != id
                || ids[at - w] != id
                || ids[at + w] != id;
            if !edge {
                continue;
            }
            for dy in -RING..=RING {
                for dx in -RING..=RING {
                    let d2 = dx * dx + dy * dy;
                    let (nx, ny) = (x as i64 + dx as i64, y as i64 + dy as i64);
                    if d2 > r2 || nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                        continue;
                    }
                    let n = ny as usize * w + nx as usize;
                    if ids[n] != id {
                        // 0: tint (within two thirds of the ring), 1: black
                        ring.push((n, u8::from(d2 * 9 > r2 * 4)));
                    }
                }
            }
        }
    }
    // tint wins over black where the two overlap
    ring.sort_unstable();
    ring.dedup_by_key(|(n, _)| *n);
    for (n, outer) in ring {
        let colour = if outer == 1 { [0, 0, 0] } else { tint };
        rgba[n * 4..n * 4 + 3].copy_from_slice(&colour);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::scene_json;

    const TEXT: &str = "camera eye 0 0 10 look 0 0 0 up 0 1 0 fov 40\n\
                        sphere 0 0 0 1\n\
                        mesh m.obj\n";
    const OBJ: &str = "v -4 -3 -1\nv 4 -3 -1\nv 4 3 -1\nv -4 3 -1\nf 1 2 3\nf 1 3 4\n";

    #[test]
    fn picks_name_the_primitive_its_line_face_and_hit_point() {
        let mut s = State::default();
        s.files.insert("m.obj".into(), OBJ.as_bytes().to_vec());
        s.load("dir/a.sc", TEXT.as_bytes()).unwrap();
        s.render(41, 41, None).unwrap();
        let centre = s.pick(20, 20).unwrap();
        assert_eq!((centre.id, centre.kind, centre.line), (0, "sphere", 2));
        assert_eq!(centre.face, None);
        assert!((centre.depth - 9.0).abs() < 1e-5, "{centre:?}");
        assert!((centre.point[2] - 1.0).abs() < 1e-5, "{centre:?}");
        let corner = s.pick(2, 8).unwrap(); // upper left: the second face of the mesh
        assert_eq!((corner.id, corner.kind, corner.line), (2, "triangle", 3));
        assert_eq!(corner.face, Some(1));
        assert!((corner.point[2] + 1.0).abs() < 1e-5, "{corner:?}");
        assert!(s.pick(41, 0).is_none());
    }

    /// Frames of an orbit about the bunny, at changing sizes (the chosen engine changing with
    /// them), then by each engine forced, all through the one scene the session keeps (the
    /// world engine's prepared scene and working buffers reused): each is the frame of a
    /// one-camera renderer of its own with that engine's `--accel`, ids and depths.
    #[test]
    fn every_frame_of_an_orbit_renders_as_a_renderer_of_its_own() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let obj = std::fs::read(root.join("scenes/meshes/bunny.obj")).unwrap();
        let mut s = State::default();
        s.load("bunny.obj", &obj).unwrap();
        let first = s.loaded.as_ref().unwrap().scene().camera;
        let mut seen = Vec::new();
        for force in [None, Some(Engine::Tiles), Some(Engine::World)] {
            s.force = force;
            for k in 0..6u32 {
                let a = f64::from(k) * 0.2;
                let offset = first.eye - first.look;
                let spec = CameraSpec {
                    eye: first.look + glam::DQuat::from_rotation_y(a) * offset,
                    ..first
                };
                // 3,674 triangles: the world engine up to 14,696 pixels, then the per-eye path
                let (w, h) = (96 + 64 * k, 64 + 48 * k);
                let got = s.render(w, h, Some(spec)).unwrap().clone();
                let engine = s.engine.unwrap();
                assert_eq!(
                    engine,
                    force.unwrap_or(engine::choose(s.loaded.as_ref().unwrap().scene(), w, h))
                );
                seen.push(engine);
                let accel = match engine {
                    Engine::Tiles => lanecast::Accel::Auto,
                    Engine::World => lanecast::Accel::World,
                };
                let scene = s.loaded.as_ref().unwrap().scene();
                let camera = Camera::look_at(&spec, w, h).unwrap();
                let options = Options {
                    accel,
                    ..Options::default()
                };
                let want = Renderer::new(scene, &camera, &options).unwrap().render();
                assert_eq!(got.ids, want.ids, "frame {k} by {engine:?}");
                let bits = |d: &[f32]| d.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&got.depth),
                    bits(&want.depth),
                    "frame {k} by {engine:?}"
                );
                assert!(got.ids.iter().any(|&i| i >= 0), "frame {k} shows the bunny");
            }
        }
        assert!(seen[..6].contains(&Engine::Tiles) && seen[..6].contains(&Engine::World));
    }

    #[test]
    fn a_bad_file_keeps_the_previous_scene() {
        let mut s = State::default();
        s.load(
            "a.sc",
            b"camera eye 0 0 10 look 0 0 0 up 0 1 0\nsphere 0 0 0 2\n",
        )
        .unwrap();
        let e = s.load(
            "bad.sc",
            b"camera eye 0 0 10 look 0 0 0 up 0 1 0\nsphere 0 0\n",
        );
        assert!(e.unwrap_err().starts_with("bad.sc:2:"));
        let e = s.load("a.sc", TEXT.as_bytes()).unwrap_err();
        assert!(e.starts_with("a.sc:3:") && e.contains("m.obj"), "{e}");
        assert_eq!(s.render(8, 8, None).unwrap().ids[27], 0);
        assert!(s.loaded.as_ref().unwrap().scene().source.ends_with("a.sc"));
    }

    #[test]
    fn shading_highlights_the_hovered_primitive() {
        let mut s = State::default();
        s.load(
            "a.sc",
            b"camera eye 0 0 10 look 0 0 0 up 0 1 0\nsphere 0 0 0 3\n",
        )
        .unwrap();
        s.render(16, 16, None).unwrap();
        let plain = s
            .shade(ColorMode::Random, Variation::Linear, 0, -1, -1)
            .to_vec();
        let lit = s
            .shade(ColorMode::Random, Variation::Linear, 0, 0, -1)
            .to_vec();
        let at = (8 * 16 + 8) * 4;
        assert_ne!(plain[at..at + 3], lit[at..at + 3]);
        assert_eq!(plain[..4], lit[..4]); // background untouched
        assert!(
            scene_json(
                s.loaded.as_ref().unwrap().scene(),
                s.loaded.as_ref().unwrap().bounds()
            )
            .contains("\"primitives\":1")
        );
    }

    /// A face of the bunny that covers two pixels or fewer at 160x120 still changes dozens when
    /// pinned: its pixels and the ring around them (a 1-pixel outline changed two).
    #[test]
    fn a_pinned_face_of_a_dense_mesh_stands_out() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let obj = std::fs::read(root.join("scenes/meshes/bunny.obj")).unwrap();
        let mut s = State::default();
        s.load("bunny.obj", &obj).unwrap();
        let (w, h) = (160, 120);
        let ids = s.render(w, h, None).unwrap().ids.clone();
        let mut count = HashMap::new();
        for &i in ids.iter().filter(|&&i| i >= 0) {
            *count.entry(i).or_insert(0usize) += 1;
        }
        let (&small, _) = count.iter().filter(|(_, n)| **n <= 2).min().unwrap();
        let plain = s
            .shade(ColorMode::Random, Variation::Linear, 0, -1, -1)
            .to_vec();
        let lit = s
            .shade(ColorMode::Random, Variation::Linear, 0, -1, small)
            .to_vec();
        let changed: Vec<usize> = (0..ids.len())
            .filter(|&k| plain[4 * k..4 * k + 3] != lit[4 * k..4 * k + 3])
            .collect();
        assert!(
            changed.len() >= 20,
            "face {small}: {} pixels changed",
            changed.len()
        );
        // all of them near the face: within the ring
        let own: Vec<usize> = (0..ids.len()).filter(|&k| ids[k] == small).collect();
        for k in changed {
            let near = own.iter().any(|&o| {
                let (dx, dy) = (
                    (k % 160) as i32 - (o % 160) as i32,
                    (k / 160) as i32 - (o / 160) as i32,
                );
                dx * dx + dy * dy <= RING * RING
            });
            assert!(near, "pixel {k} changed, away from face {small}");
        }
        // the ring is both light (the pin's yellow) and dark: it shows on any neighbour
        let colours: Vec<&[u8]> = lit.chunks_exact(4).map(|p| &p[..3]).collect();
        assert!(colours.contains(&&[255u8, 220, 0][..]) && colours.contains(&&[0u8, 0, 0][..]));
    }

    /// A view the page moved to (zoomed far out) that the engine refuses names the camera, not
    /// the scene's line: the scene's file is not at fault. From the scene's own camera a
    /// refusal keeps the command line's FILE:LINE:COL.
    #[test]
    fn a_refused_view_from_the_callers_camera_blames_the_camera() {
        let mut s = State::default();
        s.load(
            "far.sc",
            b"camera eye 0 0 10 look 0 0 0 up 0 1 0\ntriangle 0 0 0 1 0 0 0 1 0\n",
        )
        .unwrap();
        let own = s.loaded.as_ref().unwrap().scene().camera;
        assert!(s.render(16, 16, Some(own)).is_ok());
        let far = CameraSpec {
            eye: glam::DVec3::new(0.0, 0.0, 1e25),
            ..own
        };
        let e = s.render(16, 16, Some(far)).unwrap_err();
        assert!(!e.starts_with("far.sc"), "{e}");
        assert!(e.starts_with("this view cannot be rendered (camera eye 0 0 10000000000000000000000000 look 0 0 0): "), "{e}");
        assert!(
            scene_json(
                s.loaded.as_ref().unwrap().scene(),
                s.loaded.as_ref().unwrap().bounds()
            )
            .contains("\"bounds\":[[0,0,0],[1,1,0]]")
        );
    }
}

//! lanecast in the browser: the library compiled to WebAssembly behind a handful of coarse
//! `extern "C"` calls, for the hand-written loader `web/www/lanecast.js` (no wasm-bindgen).
//!
//! One engine: this crate only converts (bytes and numbers in, pointers to frames out) and
//! delegates to the `lanecast` library. Every render goes through [`lanecast::Views`] on the
//! scene loaded once; nothing is re-parsed when only the camera moves.
//!
//! The calls, in the order a page makes them:
//!
//! - `lc_alloc(len)` / `lc_free(ptr, len)`: buffers in wasm memory for JS to fill.
//! - `lc_file_add(name, len, data, len)`: a file that a scene's `mesh` lines may name
//!   (ownership of `data` passes to the module), matched against the path a `mesh` line
//!   resolves to by its trailing components (`meshes/x.obj` or `x.obj` matches
//!   `scenes/meshes/x.obj`); `lc_files_clear()` forgets them all.
//! - `lc_load(name, len, data, len)`: a `.sc` scene, or a bare `.obj` / `.ply` by its name;
//!   0 on success (scene info as JSON in the message), 1 on failure (the command line's
//!   `FILE:LINE:COL: message` in the message; the previous scene stays).
//! - `lc_render(width, height, camera)`: camera points at 10 f64 (eye, look, up, fov; a NaN
//!   fov means the scene's, else the default), or is null for the scene's own camera.
//! - `lc_ids()`, `lc_depth()`: the last frame's ids (i32) and depths (f32), row-major.
//! - `lc_shade(mode, variation, seed, hover, pinned)`: the last frame as RGBA, with the
//!   primitives `hover` and `pinned` (-1: none) highlighted; returns its pointer.
//! - `lc_pick(x, y)`: the id at pixel (x, y) of the last frame, with id, type, scene line,
//!   mesh face, depth and hit point as JSON in the message.
//! - `lc_message()`, `lc_message_len()`: the last message (UTF-8).

use lanecast::scene::{Shape, parse_mesh_bytes, parse_scene_with};
use lanecast::{Camera, CameraSpec, ColorMode, Frame, Options, Scene, Variation, Views};
use std::cell::RefCell;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

/// A scene ready for views, with what picking needs beside it.
#[derive(Debug)]
pub struct Loaded {
    /// The parsed scene.
    pub scene: Scene,
    /// For each scene line holding a `mesh` (0 for a bare mesh), the id of its first face.
    mesh_first: HashMap<usize, usize>,
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
        Loaded { scene, mesh_first }
    }

    /// The mesh face index of primitive `id` when it is a mesh triangle.
    pub fn face(&self, id: usize) -> Option<usize> {
        let line = self.scene.shapes.line(id);
        self.mesh_first.get(&line).map(|first| id - first)
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
    rgba: Vec<u8>,
    message: String,
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
        self.frame = None;
        Ok(self.loaded.insert(Loaded::new(scene)))
    }

    /// Renders the loaded scene from `spec` (the scene's camera when `None`) at the given size,
    /// through [`Views`], reusing the last frame's buffers.
    pub fn render(
        &mut self,
        width: u32,
        height: u32,
        spec: Option<CameraSpec>,
    ) -> Result<&Frame<f32>, String> {
        let loaded = self.loaded.as_ref().ok_or("no scene loaded")?;
        let scene = &loaded.scene;
        let camera = match spec {
            Some(spec) => Camera::look_at(&spec, width, height),
            None => Camera::for_scene(scene, width, height, None),
        }
        .map_err(|e| e.to_string())?;
        let options = Options::default();
        let views = Views::new(scene, &options).map_err(|e| e.to_string())?;
        if let Some((spare, _)) = self.frame.take() {
            views.recycle(spare);
        }
        let frame = views.render(&camera).map_err(|e| e.to_string())?;
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
        let Some((frame, _)) = &self.frame else {
            self.rgba.clear();
            return &self.rgba;
        };
        let rgb = frame.rgb(mode, variation, seed);
        let (w, h) = (frame.width as usize, frame.height as usize);
        self.rgba.resize(w * h * 4, 255);
        for (o, i) in self.rgba.chunks_exact_mut(4).zip(rgb.chunks_exact(3)) {
            o[..3].copy_from_slice(i);
        }
        for (id, tint) in [(hover, [255u16, 255, 255]), (pinned, [255, 220, 0])] {
            if id >= 0 {
                highlight(&mut self.rgba, &frame.ids, w, h, id, tint);
            }
        }
        &self.rgba
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
        let shapes = &loaded.scene.shapes;
        let id_u = id as usize;
        let kind = match shapes.get(id_u) {
            Shape::Sphere { .. } => "sphere",
            Shape::Triangle(_) => "triangle",
            Shape::Quad(_) => "quad",
        };
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

/// Brightens primitive `id`'s pixels toward `tint` and draws its outline in `tint`.
fn highlight(rgba: &mut [u8], ids: &[i32], w: usize, h: usize, id: i32, tint: [u16; 3]) {
    for y in 0..h {
        for x in 0..w {
            let at = y * w + x;
            if ids[at] != id {
                continue;
            }
            let edge = x == 0
                || y == 0
                || x + 1 == w
                || y + 1 == h
                || ids[at - 1] != id
                || ids[at + 1] != id
                || ids[at - w] != id
                || ids[at + w] != id;
            let p = &mut rgba[at * 4..at * 4 + 3];
            for (c, t) in p.iter_mut().zip(tint) {
                *c = if edge {
                    t as u8
                } else {
                    ((*c as u16 * 2 + t) / 3) as u8
                };
            }
        }
    }
}

/// What a click on a primitive reports, as `--ids` and `--depth` would give it.
#[derive(Debug, Clone, PartialEq)]
pub struct Pick {
    /// The primitive's id (its index among the scene's primitives).
    pub id: i32,
    /// `sphere`, `triangle` or `quad`.
    pub kind: &'static str,
    /// Its 1-based scene line (a mesh face: the `mesh` line; 0 for a bare mesh).
    pub line: usize,
    /// Its face index within its mesh, for a mesh triangle.
    pub face: Option<usize>,
    /// The depth at the pixel: distance from the eye along the ray (f32, as `--depth`).
    pub depth: f32,
    /// The hit point, eye + depth * ray direction.
    pub point: [f64; 3],
}

impl Pick {
    /// As JSON.
    pub fn json(&self) -> String {
        let face = self.face.map_or("null".to_string(), |f| f.to_string());
        let [x, y, z] = self.point;
        format!(
            "{{\"id\":{},\"type\":\"{}\",\"line\":{},\"face\":{face},\"depth\":{},\"point\":[{x},{y},{z}]}}",
            self.id, self.kind, self.line, self.depth
        )
    }
}

/// A scene's summary, as JSON: its name, camera, primitive counts and warnings.
pub fn scene_json(loaded: &Loaded) -> String {
    let s = &loaded.scene;
    let c = s.camera;
    let v = |v: glam::DVec3| format!("[{},{},{}]", v.x, v.y, v.z);
    let fov = c.fov_deg.map_or("null".to_string(), |f| f.to_string());
    let (spheres, triangles, quads) = s.counts();
    let mut warnings = String::new();
    for (k, w) in s.warnings.iter().enumerate() {
        let sep = if k > 0 { "," } else { "" };
        let _ = write!(warnings, "{sep}{}", json_string(w));
    }
    format!(
        "{{\"source\":{},\"camera\":{{\"eye\":{},\"look\":{},\"up\":{},\"fov\":{fov}}},\"default_fov\":{},\"primitives\":{},\"spheres\":{spheres},\"triangles\":{triangles},\"quads\":{quads},\"warnings\":[{warnings}]}}",
        json_string(&s.source.to_string_lossy()),
        v(c.eye),
        v(c.look),
        v(c.up),
        lanecast::DEFAULT_FOV,
        s.shapes.len(),
    )
}

fn json_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

fn with<T>(f: impl FnOnce(&mut State) -> T) -> T {
    STATE.with(|s| f(&mut s.borrow_mut()))
}

/// # Safety
/// `ptr` must point at `len` readable bytes.
unsafe fn str_at<'a>(ptr: *const u8, len: usize) -> &'a str {
    if len == 0 {
        return "";
    }
    let bytes = unsafe { std::slice::from_raw_parts(ptr, len) };
    std::str::from_utf8(bytes).unwrap_or("<name not UTF-8>")
}

/// # Safety
/// `ptr`/`len` must come from [`lc_alloc`] (or be null/0); ownership passes to the caller.
unsafe fn take_buffer(ptr: *mut u8, len: usize) -> Vec<u8> {
    if ptr.is_null() || len == 0 {
        return Vec::new();
    }
    unsafe { Vec::from_raw_parts(ptr, len, len) }
}

/// A buffer of `len` bytes in wasm memory, for JS to fill.
#[unsafe(no_mangle)]
pub extern "C" fn lc_alloc(len: usize) -> *mut u8 {
    let mut v = vec![0u8; len].into_boxed_slice();
    let p = v.as_mut_ptr();
    std::mem::forget(v);
    p
}

/// Frees a buffer from [`lc_alloc`].
///
/// # Safety
/// `ptr` and `len` must be those of one [`lc_alloc`] call, not passed on to another call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn lc_free(ptr: *mut u8, len: usize) {
    drop(unsafe { take_buffer(ptr, len) });
}

/// Adds a file that `mesh` lines may name; the module takes `data` (from [`lc_alloc`]).
///
/// # Safety
/// `name` points at `name_len` bytes; `data`/`data_len` come from one [`lc_alloc`] call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn lc_file_add(
    name: *const u8,
    name_len: usize,
    data: *mut u8,
    data_len: usize,
) {
    let name = unsafe { str_at(name, name_len) }.to_string();
    let data = unsafe { take_buffer(data, data_len) };
    with(|s| s.files.insert(name, data));
}

/// Forgets every file added by [`lc_file_add`].
#[unsafe(no_mangle)]
pub extern "C" fn lc_files_clear() {
    with(|s| s.files.clear());
}

/// Loads a scene (or a bare mesh, by its extension) named `name` from `data` (taken, from
/// [`lc_alloc`]). 0: loaded, scene JSON in the message; 1: refused, the command line's error
/// in the message, and the previous scene stays.
///
/// # Safety
/// `name` points at `name_len` bytes; `data`/`data_len` come from one [`lc_alloc`] call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn lc_load(
    name: *const u8,
    name_len: usize,
    data: *mut u8,
    data_len: usize,
) -> i32 {
    let name = unsafe { str_at(name, name_len) }.to_string();
    let data = unsafe { take_buffer(data, data_len) };
    with(|s| match s.load(&name, &data) {
        Ok(loaded) => {
            s.message = scene_json(loaded);
            0
        }
        Err(e) => {
            s.message = e;
            1
        }
    })
}

/// Renders the loaded scene at `width` x `height` from `camera` (10 f64: eye, look, up, fov,
/// a NaN fov meaning the scene's or the default), or from the scene's camera when null.
/// 0: rendered; 1: refused, the reason in the message.
///
/// # Safety
/// `camera` is null or points at 10 readable f64.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn lc_render(width: u32, height: u32, camera: *const f64) -> i32 {
    let spec = (!camera.is_null()).then(|| {
        let c = unsafe { std::slice::from_raw_parts(camera, 10) };
        let v = |i: usize| glam::DVec3::new(c[i], c[i + 1], c[i + 2]);
        CameraSpec {
            eye: v(0),
            look: v(3),
            up: v(6),
            fov_deg: (!c[9].is_nan()).then_some(c[9]),
        }
    });
    with(|s| {
        let spec = spec.map(|sp| CameraSpec {
            fov_deg: sp
                .fov_deg
                .or_else(|| s.loaded.as_ref()?.scene.camera.fov_deg),
            ..sp
        });
        match s.render(width, height, spec) {
            Ok(_) => 0,
            Err(e) => {
                s.message = e;
                1
            }
        }
    })
}

/// The last frame's ids (`width * height` i32, row-major, -1 background), or null.
#[unsafe(no_mangle)]
pub extern "C" fn lc_ids() -> *const i32 {
    with(|s| {
        s.frame
            .as_ref()
            .map_or(std::ptr::null(), |f| f.0.ids.as_ptr())
    })
}

/// The last frame's depths (`width * height` f32, +inf background), or null.
#[unsafe(no_mangle)]
pub extern "C" fn lc_depth() -> *const f32 {
    with(|s| {
        s.frame
            .as_ref()
            .map_or(std::ptr::null(), |f| f.0.depth.as_ptr())
    })
}

/// The last frame shaded as RGBA (`width * height * 4` bytes): `mode` 0 random, 1 ordered;
/// `variation` 0 linear, 1 log; `hover` and `pinned` ids highlighted (-1: none).
#[unsafe(no_mangle)]
pub extern "C" fn lc_shade(
    mode: u32,
    variation: u32,
    seed: f64,
    hover: i32,
    pinned: i32,
) -> *const u8 {
    let mode = if mode == 1 {
        ColorMode::Ordered
    } else {
        ColorMode::Random
    };
    let variation = if variation == 1 {
        Variation::Log
    } else {
        Variation::Linear
    };
    let seed = if seed.is_finite() && seed >= 0.0 {
        seed as u64
    } else {
        0
    };
    with(|s| s.shade(mode, variation, seed, hover, pinned).as_ptr())
}

/// The id at pixel (x, y) of the last frame (-1: background or outside), with the pick as
/// JSON in the message (`null` when none).
#[unsafe(no_mangle)]
pub extern "C" fn lc_pick(x: u32, y: u32) -> i32 {
    with(|s| match s.pick(x, y) {
        Some(p) => {
            s.message = p.json();
            p.id
        }
        None => {
            s.message = "null".into();
            -1
        }
    })
}

/// The last message: scene JSON, pick JSON or an error.
#[unsafe(no_mangle)]
pub extern "C" fn lc_message() -> *const u8 {
    with(|s| s.message.as_ptr())
}

/// The last message's length in bytes.
#[unsafe(no_mangle)]
pub extern "C" fn lc_message_len() -> usize {
    with(|s| s.message.len())
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert!(s.loaded.as_ref().unwrap().scene.source.ends_with("a.sc"));
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
        assert!(scene_json(s.loaded.as_ref().unwrap()).contains("\"primitives\":1"));
    }
}

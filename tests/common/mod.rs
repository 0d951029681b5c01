//! Helpers shared by the integration tests: fresh temp folders, running the binary, the seed
//! scenes, a seeded xorshift generator and builders of random and meshed scenes.
//!
//! Each test file compiles its own copy of this module and uses only part of it.
#![allow(dead_code)]

use glam::DVec3;
use lanecast::Camera;
use lanecast::scene::{CameraSpec, Scene, Shape, parse_scene};
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
#[cfg(feature = "cli")]
use std::process::Command;
use std::process::Output;
use std::sync::atomic::{AtomicU64, Ordering};

mod meshes;
#[allow(unused_imports)] // (each test file uses only part of this module)
pub use meshes::*;

// ---------------------------------------------------------------------------------------------
// Files and the binary

/// A fresh, empty folder under the system temp dir with a unique name, removed on drop unless
/// the test is panicking (so a failing test leaves its files for inspection).
pub struct TempDir {
    pub path: PathBuf,
}

impl TempDir {
    pub fn new(name: &str) -> TempDir {
        static N: AtomicU64 = AtomicU64::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos());
        let path = std::env::temp_dir().join(format!(
            "lanecast-test-{name}-{}-{n}-{nanos}",
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap();
        TempDir { path }
    }

    pub fn join(&self, name: &str) -> PathBuf {
        self.path.join(name)
    }

    /// Writes `text` to `name` in the folder; returns its path.
    pub fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.join(name);
        fs::write(&p, text).unwrap();
        p
    }

    /// Copies `src` into the folder as `name`; returns its path.
    pub fn copy_in(&self, src: &Path, name: &str) -> PathBuf {
        let p = self.join(name);
        fs::copy(src, &p).unwrap_or_else(|e| panic!("cannot copy {}: {e}", src.display()));
        p
    }

    /// Names of the entries in the folder, sorted (hidden temporary files included).
    pub fn entries(&self) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(&self.path)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            // (a test may have made the folder read-only)
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                let _ = fs::set_permissions(&self.path, fs::Permissions::from_mode(0o755));
            }
            let _ = fs::remove_dir_all(&self.path);
        }
    }
}

/// Runs the lanecast binary with `args` in the folder `cwd`. (The binary exists with feature
/// `cli` only: the tests that run it require it in Cargo.toml, and the others compile this
/// module without it.)
#[cfg(feature = "cli")]
pub fn run(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("cannot start the lanecast binary")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Panics with the command's output unless it exited with code 0.
pub fn assert_success(o: &Output, what: &str) {
    assert_eq!(
        o.status.code(),
        Some(0),
        "{what}: exit {:?}\nstdout: {}\nstderr: {}",
        o.status.code(),
        stdout(o),
        stderr(o)
    );
}

/// The path of seed scene `n` (scenes/scene{n}.sc); panics with a clear message if missing.
pub fn seed_scene(n: usize) -> PathBuf {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("scene{n}.sc"));
    assert!(p.is_file(), "seed scene {} is missing", p.display());
    p
}

/// The seven seed scenes, parsed.
pub fn seed_scenes() -> Vec<(String, Scene)> {
    (1..=7)
        .map(|n| {
            let p = seed_scene(n);
            let scene = lanecast::scene::load_scene(&p)
                .unwrap_or_else(|e| panic!("seed scene {}: {e}", p.display()));
            (format!("scene{n}"), scene)
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Scenes

/// xorshift64* (Vigna 2016): small, seeded, no external crate.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        // splitmix64 of the seed, so small seeds give unrelated streams; never 0.
        let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        Rng((z ^ (z >> 31)) | 1)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }

    /// Uniform in the box [-h, h]^3 around `c`.
    pub fn in_box(&mut self, c: DVec3, h: f64) -> DVec3 {
        c + DVec3::new(self.range(-h, h), self.range(-h, h), self.range(-h, h))
    }

    /// A uniformly distributed unit vector.
    pub fn direction(&mut self) -> DVec3 {
        loop {
            let v = self.in_box(DVec3::ZERO, 1.0);
            let l = v.length_squared();
            if l > 1e-3 && l <= 1.0 {
                return v / l.sqrt();
            }
        }
    }
}

pub fn camera_line(eye: DVec3, look: DVec3, up: DVec3, fov: f64) -> String {
    format!(
        "camera eye {} {} {} look {} {} {} up {} {} {} fov {fov}\n",
        eye.x, eye.y, eye.z, look.x, look.y, look.z, up.x, up.y, up.z
    )
}

/// One primitive as a scene line. `f64`'s `Display` round-trips exactly, so the parsed scene
/// holds the very values built here.
pub fn shape_line(s: &Shape) -> String {
    let mut out = String::new();
    let mut pts = |kw: &str, v: &[DVec3]| {
        out += kw;
        for p in v {
            write!(out, " {} {} {}", p.x, p.y, p.z).unwrap();
        }
    };
    match s {
        Shape::Sphere { center, radius } => {
            pts("sphere", &[*center]);
            write!(out, " {radius}").unwrap();
        }
        Shape::Triangle(v) => pts("triangle", v),
        Shape::Quad(v) => pts("quad", v),
    }
    out.push('\n');
    out
}

/// Scene text for `camera` and `shapes`.
pub fn scene_text(camera: &CameraSpec, shapes: &[Shape]) -> String {
    let mut t = match camera.lens {
        // the scene file's own words, every number in full (`{:?}` round-trips)
        Some(lanecast::Lens::Pinhole(k)) => format!(
            "camera eye {:?} {:?} {:?} look {:?} {:?} {:?} up {:?} {:?} {:?} K {:?} {:?} {:?} {:?}\n",
            camera.eye.x,
            camera.eye.y,
            camera.eye.z,
            camera.look.x,
            camera.look.y,
            camera.look.z,
            camera.up.x,
            camera.up.y,
            camera.up.z,
            k.fx,
            k.fy,
            k.cx,
            k.cy
        ),
        _ => camera_line(
            camera.eye,
            camera.look,
            camera.up,
            camera.fov_deg().unwrap_or(60.0),
        ),
    };
    for s in shapes {
        t += &shape_line(s);
    }
    t
}

/// Writes `shapes` as scene text and parses it back: the scene goes through the same
/// validation as a file.
pub fn build_scene(name: &str, camera: CameraSpec, shapes: &[Shape]) -> Scene {
    let text = scene_text(&camera, shapes);
    parse_scene(&text, Path::new(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The scene and its camera moved by `by` (both, so every eye-relative quantity is the same up
/// to the rounding of the moved coordinates).
pub fn translated(scene: &Scene, by: DVec3) -> Scene {
    let mut shapes = lanecast::scene::Shapes::new();
    for (i, s) in scene.shapes.iter().enumerate() {
        let moved = match s {
            Shape::Sphere { center, radius } => Shape::Sphere {
                center: center + by,
                radius,
            },
            Shape::Triangle(v) => Shape::Triangle(v.map(|p| p + by)),
            Shape::Quad(v) => Shape::Quad(v.map(|p| p + by)),
        };
        shapes.push(moved, scene.shapes.line(i));
    }
    let mut camera = scene.camera;
    camera.eye += by;
    camera.look += by;
    Scene {
        source: scene.source.clone(),
        camera,
        camera_at: scene.camera_at,
        shapes,
        warnings: Vec::new(),
    }
}

/// The offset of the "far from the origin" variants.
pub const FAR: DVec3 = DVec3::new(1000.0, -1000.0, 1000.0);

/// `scene` seen by `camera` with the packet kernel in `precision`, through `accel`.
pub fn render_packets(
    scene: &Scene,
    camera: &Camera,
    precision: lanecast::Precision,
    accel: lanecast::Accel,
) -> lanecast::Frame<f32> {
    let options = lanecast::Options {
        precision,
        accel,
        kernel: lanecast::Kernel::Packet,
    };
    lanecast::Renderer::new(scene, camera, &options)
        .unwrap()
        .render()
}

/// The camera of `scene` at `w` x `h`, with the scene's lens (fov or intrinsics) or 60 degrees.
pub fn camera_of(scene: &Scene, w: u32, h: u32) -> Camera {
    Camera::look_at(&scene.camera, w, h).expect("a test scene's camera is valid")
}

/// `spec` as a pinhole for `w` x `h` images, as a rig's calibration gives one: its field of
/// view's focal length along x, `fy` within 0.7 to 1.4 times `fx`, and the principal point up
/// to 0.3 image sizes off the centre (farther turns the random scenes mostly out of view;
/// `camera`'s and `accel::reach`'s tests take principal points far off the image).
pub fn random_pinhole(rng: &mut Rng, spec: CameraSpec, w: u32, h: u32) -> CameraSpec {
    let fov = spec.fov_deg().unwrap_or(60.0);
    let fx = w as f64 / (2.0 * (fov.to_radians() / 2.0).tan());
    let k = lanecast::Intrinsics {
        fx,
        fy: fx * 2f64.powf(rng.range(-0.5, 0.5)),
        cx: w as f64 * (0.5 + rng.range(-0.3, 0.3)),
        cy: h as f64 * (0.5 + rng.range(-0.3, 0.3)),
    };
    CameraSpec {
        lens: Some(lanecast::Lens::Pinhole(k)),
        ..spec
    }
}

pub fn spec(eye: DVec3, look: DVec3, up: DVec3, fov: f64) -> CameraSpec {
    CameraSpec {
        eye,
        look,
        up,
        lens: Some(lanecast::Lens::Fov(fov)),
    }
}

/// A random camera on a sphere of radius 8..14 around the origin, looking at a point near it.
pub fn random_camera(rng: &mut Rng) -> CameraSpec {
    let eye = rng.direction() * rng.range(8.0, 14.0);
    let look = rng.in_box(DVec3::ZERO, 0.5);
    let mut up = rng.direction();
    if (look - eye).normalize().cross(up).length() < 0.1 {
        up = (look - eye).any_orthonormal_vector();
    }
    spec(eye, look, up, rng.range(40.0, 80.0))
}

/// `n` spheres of radius 0.2..1.2 in the box [-4, 4]^3.
pub fn random_spheres(rng: &mut Rng, n: usize) -> Vec<Shape> {
    (0..n)
        .map(|_| Shape::Sphere {
            center: rng.in_box(DVec3::ZERO, 4.0),
            radius: rng.range(0.2, 1.2),
        })
        .collect()
}

/// `n` triangles, each with vertices within 1.5 of a centre in [-4, 4]^3, none thin.
pub fn random_triangles(rng: &mut Rng, n: usize) -> Vec<Shape> {
    let mut out = Vec::new();
    while out.len() < n {
        let c = rng.in_box(DVec3::ZERO, 4.0);
        let v = [rng.in_box(c, 1.5), rng.in_box(c, 1.5), rng.in_box(c, 1.5)];
        let area2 = (v[1] - v[0]).cross(v[2] - v[0]).length();
        if area2 > 0.2 {
            out.push(Shape::Triangle(v));
        }
    }
    out
}

/// `n` planar convex quads in random planes: alternately parallelograms (A, A+a, A+a+b, A+b)
/// and quads inscribed in a circle (four sorted angles, so convex), none thin.
pub fn random_quads(rng: &mut Rng, n: usize) -> Vec<Shape> {
    let mut out = Vec::new();
    while out.len() < n {
        let c = rng.in_box(DVec3::ZERO, 4.0);
        let e1 = rng.direction();
        let e2 = e1.cross(rng.direction());
        if e2.length() < 0.2 {
            continue;
        }
        let e2 = e2.normalize();
        let v = if out.len() % 2 == 0 {
            let a = e1 * rng.range(0.5, 2.5);
            let b = (e2 * rng.range(0.5, 2.5)) + e1 * rng.range(-1.0, 1.0);
            [c, c + a, c + a + b, c + b]
        } else {
            let r = rng.range(0.5, 1.8);
            let mut ang: Vec<f64> = (0..4)
                .map(|_| rng.range(0.0, std::f64::consts::TAU))
                .collect();
            ang.sort_by(f64::total_cmp);
            let gaps_ok = (0..4).all(|i| {
                let next = if i == 3 {
                    ang[0] + std::f64::consts::TAU
                } else {
                    ang[i + 1]
                };
                next - ang[i] > 0.3
            });
            if !gaps_ok {
                continue;
            }
            let p = |a: f64| c + (e1 * a.cos() + e2 * a.sin()) * r;
            [p(ang[0]), p(ang[1]), p(ang[2]), p(ang[3])]
        };
        if lanecast::experimental::scene::validate::quad(&v).is_ok() {
            out.push(Shape::Quad(v));
        }
    }
    out
}

//! End to end through the real binary: the original invocations and their GNU long forms,
//! `.npy` side outputs, known pixels, rejected input and arguments, `-h`, `compare`.
//! Every test works in its own fresh temp folder, with the scene copied into it.

mod common;

use common::*;
use image::{GenericImageView, RgbImage};
use std::fs;
use std::path::Path;

/// The decoded image at `path` as RGB8, checking its size.
fn image_of(path: &Path, w: u32, h: u32) -> RgbImage {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(img.dimensions(), (w, h), "{}", path.display());
    img.to_rgb8()
}

/// A temp folder holding a copy of seed scene 1 as `scene1.sc`.
fn with_scene1(name: &str) -> TempDir {
    let dir = TempDir::new(name);
    dir.copy_in(&seed_scene(1), "scene1.sc");
    dir
}

/// Runs the binary in `dir` and asserts success.
fn ok(dir: &TempDir, args: &[&str]) -> std::process::Output {
    let o = run(&dir.path, args);
    assert_success(&o, &args.join(" "));
    o
}

// ---------------------------------------------------------------------------------------------
// The seven original invocations, the long forms, BMP

#[test]
fn plain_input_writes_png_beside_it_at_640x480() {
    let dir = with_scene1("plain");
    ok(&dir, &["-i", "scene1.sc"]);
    let img = image_of(&dir.join("scene1.png"), 640, 480);
    assert!(
        img.pixels().any(|p| p.0 != [0, 0, 0]),
        "scene1 renders something"
    );
    assert!(
        img.pixels().any(|p| p.0 == [0, 0, 0]),
        "and some background"
    );
    assert_eq!(dir.entries(), ["scene1.png", "scene1.sc"]);
    // "beside the input" is the input's folder, not the working folder
    fs::create_dir(dir.join("sub")).unwrap();
    dir.copy_in(&seed_scene(1), "sub/s.sc");
    ok(&dir, &["-i", "sub/s.sc", "-size", "64x48"]);
    image_of(&dir.join("sub/s.png"), 64, 48);
    assert_eq!(dir.entries(), ["scene1.png", "scene1.sc", "sub"]);
}

#[test]
fn explicit_output() {
    let dir = with_scene1("output");
    ok(&dir, &["-i", "scene1.sc", "-o", "scene1.png"]);
    image_of(&dir.join("scene1.png"), 640, 480);
    // in a subfolder too, and the default name is not written
    fs::create_dir(dir.join("sub")).unwrap();
    ok(&dir, &["-i", "scene1.sc", "-o", "sub/other.png"]);
    image_of(&dir.join("sub/other.png"), 640, 480);
    assert_eq!(dir.entries(), ["scene1.png", "scene1.sc", "sub"]);
}

#[test]
fn size_option() {
    let dir = with_scene1("size");
    ok(&dir, &["-i", "scene1.sc", "-size", "800x600"]);
    image_of(&dir.join("scene1.png"), 800, 600);
    ok(&dir, &["-i", "scene1.sc", "-size", "37x5", "-o", "odd.png"]);
    image_of(&dir.join("odd.png"), 37, 5);
}

#[test]
fn fov_option_changes_the_view() {
    let dir = with_scene1("fov");
    ok(&dir, &["-i", "scene1.sc", "-o", "default.png"]);
    ok(&dir, &["-i", "scene1.sc", "-fov", "80", "-o", "fov80.png"]);
    let a = image_of(&dir.join("default.png"), 640, 480);
    let b = image_of(&dir.join("fov80.png"), 640, 480);
    assert_ne!(a, b, "-fov 80 renders a different view");
    // A wider view shows the same objects smaller: fewer covered pixels.
    let covered = |img: &RgbImage| img.pixels().filter(|p| p.0 != [0, 0, 0]).count();
    assert!(
        covered(&b) < covered(&a),
        "{} vs {}",
        covered(&b),
        covered(&a)
    );
}

#[test]
fn ordered_colour_mode_uses_the_palette() {
    let dir = with_scene1("ordered");
    ok(&dir, &["-i", "scene1.sc", "-o", "random.png"]);
    ok(
        &dir,
        &["-i", "scene1.sc", "-cm", "ordered", "-o", "ordered.png"],
    );
    let random = image_of(&dir.join("random.png"), 640, 480);
    let ordered = image_of(&dir.join("ordered.png"), 640, 480);
    assert_ne!(random, ordered);
    // Same coverage: only colours change.
    for (a, b) in random.pixels().zip(ordered.pixels()) {
        assert_eq!(a.0 == [0, 0, 0], b.0 == [0, 0, 0]);
    }
    // Every lit pixel is a palette colour dimmed by one factor b in [B_MIN, 1]: channels that
    // are zero in the palette colour stay zero, the others scale together (within rounding).
    let palette = lanecast::experimental::shade::PALETTE;
    let is_dimmed = |p: [u8; 3], c: [u8; 3]| {
        let k = (0..3).max_by_key(|&k| c[k]).unwrap();
        let b = p[k] as f64 / c[k] as f64;
        (lanecast::experimental::shade::B_MIN - 0.01..=1.0).contains(&b)
            && (0..3).all(|k| (p[k] as f64 - c[k] as f64 * b).abs() <= 1.0)
    };
    for p in ordered.pixels().filter(|p| p.0 != [0, 0, 0]) {
        assert!(
            palette.iter().any(|&c| is_dimmed(p.0, c)),
            "{:?} is not a dimmed palette colour",
            p.0
        );
    }
}

#[test]
fn log_colour_variation_changes_brightness_only() {
    let dir = with_scene1("log");
    ok(&dir, &["-i", "scene1.sc", "-o", "linear.png"]);
    ok(&dir, &["-i", "scene1.sc", "-cv", "log", "-o", "log.png"]);
    let lin = image_of(&dir.join("linear.png"), 640, 480);
    let log = image_of(&dir.join("log.png"), 640, 480);
    assert_ne!(lin, log);
    for (a, b) in lin.pixels().zip(log.pixels()) {
        assert_eq!(a.0 == [0, 0, 0], b.0 == [0, 0, 0]);
    }
}

#[test]
fn time_option_reports_every_phase() {
    let dir = with_scene1("time");
    let o = ok(&dir, &["-i", "scene1.sc", "-time"]);
    image_of(&dir.join("scene1.png"), 640, 480);
    let err = stderr(&o);
    for word in ["parse", "setup", "render", "write", "Mrays/s"] {
        assert!(err.contains(word), "-time output lacks {word:?}: {err}");
    }
    // without -time, nothing on stderr
    let o = ok(&dir, &["-i", "scene1.sc", "-o", "quiet.png"]);
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
}

#[test]
fn gnu_long_forms_match_the_single_dash_forms() {
    let dir = with_scene1("long");
    let short = ok(
        &dir,
        &[
            "-i",
            "scene1.sc",
            "-o",
            "short.png",
            "-size",
            "320x200",
            "-fov",
            "45",
            "-cm",
            "ordered",
            "-cv",
            "log",
            "-time",
        ],
    );
    let long = ok(
        &dir,
        &[
            "--input",
            "scene1.sc",
            "--output",
            "long.png",
            "--size",
            "320x200",
            "--fov",
            "45",
            "--color-mode",
            "ordered",
            "--color-variation",
            "log",
            "--time",
        ],
    );
    let a = image_of(&dir.join("short.png"), 320, 200);
    let b = image_of(&dir.join("long.png"), 320, 200);
    assert_eq!(a, b);
    for o in [&short, &long] {
        assert!(stderr(o).contains("Mrays/s"), "{}", stderr(o));
    }
    // `=` forms too
    ok(
        &dir,
        &[
            "--input=scene1.sc",
            "--output=eq.png",
            "--size=320x200",
            "--fov=45",
            "--color-mode=ordered",
            "--color-variation=log",
        ],
    );
    assert_eq!(image_of(&dir.join("eq.png"), 320, 200), a);
}

#[test]
fn bmp_output_has_the_same_pixels_as_png() {
    let dir = with_scene1("bmp");
    ok(
        &dir,
        &["-i", "scene1.sc", "-size", "101x67", "-o", "out.bmp"],
    );
    ok(
        &dir,
        &["-i", "scene1.sc", "-size", "101x67", "-o", "out.png"],
    );
    let bytes = fs::read(dir.join("out.bmp")).unwrap();
    assert_eq!(&bytes[..2], b"BM", "a BMP file");
    assert_eq!(
        image_of(&dir.join("out.bmp"), 101, 67),
        image_of(&dir.join("out.png"), 101, 67)
    );
    // extension case does not matter
    ok(
        &dir,
        &["-i", "scene1.sc", "-size", "101x67", "-o", "upper.BMP"],
    );
    assert_eq!(&fs::read(dir.join("upper.BMP")).unwrap()[..2], b"BM");
}

// ---------------------------------------------------------------------------------------------
// .npy side outputs and known pixels

/// A parsed `.npy` (format 1.0) file: its header dict and its data bytes.
struct Npy {
    dict: String,
    data: Vec<u8>,
}

fn read_npy(path: &Path) -> Npy {
    let bytes = fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..6], b"\x93NUMPY", "magic");
    assert_eq!(bytes[6], 1, "major version 1");
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!((10 + len) % 64, 0, "header padded to a multiple of 64");
    let dict = std::str::from_utf8(&bytes[10..10 + len])
        .unwrap()
        .to_string();
    assert!(dict.ends_with('\n'), "{dict:?}");
    assert!(dict.contains("'fortran_order': False"), "{dict:?}");
    Npy {
        dict,
        data: bytes[10 + len..].to_vec(),
    }
}

impl Npy {
    fn check(&self, descr: &str, w: usize, h: usize) {
        assert!(
            self.dict.contains(&format!("'descr': '{descr}'")),
            "{:?}",
            self.dict
        );
        assert!(
            self.dict.contains(&format!("'shape': ({h}, {w})")),
            "{:?}",
            self.dict
        );
        assert_eq!(self.data.len(), w * h * 4);
    }

    fn i32s(&self) -> Vec<i32> {
        let c = self.data.chunks_exact(4);
        c.map(|b| i32::from_le_bytes(b.try_into().unwrap()))
            .collect()
    }

    fn f32s(&self) -> Vec<f32> {
        let c = self.data.chunks_exact(4);
        c.map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect()
    }
}

/// Eye (0, 0, 5) looking down -z, fov 90 (half_w = 1); a unit sphere at the origin (id 0) and
/// one quad per quadrant behind it, each at its own depth, clear of the axes so that rays in
/// the plane y = 0 see the background: top-left z = -10 (id 1), top-right z = -12 (id 2),
/// bottom-left z = -14 (id 3), bottom-right z = -16 (id 4).
const KNOWN: &str = "\
# known pixels
camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 90
sphere 0 0 0 1
quad -100 2 -10  -2 2 -10  -2 100 -10  -100 100 -10
quad 2 2 -12  100 2 -12  100 100 -12  2 100 -12
quad -100 -100 -14  -2 -100 -14  -2 -2 -14  -100 -2 -14
quad 2 -100 -16  100 -100 -16  100 -2 -16  2 -2 -16
";

const KW: usize = 65;
const KH: usize = 49;

/// The camera formula by hand, in f64: the unit direction of pixel (x, y) for the KNOWN camera
/// (f = -z, r = +x, u = +y, half_w = tan(45 deg) = 1, half_h = H / W).
fn known_dir(x: usize, y: usize) -> [f64; 3] {
    let half_w = 1.0;
    let sx = (2.0 * (x as f64 + 0.5) / KW as f64 - 1.0) * half_w;
    let sy = (1.0 - 2.0 * (y as f64 + 0.5) / KH as f64) * half_w * KH as f64 / KW as f64;
    let v = [sx, sy, -1.0];
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / len)
}

#[test]
fn ids_and_depth_npy_hold_known_pixels_in_every_kernel() {
    let dir = TempDir::new("known");
    dir.write("known.sc", KNOWN);
    let size = format!("{KW}x{KH}");
    for kernel in ["simd", "scalar", "scalar-f32"] {
        let (ids_name, depth_name) = (format!("ids-{kernel}.npy"), format!("depth-{kernel}.npy"));
        let png = format!("{kernel}.png");
        ok(
            &dir,
            &[
                "-i",
                "known.sc",
                "-size",
                &size,
                "--kernel",
                kernel,
                "-o",
                &png,
                "--ids",
                &ids_name,
                "--depth",
                &depth_name,
                "-cm",
                "ordered",
            ],
        );
        let ids = read_npy(&dir.join(&ids_name));
        ids.check("<i4", KW, KH);
        let depth = read_npy(&dir.join(&depth_name));
        depth.check("<f4", KW, KH);
        let (ids, depth) = (ids.i32s(), depth.f32s());
        let at = |x: usize, y: usize| (ids[y * KW + x], depth[y * KW + x]);

        // Centre pixel: with W and H odd, sx = sy = 0, the ray is exactly the view direction
        // and hits the sphere's front at distance 5 - 1 = 4.
        let (id, t) = at(KW / 2, KH / 2);
        assert_eq!(id, 0, "{kernel}: centre id");
        assert!((t - 4.0).abs() <= 1e-6, "{kernel}: centre depth {t}");

        // The left and right ends of the middle row (y = 0 plane) see the background.
        for x in [0, KW - 1] {
            let (id, t) = at(x, KH / 2);
            assert_eq!(id, -1, "{kernel}: ({x}, {}) background id", KH / 2);
            assert_eq!(t, f32::INFINITY, "{kernel}: background depth");
        }

        // Corners: row 0 is the top. Depth = (5 - z_plane) / -d.z, from the formula by hand.
        for (x, y, id_want, z_plane) in [
            (0, 0, 1, -10.0),
            (KW - 1, 0, 2, -12.0),
            (0, KH - 1, 3, -14.0),
            (KW - 1, KH - 1, 4, -16.0),
        ] {
            let d = known_dir(x, y);
            let want = (5.0 - z_plane) / -d[2];
            let (id, t) = at(x, y);
            assert_eq!(id, id_want, "{kernel}: ({x}, {y}) id");
            let rel = (t as f64 - want).abs() / want;
            assert!(
                rel <= 1e-6,
                "{kernel}: ({x}, {y}) depth {t}, by hand {want}"
            );
        }

        // The image agrees: background black, the rest not.
        let img = image_of(&dir.join(&png), KW as u32, KH as u32);
        for (i, p) in img.pixels().enumerate() {
            assert_eq!(
                p.0 == [0, 0, 0],
                ids[i] < 0,
                "{kernel}: pixel {i}: {:?}",
                p.0
            );
        }
    }
    // The kernels agree on every id here (no pixel is near an edge at this size).
    let simd = read_npy(&dir.join("ids-simd.npy")).i32s();
    assert_eq!(simd, read_npy(&dir.join("ids-scalar.npy")).i32s());
    assert_eq!(simd, read_npy(&dir.join("ids-scalar-f32.npy")).i32s());
}

#[test]
fn npy_of_a_seed_scene_matches_its_image() {
    let dir = with_scene1("npy");
    ok(
        &dir,
        &[
            "-i",
            "scene1.sc",
            "-size",
            "160x120",
            "--ids",
            "ids.npy",
            "--depth",
            "depth.npy",
        ],
    );
    let ids = read_npy(&dir.join("ids.npy"));
    ids.check("<i4", 160, 120);
    let depth = read_npy(&dir.join("depth.npy"));
    depth.check("<f4", 160, 120);
    let (ids, depth) = (ids.i32s(), depth.f32s());
    let img = image_of(&dir.join("scene1.png"), 160, 120);
    let scene = lanecast::scene::load_scene(&dir.join("scene1.sc")).unwrap();
    assert!(ids.iter().any(|&i| i >= 0) && ids.contains(&-1));
    for (i, (&id, &t)) in ids.iter().zip(&depth).enumerate() {
        if id < 0 {
            assert_eq!(t, f32::INFINITY, "pixel {i}");
            assert_eq!(img.as_raw()[3 * i..3 * i + 3], [0, 0, 0], "pixel {i}");
        } else {
            assert!((id as usize) < scene.shapes.len(), "pixel {i}: id {id}");
            assert!(t.is_finite() && t > 0.0, "pixel {i}: depth {t}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Rejected input

/// The line a fixture's error must name, from its `# expect: LINE (why)` header
/// (see tests/bad/README.md); `None` for whole-file errors.
fn fixture_line(text: &str) -> Option<usize> {
    let spec = text
        .lines()
        .next()
        .and_then(|l| l.strip_prefix("# expect: "))
        .expect("fixture header");
    spec.split_whitespace().next().unwrap().parse().ok()
}

/// Asserts a rejected run: exit `code`, a `lanecast: error:` message containing
/// every one of `words`, nothing on stdout, and the folder left with exactly `entries`.
fn assert_rejected(
    o: &std::process::Output,
    code: i32,
    words: &[&str],
    dir: &TempDir,
    entries: &[&str],
) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(code), "{err}");
    assert!(err.starts_with("lanecast: error: "), "{err:?}");
    for w in words {
        assert!(err.contains(w), "{err:?} lacks {w:?}");
    }
    assert!(o.stdout.is_empty());
    assert_eq!(
        dir.entries(),
        entries,
        "no output or temporary file is left behind"
    );
}

#[test]
fn bad_scenes_are_rejected_naming_file_and_line_and_write_nothing() {
    // (fixture in tests/bad/, a word the message must contain)
    let cases = [
        ("unknown_keyword.sc", "unknown keyword"),
        ("too_few_numbers.sc", "too few numbers"),
        ("nan_token.sc", "'nan'"),
        ("degenerate_triangle.sc", "degenerate triangle"),
        ("nonplanar_quad.sc", "not planar"),
        ("radius_zero.sc", "radius"),
        ("no_camera.sc", "no camera"),
        ("two_cameras.sc", "second camera"),
    ];
    for (fixture, word) in cases {
        let dir = TempDir::new("bad");
        let src = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/bad")
            .join(fixture);
        let text = fs::read_to_string(&src).unwrap();
        dir.write("bad.sc", &text);
        let at = match fixture_line(&text) {
            Some(line) => format!("lanecast: error: bad.sc:{line}:"),
            None => "lanecast: error: bad.sc: ".to_string(),
        };
        let o = run(
            &dir.path,
            &[
                "-i",
                "bad.sc",
                "-size",
                "32x24",
                "--ids",
                "ids.npy",
                "--depth",
                "depth.npy",
            ],
        );
        assert_rejected(&o, 2, &[&at, word], &dir, &["bad.sc"]);
        assert_eq!(stderr(&o).lines().count(), 1, "one line: {}", stderr(&o));
        // explicit output and the compare subcommand reject it the same way
        let o = run(&dir.path, &["-i", "bad.sc", "-o", "out.bmp"]);
        assert_rejected(&o, 2, &[&at, word], &dir, &["bad.sc"]);
        let o = run(&dir.path, &["compare", "-i", "bad.sc", "-o", "diff.png"]);
        assert_rejected(&o, 2, &[&at, word], &dir, &["bad.sc"]);
    }
}

#[test]
fn missing_input_file_is_an_io_error_naming_the_file() {
    // Reading the scene fails with an I/O error: exit 1 by the documented table ("1 anything
    // else (I/O errors ...)"), and the message names the file.
    let dir = TempDir::new("missing");
    let o = run(&dir.path, &["-i", "missing.sc"]);
    assert_rejected(&o, 1, &["missing.sc"], &dir, &[]);
    let o = run(
        &dir.path,
        &["-i", "missing.sc", "-o", "out.png", "--ids", "i.npy"],
    );
    assert_rejected(&o, 1, &["missing.sc"], &dir, &[]);
}

#[test]
fn bad_arguments_are_rejected_naming_the_argument() {
    let dir = with_scene1("args");
    let cases: [(&[&str], &[&str]); 11] = [
        (&["-size", "0x10"], &["-size 0x10"]),
        (&["-size", "100000x100000"], &["-size 100000x100000"]),
        (&["-size", "640"], &["-size 640"]),
        (&["-size", "axb"], &["-size axb"]),
        (&["-fov", "0"], &["-fov 0"]),
        (&["-fov", "180"], &["-fov 180"]),
        (&["-fov", "-30"], &["-fov -30"]),
        (&["-o", "out.jpg2"], &["out.jpg2"]),
        (&["-o", "noextension"], &["noextension"]),
        (&["--threads", "0"], &["--threads"]),
        (&["--kernel", "gpu"], &["gpu"]),
    ];
    for (extra, words) in cases {
        let mut args = vec!["-i", "scene1.sc"];
        args.extend_from_slice(extra);
        let o = run(&dir.path, &args);
        assert_rejected(&o, 2, words, &dir, &["scene1.sc"]);
    }
    // no input at all
    let o = run(&dir.path, &["-o", "x.png"]);
    assert_rejected(&o, 2, &["--input"], &dir, &["scene1.sc"]);
}

/// `-fov=-30` was split by clap into `-f ov=-30` ("unexpected argument '-f'"): every
/// single-dash option of the original assignment takes the `=` form as its GNU long form
/// does, and a bad value gets the same message, spelled as typed.
#[test]
fn single_dash_options_take_the_equals_form() {
    let dir = with_scene1("single-dash-eq");
    for (arg, words, long) in [
        ("-fov=-30", &["-fov -30", "180"][..], "--fov"),
        ("-fov=0", &["-fov 0"], "--fov"),
        ("-size=0x10", &["-size 0x10"], "--size"),
        ("-cm=rainbow", &["rainbow", "-cm"], "--color-mode"),
        ("-cv=curvy", &["curvy", "-cv"], "--color-variation"),
        ("-time=yes", &["yes", "-time"], "--time"),
    ] {
        let o = run(&dir.path, &["-i", "scene1.sc", arg]);
        assert_rejected(&o, 2, words, &dir, &["scene1.sc"]);
        assert!(!stderr(&o).contains("'-f'"), "{arg}: {}", stderr(&o));
        assert!(
            !stderr(&o).contains(long),
            "{arg}: spelled as typed: {}",
            stderr(&o)
        );
    }
    // and the valid values render exactly as the space form
    ok(
        &dir,
        &[
            "-i",
            "scene1.sc",
            "-o",
            "eq.png",
            "-size=320x200",
            "-fov=45",
            "-cm=ordered",
            "-cv=log",
        ],
    );
    ok(
        &dir,
        &[
            "-i",
            "scene1.sc",
            "-o",
            "sp.png",
            "-size",
            "320x200",
            "-fov",
            "45",
            "-cm",
            "ordered",
            "-cv",
            "log",
        ],
    );
    assert_eq!(
        image_of(&dir.join("eq.png"), 320, 200),
        image_of(&dir.join("sp.png"), 320, 200)
    );
}

/// `-i scene.png` with no `-o`: the default output (the input's name with `.png`) is the input
/// itself. The message names what the user typed and the default that caused it, not a flag
/// that was never given.
#[test]
fn default_output_equal_to_input_names_the_default_not_output_flag() {
    let dir = TempDir::new("same-default");
    dir.write("scene.png", KNOWN);
    for flag in ["-i", "--input"] {
        let o = run(&dir.path, &[flag, "scene.png", "-size", "16x12"]);
        assert_rejected(
            &o,
            2,
            &[
                &format!("{flag} scene.png"),
                "default output scene.png",
                "overwrite",
                "-o IMAGE",
            ],
            &dir,
            &["scene.png"],
        );
        assert!(!stderr(&o).contains("--output"), "{}", stderr(&o));
        assert_eq!(fs::read_to_string(dir.join("scene.png")).unwrap(), KNOWN);
    }
}

#[test]
fn output_equal_to_input_is_refused_and_the_input_kept() {
    let dir = TempDir::new("same");
    // A scene file with an image extension, so only the same-file rule can refuse it.
    dir.write("scene.png", KNOWN);
    for extra in [
        &["-o", "scene.png"][..],
        &["-o", "./scene.png"],
        &[], // the default output: the input with extension .png, i.e. itself
    ] {
        let mut args = vec!["-i", "scene.png", "-size", "16x12"];
        args.extend_from_slice(extra);
        let o = run(&dir.path, &args);
        assert_rejected(&o, 2, &["scene.png", "input"], &dir, &["scene.png"]);
        assert_eq!(fs::read_to_string(dir.join("scene.png")).unwrap(), KNOWN);
    }
    // the side outputs too
    dir.write("scene.sc", KNOWN);
    for flag in ["--ids", "--depth"] {
        let o = run(
            &dir.path,
            &["-i", "scene.sc", "-o", "out.png", flag, "scene.sc"],
        );
        assert_rejected(&o, 2, &[flag, "scene.sc"], &dir, &["scene.png", "scene.sc"]);
        assert_eq!(fs::read_to_string(dir.join("scene.sc")).unwrap(), KNOWN);
    }
}

#[test]
fn existing_output_survives_a_failed_render() {
    let dir = TempDir::new("survive");
    let before = b"not really a png, but it was here first";
    fs::write(dir.join("existing.png"), before).unwrap();
    fs::write(dir.join("ids.npy"), before).unwrap();
    let bad = KNOWN.replace("sphere 0 0 0 1", "sphere 0 0 0 -1");
    dir.write("bad.sc", &bad);
    let o = run(
        &dir.path,
        &[
            "-i",
            "bad.sc",
            "-o",
            "existing.png",
            "--ids",
            "ids.npy",
            "-size",
            "16x12",
        ],
    );
    assert_rejected(
        &o,
        2,
        &["bad.sc:3:"],
        &dir,
        &["bad.sc", "existing.png", "ids.npy"],
    );
    assert_eq!(fs::read(dir.join("existing.png")).unwrap(), before);
    assert_eq!(fs::read(dir.join("ids.npy")).unwrap(), before);
    // A bad argument leaves it alone too.
    dir.write("good.sc", KNOWN);
    let o = run(
        &dir.path,
        &["-i", "good.sc", "-o", "existing.png", "-fov", "180"],
    );
    assert_rejected(
        &o,
        2,
        &["-fov 180"],
        &dir,
        &["bad.sc", "existing.png", "good.sc", "ids.npy"],
    );
    assert_eq!(fs::read(dir.join("existing.png")).unwrap(), before);
    // and a good render replaces it
    ok(
        &dir,
        &["-i", "good.sc", "-o", "existing.png", "-size", "16x12"],
    );
    image_of(&dir.join("existing.png"), 16, 12);
}

// ---------------------------------------------------------------------------------------------
// Help and compare

#[test]
fn help_lists_every_option_and_an_example() {
    let dir = TempDir::new("help");
    for flag in ["-h", "--help"] {
        let o = run(&dir.path, &[flag]);
        assert_success(&o, flag);
        let out = stdout(&o);
        for opt in [
            "--input",
            "--output",
            "--size",
            "--fov",
            "--color-mode",
            "--color-variation",
            "--time",
            "--kernel",
            "--threads",
            "--seed",
            "--ids",
            "--depth",
            "compare",
        ] {
            assert!(out.contains(opt), "{flag}: help lacks {opt}:\n{out}");
        }
        for single in ["-size", "-fov", "-cm", "-cv", "-time"] {
            assert!(out.contains(single), "{flag}: help lacks {single}");
        }
        assert!(out.contains("Example"), "{flag}: no example:\n{out}");
        assert!(
            out.contains("lanecast -i "),
            "{flag}: no example command:\n{out}"
        );
    }
    assert!(dir.entries().is_empty());
    // the subcommand has its own help
    let o = run(&dir.path, &["compare", "-h"]);
    assert_success(&o, "compare -h");
    assert!(stdout(&o).contains("--max-mismatch-ppm"), "{}", stdout(&o));
}

#[test]
fn compare_reports_and_writes_a_diff_image() {
    let dir = with_scene1("compare");
    let o = ok(&dir, &["compare", "-i", "scene1.sc", "-size", "96x64"]);
    let out = stdout(&o);
    for word in ["pixels", "96x64", "mismatches", "unexcused", "depth rel"] {
        assert!(out.contains(word), "compare output lacks {word:?}:\n{out}");
    }
    assert_eq!(dir.entries(), ["scene1.sc"], "no image without -o");
    ok(
        &dir,
        &[
            "compare",
            "-i",
            "scene1.sc",
            "-size",
            "96x64",
            "-o",
            "diff.png",
            "--threads",
            "1",
        ],
    );
    let img = image_of(&dir.join("diff.png"), 96, 64);
    assert!(img.pixels().any(|p| p.0 != [0, 0, 0]));
    // bad arguments are refused before any work
    let o = run(
        &dir.path,
        &["compare", "-i", "scene1.sc", "-o", "diff.jpg2"],
    );
    assert_rejected(&o, 2, &["diff.jpg2"], &dir, &["diff.png", "scene1.sc"]);
}

// ---------------------------------------------------------------------------------------------
// --stats

#[test]
fn stats_record_is_json_with_the_run_in_it() {
    let dir = with_scene1("stats");
    // A scene name that needs escaping in JSON.
    dir.copy_in(&seed_scene(1), "we\"ird\\name.sc");
    ok(
        &dir,
        &[
            "-i",
            "we\"ird\\name.sc",
            "-o",
            "out.png",
            "-size",
            "64x48",
            "--threads",
            "1",
            "--repeat",
            "2",
            "--stats",
            "run.json",
        ],
    );
    let text = fs::read_to_string(dir.join("run.json")).unwrap();
    let v: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert_eq!(v["scene"], "we\"ird\\name.sc");
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(64), Some(48))
    );
    let (spheres, triangles, quads) = lanecast::load_scene(&seed_scene(1)).unwrap().counts();
    let count = |k: &str| v["primitives"][k].as_u64().map(|n| n as usize);
    assert_eq!(
        (count("spheres"), count("triangles"), count("quads")),
        (Some(spheres), Some(triangles), Some(quads))
    );
    assert_eq!(v["kernel"], "simd");
    assert_eq!(v["threads"].as_u64(), Some(1));
    assert_eq!(v["renders_s"].as_array().map(Vec::len), Some(2));
    let best = v["render_best_s"].as_f64().expect("a number");
    assert!(best > 0.0 && best <= v["render_median_s"].as_f64().unwrap());
    for phase in ["parse", "setup", "render", "shade", "write"] {
        assert!(
            v["phases_s"][phase].as_f64().is_some(),
            "phase {phase}: {text}"
        );
    }
}

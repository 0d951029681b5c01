//! Many views from one run (`--views FILE`, `--orbit N`): every view's ids and depths equal a
//! one-view run with the same camera, byte for byte, whatever the acceleration or thread count;
//! numbered outputs, `-o -` as a stream of images, `--skip-existing`, and the refusals that
//! come before anything is written.

#[path = "../common/mod.rs"]
mod common;

use common::*;
use glam::DVec3;
use lanecast::scene::cameras::orbit;
use std::fs;
use std::path::Path;

/// A views file of `n` cameras on an orbit of `scene`'s camera, fovs varied, written with
/// Rust's shortest round-trip formatting so `--eye`/`--look`/`--up` can repeat them exactly.
fn views_of(scene: &Path, n: usize) -> (String, Vec<[String; 4]>) {
    let s = lanecast::load_scene(scene).unwrap();
    let mut text = String::from("# an orbit\n\n");
    let mut flags = Vec::new();
    for (k, c) in orbit(&s.camera, n).iter().enumerate() {
        let v = |p: DVec3| format!("{},{},{}", p.x, p.y, p.z);
        let w = |p: DVec3| format!("{} {} {}", p.x, p.y, p.z);
        let fov = 20.0 + 13.0 * k as f64;
        text += &format!(
            "camera eye {} look {} up {} fov {fov}\n",
            w(c.eye),
            w(c.look),
            w(c.up)
        );
        flags.push([v(c.eye), v(c.look), v(c.up), fov.to_string()]);
    }
    (text, flags)
}

fn read(p: &Path) -> Vec<u8> {
    fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// A one-view run of `scene` with the camera `[eye, look, up, fov]` at 96x64 through `accel`,
/// into `one.bmp`, `one_i.npy` and `one_d.npy`.
fn one_view(dir: &TempDir, scene: &str, camera: &[String; 4], accel: &str) {
    let [eye, look, up, fov] = camera;
    let o = run(
        &dir.path,
        &[
            "-i",
            scene,
            "--eye",
            eye,
            "--look",
            look,
            "--up",
            up,
            "-fov",
            fov,
            "-size",
            "96x64",
            "--accel",
            accel,
            "-o",
            "one.bmp",
            "--ids",
            "one_i.npy",
            "--depth",
            "one_d.npy",
        ],
    );
    assert_success(&o, &format!("one view through {accel}"));
}

mod dataset;
mod ffmpeg;
mod refusals;
mod resume;
mod world;

#[test]
fn every_view_equals_a_run_of_its_own() {
    let dir = TempDir::new("views-equal");
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/teapot.sc");
    let stress = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/stress/grazing.sc");
    for scene in [seed_scene(2), seed_scene(4), mesh, stress] {
        let (text, flags) = views_of(&scene, 5);
        let views = dir.write("views.txt", &text);
        let scene_s = scene.to_str().unwrap();
        for accel in ["auto", "none", "bvh"] {
            for threads in ["1", "2"] {
                let o = run(
                    &dir.path,
                    &[
                        "-i",
                        scene_s,
                        "--views",
                        views.to_str().unwrap(),
                        "-size",
                        "96x64",
                        "--accel",
                        accel,
                        "--threads",
                        threads,
                        "-o",
                        "f%d.bmp",
                        "--ids",
                        "i%d.npy",
                        "--depth",
                        "d%d.npy",
                    ],
                );
                assert_success(&o, &format!("{scene_s} {accel} {threads}"));
                for (k, camera) in flags.iter().enumerate() {
                    one_view(&dir, scene_s, camera, "none");
                    let what = format!("{scene_s} view {k} accel {accel} threads {threads}");
                    for (many, one) in [
                        (format!("f{k}.bmp"), "one.bmp"),
                        (format!("i{k}.npy"), "one_i.npy"),
                        (format!("d{k}.npy"), "one_d.npy"),
                    ] {
                        assert!(
                            read(&dir.join(&many)) == read(&dir.join(one)),
                            "{what}: {many}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn an_orbit_is_the_views_file_of_its_cameras() {
    let dir = TempDir::new("views-orbit");
    let scene = seed_scene(1);
    let s = lanecast::load_scene(&scene).unwrap();
    let text: String = orbit(&s.camera, 7)
        .iter()
        .map(|c| {
            let w = |p: DVec3| format!("{} {} {}", p.x, p.y, p.z);
            format!(
                "camera eye {} look {} up {}\n",
                w(c.eye),
                w(c.look),
                w(c.up)
            )
        })
        .collect();
    dir.write("v.txt", &text);
    let scene = scene.to_str().unwrap();
    let o = run(
        &dir.path,
        &[
            "-i", scene, "--orbit", "7", "--ids", "o%d.npy", "-o", "o%d.png",
        ],
    );
    assert_success(&o, "orbit");
    let o = run(
        &dir.path,
        &[
            "-i", scene, "--views", "v.txt", "--ids", "v%d.npy", "-o", "v%d.png",
        ],
    );
    assert_success(&o, "views");
    let mut distinct = std::collections::HashSet::new();
    for k in 0..7 {
        let (a, b) = (
            read(&dir.join(&format!("o{k}.npy"))),
            read(&dir.join(&format!("v{k}.npy"))),
        );
        assert!(a == b, "view {k}");
        distinct.insert(a);
    }
    assert_eq!(distinct.len(), 7, "a turntable's views differ");
    assert!(!dir.join("o7.npy").exists());
}

/// `--orbit N --save-views FILE` writes the views file of its cameras: `--views FILE` renders
/// the same ids and depths, byte for byte; `--stats` records every view's camera, K,
/// world-to-camera matrix and outputs, for the orbit and for a rig's views file alike.
#[test]
fn an_orbit_saved_as_a_views_file_renders_again_bit_for_bit() {
    let dir = TempDir::new("views-save");
    let scene = seed_scene(1);
    let scene = scene.to_str().unwrap();
    let common = ["-i", scene, "-size", "96x64", "-fov", "37.3"];
    let mut orbit_args = common.to_vec();
    orbit_args.extend([
        "--orbit",
        "5",
        "-o",
        "o%d.png",
        "--ids",
        "o%d.npy",
        "--depth",
        "od%d.npy",
        "--save-views",
        "v.txt",
        "--stats",
        "o.json",
    ]);
    assert_success(&run(&dir.path, &orbit_args), "orbit");
    let mut views_args = common.to_vec();
    views_args.extend([
        "--views", "v.txt", "-o", "v%d.png", "--ids", "v%d.npy", "--depth", "vd%d.npy", "--stats",
        "v.json",
    ]);
    assert_success(&run(&dir.path, &views_args), "views");
    for k in 0..5 {
        for (a, b) in [("o", "v"), ("od", "vd")] {
            let (a, b) = (format!("{a}{k}.npy"), format!("{b}{k}.npy"));
            assert!(
                read(&dir.join(&a)) == read(&dir.join(&b)),
                "{a} against {b}"
            );
        }
    }
    let json = |name: &str| -> serde_json::Value {
        serde_json::from_slice(&read(&dir.join(name))).unwrap()
    };
    let (o, v) = (json("o.json"), json("v.json"));
    let views = o["views"].as_array().unwrap();
    assert_eq!(views.len(), 5);
    for (k, view) in views.iter().enumerate() {
        // the same camera, K and matrix whichever way the views came
        for key in ["camera", "K", "world_to_camera"] {
            assert_eq!(view[key], v["views"][k][key], "view {k}: {key}");
        }
        assert_eq!(view["camera"]["fov"], 37.3);
        assert_eq!(view["outputs"]["ids"], format!("o{k}.npy"));
        assert_eq!(view["outputs"]["depth"], format!("od{k}.npy"));
        let f = 96.0 / (2.0 * (37.3f64.to_radians() / 2.0).tan());
        let km = &view["K"];
        assert!((km[0][0].as_f64().unwrap() / f - 1.0).abs() < 1e-12, "{km}");
        assert_eq!(
            (km[0][2].as_f64(), km[1][2].as_f64()),
            (Some(48.0), Some(32.0))
        );
        assert_eq!(km[2], serde_json::json!([0.0, 0.0, 1.0]));
        // the matrix takes the eye to the origin and the look point onto +z
        let m = &view["world_to_camera"];
        let apply = |p: &serde_json::Value| -> [f64; 3] {
            std::array::from_fn(|i| {
                (0..3)
                    .map(|j| m[i][j].as_f64().unwrap() * p[j].as_f64().unwrap())
                    .sum::<f64>()
                    + m[i][3].as_f64().unwrap()
            })
        };
        let eye = apply(&view["camera"]["eye"]);
        assert!(eye.iter().all(|c| c.abs() < 1e-9), "{eye:?}");
        let look = apply(&view["camera"]["look"]);
        assert!(
            look[0].abs() < 1e-9 && look[1].abs() < 1e-9 && look[2] > 0.0,
            "{look:?}"
        );
        assert_eq!(m[3], serde_json::json!([0.0, 0.0, 0.0, 1.0]));
    }
    // a rig's views: K as given, the matrix as given (to rounding)
    dir.write(
        "rig.txt",
        "extrinsic 1 0 0 0  0 -1 0 0  0 0 -1 9  0 0 0 1 K 70.5 81.25 40.75 20.5\n",
    );
    let o = run(
        &dir.path,
        &[
            "-i", scene, "-size", "96x64", "--views", "rig.txt", "-o", "r%d.png", "--stats",
            "r.json",
        ],
    );
    assert_success(&o, "rig");
    let r = json("r.json");
    let view = &r["views"][0];
    assert_eq!(
        view["K"],
        serde_json::json!([[70.5, 0.0, 40.75], [0.0, 81.25, 20.5], [0.0, 0.0, 1.0]])
    );
    assert_eq!(
        view["camera"]["K"],
        serde_json::json!({"fx": 70.5, "fy": 81.25, "cx": 40.75, "cy": 20.5})
    );
    let want = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, -1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0, 9.0],
    ];
    for (i, row) in want.iter().enumerate() {
        for (j, &x) in row.iter().enumerate() {
            let got = view["world_to_camera"][i][j].as_f64().unwrap();
            assert!((got - x).abs() < 1e-12, "{i},{j}: {got}");
        }
    }
}

#[test]
fn standard_output_carries_one_image_per_view() {
    let dir = TempDir::new("views-stdout");
    let scene = seed_scene(3);
    let o = run(
        &dir.path,
        &[
            "-i",
            scene.to_str().unwrap(),
            "--orbit",
            "4",
            "-o",
            "-",
            "-size",
            "64x48",
        ],
    );
    assert_success(&o, "-o -");
    let png = b"\x89PNG\r\n\x1a\n";
    let starts = o.stdout.windows(8).filter(|w| w == png).count();
    assert_eq!(starts, 4);
    assert!(o.stdout.starts_with(png));
    // with --format bmp and numbered ids beside
    let o = run(
        &dir.path,
        &[
            "-i",
            scene.to_str().unwrap(),
            "--orbit",
            "3",
            "-o",
            "-",
            "--format",
            "bmp",
            "-size",
            "64x48",
            "--ids",
            "i%d.npy",
        ],
    );
    assert_success(&o, "-o - bmp");
    assert_eq!(o.stdout.len(), 3 * (54 + 64 * 48 * 3));
    // the files, each view's with its record (`--skip-existing` reads it)
    let files = ["i0.npy", "i1.npy", "i2.npy"];
    let records = files.map(|f| format!(".{f}.lanecast-view"));
    assert_eq!(
        dir.entries(),
        [&records[..], &files.map(String::from)[..]].concat()
    );
}

/// The share of pixels re-decided in f64 is counted against every rendered view's pixels:
/// four copies of scene 7's camera re-decide four times the pixels of one, and report the
/// same fraction, in `--stats` and in `-time`.
#[test]
fn redecided_fraction_counts_every_views_pixels() {
    let dir = TempDir::new("views-redecided");
    let scene = seed_scene(7);
    let scene = scene.to_str().unwrap();
    let camera = "camera eye 0 0 0 look 0 0 -1 up 0 1 0\n";
    let mut runs = Vec::new();
    for n in [1, 4] {
        dir.write("views.txt", &camera.repeat(n));
        let o = run(
            &dir.path,
            &[
                "-i",
                scene,
                "--views",
                "views.txt",
                "-o",
                "f%d.png",
                "--stats",
                "s.json",
                "-time",
            ],
        );
        assert_success(&o, "views run");
        let stats: serde_json::Value = serde_json::from_slice(&read(&dir.join("s.json"))).unwrap();
        let percent = stderr(&o)
            .lines()
            .find_map(|l| {
                l.split_once(" re-decided in f64: ")
                    .map(|(_, r)| r.to_string())
            })
            .unwrap_or_else(|| panic!("{}", stderr(&o)));
        runs.push((
            stats["redecided_pixels"].as_u64().unwrap(),
            stats["redecided_fraction"].as_f64().unwrap(),
            percent,
        ));
    }
    let (one, four) = (&runs[0], &runs[1]);
    assert!(one.0 > 0, "scene 7 re-decides some pixels: {runs:?}");
    assert_eq!(four.0, 4 * one.0, "{runs:?}");
    assert_eq!(one.1, one.0 as f64 / (640.0 * 480.0), "{runs:?}");
    assert_eq!(four.1, one.1, "{runs:?}");
    // the text gives the same percentage, of every view's pixels
    let pct = |t: &str| {
        t.split_once('(')
            .unwrap()
            .1
            .split('%')
            .next()
            .unwrap()
            .to_string()
    };
    assert_eq!(pct(&four.2), pct(&one.2), "{runs:?}");
    assert!(four.2.contains("of 4 views' pixels"), "{runs:?}");
}

//! Many views from one run (`--views FILE`, `--orbit N`): every view's ids and depths equal a
//! one-view run with the same camera, byte for byte, whatever the acceleration or thread count;
//! numbered outputs, `-o -` as a stream of images, `--skip-existing`, and the refusals that
//! come before anything is written.

mod common;

use common::*;
use glam::DVec3;
use lanecast::scene::views::orbit;
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
                for (k, [eye, look, up, fov]) in flags.iter().enumerate() {
                    let o = run(
                        &dir.path,
                        &[
                            "-i",
                            scene_s,
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
                            "none",
                            "-o",
                            "one.bmp",
                            "--ids",
                            "one_i.npy",
                            "--depth",
                            "one_d.npy",
                        ],
                    );
                    assert_success(&o, "one view");
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
    assert_eq!(dir.entries(), ["i0.npy", "i1.npy", "i2.npy"]);
}

#[test]
fn skip_existing_renders_only_missing_views() {
    let dir = TempDir::new("views-skip");
    let scene = seed_scene(5);
    let args = |extra: &[&'static str]| {
        let mut a = vec![
            "-i",
            scene.to_str().unwrap(),
            "--orbit",
            "5",
            "-o",
            "f%d.png",
            "--ids",
            "i%d.npy",
            "--stats",
            "s.json",
            "-size",
            "64x48",
        ];
        a.extend_from_slice(extra);
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    fn as_refs(v: &[String]) -> Vec<&str> {
        v.iter().map(String::as_str).collect()
    }
    let full = args(&[]);
    assert_success(&run(&dir.path, &as_refs(&full)), "first run");
    let before: Vec<Vec<u8>> = (0..5)
        .map(|k| read(&dir.join(&format!("i{k}.npy"))))
        .collect();
    fs::remove_file(dir.join("f2.png")).unwrap();
    fs::remove_file(dir.join("i4.npy")).unwrap();
    fs::write(dir.join("i0.npy"), b"kept").unwrap();
    let again = args(&["--skip-existing"]);
    assert_success(&run(&dir.path, &as_refs(&again)), "rerun");
    let stats: serde_json::Value = serde_json::from_slice(&read(&dir.join("s.json"))).unwrap();
    assert_eq!(stats["views"]["rendered"], 2);
    assert_eq!(stats["views"]["skipped"], 3);
    // each rendered view records what it left out and how many renders it took; the first
    // view of a run has nothing to guess from and leaves nothing out
    let each = stats["views"]["each"].as_array().unwrap();
    assert_eq!(each.len(), 2);
    assert_eq!(
        (each[0]["left_out"].as_u64(), each[0]["renders"].as_u64()),
        (Some(0), Some(1))
    );
    assert!(
        each.iter()
            .all(|v| v["renders"].as_u64().is_some_and(|r| (1..=3).contains(&r)))
    );
    assert_eq!(
        read(&dir.join("i0.npy")),
        b"kept",
        "a complete view is left alone"
    );
    for (k, was) in before.iter().enumerate().skip(1) {
        assert!(read(&dir.join(&format!("i{k}.npy"))) == *was, "view {k}");
        assert!(dir.join(&format!("f{k}.png")).is_file());
    }
    // --skip-existing needs views
    let o = run(
        &dir.path,
        &["-i", scene.to_str().unwrap(), "--skip-existing"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--skip-existing applies to runs of many views"),
        "{}",
        stderr(&o)
    );
}

/// Each refusal: exit 2, the message, and nothing written in the folder.
#[test]
fn bad_views_and_patterns_are_refused_before_anything_is_written() {
    let dir = TempDir::new("views-bad");
    let scene = seed_scene(1);
    let scene = scene.to_str().unwrap();
    dir.write(
        "good.txt",
        "camera eye 0 2 9 look 0 0 0 up 0 1 0\ncamera eye 9 2 0 look 0 0 0 up 0 1 0\n",
    );
    dir.write(
        "bad.txt",
        "camera eye 0 2 9 look 0 0 0 up 0 1 0\n# fine\ncamera eye 1 2 x look 0 0 0 up 0 1 0\n",
    );
    dir.write(
        "parallel.txt",
        "camera eye 0 2 9 look 0 0 0 up 0 1 0\ncamera eye 0 9 0 look 0 0 0 up 0 1 0\n",
    );
    dir.write("shape.txt", "sphere 0 0 0 1\n");
    let cases: &[(&[&str], &str)] = &[
        (&["--views", "bad.txt", "-o", "f%d.png"], "bad.txt:3:16:"),
        (
            &["--views", "parallel.txt", "-o", "f%d.png"],
            "parallel.txt:2:",
        ),
        (
            &["--views", "shape.txt", "-o", "f%d.png"],
            "shape.txt:1:1: expected a camera line",
        ),
        (
            &["--views", "good.txt", "-o", "f.png"],
            "-o f.png: it holds no %d",
        ),
        (
            &["--views", "good.txt", "-o", "f%d.png", "--ids", "i.npy"],
            "--ids i.npy: it holds no %d",
        ),
        (
            &[
                "--orbit",
                "12",
                "-o",
                "f%d.png",
                "--ids",
                "a%d.npy",
                "--depth",
                "a%02d.npy",
            ],
            "would both write",
        ),
        (
            &[
                "--views",
                "good.txt",
                "-o",
                "f%d.png",
                "--ids",
                "good%d.txt",
            ],
            "must end in .npy",
        ),
        (
            &["--orbit", "3", "-o", "f%d.png", "--stats", "s%d.json"],
            "one record covers every view",
        ),
        (
            &["--views", "good.txt", "--eye", "1,2,3", "-o", "f%d.png"],
            "--eye: --views good.txt gives every view's camera",
        ),
        (
            &["--orbit", "3", "--repeat", "2", "-o", "f%d.png"],
            "--repeat 2",
        ),
        (
            &["--orbit", "3", "--views", "good.txt", "-o", "f%d.png"],
            "cannot be used with",
        ),
        (&["--orbit", "0", "-o", "f%d.png"], "--orbit"),
        (
            &["--orbit", "2", "-o", "f%d.png", "-fov", "180"],
            "field of view",
        ),
    ];
    let before = dir.entries();
    for (extra, needle) in cases {
        let mut args = vec!["-i", scene];
        args.extend_from_slice(extra);
        let o = run(&dir.path, &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert_eq!(dir.entries(), before, "{args:?} wrote something");
    }
    // a views file that cannot be read is an I/O error, as a scene's is
    let o = run(
        &dir.path,
        &["-i", scene, "--views", "missing.txt", "-o", "f%d.png"],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("missing.txt: cannot read views"),
        "{}",
        stderr(&o)
    );
    assert_eq!(dir.entries(), before);
    // an output pattern naming the views file itself
    dir.write("v0.npy", "camera eye 0 2 9 look 0 0 0 up 0 1 0\n");
    let o = run(
        &dir.path,
        &[
            "-i", scene, "--views", "v0.npy", "-o", "f%d.png", "--ids", "v%d.npy",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("is the views file"), "{}", stderr(&o));
}

/// A run killed part way leaves its finished views whole and no temporary file; a rerun with
/// `--skip-existing` completes the set, equal to an uninterrupted run.
#[cfg(unix)]
#[test]
fn a_killed_run_keeps_finished_views_and_a_rerun_completes_them() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let dir = TempDir::new("views-kill");
    // slow enough per view (scalar f64 kernel, no acceleration) to be killed in the middle
    let mut text = String::from("camera eye 0 0 30 look 0 0 0 up 0 1 0\n");
    for i in 0..200 {
        text += &format!(
            "sphere {} {} 0 0.4\n",
            (i % 20) as f64 - 10.0,
            (i / 20) as f64 - 5.0
        );
    }
    dir.write("s.sc", &text);
    let args = [
        "-i",
        "s.sc",
        "--orbit",
        "12",
        "-size",
        "320x240",
        "--kernel",
        "scalar",
        "--accel",
        "none",
        "--threads",
        "1",
        "-o",
        "f%02d.png",
        "--ids",
        "i%02d.npy",
    ];
    let mut child = Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args(args)
        .current_dir(&dir.path)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !dir.join("i01.npy").exists() && start.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let entries = dir.entries();
    let done: Vec<usize> = (0..12)
        .filter(|k| dir.join(&format!("i{k:02}.npy")).exists())
        .collect();
    assert!(
        !done.is_empty() && done.len() < 12,
        "killed with {done:?} done"
    );
    for &k in &done {
        assert!(
            dir.join(&format!("f{k:02}.png")).exists(),
            "view {k} is whole: {entries:?}"
        );
    }
    // the next run removes the killed run's temporaries, then fills in the rest
    let mut again: Vec<&str> = args.to_vec();
    again.push("--skip-existing");
    assert_success(&run(&dir.path, &again), "rerun");
    let after = dir.entries();
    assert!(
        after.iter().all(|e| !e.ends_with(".lanecast-tmp")),
        "{after:?}"
    );
    let fresh = TempDir::new("views-kill-fresh");
    fresh.write("s.sc", &text);
    assert_success(&run(&fresh.path, &args), "uninterrupted");
    for k in 0..12 {
        for name in [format!("f{k:02}.png"), format!("i{k:02}.npy")] {
            assert!(read(&dir.join(&name)) == read(&fresh.join(&name)), "{name}");
        }
    }
}

/// A view whose eye puts a primitive outside the f32 range rule (scene 6's flat star seen from
/// 4e-16 off its plane, an edge pointing at the eye) is refused before any view renders,
/// naming the views file's line and the scene's; the orbit that crosses that plane does so
/// exactly (quarter turns are exact) and renders whole.
#[test]
fn a_view_out_of_range_is_refused_before_anything_renders() {
    let dir = TempDir::new("views-range");
    let scene = seed_scene(6);
    let scene = scene.to_str().unwrap();
    dir.write(
        "v.txt",
        "camera eye 0 0 7 look 0 0 0 up 0 1 0\ncamera eye 7 0 4.3e-16 look 0 0 0 up 0 1 0\n",
    );
    let o = run(
        &dir.path,
        &["-i", scene, "--views", "v.txt", "-o", "f%d.png"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("v.txt:2: view 1:") && e.contains("scene6.sc:"),
        "{e}"
    );
    assert_eq!(dir.entries(), ["v.txt"]);
    let o = run(
        &dir.path,
        &["-i", scene, "--orbit", "12", "-o", "o%02d.png"],
    );
    assert_success(&o, "scene 6 orbit");
    assert_eq!(dir.entries().len(), 13);
}

/// Two many-view runs writing different frames into one folder at once both complete: each
/// view's set takes the folder's lock only to create its temporaries and to commit.
#[cfg(unix)]
#[test]
fn concurrent_view_runs_into_one_folder_both_complete() {
    use std::process::{Command, Stdio};
    let dir = TempDir::new("views-concurrent");
    let scene = seed_scene(2);
    let scene = scene.to_str().unwrap();
    let spawn = |prefix: &str| {
        Command::new(env!("CARGO_BIN_EXE_lanecast"))
            .args([
                "-i",
                scene,
                "--orbit",
                "8",
                "-size",
                "160x120",
                "--threads",
                "1",
            ])
            .args([
                "-o",
                &format!("{prefix}%d.png"),
                "--ids",
                &format!("{prefix}%d.npy"),
            ])
            .current_dir(&dir.path)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let (a, b) = (spawn("a"), spawn("b"));
    for child in [a, b] {
        let o = child.wait_with_output().unwrap();
        assert_success(&o, "concurrent view run");
    }
    for k in 0..8 {
        let (ia, ib) = (format!("a{k}.npy"), format!("b{k}.npy"));
        assert!(read(&dir.join(&ia)) == read(&dir.join(&ib)), "view {k}");
    }
    let entries = dir.entries();
    assert_eq!(entries.len(), 32, "{entries:?}");
}

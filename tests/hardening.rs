//! Hardening through the real binary: every rejected input in tests/bad/ ends in a
//! clear message, exit code 2 and no output; failed or interrupted runs never damage an
//! existing output file nor leave a temporary file; numbers that parse but break f32
//! arithmetic are rejected or rendered without NaN; regressions found by fuzzing.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicU64, Ordering};

const CAM: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0\n";

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_lanecast"))
}

fn bad_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("bad")
}

/// A fresh, empty folder under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        static N: AtomicU64 = AtomicU64::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!(
            "lanecast-hardening-{}-{n}-{name}",
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// Entry names, sorted (temporary files included).
    fn entries(&self) -> Vec<String> {
        entries(&self.0)
    }
}

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

impl Drop for TempDir {
    fn drop(&mut self) {
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let _ = fs::set_permissions(&self.0, fs::Permissions::from_mode(0o755));
        }
        let _ = fs::remove_dir_all(&self.0);
    }
}

fn run(args: &[&std::ffi::OsStr]) -> Output {
    bin().args(args).output().expect("run lanecast")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Renders `input` small into `out` with ids and depth next to it; returns the output.
fn render_into(input: &Path, out: &TempDir) -> Output {
    let (png, ids, depth) = (
        out.path("out.png"),
        out.path("ids.npy"),
        out.path("depth.npy"),
    );
    run(&[
        "-i".as_ref(),
        input.as_os_str(),
        "-o".as_ref(),
        png.as_os_str(),
        "--ids".as_ref(),
        ids.as_os_str(),
        "--depth".as_ref(),
        depth.as_os_str(),
        "-size".as_ref(),
        "32x24".as_ref(),
    ])
}

/// Files in tests/bad/ whose first line cannot carry an `# expect:` comment.
const NO_HEADER: [(&str, Option<usize>); 1] = [("empty.sc", None)];

/// The expected line of a fixture: from `# expect: N` (`-`: whole-file error, no line).
fn expected_line(path: &Path) -> Option<usize> {
    let name = path.file_name().unwrap().to_str().unwrap();
    if let Some((_, line)) = NO_HEADER.iter().find(|(n, _)| *n == name) {
        return *line;
    }
    let bytes = fs::read(path).unwrap();
    let first = bytes.split(|&b| b == b'\n').next().unwrap();
    let first = std::str::from_utf8(first).unwrap();
    let spec = first
        .strip_prefix("# expect: ")
        .unwrap_or_else(|| panic!("{name}: first line must be `# expect: LINE (why)`"));
    let word = spec.split_whitespace().next().unwrap();
    if word == "-" {
        None
    } else {
        Some(word.parse().unwrap())
    }
}

/// Asserts a rejected run: exit 2, one `lanecast: error: ` message naming the file and the
/// line, and nothing written into `out`.
fn assert_rejected(input: &Path, line: Option<usize>, o: &Output, out: &TempDir) {
    let name = input.file_name().unwrap().to_str().unwrap();
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{name}: {err}");
    assert!(err.starts_with("lanecast: error: "), "{name}: {err:?}");
    let at = match line {
        Some(l) => format!("{name}:{l}:"),
        None => format!("{name}: "),
    };
    assert!(err.contains(&at), "{name}: expected {at:?} in {err:?}");
    assert_eq!(
        err.lines().count(),
        1,
        "{name}: one line of message: {err:?}"
    );
    assert!(o.stdout.is_empty(), "{name}");
    assert_eq!(
        out.entries(),
        Vec::<String>::new(),
        "{name}: output appeared"
    );
}

#[test]
fn every_bad_fixture_is_rejected_with_its_line_and_no_output() {
    let mut checked = 0;
    for entry in fs::read_dir(bad_dir()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        if path.extension().is_none_or(|e| e != "sc") || name == "bom_crlf_valid.sc" {
            continue;
        }
        let out = TempDir::new("bad");
        let o = render_into(&path, &out);
        assert_rejected(&path, expected_line(&path), &o, &out);
        checked += 1;
    }
    assert!(checked >= 27, "only {checked} fixtures");
}

#[test]
fn bom_crlf_valid_scene_renders() {
    let out = TempDir::new("bom");
    let o = render_into(&bad_dir().join("bom_crlf_valid.sc"), &out);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
    assert_eq!(out.entries(), ["depth.npy", "ids.npy", "out.png"]);
    let img = fs::read(out.path("out.png")).unwrap();
    assert_eq!(&img[..8], b"\x89PNG\r\n\x1a\n");
    // Both primitives are visible: ids 0 and 1 appear in the id buffer.
    let ids = fs::read(out.path("ids.npy")).unwrap();
    let ids: Vec<i32> = ids[128..]
        .chunks(4)
        .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert!(ids.contains(&0) && ids.contains(&1), "{ids:?}");
}

#[test]
fn one_megabyte_line_is_rejected() {
    let input = TempDir::new("long-in");
    let path = input.path("long_line.sc");
    let mut text = String::from(CAM);
    text.push_str("sphere 0 0 0 1 ");
    text.push_str(&"7 ".repeat(512 * 1024));
    text.push('\n');
    assert!(text.len() > 1 << 20);
    fs::write(&path, text).unwrap();
    let out = TempDir::new("long-out");
    let o = render_into(&path, &out);
    assert_rejected(&path, Some(2), &o, &out);
    assert!(stderr(&o).contains("line is"), "{}", stderr(&o));
    // A long line is reported in bytes, not echoed.
    assert!(stderr(&o).len() < 300);
}

/// A small valid scene written to `dir/name`.
fn good_scene(dir: &TempDir, name: &str) -> PathBuf {
    let p = dir.path(name);
    fs::write(&p, format!("{CAM}sphere 0 0 0 1\n")).unwrap();
    p
}

#[test]
fn missing_output_folder_fails_and_creates_nothing() {
    let dir = TempDir::new("missing");
    let scene = good_scene(&dir, "s.sc");
    for flag in ["-o", "--ids", "--depth"] {
        let target = dir
            .path("nope")
            .join(if flag == "-o" { "x.png" } else { "x.npy" });
        let png = dir.path("ok.png");
        let mut args: Vec<&std::ffi::OsStr> = vec!["-i".as_ref(), scene.as_os_str()];
        if flag != "-o" {
            args.extend(["-o".as_ref(), png.as_os_str()]);
        }
        args.extend([
            flag.as_ref(),
            target.as_os_str(),
            "-size".as_ref(),
            "8x8".as_ref(),
        ]);
        let o = run(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{flag}: {err}");
        assert!(err.starts_with("lanecast: error: "), "{err}");
        assert!(err.contains(&target.display().to_string()), "{err}");
        assert!(!dir.path("nope").exists());
        let _ = fs::remove_file(&png);
        assert_eq!(dir.entries(), ["s.sc"], "{flag}");
    }
}

#[cfg(unix)]
#[test]
fn read_only_folder_keeps_existing_file() {
    use std::os::unix::fs::PermissionsExt;
    let dir = TempDir::new("ro");
    let scene_dir = TempDir::new("ro-scene");
    let scene = good_scene(&scene_dir, "s.sc");
    let target = dir.path("out.png");
    fs::write(&target, b"old").unwrap();
    fs::set_permissions(&dir.0, fs::Permissions::from_mode(0o555)).unwrap();
    let probe = dir.path("probe");
    if fs::File::create(&probe).is_ok() {
        // Running as root: permission bits are not enforced, nothing to test.
        let _ = fs::remove_file(&probe);
        eprintln!("skipped: permissions are not enforced for this user (root?)");
        return;
    }
    let o = run(&[
        "-i".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        target.as_os_str(),
        "-size".as_ref(),
        "8x8".as_ref(),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(&target.display().to_string()), "{err}");
    assert_eq!(fs::read(&target).unwrap(), b"old");
    assert_eq!(dir.entries(), ["out.png"]);
}

#[test]
fn existing_output_survives_a_failed_render() {
    let dir = TempDir::new("survive");
    let scene = dir.path("bad.sc");
    fs::write(&scene, format!("{CAM}sphere 0 0 0 -1\n")).unwrap();
    for (name, old) in [
        ("out.png", "old png"),
        ("ids.npy", "old ids"),
        ("d.npy", "old d"),
    ] {
        fs::write(dir.path(name), old).unwrap();
    }
    let (png, ids, depth) = (dir.path("out.png"), dir.path("ids.npy"), dir.path("d.npy"));
    let o = run(&[
        "-i".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        png.as_os_str(),
        "--ids".as_ref(),
        ids.as_os_str(),
        "--depth".as_ref(),
        depth.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("bad.sc:2:"), "{}", stderr(&o));
    assert_eq!(fs::read(&png).unwrap(), b"old png");
    assert_eq!(fs::read(&ids).unwrap(), b"old ids");
    assert_eq!(fs::read(&depth).unwrap(), b"old d");
    assert_eq!(dir.entries(), ["bad.sc", "d.npy", "ids.npy", "out.png"]);
}

#[test]
fn existing_output_survives_a_failed_write() {
    let dir = TempDir::new("failwrite");
    let scene = good_scene(&dir, "s.sc");
    let old = dir.path("old.png");
    fs::write(&old, b"old").unwrap();
    // A "folder" that is a file.
    let into_file = old.join("x.png");
    let o = run(&[
        "-i".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        into_file.as_os_str(),
        "-size".as_ref(),
        "8x8".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(fs::read(&old).unwrap(), b"old");
    // A target that is a folder: the rename fails, the folder and its content stay.
    let folder = dir.path("dir.png");
    fs::create_dir(&folder).unwrap();
    fs::write(folder.join("keep"), b"k").unwrap();
    let o = run(&[
        "-i".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        folder.as_os_str(),
        "-size".as_ref(),
        "8x8".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(fs::read(folder.join("keep")).unwrap(), b"k");
    // A later output that cannot be written (ids into a file-as-folder): refused before any
    // work, so the image is not written either (the outputs are a set) and nothing temporary
    // is left.
    let png = dir.path("new.png");
    let ids = old.join("ids.npy");
    let o = run(&[
        "-i".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        png.as_os_str(),
        "--ids".as_ref(),
        ids.as_os_str(),
        "-size".as_ref(),
        "8x8".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(fs::read(&old).unwrap(), b"old");
    assert!(stderr(&o).contains("--ids"), "{}", stderr(&o));
    assert_eq!(dir.entries(), ["dir.png", "old.png", "s.sc"]);
}

#[test]
fn output_equal_to_input_is_refused() {
    let dir = TempDir::new("same");
    let other = dir.path("out.png");
    for flag in ["-o", "--ids", "--depth"] {
        // The scene is named like the output so that only the same-file rule can refuse it.
        let name = if flag == "-o" {
            "scene.png"
        } else {
            "scene.npy"
        };
        let scene = good_scene(&dir, name);
        let text = fs::read(&scene).unwrap();
        let mut args: Vec<&std::ffi::OsStr> = vec!["-i".as_ref(), scene.as_os_str()];
        if flag != "-o" {
            args.extend(["-o".as_ref(), other.as_os_str()]);
        }
        // Same file under another spelling.
        let spelled = dir.0.join(".").join(name);
        args.extend([
            flag.as_ref(),
            spelled.as_os_str(),
            "-size".as_ref(),
            "8x8".as_ref(),
        ]);
        let o = run(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{flag}: {err}");
        assert!(err.starts_with("lanecast: error: "), "{err}");
        assert!(err.contains(flag) && err.contains("input scene"), "{err}");
        assert_eq!(fs::read(&scene).unwrap(), text, "{flag}");
        assert_eq!(dir.entries(), [name], "{flag}");
        fs::remove_file(&scene).unwrap();
    }
}

/// A scene of `n` small spheres in a grid in front of the camera.
fn many_spheres(n: usize) -> String {
    let mut s = String::from("camera eye 0 0 60 look 0 0 0 up 0 1 0\n");
    let side = (n as f64).sqrt().ceil() as usize;
    for i in 0..n {
        let (x, y) = ((i % side) as f64, (i / side) as f64);
        s += &format!(
            "sphere {} {} {} 0.4\n",
            x - side as f64 / 2.0,
            y - side as f64 / 2.0,
            -(i as f64 % 7.0)
        );
    }
    s
}

#[cfg(unix)]
fn sigint(pid: u32) {
    let st = Command::new("kill")
        .args(["-INT", &pid.to_string()])
        .status()
        .unwrap();
    assert!(st.success());
}

#[cfg(unix)]
#[test]
fn sigint_during_render_keeps_previous_output() {
    use std::time::{Duration, Instant};
    let dir = TempDir::new("sigint");
    let scene = dir.path("many.sc");
    fs::write(&scene, many_spheres(2000)).unwrap();
    let out = dir.path("out.png");
    fs::write(&out, b"previous").unwrap();
    let child = bin()
        .args([
            "-i".as_ref(),
            scene.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
        .args([
            "-size",
            "4096x4096",
            "--kernel",
            "scalar",
            "--accel",
            "none",
        ])
        .args(["--threads", "1"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let start = Instant::now();
    sigint(child.id());
    let o = child.wait_with_output().unwrap();
    assert!(start.elapsed() < Duration::from_secs(10));
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(stderr(&o).contains("interrupted"), "{}", stderr(&o));
    assert_eq!(fs::read(&out).unwrap(), b"previous");
    assert_eq!(dir.entries(), ["many.sc", "out.png"]);
}

/// SIGINT while a temporary file exists: the handler removes it. The write is short, so the test
/// polls for the temporary file; if the run finishes first it retries, and only checks the
/// final state (complete outputs, no temporary file) when it never catches one.
#[cfg(unix)]
#[test]
fn sigint_during_write_removes_temporary_file() {
    use std::time::{Duration, Instant};
    let dir = TempDir::new("sigint-write");
    let scene_dir = TempDir::new("sigint-write-scene");
    let scene = scene_dir.path("s.sc");
    fs::write(&scene, format!("{CAM}sphere 0 0 0 1\n")).unwrap();
    let (png, ids, depth) = (
        dir.path("out.png"),
        dir.path("ids.npy"),
        dir.path("depth.npy"),
    );
    let mut caught = 0;
    for _attempt in 0..5 {
        for p in [&png, &ids, &depth] {
            fs::write(p, b"previous").unwrap();
        }
        let mut child = bin()
            .args([
                "-i".as_ref(),
                scene.as_os_str(),
                "-o".as_ref(),
                png.as_os_str(),
            ])
            .args([
                "--ids".as_ref(),
                ids.as_os_str(),
                "--depth".as_ref(),
                depth.as_os_str(),
            ])
            .args(["-size", "4096x4096", "--threads", "1"])
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let deadline = Instant::now() + Duration::from_secs(60);
        let mut sent = false;
        while Instant::now() < deadline {
            if child.try_wait().unwrap().is_some() {
                break;
            }
            if dir.entries().iter().any(|e| e.ends_with(".lanecast-tmp")) {
                sigint(child.id());
                sent = true;
                break;
            }
            std::thread::sleep(Duration::from_micros(500));
        }
        let o = child.wait_with_output().unwrap();
        let names = dir.entries();
        assert!(
            !names.iter().any(|e| e.ends_with(".lanecast-tmp")),
            "temporary file left: {names:?}"
        );
        assert_eq!(names, ["depth.npy", "ids.npy", "out.png"]);
        if sent && o.status.code() == Some(130) {
            caught += 1;
            // Each output is either the previous content or a complete new file.
            for (p, len) in [
                (&ids, 128 + 4 * 4096 * 4096),
                (&depth, 128 + 4 * 4096 * 4096),
            ] {
                let n = fs::metadata(p).unwrap().len();
                assert!(n == 8 || n == len as u64, "{}: {n} bytes", p.display());
            }
            break;
        }
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
    eprintln!("caught a temporary file in {caught} of the runs");
}

// ---- Numbers that parse but break f32 arithmetic (README: "Limits") ----

fn scene_in(dir: &TempDir, body: &str) -> PathBuf {
    let p = dir.path("s.sc");
    fs::write(&p, body).unwrap();
    p
}

/// Renders `body` 64x48 with both the packet and the f64 scalar kernel; returns the id buffers
/// and asserts no NaN depth, and that `lanecast compare` finds no unexcused mismatch.
fn render_both(body: &str) -> Vec<Vec<i32>> {
    let dir = TempDir::new("numeric");
    let scene = scene_in(&dir, body);
    let o = run(&[
        "compare".as_ref(),
        "-i".as_ref(),
        scene.as_os_str(),
        "-size".as_ref(),
        "64x48".as_ref(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "compare: {}{}",
        String::from_utf8_lossy(&o.stdout),
        stderr(&o)
    );
    let mut all = Vec::new();
    for kernel in ["simd", "scalar"] {
        let (png, ids, depth) = (dir.path("o.png"), dir.path("i.npy"), dir.path("d.npy"));
        let o = run(&[
            "-i".as_ref(),
            scene.as_os_str(),
            "-o".as_ref(),
            png.as_os_str(),
            "--ids".as_ref(),
            ids.as_os_str(),
            "--depth".as_ref(),
            depth.as_os_str(),
            "-size".as_ref(),
            "64x48".as_ref(),
            "--kernel".as_ref(),
            kernel.as_ref(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{kernel}: {}", stderr(&o));
        let d = fs::read(&depth).unwrap();
        let nan = d[128..]
            .chunks(4)
            .any(|c| f32::from_le_bytes(c.try_into().unwrap()).is_nan());
        assert!(!nan, "{kernel}: NaN depth");
        let i = fs::read(&ids).unwrap();
        all.push(
            i[128..]
                .chunks(4)
                .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
                .collect(),
        );
    }
    all
}

fn rejected_with(body: &str, line: usize, words: &[&str]) {
    let dir = TempDir::new("numeric-bad");
    let scene = scene_in(&dir, body);
    let out = TempDir::new("numeric-bad-out");
    let o = render_into(&scene, &out);
    assert_rejected(&scene, Some(line), &o, &out);
    for w in words {
        assert!(stderr(&o).contains(w), "{w:?} not in {}", stderr(&o));
    }
}

#[test]
fn coordinates_near_f32_max_far_from_the_eye_are_rejected() {
    rejected_with(
        &format!("{CAM}sphere 3e38 0 0 1\n"),
        2,
        &["from the camera eye"],
    );
    rejected_with(
        &format!("{CAM}sphere 0 0 0 1\nquad 0 0 -3e38  1 0 -3e38  1 1 -3e38  0 1 -3e38\n"),
        3,
        &["vertex A", "from the camera eye"],
    );
    rejected_with(
        &format!("{CAM}sphere 0 0 0 2e18\n"),
        2,
        &["from the camera eye"],
    );
}

#[test]
fn huge_coordinates_near_the_eye_render() {
    // Absolute coordinates of 1e33 (f32 could not even place them: its spacing there is 1e26),
    // but eye-relative values of at most 6e17: the kernels subtract the eye in f64, so this
    // renders. (Near 3e38 itself, f64's own spacing is 6e22 > MAX_EYE_DISTANCE, so a scene
    // there is always rejected unless a primitive sits exactly on the eye.)
    let far = "camera eye 1e33 1e33 1.0000000000000005e33 look 1e33 1e33 1e33 up 0 1 0\n\
               sphere 1e33 1e33 1e33 1e17\n";
    let ids = render_both(far);
    assert!(ids[0].contains(&0) && ids[0].contains(&-1));
}

#[test]
fn radius_below_the_f32_limit_is_rejected() {
    rejected_with(
        &format!("{CAM}sphere 0 0 0 1e-30\n"),
        2,
        &["radius", "1e-30"],
    );
    // At the limit a tiny sphere seen from close up renders, identically in both kernels.
    let ids = render_both("camera eye 0 0 5e-18 look 0 0 0 up 0 1 0\nsphere 0 0 0 1e-18\n");
    assert!(ids[0].contains(&0) && ids[1].contains(&0));
}

#[test]
fn triangle_whose_area_underflows_f32_renders() {
    // Sides of 1e-20: twice the area is 1e-40, below the smallest normal f32 (1.2e-38) but
    // fine in f64. The edge planes are normalised in f64 before rounding, so the f32 kernel
    // sees unit normals and renders it like the same triangle at scale 1.
    let tiny = "camera eye 0 0 5e-20 look 0 0 0 up 0 1 0\n\
                triangle -1e-20 -1e-20 0  1e-20 -1e-20 0  0 1e-20 0\n";
    let unit = "camera eye 0 0 5 look 0 0 0 up 0 1 0\ntriangle -1 -1 0  1 -1 0  0 1 0\n";
    let (a, b) = (render_both(tiny), render_both(unit));
    let hits = |ids: &[i32]| ids.iter().filter(|&&i| i == 0).count();
    assert!(hits(&a[0]) > 100);
    // Scale 1e-20 renders as scale 1, up to rounding on edge pixels.
    assert!(
        hits(&a[0]).abs_diff(hits(&b[0])) <= 4,
        "{} vs {}",
        hits(&a[0]),
        hits(&b[0])
    );
}

#[test]
fn eye_a_hair_off_a_polygon_plane_is_rejected() {
    rejected_with(
        "camera eye 0.2 0.2 1e-300 look 0 0 -1 up 0 1 0\ntriangle 0 0 0  1 0 0  0 1 0\n",
        2,
        &["plane", "f32"],
    );
    // In the plane exactly: accepted (seen edge-on, the triangle covers no pixel).
    let ids = render_both("camera eye 5 5 0 look 0 0 -1 up 0 1 0\ntriangle 0 0 0  1 0 0  0 1 0\n");
    assert!(ids[0].iter().all(|&i| i == -1));
}

// ---- Limits (src/limits.rs), each refused before the allocation it guards ----

#[test]
fn image_limits_are_refused_before_any_work() {
    use lanecast::limits::{MAX_PIXELS, MAX_SIDE};
    let dir = TempDir::new("limits");
    let scene = good_scene(&dir, "s.sc");
    let out = dir.path("o.png");
    let too_wide = format!("{}x1", MAX_SIDE + 1);
    let side = (MAX_PIXELS as f64).sqrt() as u64 + 1;
    let too_many = format!("{side}x{side}");
    for size in [too_wide.as_str(), too_many.as_str()] {
        let t = std::time::Instant::now();
        let o = run(&[
            "-i".as_ref(),
            scene.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
            "-size".as_ref(),
            size.as_ref(),
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{size}: {err}");
        assert!(err.starts_with("lanecast: error: -size"), "{err}");
        assert!(t.elapsed().as_secs() < 5, "{size}: refused late");
    }
    assert_eq!(dir.entries(), ["s.sc"]);
}

#[test]
fn scene_file_over_the_size_limit_is_refused_before_reading() {
    use lanecast::limits::MAX_SCENE_BYTES;
    let dir = TempDir::new("bigfile");
    let path = dir.path("huge.sc");
    // A sparse file: no disk space used, and lanecast must not read it.
    fs::File::create(&path)
        .unwrap()
        .set_len(MAX_SCENE_BYTES + 1)
        .unwrap();
    let out = TempDir::new("bigfile-out");
    let t = std::time::Instant::now();
    let o = render_into(&path, &out);
    assert_rejected(&path, None, &o, &out);
    assert!(stderr(&o).contains("limit"), "{}", stderr(&o));
    assert!(t.elapsed().as_secs() < 5);
}

// ---- Regressions found by fuzzing (fuzz/, CONTRIBUTING.md) ----

/// fuzz `render` crash-89bb9530: a 12-unit triangle seen from 5e17 away. Subtracting the eye
/// in f64 (spacing 64 there) merged two vertices, one edge plane normal became zero, and the
/// triangle turned into an endless wedge: the packet kernel drew it across the image where the
/// oracle did not. Now rejected: its edges subtend less than `limits::MIN_EDGE_ANGLE`.
#[test]
fn fuzz_far_tiny_triangle_collapses_eye_relative() {
    rejected_with(
        "# Sc 4: along theg bes show f-1\n\
         triangle -6 2 -1   6 2 1   6 2 -1.\n\
         \n\
         camera eye -5e17 5.19 8.68 look -5.02 0.38 -0.25 up 0 07 1\n",
        2,
        &["triangle edge", "subtends", "rad"],
    );
    // The same triangle from an ordinary distance renders, both kernels agreeing.
    let ids = render_both(
        "triangle -6 2 -1   6 2 1   6 2 -1.\n\
         camera eye -5 5.19 8.68 look -5.02 0.38 -0.25 up 0 07 1\n",
    );
    assert!(ids[0].contains(&0));
}

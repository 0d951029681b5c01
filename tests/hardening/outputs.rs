//! Failed and interrupted runs: existing outputs kept, no temporary left.

use super::*;

#[test]
fn missing_output_folder_fails_and_creates_nothing() {
    let dir = TempDir::new("missing");
    let scene = good_scene(&dir, "s.sc");
    for flag in ["-o", "--ids", "--depth"] {
        let target = dir
            .join("nope")
            .join(if flag == "-o" { "x.png" } else { "x.npy" });
        let png = dir.join("ok.png");
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
        assert!(!dir.join("nope").exists());
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
    let target = dir.join("out.png");
    fs::write(&target, b"old").unwrap();
    fs::set_permissions(&dir.path, fs::Permissions::from_mode(0o555)).unwrap();
    let probe = dir.join("probe");
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
    let scene = dir.join("bad.sc");
    fs::write(&scene, format!("{CAM}sphere 0 0 0 -1\n")).unwrap();
    for (name, old) in [
        ("out.png", "old png"),
        ("ids.npy", "old ids"),
        ("d.npy", "old d"),
    ] {
        fs::write(dir.join(name), old).unwrap();
    }
    let (png, ids, depth) = (dir.join("out.png"), dir.join("ids.npy"), dir.join("d.npy"));
    let o = render_outputs(&scene, [&png, &ids, &depth], &[]);
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
    let old = dir.join("old.png");
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
    let folder = dir.join("dir.png");
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
    let png = dir.join("new.png");
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
    let other = dir.join("out.png");
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
        let spelled = dir.path.join(".").join(name);
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
    let scene = dir.join("many.sc");
    fs::write(&scene, many_spheres(2000)).unwrap();
    let out = dir.join("out.png");
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
    let scene = scene_dir.join("s.sc");
    fs::write(&scene, format!("{CAM}sphere 0 0 0 1\n")).unwrap();
    let (png, ids, depth) = (
        dir.join("out.png"),
        dir.join("ids.npy"),
        dir.join("depth.npy"),
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

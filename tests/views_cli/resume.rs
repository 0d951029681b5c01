//! Runs that stop, skip or share a folder: finished views kept whole, reruns completing them.

use super::*;

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
    // a complete view is one whose files are whole and hold the bytes its record names: a
    // valid .npy of the right shape, with other values, is not this run's and is rendered
    // again
    let mut changed = before[0].clone();
    *changed.last_mut().unwrap() ^= 0x55;
    fs::write(dir.join("i0.npy"), &changed).unwrap();
    let again = args(&["--skip-existing"]);
    assert_success(&run(&dir.path, &as_refs(&again)), "rerun");
    let stats: serde_json::Value = serde_json::from_slice(&read(&dir.join("s.json"))).unwrap();
    assert_eq!(stats["views_summary"]["rendered"], 3);
    assert_eq!(stats["views_summary"]["skipped"], 2);
    // each rendered view records what it left out and how many renders it took; the first
    // view of a run has nothing to guess from and leaves nothing out
    let views = stats["views"].as_array().unwrap();
    assert_eq!(views.len(), 5);
    let each: Vec<_> = views.iter().filter(|v| v["skipped"] == false).collect();
    assert_eq!(each.len(), 3);
    assert!(
        views
            .iter()
            .filter(|v| v["skipped"] == true)
            .all(|v| v["render_s"].is_null())
    );
    assert_eq!(
        (each[0]["left_out"].as_u64(), each[0]["renders"].as_u64()),
        (Some(0), Some(1))
    );
    assert!(
        each.iter()
            .all(|v| v["renders"].as_u64().is_some_and(|r| (1..=3).contains(&r)))
    );
    for (k, was) in before.iter().enumerate() {
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
    // each view's two files and its record, for both runs
    let entries = dir.entries();
    assert_eq!(entries.len(), 48, "{entries:?}");
}

/// A view counts as complete only when every output it names is whole: a 0-byte or truncated
/// PNG, BMP or `.npy`, or one of another size, is rendered again (and rewritten equal to a
/// fresh run's), while the whole views are left alone.
#[test]
fn skip_existing_renders_views_whose_files_are_truncated_or_empty() {
    let dir = TempDir::new("views-skip-valid");
    let scene = seed_scene(2);
    let scene = scene.to_str().unwrap();
    for ext in ["png", "bmp"] {
        let image = format!("f%d.{ext}");
        let args = [
            "-i", scene, "--orbit", "6", "-size", "64x48", "-o", &image, "--ids", "i%d.npy",
            "--depth", "d%d.npy",
        ];
        assert_success(&run(&dir.path, &args), "first run");
        let names = |k: usize| {
            [
                format!("f{k}.{ext}"),
                format!("i{k}.npy"),
                format!("d{k}.npy"),
            ]
        };
        let before: Vec<Vec<Vec<u8>>> = (0..6)
            .map(|k| names(k).iter().map(|n| read(&dir.join(n))).collect())
            .collect();
        let cut = |name: String, keep: &dyn Fn(usize) -> usize| {
            let bytes = read(&dir.join(&name));
            fs::write(dir.join(&name), &bytes[..keep(bytes.len())]).unwrap();
        };
        cut(format!("f0.{ext}"), &|_| 0); // 0 bytes
        cut(format!("f1.{ext}"), &|n| n - 1); // the PNG's IEND cut short, the BMP's last row
        cut("i2.npy".into(), &|n| n - 4); // one value short
        cut("d3.npy".into(), &|_| 100); // a header alone
        // the same file at another size: whole, but not this run's
        let small = TempDir::new("views-skip-valid-small");
        let other = [
            "-i", scene, "-size", "32x48", "-o", "x.png", "--ids", "x.npy", "--eye", "0,2,9",
        ];
        assert_success(&run(&small.path, &other), "another size");
        fs::copy(small.join("x.npy"), dir.join("i4.npy")).unwrap();
        let mut again = args.to_vec();
        again.extend(["--skip-existing", "--stats", "s.json"]);
        assert_success(&run(&dir.path, &again), "rerun");
        let stats: serde_json::Value = serde_json::from_slice(&read(&dir.join("s.json"))).unwrap();
        assert_eq!(
            (
                stats["views_summary"]["rendered"].as_u64(),
                stats["views_summary"]["skipped"].as_u64()
            ),
            (Some(5), Some(1)),
            "{ext}: views 0-4 had a broken file, view 5 was whole"
        );
        for (k, was) in before.iter().enumerate() {
            for (name, bytes) in names(k).iter().zip(was) {
                assert!(read(&dir.join(name)) == *bytes, "{name} rewritten whole");
            }
        }
    }
}

/// `-time` when `--skip-existing` left out every view says so, with no NaN or negative time;
/// the record's counts agree.
#[test]
fn time_says_no_view_rendered_when_every_view_was_skipped() {
    let dir = TempDir::new("views-skip-all");
    let scene = seed_scene(1);
    let scene = scene.to_str().unwrap();
    let args = [
        "-i", scene, "--orbit", "3", "-size", "32x24", "-o", "f%d.png",
    ];
    assert_success(&run(&dir.path, &args), "first run");
    let mut again = args.to_vec();
    again.extend(["--skip-existing", "-time", "--stats", "s.json"]);
    let o = run(&dir.path, &again);
    assert_success(&o, "rerun");
    let err = stderr(&o);
    assert!(err.contains("no view rendered: all 3 skipped"), "{err}");
    for bad in ["NaN", "inf", "-0.000"] {
        assert!(!err.contains(bad), "{bad} in: {err}");
    }
    let stats: serde_json::Value = serde_json::from_slice(&read(&dir.join("s.json"))).unwrap();
    assert_eq!(stats["views_summary"]["rendered"], 0);
    assert_eq!(stats["views_summary"]["skipped"], 3);
    assert!(stats["rays_per_s"].is_null(), "no render, no rate");
}

/// `-o -` with `--ids`: the ids files tell which views are done, so `--skip-existing` applies.
#[test]
fn skip_existing_with_stdout_and_ids_streams_only_missing_views() {
    let dir = TempDir::new("views-skip-stdout");
    let scene = seed_scene(1);
    let scene = scene.to_str().unwrap();
    let args = [
        "-i", scene, "--orbit", "3", "-size", "32x24", "-o", "-", "--ids", "i%d.npy",
    ];
    assert_success(&run(&dir.path, &args), "first run");
    fs::remove_file(dir.join("i1.npy")).unwrap();
    let mut again = args.to_vec();
    again.push("--skip-existing");
    let o = run(&dir.path, &again);
    assert_success(&o, "rerun");
    let pngs = o
        .stdout
        .windows(8)
        .filter(|w| *w == b"\x89PNG\r\n\x1a\n")
        .count();
    assert_eq!(pngs, 1, "only view 1 streams again");
}

/// What `--skip-existing` found: (rendered, skipped) from `--stats`, and each view's
/// `skipped`.
fn skips(dir: &TempDir, stats: &str) -> (u64, u64, Vec<bool>) {
    let v: serde_json::Value = serde_json::from_slice(&read(&dir.join(stats))).unwrap();
    let each = (v["views"].as_array().unwrap().iter())
        .map(|v| v["skipped"].as_bool().unwrap())
        .collect();
    let summary = &v["views_summary"];
    (
        summary["rendered"].as_u64().unwrap(),
        summary["skipped"].as_u64().unwrap(),
        each,
    )
}

/// The case: files of a 10-view orbit, then a 12-view orbit with `--skip-existing`
/// into the same names. Every view whose camera differs is rendered again (view 0, the
/// scene's camera in both, is the same view and is kept), and what is on disk, and what
/// `--stats` says of it, is a fresh 12-view run's, byte for byte. An identical rerun skips
/// every view; another colour mode, size, precision, scene content, or a file written over
/// by another run renders again exactly the views it touches.
#[test]
fn skip_existing_renders_again_views_made_with_other_settings() {
    let dir = TempDir::new("views-skip-settings");
    let fresh = TempDir::new("views-skip-fresh");
    dir.copy_in(&seed_scene(1), "s.sc");
    fresh.copy_in(&seed_scene(1), "s.sc");
    let base = [
        "-i",
        "s.sc",
        "-size",
        "64x48",
        "-o",
        "f%02d.png",
        "--ids",
        "i%02d.npy",
    ];
    let with = |extra: &[&'static str]| [&base[..], extra].concat();
    assert_success(&run(&dir.path, &with(&["--orbit", "10"])), "10 views");
    let twelve = with(&["--orbit", "12", "--skip-existing", "--stats", "s.json"]);
    assert_success(&run(&dir.path, &twelve), "12 views over 10");
    let (rendered, skipped, each) = skips(&dir, "s.json");
    assert_eq!((rendered, skipped), (11, 1), "{each:?}");
    assert!(each[0] && each[1..].iter().all(|s| !s), "{each:?}");
    assert_success(&run(&fresh.path, &twelve), "12 views, fresh");
    for k in 0..12 {
        for name in [format!("f{k:02}.png"), format!("i{k:02}.npy")] {
            assert!(read(&dir.join(&name)) == read(&fresh.join(&name)), "{name}");
        }
    }
    let json = |d: &TempDir| -> serde_json::Value {
        serde_json::from_slice(&read(&d.join("s.json"))).unwrap()
    };
    for k in 0..12 {
        for key in ["camera", "K", "world_to_camera", "outputs"] {
            assert_eq!(
                json(&dir)["views"][k][key],
                json(&fresh)["views"][k][key],
                "{k} {key}"
            );
        }
    }
    // the same settings again: nothing to render
    assert_success(&run(&dir.path, &twelve), "the same again");
    assert_eq!(skips(&dir, "s.json").0, 0);
    // each of these makes other files for every view
    for change in [
        &["-cm", "ordered"][..],
        &["-cm", "ordered", "-cv", "log"][..],
        &["-cm", "ordered", "-cv", "log", "--precision", "f64"][..],
    ] {
        let args = [&twelve[..], change].concat();
        assert_success(&run(&dir.path, &args), &format!("{change:?}"));
        assert_eq!(skips(&dir, "s.json").0, 12, "{change:?}");
        assert_success(&run(&dir.path, &args), &format!("{change:?} again"));
        assert_eq!(skips(&dir, "s.json").0, 0, "{change:?} again");
    }
    let now = [
        &twelve[..],
        &["-cm", "ordered", "-cv", "log", "--precision", "f64"],
    ]
    .concat();
    // the scene's content: a sphere's radius, not a comment
    let text = fs::read_to_string(dir.join("s.sc")).unwrap();
    fs::write(dir.join("s.sc"), format!("# a comment\n{text}")).unwrap();
    assert_success(&run(&dir.path, &now), "a comment more");
    assert_eq!(skips(&dir, "s.json").0, 0);
    let bigger = text.replacen("sphere 0 6 0 1\n", "sphere 0 6 0 1.25\n", 1);
    assert_ne!(bigger, text, "scene 1 has its apex sphere");
    fs::write(dir.join("s.sc"), bigger).unwrap();
    assert_success(&run(&dir.path, &now), "another radius");
    assert_eq!(skips(&dir, "s.json").0, 12);
    // a file another run wrote over (a one-view run's image, whole and of this size)
    let one = [
        "-i", "s.sc", "-size", "64x48", "-o", "f05.png", "-cm", "ordered",
    ];
    assert_success(&run(&dir.path, &one), "one view over f05.png");
    // buffers only, another camera, over view 7's ids (its record is another)
    let ids = [
        "-i",
        "s.sc",
        "-size",
        "64x48",
        "--orbit",
        "9",
        "--ids",
        "i%02d.npy",
    ];
    assert_success(&run(&dir.path, &ids), "9 views' ids");
    assert_success(&run(&dir.path, &now), "after the others");
    // views 1 to 8 (view 0's camera is the 9-view orbit's view 0 too); 9 to 11 untouched
    let (_, _, each) = skips(&dir, "s.json");
    assert!(
        each[1..9].iter().all(|s| !s) && each[9..].iter().all(|&s| s),
        "{each:?}"
    );
}

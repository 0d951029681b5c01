//! Temporary files of runs killed with SIGKILL (which no handler sees) are removed by the next
//! run that writes into the same folder; a live run's temporary files are never taken for
//! stale. Each temporary file is locked (flock) by the run that created it for as long as it
//! exists, so a later run removes only those no live process holds.

#![cfg(unix)]

use crate::common;

use common::*;
use std::fs;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn spawn(cwd: &Path, args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args(args)
        .current_dir(cwd)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot start the lanecast binary")
}

fn temporaries(dir: &TempDir) -> Vec<String> {
    dir.entries()
        .into_iter()
        .filter(|e| e.ends_with(".lanecast-tmp"))
        .collect()
}

/// A scene that takes minutes with the scalar kernel and no acceleration at 4000x3000: runs of
/// it are killed long before they finish.
fn slow_scene() -> String {
    let mut s = String::from("camera eye 0 0 30 look 0 0 0 up 0 1 0\n");
    for i in 0..400 {
        let (x, y) = ((i % 20) as f64 - 10.0, (i / 20) as f64 - 10.0);
        s += &format!("sphere {x} {y} 0 0.4\n");
    }
    s
}

const SLOW: [&str; 16] = [
    "-i",
    "slow.sc",
    "-o",
    "out.png",
    "--ids",
    "ids.npy",
    "--depth",
    "depth.npy",
    "-size",
    "4000x3000",
    "--kernel",
    "scalar",
    "--accel",
    "none",
    "--threads",
    "1",
];

const FAST: [&str; 12] = [
    "-i",
    "s.sc",
    "-o",
    "out.png",
    "--ids",
    "ids.npy",
    "--depth",
    "depth.npy",
    "-size",
    "4000x3000",
    "--threads",
    "2",
];

/// Polls (every half millisecond, for at most a minute) until `ready` holds or the child ends;
/// true when `ready` held with the child still running.
fn wait_for(child: &mut Child, mut ready: impl FnMut() -> bool) -> bool {
    let deadline = Instant::now() + Duration::from_secs(60);
    while Instant::now() < deadline {
        if child.try_wait().unwrap().is_some() {
            return false;
        }
        if ready() {
            return true;
        }
        std::thread::sleep(Duration::from_micros(500));
    }
    panic!("the run neither finished nor reached the point in a minute");
}

/// Runs killed with SIGKILL as soon as their temporary files exist, in the middle of the
/// render, and while the image is being written leave those files behind and the previous
/// outputs intact; the next run into the folder (writing another output) removes every one
/// (each killed run here already removes those of the one before).
#[test]
fn temporaries_of_runs_killed_with_sigkill_are_removed_by_the_next_run() {
    let dir = TempDir::new("stale-kill");
    dir.copy_in(&seed_scene(1), "s.sc");
    dir.write("slow.sc", &slow_scene());
    let first = run(
        &dir.path,
        &[
            "-i",
            "s.sc",
            "-o",
            "out.png",
            "--ids",
            "ids.npy",
            "--depth",
            "depth.npy",
            "-size",
            "64x48",
        ],
    );
    assert_success(&first, "the first run");
    let outputs = ["out.png", "ids.npy", "depth.npy"];
    let old: Vec<Vec<u8>> = outputs
        .iter()
        .map(|n| fs::read(dir.join(n)).unwrap())
        .collect();
    let image_temp_written = |dir: &TempDir| {
        temporaries(dir).iter().any(|t| {
            t.starts_with(".out.png.") && fs::metadata(dir.join(t)).is_ok_and(|m| m.len() > 0)
        })
    };
    for point in ["temporaries created", "mid-render", "writing the image"] {
        let mut caught = false;
        for _attempt in 0..5 {
            let mut child = spawn(
                &dir.path,
                if point == "writing the image" {
                    &FAST
                } else {
                    &SLOW
                },
            );
            let mark = format!(".{}.", child.id());
            let own = |dir: &TempDir| {
                let t = temporaries(dir);
                t.into_iter().filter(|t| t.contains(&mark)).count()
            };
            let ready = match point {
                "writing the image" => wait_for(&mut child, || image_temp_written(&dir)),
                _ => wait_for(&mut child, || own(&dir) == 3),
            };
            if ready && point == "mid-render" {
                std::thread::sleep(Duration::from_millis(300));
            }
            child.kill().unwrap(); // SIGKILL
            let status = child.wait().unwrap();
            for (n, bytes) in outputs.iter().zip(&old) {
                if ready {
                    assert_eq!(
                        &fs::read(dir.join(n)).unwrap(),
                        bytes,
                        "{point}: {n} changed"
                    );
                } else {
                    // the run ended before the point: put the previous outputs back
                    fs::write(dir.join(n), bytes).unwrap();
                }
            }
            if ready {
                assert!(status.code().is_none(), "{point}: killed by a signal");
                assert_eq!(own(&dir), 3, "{point}: the kill left its temporaries");
                caught = true;
                break;
            }
        }
        assert!(caught, "{point}: never reached in 5 runs");
    }
    let o = run(
        &dir.path,
        &["-i", "s.sc", "-o", "other.png", "-size", "32x24"],
    );
    assert_success(&o, "the next run");
    assert_eq!(
        temporaries(&dir),
        Vec::<String>::new(),
        "stale temporaries removed"
    );
    for (n, bytes) in outputs.iter().zip(&old) {
        assert_eq!(&fs::read(dir.join(n)).unwrap(), bytes, "{n} intact");
    }
    assert_eq!(
        dir.entries(),
        [
            "depth.npy",
            "ids.npy",
            "other.png",
            "out.png",
            "s.sc",
            "slow.sc"
        ]
    );
}

/// A run in progress keeps its temporary files while other runs write into the same folder;
/// interrupted, it removes them itself.
#[test]
fn a_live_runs_temporaries_are_not_taken_for_stale() {
    let dir = TempDir::new("stale-live");
    dir.copy_in(&seed_scene(1), "s.sc");
    dir.write("slow.sc", &slow_scene());
    let mut slow = spawn(&dir.path, &SLOW);
    assert!(
        wait_for(&mut slow, || temporaries(&dir).len() == 3),
        "the slow run started"
    );
    let live = temporaries(&dir);
    for k in 0..3 {
        let out = format!("b{k}.png");
        assert_success(
            &run(&dir.path, &["-i", "s.sc", "-o", &out, "-size", "32x24"]),
            &out,
        );
        assert_eq!(temporaries(&dir), live, "the live run's temporaries stay");
    }
    let st = Command::new("kill")
        .args(["-INT", &slow.id().to_string()])
        .status()
        .unwrap();
    assert!(st.success());
    let o = slow.wait_with_output().unwrap();
    assert_eq!(
        o.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        dir.entries(),
        ["b0.png", "b1.png", "b2.png", "s.sc", "slow.sc"]
    );
}

/// What counts as a stale temporary file: a regular file named as lanecast names them, that no
/// process holds locked and (where /proc tells) whose process is gone. A file named with a live
/// process's number is kept (an older lanecast does not lock its temporary files), and so are
/// other names and symbolic links.
#[cfg(target_os = "linux")]
#[test]
fn only_unlocked_temporaries_of_dead_processes_are_removed() {
    let dir = TempDir::new("stale-names");
    dir.copy_in(&seed_scene(1), "s.sc");
    let mut gone = Command::new("true").spawn().unwrap();
    gone.wait().unwrap();
    let dead = gone.id();
    let alive = std::process::id();
    let keep_target = TempDir::new("stale-names-target");
    let target = keep_target.write("precious", "keep me");
    let stale = [
        format!(".out.png.{dead}.0.lanecast-tmp"),
        format!(".other.npy.{dead}.17.lanecast-tmp"),
    ];
    let kept = [
        format!(".out.png.{alive}.3.lanecast-tmp"),
        format!(".out.png.{dead}.x.lanecast-tmp"),
        format!("out.png.{dead}.4.lanecast-tmp"),
        ".lanecast-tmp".to_string(),
    ];
    for name in stale.iter().chain(&kept) {
        dir.write(name, "partial");
    }
    let link = format!(".link.png.{dead}.5.lanecast-tmp");
    std::os::unix::fs::symlink(&target, dir.join(&link)).unwrap();
    let o = run(
        &dir.path,
        &["-i", "s.sc", "-o", "out.png", "-size", "32x24"],
    );
    assert_success(&o, "the run");
    let names = dir.entries();
    for name in &stale {
        assert!(!names.contains(name), "{name} removed: {names:?}");
    }
    for name in kept.iter().chain([&link]) {
        assert!(names.contains(name), "{name} kept: {names:?}");
    }
    assert_eq!(fs::read_to_string(&target).unwrap(), "keep me");
}

//! Runs that write the same outputs at the same time (make -j, a retried job, two terminals):
//! each run's commit (the renames and folder syncs) holds the locks of its outputs' folders,
//! so the set left behind is always one run's whole set; runs on disjoint sets in one folder
//! all complete; a run that cannot get a lock within the bound exits 75 and writes nothing.

use crate::common;

use common::*;
use std::fs;
use std::path::Path;
use std::process::{Child, Command, Stdio};

/// The seed scenes the concurrent runs draw from: each leaves different ids and images.
const SCENES: [usize; 4] = [1, 2, 5, 6];

/// Starts the binary in `cwd` with `args`, output captured.
fn spawn(cwd: &Path, args: &[String]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args(args)
        .current_dir(cwd)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot start the lanecast binary")
}

/// The arguments of a run of seed scene `n` (copied in as `sN.sc`) writing `out.png`,
/// `ids.npy` and `st.json` under the names `prefix`+name.
fn args(n: usize, prefix: &str, size: &str) -> Vec<String> {
    [
        "-i".to_string(),
        format!("s{n}.sc"),
        "-o".into(),
        format!("{prefix}out.png"),
        "--ids".into(),
        format!("{prefix}ids.npy"),
        "--stats".into(),
        format!("{prefix}st.json"),
        "-size".into(),
        size.into(),
        "--threads".into(),
        "1".into(),
    ]
    .to_vec()
}

/// A folder with the seed scenes of [`SCENES`] and, for each, the image and ids a run of it
/// alone leaves (`refN.png`, `refN.npy`).
fn with_references(name: &str, size: &str) -> TempDir {
    let dir = TempDir::new(name);
    for n in SCENES {
        dir.copy_in(&seed_scene(n), &format!("s{n}.sc"));
        let o = spawn(&dir.path, &args(n, &format!("ref{n}-"), size))
            .wait_with_output()
            .unwrap();
        assert_success(&o, &format!("reference run of scene {n}"));
        fs::rename(
            dir.join(&format!("ref{n}-out.png")),
            dir.join(&format!("ref{n}.png")),
        )
        .unwrap();
        fs::rename(
            dir.join(&format!("ref{n}-ids.npy")),
            dir.join(&format!("ref{n}.npy")),
        )
        .unwrap();
        fs::remove_file(dir.join(&format!("ref{n}-st.json"))).unwrap();
    }
    dir
}

/// Which scene each of the set `prefix`+{out.png, ids.npy, st.json} came from.
fn origins(dir: &TempDir, prefix: &str) -> [Option<usize>; 3] {
    let read = |name: &str| fs::read(dir.join(name)).unwrap();
    let (png, ids) = (
        read(&format!("{prefix}out.png")),
        read(&format!("{prefix}ids.npy")),
    );
    let stats: serde_json::Value =
        serde_json::from_slice(&read(&format!("{prefix}st.json"))).unwrap();
    let from_stats = SCENES
        .into_iter()
        .find(|n| stats["scene"].as_str() == Some(&format!("s{n}.sc")));
    [
        SCENES
            .into_iter()
            .find(|n| read(&format!("ref{n}.png")) == png),
        SCENES
            .into_iter()
            .find(|n| read(&format!("ref{n}.npy")) == ids),
        from_stats,
    ]
}

/// No temporary file in `dir`.
fn assert_no_temporaries(dir: &TempDir) {
    let names = dir.entries();
    assert!(
        !names.iter().any(|e| e.ends_with(".lanecast-tmp")),
        "temporary file left: {names:?}"
    );
}

/// Many runs of different scenes write one output set at once, round after round: every round
/// leaves one run's whole set (image, ids and stats from the same scene). With the renames of
/// concurrent runs interleaving, about one round in twenty left a mixed set: 100 rounds of 16
/// runs found some in every trial.
#[test]
fn concurrent_runs_on_one_output_set_leave_one_runs_whole_set() {
    let size = "32x24";
    let dir = with_references("concurrent-same", size);
    let rounds = 100;
    let per_round = 16;
    let mut mixed = Vec::new();
    for round in 0..rounds {
        let children: Vec<Child> = (0..per_round)
            .map(|k| spawn(&dir.path, &args(SCENES[k % SCENES.len()], "", size)))
            .collect();
        for c in children {
            let o = c.wait_with_output().unwrap();
            assert_success(&o, &format!("round {round}"));
        }
        let from = origins(&dir, "");
        assert!(
            from[0].is_some(),
            "round {round}: an image of no run: {from:?}"
        );
        if from.iter().any(|f| *f != from[0]) {
            mixed.push((round, from));
        }
        assert_no_temporaries(&dir);
    }
    assert!(
        mixed.is_empty(),
        "mixed sets (round, [image, ids, stats] scene): {mixed:?}"
    );
}

/// Runs writing disjoint output sets in one folder at once all complete, each with its own
/// scene's whole set, and leave no temporary file.
#[test]
fn concurrent_runs_on_disjoint_sets_in_one_folder_all_complete() {
    let size = "64x48";
    let dir = with_references("concurrent-disjoint", size);
    for round in 0..5 {
        let runs: Vec<(usize, String, Child)> = (0..12)
            .map(|k| {
                let n = SCENES[k % SCENES.len()];
                let prefix = format!("r{round}-{k}-");
                let child = spawn(&dir.path, &args(n, &prefix, size));
                (n, prefix, child)
            })
            .collect();
        for (n, prefix, child) in runs {
            let o = child.wait_with_output().unwrap();
            assert_success(&o, &format!("round {round}, {prefix}"));
            assert_eq!(origins(&dir, &prefix), [Some(n); 3], "{prefix}");
        }
        assert_no_temporaries(&dir);
    }
}

/// The lock of an output folder held elsewhere for longer than `LANECAST_LOCK_WAIT` seconds:
/// the run says so, exits 75 and writes nothing; once the lock is free, the same run succeeds.
#[cfg(unix)]
#[test]
fn a_run_that_cannot_lock_its_output_folder_exits_75_and_writes_nothing() {
    let dir = TempDir::new("concurrent-locked");
    dir.copy_in(&seed_scene(1), "s1.sc");
    fs::create_dir(dir.join("out")).unwrap();
    fs::write(dir.join("out/out.png"), b"previous").unwrap();
    let run_locked = || {
        Command::new(env!("CARGO_BIN_EXE_lanecast"))
            .args([
                "-i",
                "s1.sc",
                "-o",
                "out/out.png",
                "--ids",
                "ids.npy",
                "-size",
                "32x24",
            ])
            .env("LANECAST_LOCK_WAIT", "0.3")
            .current_dir(&dir.path)
            .output()
            .unwrap()
    };
    let held = fs::File::open(dir.join("out")).unwrap();
    held.lock().unwrap();
    let o = run_locked();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(75), "{err}");
    assert!(err.starts_with("lanecast: error: "), "{err}");
    for word in ["out", "lock", "another", "nothing written"] {
        assert!(err.contains(word), "{err:?} lacks {word:?}");
    }
    assert_eq!(dir.entries(), ["out", "s1.sc"]);
    assert_eq!(fs::read_dir(dir.join("out")).unwrap().count(), 1);
    assert_eq!(fs::read(dir.join("out/out.png")).unwrap(), b"previous");
    drop(held);
    assert_success(&run_locked(), "after the lock is released");
    assert_eq!(dir.entries(), ["ids.npy", "out", "s1.sc"]);
    assert_ne!(fs::read(dir.join("out/out.png")).unwrap(), b"previous");
}

/// A bad `LANECAST_LOCK_WAIT` is refused, naming the variable, before anything is written.
#[test]
fn a_bad_lock_wait_is_refused() {
    let dir = TempDir::new("concurrent-bad-wait");
    dir.copy_in(&seed_scene(1), "s1.sc");
    for bad in ["-1", "soon", "nan", "inf"] {
        let o = Command::new(env!("CARGO_BIN_EXE_lanecast"))
            .args(["-i", "s1.sc", "-o", "out.png", "-size", "32x24"])
            .env("LANECAST_LOCK_WAIT", bad)
            .current_dir(&dir.path)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{bad}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(&format!("LANECAST_LOCK_WAIT={bad}")),
            "{}",
            stderr(&o)
        );
        assert_eq!(dir.entries(), ["s1.sc"]);
    }
}

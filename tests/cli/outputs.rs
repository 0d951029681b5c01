//! The outputs of a run are a set, through the real binary: every output checked
//! before any work (extension, no output naming a file the run reads or another output,
//! writable folder), written to temporary files and renamed into place together, so a failure
//! or an interrupt leaves every previous output byte-identical and no temporary file. Also the
//! exit code of a missing scene or mesh file, and what `--stats` records about the run.

use crate::common;

use common::*;
use std::fs;
use std::path::Path;
use std::process::Output;

const CAM: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0\n";

/// A scene `m/s.sc` that loads the mesh `m/meshes/{mesh}` (one triangle facing the camera).
fn mesh_scene(dir: &TempDir, mesh: &str) {
    fs::create_dir_all(dir.join("m/meshes")).unwrap();
    dir.write(
        &format!("m/meshes/{mesh}"),
        "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n",
    );
    dir.write("m/s.sc", &format!("{CAM}mesh meshes/{mesh}\n"));
}

/// A scene that fails to parse at line 2: a run that reports anything else first did its
/// check before reading the scene.
fn bad_scene(dir: &TempDir) {
    dir.write("bad.sc", &format!("{CAM}sphere 0 0 0 -1\n"));
}

/// Names in `dir` (recursively, relative) that are temporary files.
fn temporaries(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for e in fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let name = e.file_name().to_string_lossy().into_owned();
        if e.file_type().unwrap().is_dir() {
            out.extend(temporaries(&e.path()));
        } else if name.ends_with(".lanecast-tmp") {
            out.push(e.path().display().to_string());
        }
    }
    out
}

/// Asserts exit `code`, a message containing every word, and no temporary file in `dir`.
fn refused(o: &Output, code: i32, words: &[&str], dir: &TempDir) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(code), "{err}");
    assert!(err.starts_with("lanecast: error: "), "{err}");
    for w in words {
        assert!(err.contains(w), "missing {w:?} in: {err}");
    }
    assert_eq!(temporaries(&dir.path), Vec::<String>::new());
}

// ---------------------------------------------------------------------------------------------
// No output names a file the run reads

#[test]
fn outputs_never_replace_a_mesh_the_scene_reads() {
    let dir = TempDir::new("mesh-guard");
    // A first-seen case: `--ids` onto the OBJ, refused by its extension already.
    mesh_scene(&dir, "tri.obj");
    let obj = fs::read(dir.join("m/meshes/tri.obj")).unwrap();
    let o = run(&dir.path, &["-i", "m/s.sc", "--ids", "m/meshes/tri.obj"]);
    refused(&o, 2, &["--ids", "m/meshes/tri.obj", ".npy"], &dir);
    assert_eq!(fs::read(dir.join("m/meshes/tri.obj")).unwrap(), obj);
    assert!(!dir.join("m/s.png").exists());

    // Meshes named like outputs, so that only the read-file rule can refuse them.
    for (mesh, flag) in [
        ("tri.npy", "--ids"),
        ("tri.npy", "--depth"),
        ("tri.png", "-o"),
        ("tri.json", "--stats"),
    ] {
        mesh_scene(&dir, mesh);
        let target = dir.join("m/meshes").join(mesh);
        let before = fs::read(&target).unwrap();
        fs::hard_link(&target, dir.join(&format!("hard-{mesh}"))).unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink(&target, dir.join(&format!("soft-{mesh}"))).unwrap();
        let spellings = [
            format!("m/meshes/{mesh}"),
            format!("./m/../m/meshes/./{mesh}"),
            target.display().to_string(),
            format!("hard-{mesh}"),
            #[cfg(unix)]
            format!("soft-{mesh}"),
        ];
        for spelled in &spellings {
            let mut args = vec!["-i", "m/s.sc", "-size", "8x8"];
            if flag != "-o" {
                args.extend(["-o", "out.png"]);
            }
            args.extend([flag, spelled.as_str()]);
            let o = run(&dir.path, &args);
            refused(&o, 2, &[flag, spelled, "mesh", "refusing"], &dir);
            assert_eq!(fs::read(&target).unwrap(), before, "{flag} {spelled}");
            assert!(!dir.join("out.png").exists(), "{flag} {spelled}");
        }
        fs::remove_file(dir.join(&format!("hard-{mesh}"))).unwrap();
        #[cfg(unix)]
        fs::remove_file(dir.join(&format!("soft-{mesh}"))).unwrap();
    }

    // compare -o follows the same rule.
    mesh_scene(&dir, "tri.png");
    let before = fs::read(dir.join("m/meshes/tri.png")).unwrap();
    let o = run(
        &dir.path,
        &[
            "compare",
            "-i",
            "m/s.sc",
            "-size",
            "8x8",
            "-o",
            "m/meshes/tri.png",
        ],
    );
    refused(&o, 2, &["--output", "tri.png", "mesh"], &dir);
    assert_eq!(fs::read(dir.join("m/meshes/tri.png")).unwrap(), before);
}

#[test]
fn outputs_naming_the_scene_or_each_other_are_refused_before_parsing() {
    let dir = TempDir::new("each-other");
    bad_scene(&dir);
    fs::write(dir.join("a.npy"), b"old a").unwrap();
    fs::hard_link(dir.join("a.npy"), dir.join("b.npy")).unwrap();
    fs::create_dir(dir.join("x")).unwrap();
    for (extra, words) in [
        (
            &["--ids", "a.npy", "--depth", "./a.npy"][..],
            &["--depth", "--ids", "same file"][..],
        ),
        (
            &["--ids", "a.npy", "--depth", "b.npy"],
            &["--depth", "--ids", "same file"],
        ),
        (
            &["--ids", "x/../a.npy", "--depth", "a.npy"],
            &["--depth", "same file"],
        ),
        (
            &["--ids", "a.npy", "--stats", "a.npy"],
            &["--stats", "a.npy", ".json"],
        ),
    ] {
        let mut args = vec!["-i", "bad.sc", "-o", "out.png"];
        args.extend_from_slice(extra);
        let o = run(&dir.path, &args);
        // Exit 2 naming the outputs, not the scene's bad line: checked before parsing.
        refused(&o, 2, words, &dir);
        assert!(!stderr(&o).contains("bad.sc:2"), "{}", stderr(&o));
        assert_eq!(fs::read(dir.join("a.npy")).unwrap(), b"old a");
    }
    let mut names = dir.entries();
    names.retain(|n| n != "x");
    assert_eq!(names, ["a.npy", "b.npy", "bad.sc"]);
}

// ---------------------------------------------------------------------------------------------
// Extensions match what is written

#[test]
fn each_output_extension_must_match_what_is_written() {
    let dir = TempDir::new("ext");
    bad_scene(&dir);
    fs::write(dir.join("x.png"), b"old").unwrap();
    for (flag, path, want) in [
        ("--ids", "x.png", ".npy"),
        ("--depth", "d.bin", ".npy"),
        ("--depth", "d", ".npy"),
        ("--stats", "s.txt", ".json"),
        ("--stats", "s.npy", ".json"),
        ("-o", "i.npy", ".png"),
        ("-o", "i.json", ".bmp"),
    ] {
        let mut args = vec!["-i", "bad.sc"];
        if flag != "-o" {
            args.extend(["-o", "out.png"]);
        }
        args.extend([flag, path]);
        let o = run(&dir.path, &args);
        let flag_long = if flag == "-o" { "--output" } else { flag };
        refused(&o, 2, &[flag_long, path, want], &dir);
        assert_eq!(dir.entries(), ["bad.sc", "x.png"], "{flag} {path}");
        assert_eq!(fs::read(dir.join("x.png")).unwrap(), b"old");
    }
    // Upper case extensions are the same extensions.
    dir.write("ok.sc", &format!("{CAM}sphere 0 0 0 1\n"));
    let o = run(
        &dir.path,
        &[
            "-i", "ok.sc", "-size", "8x8", "-o", "O.PNG", "--ids", "I.NPY", "--stats", "S.Json",
        ],
    );
    assert_success(&o, "upper-case extensions");
}

// ---------------------------------------------------------------------------------------------
// Writable destinations before any work; nothing written when one fails

#[test]
fn a_missing_output_folder_fails_before_any_work_and_writes_nothing() {
    let dir = TempDir::new("nofolder");
    dir.write("ok.sc", &format!("{CAM}sphere 0 0 0 1\n"));
    bad_scene(&dir);
    fs::write(dir.join("a.png"), b"old image").unwrap();
    fs::write(dir.join("file"), b"a file, not a folder").unwrap();
    fs::create_dir(dir.join("folder.npy")).unwrap();
    for (flag, path, word) in [
        ("--ids", "nofolder/ids.npy", "nofolder"),
        ("--depth", "nofolder/d.npy", "nofolder"),
        ("--stats", "nofolder/s.json", "nofolder"),
        ("--stats", "file/s.json", "file"),
        ("--ids", "folder.npy", "folder"),
    ] {
        for scene in ["ok.sc", "bad.sc"] {
            let o = run(
                &dir.path,
                &["-i", scene, "-size", "16x16", "-o", "a.png", flag, path],
            );
            // Exit 1 even for the bad scene: the folder is checked before parsing.
            refused(&o, 1, &[flag, path, word], &dir);
            assert_eq!(fs::read(dir.join("a.png")).unwrap(), b"old image");
            assert_eq!(
                dir.entries(),
                ["a.png", "bad.sc", "file", "folder.npy", "ok.sc"],
                "{flag} {path}"
            );
        }
    }
    let o = run(
        &dir.path,
        &["compare", "-i", "bad.sc", "-o", "nofolder/diff.png"],
    );
    refused(&o, 1, &["--output", "nofolder/diff.png"], &dir);
}

#[cfg(unix)]
#[test]
fn a_read_only_output_folder_fails_before_any_work() {
    use std::os::unix::fs::PermissionsExt;
    let dir = TempDir::new("ro");
    dir.write("ok.sc", &format!("{CAM}sphere 0 0 0 1\n"));
    fs::create_dir(dir.join("ro")).unwrap();
    fs::write(dir.join("ro/ids.npy"), b"old ids").unwrap();
    fs::write(dir.join("a.png"), b"old image").unwrap();
    fs::set_permissions(dir.join("ro"), fs::Permissions::from_mode(0o555)).unwrap();
    if fs::File::create(dir.join("ro/probe")).is_ok() {
        let _ = fs::remove_file(dir.join("ro/probe"));
        fs::set_permissions(dir.join("ro"), fs::Permissions::from_mode(0o755)).unwrap();
        eprintln!("skipped: permissions are not enforced for this user (root?)");
        return;
    }
    let o = run(
        &dir.path,
        &[
            "-i",
            "ok.sc",
            "-size",
            "8x8",
            "-o",
            "a.png",
            "--ids",
            "ro/ids.npy",
        ],
    );
    fs::set_permissions(dir.join("ro"), fs::Permissions::from_mode(0o755)).unwrap();
    refused(&o, 1, &["--ids", "ro/ids.npy"], &dir);
    assert_eq!(fs::read(dir.join("a.png")).unwrap(), b"old image");
    assert_eq!(fs::read(dir.join("ro/ids.npy")).unwrap(), b"old ids");
}

// ---------------------------------------------------------------------------------------------
// Interrupts leave the previous set, whole

/// A scene of `n` small spheres in a grid.
fn many_spheres(n: usize) -> String {
    let mut s = String::from("camera eye 0 0 60 look 0 0 0 up 0 1 0\n");
    let side = (n as f64).sqrt().ceil() as usize;
    for i in 0..n {
        let (x, y) = ((i % side) as f64, (i / side) as f64);
        let (x, y) = (x - side as f64 / 2.0, y - side as f64 / 2.0);
        s += &format!("sphere {x} {y} {} 0.4\n", -((i % 7) as f64));
    }
    s
}

#[cfg(unix)]
fn signal(pid: u32, sig: &str) {
    let st = std::process::Command::new("kill")
        .args([sig, &pid.to_string()])
        .status()
        .unwrap();
    assert!(st.success());
}

/// SIGINT or SIGTERM at many moments of a run with four outputs (during parsing, rendering,
/// writing, renaming): every run ends with exit 130 and the previous four files, or (when the
/// signal lands after the renames began, or after the run) all four new files; never a mix, and
/// never a temporary file.
#[cfg(unix)]
#[test]
fn an_interrupt_at_any_moment_leaves_the_previous_set_or_the_whole_new_one() {
    use std::time::Instant;
    let dir = TempDir::new("interrupt");
    dir.write("many.sc", &many_spheres(400));
    let names = ["prev.png", "p.npy", "d.npy", "s.json"];
    let args = [
        "-i",
        "many.sc",
        "-size",
        "4096x4096",
        "--threads",
        "1",
        "-o",
        "prev.png",
        "--ids",
        "p.npy",
        "--depth",
        "d.npy",
        "--stats",
        "s.json",
    ];
    // The new set, and how long a whole run takes.
    let start = Instant::now();
    assert_success(&run(&dir.path, &args), "reference run");
    let full = start.elapsed();
    let new: Vec<Vec<u8>> = names
        .iter()
        .map(|n| fs::read(dir.join(n)).unwrap())
        .collect();
    let (mut old_sets, mut new_sets) = (0, 0);
    for step in 0..16 {
        let old: Vec<Vec<u8>> = names
            .iter()
            .map(|n| format!("previous {n} {step}").into_bytes())
            .collect();
        for (n, b) in names.iter().zip(&old) {
            fs::write(dir.join(n), b).unwrap();
        }
        let child = std::process::Command::new(env!("CARGO_BIN_EXE_lanecast"))
            .args(args)
            .current_dir(&dir.path)
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        // From the start of the run to a little past its usual end.
        std::thread::sleep(full.mul_f64(step as f64 / 12.0));
        signal(child.id(), if step % 2 == 0 { "-INT" } else { "-TERM" });
        let o = child.wait_with_output().unwrap();
        // A signal that lands before the handler is installed (the first instants of the
        // process) ends it by the signal itself, before it touched any file.
        let early = std::os::unix::process::ExitStatusExt::signal(&o.status).is_some();
        assert!(
            early || matches!(o.status.code(), Some(0 | 130)),
            "step {step}: {:?} {}",
            o.status,
            stderr(&o)
        );
        assert_eq!(temporaries(&dir.path), Vec::<String>::new(), "step {step}");
        let now: Vec<Vec<u8>> = names
            .iter()
            .map(|n| fs::read(dir.join(n)).unwrap())
            .collect();
        if now == old {
            assert!(early || o.status.code() == Some(130), "step {step}");
            old_sets += 1;
        } else {
            // The stats record differs between runs (times); the others are bit-identical.
            assert_eq!(now[..3], new[..3], "step {step}: a mixed set");
            let stats: serde_json::Value = serde_json::from_slice(&now[3]).unwrap();
            assert_eq!(stats["outputs"]["image"], "prev.png");
            new_sets += 1;
        }
        assert_eq!(
            dir.entries(),
            ["d.npy", "many.sc", "p.npy", "prev.png", "s.json"]
        );
    }
    eprintln!("run of {full:?}: {old_sets} interrupted before the renames, {new_sets} after");
    assert!(old_sets > 0, "no run was interrupted in time");
}

// ---------------------------------------------------------------------------------------------
// Exit codes: a missing file is a missing file

#[test]
fn a_missing_scene_and_a_missing_mesh_exit_alike() {
    let dir = TempDir::new("missing");
    dir.write("s.sc", &format!("{CAM}\nmesh nowhere.obj\n"));
    let scene = run(&dir.path, &["-i", "nowhere.sc", "-o", "a.png"]);
    refused(&scene, 1, &["nowhere.sc", "cannot read scene"], &dir);
    let mesh = run(&dir.path, &["-i", "s.sc", "-o", "a.png"]);
    refused(
        &mesh,
        1,
        &["s.sc:3:", "cannot read mesh", "nowhere.obj"],
        &dir,
    );
    // A folder named as a mesh cannot be read either.
    fs::create_dir(dir.join("nowhere.obj")).unwrap();
    let folder = run(&dir.path, &["-i", "s.sc", "-o", "a.png"]);
    refused(&folder, 1, &["s.sc:3:", "nowhere.obj"], &dir);
    assert_eq!(dir.entries(), ["nowhere.obj", "s.sc"]);
}

// ---------------------------------------------------------------------------------------------
// --stats records the run

#[test]
fn stats_record_version_command_line_seed_and_outputs() {
    let dir = TempDir::new("stats");
    dir.write("s.sc", &format!("{CAM}sphere 0 0 0 1\n"));
    let args = [
        "-i", "s.sc", "-size", "8x8", "--seed", "42", "-o", "img.bmp", "--ids", "i.npy", "--depth",
        "./d.npy", "--stats", "run.json",
    ];
    assert_success(&run(&dir.path, &args), "stats run");
    let text = fs::read_to_string(dir.join("run.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["version"], env!("CARGO_PKG_VERSION"));
    let command: Vec<&str> = v["command"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    assert!(command[0].ends_with("lanecast"), "{command:?}");
    assert_eq!(command[1..], args);
    assert_eq!(v["seed"].as_u64(), Some(42));
    assert_eq!(v["outputs"]["image"], "img.bmp");
    assert_eq!(v["outputs"]["ids"], "i.npy");
    assert_eq!(v["outputs"]["depth"], "./d.npy");
    assert_eq!(v["outputs"]["stats"], "run.json");
    assert_eq!(
        dir.entries(),
        ["d.npy", "i.npy", "img.bmp", "run.json", "s.sc"]
    );
}

//! What the command line says about a camera's lens and a refused argument: `-fov` replaces
//! every lens, and says so where it replaces intrinsics; one screen rule for a field of view
//! and for `K`; refusals name the flag with its value as typed, or the file, line and column.

use crate::common;

use common::*;
use std::fs;

const K_CAMERA: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0 K 500 400 300 200\n";
const FOV_CAMERA: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 80\n";
const BALL: &str = "sphere 0.3 0 0 1\n";

/// Runs the binary in `dir` and returns (exit code, stderr).
fn code_and_stderr(dir: &TempDir, args: &[&str]) -> (Option<i32>, String) {
    let o = run(&dir.path, args);
    (o.status.code(), stderr(&o))
}

/// `-fov` over a scene's `K` renders the scene's camera with that field of view, bit for bit,
/// and notes once on stderr that it replaced the intrinsics.
#[test]
fn fov_over_a_scene_k_is_the_fov_camera_and_is_noted() {
    let dir = TempDir::new("msg-fov-k");
    dir.write("k.sc", &format!("{K_CAMERA}{BALL}"));
    dir.write("f.sc", &format!("{FOV_CAMERA}{BALL}"));
    let o = run(&dir.path, &["-i", "k.sc", "-fov", "80", "--ids", "a.npy"]);
    assert_success(&o, "-fov over K");
    let err = stderr(&o);
    assert_eq!(
        err.matches("note:").count(),
        1,
        "one note expected, got: {err}"
    );
    assert!(
        err.contains("-fov 80 replaces the scene's intrinsics (k.sc:1:1: K 500 400 300 200)"),
        "{err}"
    );
    let o = run(&dir.path, &["-i", "f.sc", "--ids", "b.npy"]);
    assert_success(&o, "fov camera");
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
    assert_eq!(
        fs::read(dir.join("a.npy")).unwrap(),
        fs::read(dir.join("b.npy")).unwrap()
    );
    // a fov over a fov is what -fov means: no note
    let o = run(&dir.path, &["-i", "f.sc", "-fov", "30", "-o", "c.png"]);
    assert_success(&o, "-fov over fov");
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
}

/// In a views file `-fov` replaces each line's own lens too (the one rule), with one note
/// counting the lines whose intrinsics it replaced.
#[test]
fn fov_replaces_every_views_lines_lens() {
    let dir = TempDir::new("msg-fov-views");
    dir.write("f.sc", &format!("{FOV_CAMERA}{BALL}"));
    dir.write(
        "v.txt",
        "camera eye 0 0 5 look 0 0 0 up 0 1 0 K 500 400 300 200\n\
         camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 20\n\
         extrinsic 1 0 0 0  0 -1 0 0  0 0 -1 5  0 0 0 1 K 700 700 320 240\n",
    );
    let o = run(
        &dir.path,
        &[
            "-i", "f.sc", "--views", "v.txt", "-fov", "80", "--ids", "v%d.npy", "-o", "v%d.png",
        ],
    );
    assert_success(&o, "--views -fov");
    let err = stderr(&o);
    assert_eq!(err.matches("note:").count(), 1, "{err}");
    assert!(
        err.contains("-fov 80 replaces the intrinsics of 2 views (first: v.txt:1)"),
        "{err}"
    );
    let o = run(&dir.path, &["-i", "f.sc", "--ids", "one.npy"]);
    assert_success(&o, "one view");
    let one = fs::read(dir.join("one.npy")).unwrap();
    for k in 0..3 {
        assert_eq!(
            fs::read(dir.path.join(format!("v{k}.npy"))).unwrap(),
            one,
            "view {k}: -fov 80 replaces its lens"
        );
    }
}

/// `-fov` is held to the screen rule intrinsics meet (`limits::check_lens`): a field of view
/// too narrow for f32 screens is refused as its equivalent `K` is, naming the flag as typed.
#[test]
fn fov_and_k_meet_one_screen_rule() {
    let dir = TempDir::new("msg-fov-screen");
    dir.write("f.sc", &format!("{FOV_CAMERA}{BALL}"));
    // fov 1e-300 degrees at 640 wide is fx = 640 / (2 tan(fov/2)) = 2.1e304 pixels
    dir.write(
        "k.sc",
        &format!("camera eye 0 0 5 look 0 0 0 up 0 1 0 K 2.1e304 2.1e304 320 240\n{BALL}"),
    );
    let (code, err) = code_and_stderr(&dir, &["-i", "f.sc", "-fov", "1e-300", "-o", "a.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("error: -fov 1e-300: a field of view of 1e-300 degrees"),
        "{err}"
    );
    assert!(err.contains("must span 1e-9 to 1e9"), "{err}");
    let (code, err) = code_and_stderr(&dir, &["-i", "k.sc", "-o", "b.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("k.sc:1:1: camera: W / fx = 3.048e-302"),
        "{err}"
    );
    assert!(err.contains("must span 1e-9 to 1e9"), "{err}");
    for wide in ["179.9999999", "1e-8"] {
        let (code, err) = code_and_stderr(&dir, &["-i", "f.sc", "--fov", wide, "-o", "c.png"]);
        assert_eq!(code, Some(2), "{wide}: {err}");
        assert!(err.contains(&format!("--fov {wide}: ")), "{err}");
    }
    assert!(!dir.join("a.png").exists() && !dir.join("c.png").exists());
    let o = run(&dir.path, &["-i", "f.sc", "-fov", "1e-6", "-o", "d.png"]);
    assert_success(&o, "a narrow fov the rule allows");
}

/// A refused `-fov` is echoed as typed, never as the number it parsed to.
#[test]
fn bad_fov_values_are_echoed_as_typed() {
    let dir = TempDir::new("msg-fov-typed");
    dir.write("f.sc", &format!("{FOV_CAMERA}{BALL}"));
    for (flag, value) in [
        ("--fov", "1e400"),
        ("-fov", "nan"),
        ("-fov", "NaN"),
        ("--fov", "-0"),
        ("-fov", "0x10"),
        ("-fov", "180"),
    ] {
        let (code, err) = code_and_stderr(&dir, &["-i", "f.sc", flag, value, "-o", "a.png"]);
        assert_eq!(code, Some(2), "{value}: {err}");
        assert!(
            err.contains(&format!("error: {flag} {value}: the field of view must")),
            "{value}: {err}"
        );
        assert!(
            !err.contains(" inf:") && !err.contains(" NaN degrees"),
            "{err}"
        );
    }
}

/// `--eye` that puts the scene out of f32's range is named, with its value as typed; the
/// scene's line is named as the primitive it reaches.
#[test]
fn an_eye_too_far_blames_the_flag() {
    let dir = TempDir::new("msg-eye");
    dir.write("ok.sc", &format!("{FOV_CAMERA}{BALL}"));
    let (code, err) = code_and_stderr(&dir, &["-i", "ok.sc", "--eye", "1e30,0,0", "-o", "a.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.starts_with("lanecast: error: --eye 1e30,0,0: seen from this eye, ok.sc:2:1: sphere"),
        "{err}"
    );
}

/// A sphere past f64's squares is refused with its true distance, not "inf".
#[test]
fn a_far_sphere_has_a_finite_distance() {
    let dir = TempDir::new("msg-far");
    dir.write("far.sc", &format!("{FOV_CAMERA}sphere 1e300 0 0 1\n"));
    let (code, err) = code_and_stderr(&dir, &["-i", "far.sc", "-o", "a.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("far.sc:2:1: sphere reaches 1.000e300 from"),
        "{err}"
    );
}

/// An `extrinsic` whose translation f64 cannot hold apart from the view direction says so.
#[test]
fn an_extrinsic_too_far_names_its_translation() {
    let dir = TempDir::new("msg-extrinsic");
    dir.write("ok.sc", &format!("{FOV_CAMERA}{BALL}"));
    dir.write(
        "v.txt",
        "\nextrinsic 1 0 0 0 0 -1 0 0 0 0 -1 1e17 0 0 0 1\n",
    );
    let (code, err) = code_and_stderr(&dir, &["-i", "ok.sc", "--views", "v.txt", "-o", "%d.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("v.txt:2:1: the world-to-camera matrix's translation"),
        "{err}"
    );
    assert!(
        err.contains("puts the eye 1.000e17 from the origin"),
        "{err}"
    );
    assert!(!err.contains("same point"), "{err}");
}

/// `--seed` takes a non-negative whole number, and says so for a negative one.
#[test]
fn a_negative_seed_is_named() {
    let dir = TempDir::new("msg-seed");
    dir.write("ok.sc", &format!("{FOV_CAMERA}{BALL}"));
    let (code, err) = code_and_stderr(&dir, &["-i", "ok.sc", "--seed", "-1", "-o", "a.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("'-1' for '--seed <N>'"), "{err}");
    assert!(
        err.contains("the seed must be a non-negative whole number"),
        "{err}"
    );
    assert!(!err.contains("unexpected argument"), "{err}");
}

/// A pattern's bad conversion is named whole (`%s`), with the accepted ones.
#[test]
fn a_bad_conversion_is_named_whole() {
    let dir = TempDir::new("msg-pattern");
    dir.write("ok.sc", &format!("{FOV_CAMERA}{BALL}"));
    let (code, err) = code_and_stderr(&dir, &["-i", "ok.sc", "--orbit", "2", "-o", "e_%s.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains(
            "-o e_%s.png: '%s' is not a number conversion (the accepted ones are %d and %0Nd"
        ),
        "{err}"
    );
}

/// A views file that is not UTF-8 is refused at the line and column of its first bad byte; an
/// empty one shows both line syntaxes.
#[test]
fn views_file_refusals_name_the_place_and_both_syntaxes() {
    let dir = TempDir::new("msg-views");
    dir.write("ok.sc", &format!("{FOV_CAMERA}{BALL}"));
    fs::write(
        dir.join("bad.txt"),
        b"camera eye 0 0 5 look 0 0 0 up 0 1 0\n# caf\xe9\n",
    )
    .unwrap();
    let (code, err) = code_and_stderr(&dir, &["-i", "ok.sc", "--views", "bad.txt", "-o", "%d.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("bad.txt:2:6: not valid UTF-8"), "{err}");
    dir.write("empty.txt", "# nothing\n\n");
    let (code, err) = code_and_stderr(
        &dir,
        &["-i", "ok.sc", "--views", "empty.txt", "-o", "%d.png"],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("`camera eye X Y Z look"), "{err}");
    assert!(err.contains("`extrinsic M00 M01 ... M33"), "{err}");
}

/// A mesh that cannot be read, and a bad OBJ line, are named with a column.
#[test]
fn mesh_errors_name_a_column() {
    let dir = TempDir::new("msg-mesh");
    dir.write("gone.sc", &format!("{FOV_CAMERA}mesh   nowhere.obj\n"));
    let (code, err) = code_and_stderr(&dir, &["-i", "gone.sc", "-o", "a.png"]);
    assert_eq!(code, Some(1), "{err}");
    assert!(err.contains("gone.sc:2:8: cannot read mesh"), "{err}");
    dir.write("m.sc", &format!("{FOV_CAMERA}mesh m.obj\n"));
    dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    let (code, err) = code_and_stderr(&dir, &["-i", "m.sc", "-o", "a.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("m.obj:4:7: vertex index 7 is out of range"),
        "{err}"
    );
}

/// `--format` with no `-o` names the default image, not an `-o` that was not typed.
#[test]
fn format_without_o_names_the_default_image() {
    let dir = TempDir::new("msg-format");
    dir.write("ok.sc", &format!("{FOV_CAMERA}{BALL}"));
    let (code, err) = code_and_stderr(&dir, &["-i", "ok.sc", "--format", "bmp"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("--format bmp: with no -o the image goes to ok.png"),
        "{err}"
    );
    assert!(!err.contains("-o ok.png"), "{err}");
    let (code, err) = code_and_stderr(&dir, &["-i", "ok.sc", "--format", "bmp", "-o", "x.png"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("--format bmp: -o x.png names a file"), "{err}");
}

/// A folder locked too long is named by its absolute path when it is the current folder.
#[cfg(unix)]
#[test]
fn the_locked_current_folder_is_named_in_full() {
    let dir = TempDir::new("msg-lock");
    dir.write("ok.sc", &format!("{FOV_CAMERA}{BALL}"));
    let held = fs::File::open(&dir.path).unwrap();
    held.lock().unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args(["-i", "ok.sc", "-o", "a.png", "-size", "8x8"])
        .env("LANECAST_LOCK_WAIT", "0.2")
        .current_dir(&dir.path)
        .output()
        .unwrap();
    drop(held);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(75), "{err}");
    let abs = fs::canonicalize(&dir.path).unwrap();
    let want = format!("error: the current folder ({}): another", abs.display());
    let also = format!(
        "error: the current folder ({}): another",
        dir.path.display()
    );
    assert!(err.contains(&want) || err.contains(&also), "{err}");
}

/// `--stats` gives a field of view's fx and fy equal (computed once, square pixels), and
/// writes no negative zero.
#[test]
fn stats_fov_camera_has_equal_focal_lengths_and_no_negative_zero() {
    let dir = TempDir::new("msg-stats");
    // fov 45 at 640x480: W / (2 half_w) and H / (2 half_h) differ by 1 ulp
    dir.write(
        "ok.sc",
        &format!("camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 45\n{BALL}"),
    );
    let o = run(
        &dir.path,
        &["-i", "ok.sc", "-o", "a.png", "--stats", "s.json"],
    );
    assert_success(&o, "--stats");
    let text = fs::read_to_string(dir.join("s.json")).unwrap();
    assert!(!text.contains("-0.0"), "{text}");
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let k = &json["views"][0]["K"];
    assert_eq!(k[0][0], k[1][1], "{k}");
}

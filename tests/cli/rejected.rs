//! Rejected input.

use super::*;
use crate::npy::KNOWN;

/// The `LINE:COL` a fixture's error must name, from its `# expect: LINE:COL (why)` header
/// (see tests/bad/README.md); `None` for whole-file errors (`-`).
fn fixture_line(text: &str) -> Option<String> {
    let spec = text
        .lines()
        .next()
        .and_then(|l| l.strip_prefix("# expect: "))
        .expect("fixture header");
    let at = spec.split_whitespace().next().unwrap();
    (at != "-").then(|| at.to_string())
}

/// Asserts a rejected run: exit `code`, a `lanecast: error:` message containing
/// every one of `words`, nothing on stdout, and the folder left with exactly `entries`.
pub(crate) fn assert_rejected(
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
            Some(line_col) => format!("lanecast: error: bad.sc:{line_col}: "),
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
/// single-dash option of the seed takes the `=` form as its GNU long form
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

/// The misreadings new users typed, through the binary: exit 2, the argument as typed and
/// what was meant (the flag walk is `cli::tests`, on clap's own `Command`).
#[test]
fn one_dash_long_flags_and_a_bare_scene_are_named_as_typed() {
    let dir = with_scene1("misread");
    for (args, want) in [
        (
            &["-i", "scene1.sc", "-szie", "800x600"][..],
            "-szie: no such flag; did you mean -size?",
        ),
        (
            &["-i", "scene1.sc", "-ids", "x.npy"],
            "-ids: long flags take two dashes: --ids",
        ),
        (
            &["-i", "scene1.sc", "-output", "x.png"],
            "-output: long flags take two dashes: --output",
        ),
        (
            &["-i", "scene1.sc", "-orbit", "4"],
            "-orbit: long flags take two dashes: --orbit",
        ),
        (
            &["scene1.sc"],
            "scene1.sc: the scene is given with -i: lanecast -i scene1.sc",
        ),
        (
            &["compare", "-i", "scene1.sc", "--kernel", "scalar"],
            "--kernel: applies to the render command",
        ),
        (
            &["-i", "scene1.sc", "--orbit", "-3"],
            "'-3' for '--orbit <N>': the number of views",
        ),
        (
            &["compare", "-i", "scene1.sc", "--max-mismatch-ppm", "-1"],
            "--max-mismatch-ppm -1: must be",
        ),
    ] {
        let o = run(&dir.path, args);
        assert_rejected(&o, 2, &[want], &dir, &["scene1.sc"]);
    }
}

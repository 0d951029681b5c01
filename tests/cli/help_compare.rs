//! Help and compare.

use super::*;
use crate::rejected::assert_rejected;

#[test]
fn help_lists_every_option_and_an_example() {
    let dir = TempDir::new("help");
    for flag in ["-h", "--help"] {
        let o = run(&dir.path, &[flag]);
        assert_success(&o, flag);
        let out = stdout(&o);
        for opt in [
            "--input",
            "--output",
            "--size",
            "--fov",
            "--color-mode",
            "--color-variation",
            "--time",
            "--kernel",
            "--threads",
            "--seed",
            "--ids",
            "--depth",
            "compare",
        ] {
            assert!(out.contains(opt), "{flag}: help lacks {opt}:\n{out}");
        }
        for single in ["-size", "-fov", "-cm", "-cv", "-time"] {
            assert!(out.contains(single), "{flag}: help lacks {single}");
        }
        assert!(out.contains("Example"), "{flag}: no example:\n{out}");
        assert!(
            out.contains("lanecast -i "),
            "{flag}: no example command:\n{out}"
        );
    }
    assert!(dir.entries().is_empty());
    // the subcommand has its own help
    let o = run(&dir.path, &["compare", "-h"]);
    assert_success(&o, "compare -h");
    assert!(stdout(&o).contains("--max-mismatch-ppm"), "{}", stdout(&o));
}

#[test]
fn compare_reports_and_writes_a_diff_image() {
    let dir = with_scene1("compare");
    let o = ok(&dir, &["compare", "-i", "scene1.sc", "-size", "96x64"]);
    let out = stdout(&o);
    for word in ["pixels", "96x64", "mismatches", "unexcused", "depth rel"] {
        assert!(out.contains(word), "compare output lacks {word:?}:\n{out}");
    }
    assert_eq!(dir.entries(), ["scene1.sc"], "no image without -o");
    ok(
        &dir,
        &[
            "compare",
            "-i",
            "scene1.sc",
            "-size",
            "96x64",
            "-o",
            "diff.png",
            "--threads",
            "1",
        ],
    );
    let img = image_of(&dir.join("diff.png"), 96, 64);
    assert!(img.pixels().any(|p| p.0 != [0, 0, 0]));
    // bad arguments are refused before any work
    let o = run(
        &dir.path,
        &["compare", "-i", "scene1.sc", "-o", "diff.jpg2"],
    );
    assert_rejected(&o, 2, &["diff.jpg2"], &dir, &["diff.png", "scene1.sc"]);
}

/// `scripts/subdivide.py --help` prints its usage and exits 0 (it exited 1), a missing
/// argument exits 2 with the usage, and a run subdivides (one level: 4 triangles a triangle).
/// Skipped where python3 is absent.
#[test]
fn subdivide_script_help_exits_0_and_subdivides() {
    use std::process::Command;
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/subdivide.py");
    let py = |args: &[&str], cwd: &Path| {
        Command::new("python3")
            .arg(&script)
            .args(args)
            .current_dir(cwd)
            .output()
    };
    let dir = TempDir::new("subdivide");
    let Ok(help) = py(&["--help"], &dir.path) else {
        eprintln!("python3 not found: skipped");
        return;
    };
    assert_eq!(help.status.code(), Some(0), "{}", stderr(&help));
    assert!(
        stdout(&help).starts_with("usage: subdivide.py"),
        "{}",
        stdout(&help)
    );
    let none = py(&[], &dir.path).unwrap();
    assert_eq!(none.status.code(), Some(2));
    assert!(
        stderr(&none).contains("usage: subdivide.py"),
        "{}",
        stderr(&none)
    );
    dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let o = py(&["t.obj", "t1.obj", "1"], &dir.path).unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = fs::read_to_string(dir.join("t1.obj")).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 4);
}

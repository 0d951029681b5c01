//! Hardening through the real binary: every rejected input in tests/bad/ ends in a
//! clear message, exit code 2 and no output; failed or interrupted runs never damage an
//! existing output file nor leave a temporary file; numbers that parse but break f32
//! arithmetic are rejected or rendered without NaN; regressions found by fuzzing.

#[path = "../common/mod.rs"]
mod common;

use common::TempDir;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const CAM: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0\n";

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_lanecast"))
}

fn bad_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("bad")
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
        out.join("out.png"),
        out.join("ids.npy"),
        out.join("depth.npy"),
    );
    render_outputs(input, [&png, &ids, &depth], &["-size", "32x24"])
}

/// Runs `input` with its image, ids and depth written to `png`, `ids` and `depth`, and the
/// flags `extra` after them.
fn render_outputs(input: &Path, [png, ids, depth]: [&Path; 3], extra: &[&str]) -> Output {
    let mut args: Vec<&std::ffi::OsStr> = vec![
        "-i".as_ref(),
        input.as_os_str(),
        "-o".as_ref(),
        png.as_os_str(),
        "--ids".as_ref(),
        ids.as_os_str(),
        "--depth".as_ref(),
        depth.as_os_str(),
    ];
    args.extend(extra.iter().map(std::ffi::OsStr::new));
    run(&args)
}

/// Files in tests/bad/ whose first line cannot carry an `# expect:` comment.
const NO_HEADER: [(&str, Option<(usize, usize)>); 1] = [("empty.sc", None)];

/// The expected line and column of a fixture: from `# expect: LINE:COL` (`-`: whole-file
/// error, no line).
fn expected_at(path: &Path) -> Option<(usize, usize)> {
    let name = path.file_name().unwrap().to_str().unwrap();
    if let Some((_, at)) = NO_HEADER.iter().find(|(n, _)| *n == name) {
        return *at;
    }
    let bytes = fs::read(path).unwrap();
    let first = bytes.split(|&b| b == b'\n').next().unwrap();
    let first = std::str::from_utf8(first).unwrap();
    let spec = first
        .strip_prefix("# expect: ")
        .unwrap_or_else(|| panic!("{name}: first line must be `# expect: LINE:COL (why)`"));
    let word = spec.split_whitespace().next().unwrap();
    if word == "-" {
        return None;
    }
    let (line, col) = word
        .split_once(':')
        .unwrap_or_else(|| panic!("{name}: `# expect: LINE:COL (why)`, got {word:?}"));
    Some((line.parse().unwrap(), col.parse().unwrap()))
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

/// A small valid scene written to `dir/name`.
fn good_scene(dir: &TempDir, name: &str) -> PathBuf {
    let p = dir.join(name);
    fs::write(&p, format!("{CAM}sphere 0 0 0 1\n")).unwrap();
    p
}

mod fixtures;
mod fuzz;
mod limits;
mod numbers;
mod outputs;

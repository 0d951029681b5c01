//! Standard output and standard error that close or fail: a reader that closes the pipe
//! (`compare | head -1`, `--help | head -1`, `-time 2>&1 | head -0`) is a quiet end with exit
//! 0; any other write error (`> /dev/full`, `2> /dev/full`) is exit 1 with a message, never a
//! panic (exit 101), and the run's files are in place either way.

use crate::common;

use common::*;
use std::fs::File;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Runs the binary in `dir` with its stdout (or stderr, `on_stderr`) a pipe whose reader has
/// already gone; the other stream is captured.
fn closed_pipe(dir: &TempDir, args: &[&str], on_stderr: bool) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args(args)
        .current_dir(&dir.path)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // the only read end, closed before the run writes anything
    match on_stderr {
        false => drop(child.stdout.take()),
        true => drop(child.stderr.take()),
    }
    child.wait_with_output().unwrap()
}

/// Runs the binary in `dir` with its stdout (or stderr) the full device `/dev/full`.
fn to_full(dir: &TempDir, args: &[&str], on_stderr: bool) -> Output {
    let full = || Stdio::from(File::options().write(true).open("/dev/full").unwrap());
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_lanecast"));
    cmd.args(args).current_dir(&dir.path);
    match on_stderr {
        false => cmd.stdout(full()).stderr(Stdio::piped()),
        true => cmd.stdout(Stdio::piped()).stderr(full()),
    };
    cmd.output().unwrap()
}

#[test]
fn a_closed_pipe_on_stdout_or_stderr_is_a_quiet_exit_0() {
    let dir = TempDir::new("streams-epipe");
    dir.copy_in(&seed_scene(1), "s.sc");
    let cases: [(&[&str], bool, &str); 4] = [
        (
            &["compare", "-i", "s.sc", "-size", "64x48", "-o", "d.png"],
            false,
            "d.png",
        ),
        (&["--help"], false, ""),
        (&["compare", "--help"], false, ""),
        (
            &["-i", "s.sc", "-size", "64x48", "-o", "t.png", "-time"],
            true,
            "t.png",
        ),
    ];
    for (args, on_stderr, file) in cases {
        for _ in 0..5 {
            let o = closed_pipe(&dir, args, on_stderr);
            let shown = format!("{args:?}: {}", stderr(&o));
            assert_eq!(o.status.code(), Some(0), "{shown}");
            assert!(on_stderr || o.stderr.is_empty(), "{shown}");
            assert!(file.is_empty() || dir.join(file).is_file(), "{shown}");
        }
    }
}

#[test]
fn a_full_stdout_or_stderr_is_exit_1_and_the_files_are_written() {
    if !Path::new("/dev/full").exists() {
        eprintln!("skipped: no /dev/full");
        return;
    }
    let dir = TempDir::new("streams-full");
    dir.copy_in(&seed_scene(1), "s.sc");
    // compare: the diff image is written, the report's failure named
    let o = to_full(
        &dir,
        &["compare", "-i", "s.sc", "-size", "64x48", "-o", "d.png"],
        false,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("<stdout>: cannot write the comparison report: No space left"),
        "{}",
        stderr(&o)
    );
    assert!(dir.join("d.png").is_file());
    let o = to_full(&dir, &["--help"], false);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("<stdout>: cannot write the help"),
        "{}",
        stderr(&o)
    );
    // -time to a full stderr: the message cannot be seen, the exit code says it
    for args in [
        &["-i", "s.sc", "-size", "64x48", "-o", "t.png", "-time"][..],
        &[
            "-i", "s.sc", "-size", "64x48", "--orbit", "2", "-o", "t%d.png", "-time",
        ][..],
    ] {
        let o = to_full(&dir, args, true);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
    }
    assert!(dir.join("t.png").is_file() && dir.join("t1.png").is_file());
}

/// A warning that cannot be written stops the run before its outputs (exit 1, nothing
/// written); one that can is written once and the run goes on.
#[test]
fn a_warning_that_cannot_be_written_stops_the_run() {
    if !Path::new("/dev/full").exists() {
        eprintln!("skipped: no /dev/full");
        return;
    }
    let dir = TempDir::new("streams-warning");
    dir.write(
        "d.obj",
        "v -1 -1 0\nv 0 -1 0\nv 1 -1 0\nv 1 1 0\nf 1 2 3\nf 1 3 4\n",
    );
    dir.write(
        "s.sc",
        "camera eye 0.3 -0.2 4 look 0.3 -0.2 0 up 0 1 0\nmesh d.obj\n",
    );
    for (args, out) in [
        (
            &["-i", "s.sc", "-size", "32x24", "-o", "o.png"][..],
            "o.png",
        ),
        (
            &[
                "-i", "s.sc", "-size", "32x24", "--orbit", "2", "-o", "v%d.png",
            ][..],
            "v0.png",
        ),
    ] {
        let o = to_full(&dir, args, true);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        assert!(!dir.join(out).exists(), "{args:?}");
        let o = run(&dir.path, args);
        assert_success(&o, "with a stderr");
        assert_eq!(stderr(&o).matches("warning").count(), 1, "{}", stderr(&o));
        assert!(dir.join(out).is_file());
    }
}

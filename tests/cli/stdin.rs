//! `-i -`: the scene read from standard input renders as the same file would, its mesh paths
//! relative to the working folder, its errors named `<stdin>`.

use crate::common;

use common::*;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Runs the binary in `cwd` with `input` on its standard input.
fn run_stdin(cwd: &Path, args: &[&str], input: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot start the lanecast binary");
    // A run refused before it reads its input closes the pipe: the write may then fail.
    let _ = child.stdin.take().unwrap().write_all(input.as_bytes());
    child.wait_with_output().unwrap()
}

#[test]
fn scene_from_stdin_renders_as_the_file_and_finds_meshes_from_the_working_folder() {
    let dir = TempDir::new("stdin");
    std::fs::create_dir(dir.join("m")).unwrap();
    dir.write(
        "m/quad.obj",
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n",
    );
    let text = "camera eye 0 0 5 look 0 0 0 up 0 1 0\nsphere 1 1 1 0.5\nmesh m/quad.obj\n";
    dir.write("s.sc", text);
    let o = run_stdin(
        &dir.path,
        &["-i", "-", "-o", "a.png", "--ids", "a.npy"],
        text,
    );
    assert_success(&o, "-i -");
    let o = run(&dir.path, &["-i", "s.sc", "-o", "b.png", "--ids", "b.npy"]);
    assert_success(&o, "-i s.sc");
    let read = |n: &str| std::fs::read(dir.join(n)).unwrap();
    assert_eq!(read("a.npy"), read("b.npy"));
    assert_eq!(read("a.png"), read("b.png"));
}

#[test]
fn stdin_errors_name_stdin_and_need_an_output() {
    let dir = TempDir::new("stdin-bad");
    let o = run_stdin(
        &dir.path,
        &["-i", "-", "-o", "x.png"],
        "camera eye 0 0 5 look 0 0 0 up 0 1 0\nsphere 0 0 x 1\n",
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("<stdin>:2:12:"), "{}", stderr(&o));
    let o = run_stdin(
        &dir.path,
        &["-i", "-"],
        "camera eye 0 0 5 look 0 0 0 up 0 1 0\n",
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("give -o IMAGE"), "{}", stderr(&o));
    assert!(
        std::fs::read_dir(&dir.path).unwrap().next().is_none(),
        "nothing written"
    );
}

/// `-o -` writes the image to standard output, byte for byte what the file would hold, PNG by
/// default and BMP with `--format bmp`; a `--format` that disagrees with a file name is refused.
#[test]
fn image_to_stdout_is_the_file_bytes_in_the_chosen_format() {
    let dir = TempDir::new("stdout");
    dir.copy_in(&seed_scene(2), "s.sc");
    for (format, ext) in [(None, "png"), (Some("bmp"), "bmp")] {
        let mut args = vec!["-i", "s.sc", "-o", "-"];
        args.extend(format.iter().flat_map(|f| ["--format", f]));
        let o = run(&dir.path, &args);
        assert_success(&o, "-o -");
        let file = format!("f.{ext}");
        assert_success(&run(&dir.path, &["-i", "s.sc", "-o", &file]), &file);
        assert_eq!(o.stdout, std::fs::read(dir.join(&file)).unwrap(), "{ext}");
    }
    let o = run(&dir.path, &["-i", "s.sc", "-o", "g.png", "--format", "bmp"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--format bmp"), "{}", stderr(&o));
    assert!(!dir.join("g.png").exists());
}

/// A reader that closes the pipe early (`lanecast -o - | head -c 8`) ends the run quietly:
/// exit 0, nothing on stderr, as ripgrep does. The BMP is 12 MB, far more than a pipe holds,
/// so the write does meet the closed pipe.
#[test]
fn a_reader_closing_the_pipe_early_is_a_quiet_end() {
    use std::io::Read;
    let dir = TempDir::new("stdout-epipe");
    dir.copy_in(&seed_scene(2), "s.sc");
    let mut child = Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args([
            "-i",
            "s.sc",
            "-o",
            "-",
            "--format",
            "bmp",
            "-size",
            "2000x2000",
        ])
        .current_dir(&dir.path)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut head = [0u8; 8];
    child.stdout.take().unwrap().read_exact(&mut head).unwrap();
    // the read end is dropped here: the rest of the image meets a closed pipe
    let o = child.wait_with_output().unwrap();
    assert_eq!(&head[..2], b"BM");
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A PNG written to a pipe whose reader has already gone (`lanecast -o - | true`) ends as
/// quietly as a BMP: exit 0, nothing on stderr. The read end is closed before the run writes
/// anything, so every size meets the closed pipe, the whole PNG in one write or many.
#[test]
fn broken_pipe_with_png_output_is_a_quiet_exit_0() {
    let dir = TempDir::new("stdout-epipe-png");
    dir.copy_in(&seed_scene(3), "s.sc");
    for (size, format) in [("64x48", "png"), ("2000x2000", "png"), ("64x48", "bmp")] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_lanecast"))
            .args(["-i", "s.sc", "-o", "-", "--format", format, "-size", size])
            .current_dir(&dir.path)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // the only read end: closed now, before the render is done
        drop(child.stdout.take());
        let o = child.wait_with_output().unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{format} {size}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(
            o.stderr.is_empty(),
            "{format} {size}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

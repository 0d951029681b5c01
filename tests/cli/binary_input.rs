//! A scene or OBJ whose first bytes hold a NUL is binary, not text: refused at once, naming the
//! file and the line of the NUL, without reading the rest (`-i /dev/zero` used to read 1 GiB
//! before refusing on size).

use crate::common;

use common::*;
use std::fs;
use std::process::{Command, Stdio};

const CAMERA: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0\n";

/// Asserts a refusal: exit 2, one `lanecast: error:` line starting with `at` and calling the
/// data binary, and the folder left as it was.
fn assert_binary(o: &std::process::Output, at: &str, dir: &TempDir, before: &[String]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.starts_with(&format!("lanecast: error: {at}")), "{err}");
    assert!(err.contains("binary data (byte 0x00)"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert_eq!(&dir.entries(), before, "nothing written");
}

#[test]
fn nul_bytes_at_the_start_refuse_a_scene_or_obj_as_binary() {
    let dir = TempDir::new("binary");
    let mut bytes = b"camera eye 0 0 5 look 0 0 0 up 0 1 0\n# ok\nsph\0re 0 0 0 1\n".to_vec();
    bytes.extend(std::iter::repeat_n(b'x', 100_000));
    fs::write(dir.join("bin.sc"), &bytes).unwrap();
    fs::write(dir.join("bin.obj"), b"\0\0\0\x01v 0 0 0\n").unwrap();
    dir.write(
        "uses.sc",
        &format!("{CAMERA}sphere 0 0 0 1\nmesh bin.obj\n"),
    );
    let before = dir.entries();
    let o = run(&dir.path, &["-i", "bin.sc", "-o", "a.png"]);
    assert_binary(&o, "bin.sc:3:4: ", &dir, &before);
    let o = run(&dir.path, &["-i", "bin.obj", "-o", "a.png"]);
    assert_binary(&o, "bin.obj:1:1: ", &dir, &before);
    let o = run(&dir.path, &["-i", "uses.sc", "-o", "a.png"]);
    assert_binary(&o, "bin.obj:1:1: ", &dir, &before);
}

/// `/dev/zero` never ends: refused from its first bytes (before, it was read up to the 1 GiB
/// limit and refused on size), as a scene, as an OBJ (through a link named `.obj`), as a mesh,
/// and on standard input.
#[cfg(target_os = "linux")]
#[test]
fn dev_zero_is_refused_as_binary_without_reading_it() {
    let dir = TempDir::new("dev-zero");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.obj")).unwrap();
    dir.write("mesh.sc", &format!("{CAMERA}mesh zero.obj\n"));
    let before = dir.entries();
    let o = run(&dir.path, &["-i", "/dev/zero", "-o", "a.png"]);
    assert_binary(&o, "/dev/zero:1:1: ", &dir, &before);
    let o = run(&dir.path, &["-i", "zero.obj", "-o", "a.png"]);
    assert_binary(&o, "zero.obj:1:1: ", &dir, &before);
    let o = run(&dir.path, &["-i", "mesh.sc", "-o", "a.png"]);
    assert_binary(&o, "zero.obj:1:1: ", &dir, &before);
    let o = Command::new(env!("CARGO_BIN_EXE_lanecast"))
        .args(["-i", "-", "-o", "a.png"])
        .current_dir(&dir.path)
        .stdin(fs::File::open("/dev/zero").unwrap())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_binary(&o, "<stdin>:1:1: ", &dir, &before);
}

/// A NUL past the first bytes read is left to the parser, which names its line too; text with
/// no NUL is untouched by the check.
#[test]
fn text_scenes_still_parse_and_a_late_nul_is_a_parse_error() {
    let dir = TempDir::new("binary-late");
    let mut text = CAMERA.to_string();
    for i in 0..2000 {
        text += &format!("sphere {i} 0 -10 0.5\n");
    }
    dir.write("ok.sc", &text);
    assert_success(&run(&dir.path, &["-i", "ok.sc", "-size", "32x24"]), "text");
    let late = format!("{text}sphere 0 0\0 0 1\n");
    dir.write("late.sc", &late);
    let o = run(&dir.path, &["-i", "late.sc", "-o", "late.png"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("late.sc:2002:"), "{}", stderr(&o));
}

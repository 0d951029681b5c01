//! `--eye`, `--look`, `--up`: each replaces that part of the scene's camera, with the camera
//! line's own rules; bad values are refused naming the flag, before anything is written.

use crate::common;

use common::*;
use std::fs;

/// The same render as a scene whose camera line says what the flags say, bit for bit.
#[test]
fn overrides_render_as_the_equivalent_camera_line() {
    let dir = TempDir::new("camera-flags");
    let text = fs::read_to_string(seed_scene(1)).unwrap();
    dir.write("a.sc", &text);
    let moved: String = text
        .lines()
        .map(|l| {
            if l.starts_with("camera") {
                "camera eye 0 3 12 look 0 1 0 up 0.1 1 0".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    dir.write("b.sc", &moved);
    let flags = ["--eye", "0,3,12", "--look", "0,1,0", "--up", "0.1,1,0"];
    let o = run(
        &dir.path,
        &[&["-i", "a.sc", "--ids", "a.npy"][..], &flags].concat(),
    );
    assert_success(&o, "overrides");
    let o = run(&dir.path, &["-i", "b.sc", "--ids", "b.npy"]);
    assert_success(&o, "camera line");
    let (a, b) = (
        fs::read(dir.join("a.npy")).unwrap(),
        fs::read(dir.join("b.npy")).unwrap(),
    );
    assert_eq!(a, b);
    let plain = run(&dir.path, &["-i", "a.sc", "--ids", "c.npy"]);
    assert_success(&plain, "scene camera");
    assert_ne!(
        fs::read(dir.join("c.npy")).unwrap(),
        a,
        "the flags must change the view"
    );
}

#[test]
fn bad_overrides_are_refused_naming_the_flag() {
    let dir = TempDir::new("camera-flags-bad");
    dir.copy_in(&seed_scene(1), "a.sc");
    for (args, want) in [
        (
            &["--eye", "1,2"][..],
            "--eye 1,2: expected three finite numbers",
        ),
        (
            &["--look", "1,2,inf"][..],
            "--look 1,2,inf: expected three finite numbers",
        ),
        (
            &["--up", "0,0,0"][..],
            "--up 0,0,0: camera up vector has zero length",
        ),
        (
            &["--eye", "0,0,0", "--look", "0,0,0"][..],
            "--eye 0,0,0 --look 0,0,0: camera eye and look",
        ),
    ] {
        let o = run(
            &dir.path,
            &[&["-i", "a.sc", "-o", "x.png"][..], args].concat(),
        );
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(want), "{args:?}: {}", stderr(&o));
        assert!(!dir.join("x.png").exists(), "{args:?}: nothing written");
    }
}

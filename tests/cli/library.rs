//! The library offers what the command line writes: `Frame::write_normals` gives the
//! `--normals` file byte for byte.

use crate::common;

use common::*;
use std::fs;

#[test]
fn write_normals_is_the_command_lines_normals_file() {
    let dir = TempDir::new("library-normals");
    let scene_path = dir.copy_in(&seed_scene(1), "s.sc");
    let o = run(
        &dir.path,
        &[
            "-i",
            "s.sc",
            "-size",
            "97x61",
            "-o",
            "a.png",
            "--normals",
            "cli.npy",
        ],
    );
    assert_success(&o, "--normals");
    let scene = lanecast::load_scene(&scene_path).unwrap();
    let camera = lanecast::Camera::for_scene(&scene, 97, 61, None).unwrap();
    let frame = lanecast::Renderer::new(&scene, &camera, &lanecast::Options::default())
        .unwrap()
        .render();
    frame
        .write_normals(&dir.join("lib.npy"), (&scene, &camera))
        .unwrap();
    assert_eq!(
        fs::read(dir.join("lib.npy")).unwrap(),
        fs::read(dir.join("cli.npy")).unwrap()
    );
}

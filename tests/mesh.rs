//! `mesh PATH` statements: OBJ triangles take consecutive ids, render like any triangle, and bad
//! OBJ files are refused naming the OBJ file and line.

mod common;

use common::*;
use lanecast::accel::Accel;
use lanecast::compare::compare_with;
use lanecast::scene::{Shape, load_scene};

#[test]
fn mesh_triangles_take_consecutive_ids_from_their_position() {
    let dir = TempDir::new("mesh-ids");
    dir.write(
        "quad.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
    );
    let sc = dir.write(
        "s.sc",
        "camera eye 0.5 0.5 3 look 0.5 0.5 0 up 0 1 0\nsphere 5 5 5 1\nmesh quad.obj\nsphere 0 0 -9 1\n",
    );
    let scene = load_scene(&sc).unwrap();
    assert_eq!(scene.shapes.len(), 4);
    assert!(matches!(scene.shapes[1], Shape::Triangle(_)));
    assert!(matches!(scene.shapes[2], Shape::Triangle(_)));
    assert!(matches!(scene.shapes[3], Shape::Sphere { .. }));
    assert_eq!(scene.lines, vec![2, 3, 3, 4]);
    assert!(scene.warnings.is_empty());
}

#[test]
fn real_meshes_agree_with_the_oracle_with_and_without_bvh() {
    for name in ["bunny", "teapot"] {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.sc"));
        let scene = load_scene(&path).unwrap();
        assert!(scene.shapes.len() > 900, "{name}: mesh loaded");
        let camera = camera_of(&scene, 320, 240);
        for accel in [Accel::None, Accel::Bvh, Accel::Tiles] {
            let (report, oracle) = compare_with(&scene, &camera, accel);
            assert_eq!(report.unexcused, 0, "{name} {accel:?}: {report:?}");
            let hits = oracle.ids.iter().filter(|&&i| i >= 0).count();
            assert!(
                hits > 320 * 240 / 10,
                "{name}: the mesh fills part of the frame"
            );
        }
    }
}

#[test]
fn bad_obj_names_obj_file_and_line_and_writes_nothing() {
    let dir = TempDir::new("mesh-bad");
    dir.write(
        "bad.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n# ok so far\nf 1 2 9\n",
    );
    dir.write(
        "s.sc",
        "camera eye 0 0 5 look 0 0 0 up 0 1 0\nmesh bad.obj\n",
    );
    let out = run(&dir.path, &["-i", "s.sc", "-o", "out.png"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.contains("bad.obj:5:") && err.contains("out of range"),
        "{err}"
    );
    assert!(!dir.join("out.png").exists());
}

#[test]
fn missing_mesh_names_the_scene_line() {
    let dir = TempDir::new("mesh-missing");
    dir.write(
        "s.sc",
        "camera eye 0 0 5 look 0 0 0 up 0 1 0\n\nmesh nowhere.obj\n",
    );
    let out = run(&dir.path, &["-i", "s.sc", "-o", "out.png"]);
    // a missing file is an I/O fault (exit 1), the scene's or a mesh's alike
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains("s.sc:3:") && err.contains("nowhere.obj"),
        "{err}"
    );
}

#[test]
fn degenerate_mesh_triangles_are_kept_never_hit_and_reported_once() {
    let dir = TempDir::new("mesh-degenerate");
    // triangle 0 is degenerate (collinear), triangle 1 faces the camera
    dir.write(
        "d.obj",
        "v -1 -1 0\nv 0 -1 0\nv 1 -1 0\nv 1 1 0\nf 1 2 3\nf 1 3 4\n",
    );
    dir.write(
        "s.sc",
        "camera eye 0.3 -0.2 4 look 0.3 -0.2 0 up 0 1 0\nmesh d.obj\n",
    );
    let out = run(
        &dir.path,
        &["-i", "s.sc", "-o", "o.png", "--ids", "ids.npy"],
    );
    assert_success(&out, "degenerate mesh");
    let err = stderr(&out);
    assert_eq!(err.matches("warning").count(), 1, "{err}");
    assert!(err.contains("1 degenerate"), "{err}");
    let ids = std::fs::read(dir.join("ids.npy")).unwrap();
    let data = &ids[ids.len() - 640 * 480 * 4..];
    let centre = (240 * 640 + 320) * 4;
    let id = i32::from_le_bytes(data[centre..centre + 4].try_into().unwrap());
    assert_eq!(
        id, 1,
        "the real triangle keeps id 1 after the degenerate one"
    );
    assert!(
        data.chunks(4)
            .all(|c| i32::from_le_bytes(c.try_into().unwrap()) != 0)
    );
}

//! `mesh PATH` statements: OBJ triangles take consecutive ids, render like any triangle, and bad
//! OBJ files are refused naming the OBJ file and line.

mod common;

use common::*;
use lanecast::Accel;
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
    assert!(matches!(scene.shapes.get(1), Shape::Triangle(_)));
    assert!(matches!(scene.shapes.get(2), Shape::Triangle(_)));
    assert!(matches!(scene.shapes.get(3), Shape::Sphere { .. }));
    assert_eq!(scene.shapes.lines().collect::<Vec<_>>(), vec![2, 3, 3, 4]);
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

/// `lanecast -i mesh.obj` renders the mesh alone with the framing camera: every face is a
/// primitive, the whole mesh is in view (no hit on the image border, and it covers a fair part
/// of the frame), the image goes beside the OBJ, and a mesh with no extent is refused.
#[test]
fn obj_renders_directly_framed_whole() {
    let dir = TempDir::new("mesh-direct");
    let bunny = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/meshes/bunny.obj");
    dir.copy_in(&bunny, "bunny.obj");
    let scene = load_scene(&dir.join("bunny.obj")).unwrap();
    assert_eq!(scene.shapes.len(), 3674);
    for (w, h) in [(320, 180), (200, 200), (180, 320)] {
        let size = format!("{w}x{h}");
        let o = run(
            &dir.path,
            &["-i", "bunny.obj", "-size", &size, "--ids", "ids.npy"],
        );
        assert_success(&o, &size);
        assert!(dir.join("bunny.png").exists());
        let ids = read_npy_i32(&dir.join("ids.npy"));
        let hit = |x: usize, y: usize| ids[y * w + x] >= 0;
        let border = (0..w).any(|x| hit(x, 0) || hit(x, h - 1))
            || (0..h).any(|y| hit(0, y) || hit(w - 1, y));
        assert!(!border, "{size}: the mesh reaches the border");
        let hits = ids.iter().filter(|&&i| i >= 0).count();
        assert!(
            hits > w * h / 50,
            "{size}: the mesh fills part of the frame ({hits})"
        );
    }
    dir.write("point.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n");
    let o = run(&dir.path, &["-i", "point.obj"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("point.obj: no faces with extent"),
        "{}",
        stderr(&o)
    );
}

/// The int32 values of a version-1 `.npy` file (header length in bytes 8..10).
fn read_npy_i32(path: &std::path::Path) -> Vec<i32> {
    let b = std::fs::read(path).unwrap();
    let start = 10 + u16::from_le_bytes([b[8], b[9]]) as usize;
    (b[start..].chunks_exact(4))
        .map(|c| i32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

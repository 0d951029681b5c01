//! `mesh PATH` statements: OBJ triangles take consecutive ids, render like any triangle, and bad
//! OBJ files are refused naming the OBJ file and line.

use crate::common;

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

/// The columns and rows the hits of `ids` (`w` wide) span, as (x0, x1, y0, y1), inclusive.
fn hit_box(ids: &[i32], w: usize) -> (usize, usize, usize, usize) {
    let mut b = (usize::MAX, 0, usize::MAX, 0);
    for (k, _) in ids.iter().enumerate().filter(|(_, i)| **i >= 0) {
        let (x, y) = (k % w, k / w);
        b = (b.0.min(x), b.1.max(x), b.2.min(y), b.3.max(y));
    }
    b
}

/// `lanecast -i mesh.obj` frames the mesh to fill most of the image (it filled about a
/// third): at the default 640x480 inside a 5% margin on each side, up to 16:9 inside 2%
/// (README "Camera"); a wider image, a narrower field of view and every view of a turntable
/// move the camera back just enough to keep the 5% margin, which the mesh then reaches.
#[test]
fn a_mesh_alone_fills_the_frame_within_the_stated_margin() {
    let dir = TempDir::new("mesh-framing");
    let meshes = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/meshes");
    for name in ["bunny.obj", "teapot.obj"] {
        dir.copy_in(&meshes.join(name), name);
        // (size, flags, margin kept, whether the mesh reaches it, the least share of the width
        // or height it fills)
        for (size, extra, margin, tight, fills) in [
            ("640x480", &[][..], 0.05, false, 0.6),
            ("320x180", &[][..], 0.02, false, 0.6),
            ("1000x300", &[][..], 0.05, true, 0.8),
            ("640x480", &["-fov", "30"][..], 0.05, true, 0.8),
            ("180x320", &[][..], 0.05, false, 0.0),
        ] {
            let mut args = vec!["-i", name, "--ids", "ids.npy", "-o", "o.png", "-size", size];
            args.extend(extra);
            assert_success(&run(&dir.path, &args), &args.join(" "));
            let (w, h) = size.split_once('x').unwrap();
            let (w, h): (usize, usize) = (w.parse().unwrap(), h.parse().unwrap());
            let ids = read_npy_i32(&dir.join("ids.npy"));
            let (x0, x1, y0, y1) = hit_box(&ids, w);
            let what = format!("{name} {size} {extra:?}: hits {x0}..={x1} x {y0}..={y1}");
            // inside the margin, a pixel of slack for the pixel grid
            let (mx, my) = (w as f64 * margin - 1.0, h as f64 * margin - 1.0);
            let gaps = [x0, w - 1 - x1, y0, h - 1 - y1].map(|g| g as f64);
            assert!(gaps[0] >= mx && gaps[1] >= mx, "{what}");
            assert!(gaps[2] >= my && gaps[3] >= my, "{what}");
            if tight {
                let near = gaps[..2].iter().any(|&g| g <= mx + 3.0)
                    || gaps[2..].iter().any(|&g| g <= my + 3.0);
                assert!(near, "{what}: the margin is reached");
            }
            let fill = ((x1 - x0 + 1) as f64 / w as f64).max((y1 - y0 + 1) as f64 / h as f64);
            assert!(fill > fills, "{what}: fills {fill:.2}");
        }
    }
    // a turntable of a mesh keeps every view inside the margin
    let o = run(
        &dir.path,
        &[
            "-i",
            "teapot.obj",
            "--orbit",
            "8",
            "-size",
            "160x120",
            "-o",
            "t%d.png",
            "--ids",
            "t%d.npy",
        ],
    );
    assert_success(&o, "orbit");
    for k in 0..8 {
        let ids = read_npy_i32(&dir.join(&format!("t{k}.npy")));
        let (x0, x1, y0, y1) = hit_box(&ids, 160);
        assert!(
            x0 >= 7 && x1 <= 152 && y0 >= 5 && y1 <= 114,
            "view {k}: {x0} {x1} {y0} {y1}"
        );
    }
}

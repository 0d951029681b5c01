//! Every rejected input of tests/bad/ and the text forms a scene may take.

use super::*;

#[test]
fn every_bad_fixture_is_rejected_with_its_line_and_no_output() {
    let mut checked = 0;
    for entry in fs::read_dir(bad_dir()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        if path.extension().is_none_or(|e| e != "sc") || name == "bom_crlf_valid.sc" {
            continue;
        }
        let out = TempDir::new("bad");
        let o = render_into(&path, &out);
        let at = expected_at(&path);
        assert_rejected(&path, at.map(|(line, _)| line), &o, &out);
        // README: every message about a line names its column too
        if let Some((line, col)) = at {
            let want = format!("{name}:{line}:{col}: ");
            assert!(
                stderr(&o).contains(&want),
                "{name}: expected {want:?} in {}",
                stderr(&o)
            );
        }
        checked += 1;
    }
    assert!(checked >= 28, "only {checked} fixtures");
}

#[test]
fn bom_crlf_valid_scene_renders() {
    let out = TempDir::new("bom");
    let o = render_into(&bad_dir().join("bom_crlf_valid.sc"), &out);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
    assert_eq!(out.entries(), ["depth.npy", "ids.npy", "out.png"]);
    let img = fs::read(out.join("out.png")).unwrap();
    assert_eq!(&img[..8], b"\x89PNG\r\n\x1a\n");
    // Both primitives are visible: ids 0 and 1 appear in the id buffer.
    let ids = fs::read(out.join("ids.npy")).unwrap();
    let ids: Vec<i32> = ids[128..]
        .chunks(4)
        .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert!(ids.contains(&0) && ids.contains(&1), "{ids:?}");
}

#[test]
fn one_megabyte_line_is_rejected() {
    let input = TempDir::new("long-in");
    let path = input.join("long_line.sc");
    let mut text = String::from(CAM);
    text.push_str("sphere 0 0 0 1 ");
    text.push_str(&"7 ".repeat(512 * 1024));
    text.push('\n');
    assert!(text.len() > 1 << 20);
    fs::write(&path, text).unwrap();
    let out = TempDir::new("long-out");
    let o = render_into(&path, &out);
    assert_rejected(&path, Some(2), &o, &out);
    assert!(
        stderr(&o).contains("long_line.sc:2:1: line is"),
        "{}",
        stderr(&o)
    );
    // A long line is reported in bytes, not echoed.
    assert!(stderr(&o).len() < 300);
}

/// A `mesh` line whose file yields no triangle (the scene itself, a text file, an OBJ of `v`
/// lines alone, a PLY of 0 faces) is refused at that line, naming the mesh file, instead of
/// rendering nothing with exit 0.
#[test]
fn a_mesh_line_whose_file_holds_no_triangles_is_refused() {
    let dir = TempDir::new("mesh-empty");
    dir.write("verts.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    dir.write("notes.txt", "just some text\n");
    dir.write(
        "nofaces.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
         property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n\
         0 0 0\n",
    );
    for mesh in ["self.sc", "verts.obj", "notes.txt", "nofaces.ply"] {
        let scene = dir.write(
            "self.sc",
            &format!("camera eye 0 0 5 look 0 0 0 up 0 1 0\n  mesh {mesh}\n"),
        );
        let out = TempDir::new("mesh-empty-out");
        let o = render_into(&scene, &out);
        assert_rejected(&scene, Some(2), &o, &out);
        let err = stderr(&o);
        assert!(err.contains("self.sc:2:8: mesh "), "{mesh}: {err}");
        assert!(
            err.contains(&format!("{mesh}: the file holds no triangles")),
            "{err}"
        );
    }
}

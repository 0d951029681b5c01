//! PLY meshes through the real binary: `-i x.ply` renders ids, depths and image byte-identical
//! to `-i x.obj` of the same data, in every encoding; `mesh x.ply` lines read PLY by extension in
//! any case; and every malformed file in tests/ply/ is refused with exit 2, one message naming
//! the file and its line or byte offset, and no output, whether named by `-i` or by a scene.

use crate::common;
use crate::ply_write;

use common::*;
use lanecast::experimental::scene::mesh::load_obj;
use ply_write::*;
use std::fs;
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/ply")
}

/// What a fixture's error message must hold: from its `comment expect: WHERE: TEXT` line,
/// `NAME:N: TEXT` (`line N`) or `NAME: at byte N: TEXT` (`byte N`); `None` for a file that
/// must render (`-`).
fn expected(path: &Path) -> Option<String> {
    let name = path.file_name().unwrap().to_str().unwrap();
    let bytes = fs::read(path).unwrap();
    let line = (bytes.split(|&b| b == b'\n'))
        .take(3)
        .find_map(|l| l.strip_prefix(b"comment expect: "))
        .unwrap_or_else(|| panic!("{name}: no `comment expect:` line"));
    let spec = std::str::from_utf8(line).unwrap().trim_end();
    if spec.starts_with('-') {
        return None;
    }
    let (place, text) = spec.split_once(": ").unwrap();
    Some(match place.split_once(' ') {
        Some(("line", n)) => format!("{name}:{n}: {text}"),
        Some(("byte", n)) => format!("{name}: at byte {n}: {text}"),
        _ => panic!("{name}: bad expectation {spec:?}"),
    })
}

/// Runs `args` in `dir` with a small image and every output; returns the run.
fn render(dir: &TempDir, input: &str) -> std::process::Output {
    let args = [
        "-i",
        input,
        "-o",
        "out.png",
        "--ids",
        "ids.npy",
        "--depth",
        "depth.npy",
    ];
    run(&dir.path, &[&args[..], &["-size", "48x32"]].concat())
}

#[test]
fn every_bad_ply_fixture_is_refused_with_its_place_and_no_output() {
    let mut checked = 0;
    let mut entries: Vec<PathBuf> = (fs::read_dir(fixtures()).unwrap())
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ply"))
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        let Some(want) = expected(&path) else {
            continue;
        };
        // named by -i, and by a scene's mesh line: the message names the PLY file either way
        let dir = TempDir::new("ply-bad");
        dir.copy_in(&path, &name);
        dir.write(
            "s.sc",
            &format!("camera eye 0 0 5 look 0 0 0 up 0 1 0\nmesh {name}\n"),
        );
        for input in [name.as_str(), "s.sc"] {
            let o = render(&dir, input);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(2), "{name} via {input}: {err}");
            assert!(err.starts_with("lanecast: error: "), "{name}: {err:?}");
            assert_eq!(err.lines().count(), 1, "{name}: one line: {err:?}");
            assert!(
                err.contains(&want),
                "{name} via {input}: {err:?}\nwant {want:?}"
            );
            let mut left = dir.entries();
            left.retain(|e| e != &name && e != "s.sc");
            assert!(left.is_empty(), "{name}: output appeared: {left:?}");
        }
        checked += 1;
    }
    assert!(checked >= 25, "only {checked} fixtures");
}

#[test]
fn valid_ply_fixtures_render_every_face() {
    let mut checked = 0;
    for name in [
        "valid_crlf_ascii.ply",
        "valid_binary_le.ply",
        "valid_binary_be.ply",
    ] {
        let path = fixtures().join(name);
        assert_eq!(expected(&path), None, "{name}");
        let dir = TempDir::new("ply-valid");
        dir.copy_in(&path, name);
        let o = render(&dir, name);
        assert_success(&o, name);
        assert!(o.stderr.is_empty(), "{name}: {}", stderr(&o));
        let ids = npy_i32(&dir.join("ids.npy"));
        let scene = lanecast::load_scene(&dir.join(name)).unwrap();
        // a quad and a polygon or triangle, fanned: each triangle is seen head-on
        for id in 0..scene.shapes.len() as i32 {
            assert!(ids.contains(&id), "{name}: triangle {id} is not hit");
        }
        checked += scene.shapes.len();
    }
    assert_eq!(checked, (2 + 3) + 2 * (2 + 1));
}

/// The int32 values of a version-1 `.npy` file (header length in bytes 8..10).
fn npy_i32(path: &Path) -> Vec<i32> {
    let b = fs::read(path).unwrap();
    let start = 10 + u16::from_le_bytes([b[8], b[9]]) as usize;
    (b[start..].chunks_exact(4))
        .map(|c| i32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// The vertices and faces of scenes/meshes/`name`.obj.
fn real(name: &str) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/meshes/{name}.obj"));
    let (mesh, _) = load_obj(&path, usize::MAX).unwrap();
    let verts = mesh.vertices.iter().map(|v| v.to_array()).collect();
    let faces = mesh.faces.iter().map(|f| f.to_vec()).collect();
    (verts, faces)
}

/// The outputs of rendering `input` in `dir`: image, ids and depth bytes.
fn outputs(dir: &TempDir, input: &str) -> [Vec<u8>; 3] {
    let o = render(dir, input);
    assert_success(&o, input);
    ["out.png", "ids.npy", "depth.npy"].map(|f| fs::read(dir.join(f)).unwrap())
}

#[test]
fn ply_renders_byte_identical_to_the_obj_of_the_same_data() {
    let dir = TempDir::new("ply-render");
    let (verts, faces) = real("bunny");
    let rounded: Vec<[f64; 3]> = (verts.iter()).map(|v| v.map(|c| c as f32 as f64)).collect();
    for (verts, ty) in [(&verts, "double"), (&rounded, "float32")] {
        dir.write("b.obj", &obj(verts, &faces));
        let want = outputs(&dir, "b.obj");
        let hits = npy_i32(&dir.join("ids.npy"))
            .iter()
            .filter(|&&i| i >= 0)
            .count();
        assert!(hits > 48 * 32 / 20, "the bunny fills part of the frame");
        for enc in ENCODINGS {
            let name = format!("b_{enc:?}.ply");
            fs::write(
                dir.join(&name),
                ply(enc, &mesh_elems(verts, &faces, ty), &[], "\n"),
            )
            .unwrap();
            assert!(
                outputs(&dir, &name) == want,
                "{name} ({ty}) renders differently"
            );
        }
    }
    // with no -o the image goes beside the PLY, as beside an OBJ
    let o = run(&dir.path, &["-i", "b_Big.ply", "-size", "16x16"]);
    assert_success(&o, "no -o");
    assert!(dir.join("b_Big.png").is_file());
}

#[test]
fn mesh_lines_read_ply_by_extension_in_any_case() {
    let dir = TempDir::new("ply-mesh-line");
    let (verts, mut faces) = real("teapot");
    // one degenerate face (a repeated vertex): kept, never hit, reported once
    faces[5] = vec![faces[5][0], faces[5][0], faces[5][1]];
    dir.write("t.obj", &obj(&verts, &faces));
    let elems = mesh_elems(&verts, &faces, "double");
    fs::write(dir.join("t.ply"), ply(Encoding::Little, &elems, &[], "\n")).unwrap();
    fs::write(
        dir.join("T2.PLY"),
        ply(Encoding::Ascii, &elems, &[], "\r\n"),
    )
    .unwrap();
    let scene = |mesh: &str| {
        let cam = "camera eye 24 18 32 look 0 -1 0 up 0 1 0 fov 50\n";
        format!("sphere -30 0 0 1\n{cam}mesh {mesh}\nsphere 0 -9 0 1\n")
    };
    dir.write("obj.sc", &scene("t.obj"));
    let want = outputs(&dir, "obj.sc");
    let warning = stderr(&run(&dir.path, &["-i", "obj.sc", "-o", "w.png"]));
    assert!(warning.contains("1 degenerate triangle kept"), "{warning}");
    for mesh in ["t.ply", "T2.PLY"] {
        dir.write("ply.sc", &scene(mesh));
        assert!(
            outputs(&dir, "ply.sc") == want,
            "{mesh}: renders differently"
        );
        let o = run(&dir.path, &["-i", "ply.sc", "-o", "w.png"]);
        let same = warning.replace("obj.sc", "ply.sc").replace("t.obj", mesh);
        assert_eq!(stderr(&o), same, "{mesh}: the same warning");
    }
    // the mesh's triangles take the ids after the first sphere's
    let ids = npy_i32(&dir.join("ids.npy"));
    let n = faces.len() as i32;
    assert!(ids.iter().any(|&i| i > 0 && i <= n), "the mesh is in view");
}

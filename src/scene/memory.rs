//! Scenes and meshes from memory: for a caller with no file system (the browser front, `web/`),
//! or one that holds its files already. The same parse as [`load_scene`](super::load_scene),
//! with the same messages; only where the bytes come from differs.
//!
//! - [`parse_scene_with`]: `.sc` bytes, each `mesh` line's file asked of a lookup function
//!   (given the path as the command line would resolve it: joined to the scene's folder).
//! - [`parse_mesh_bytes`]: an OBJ or PLY file's bytes as a scene on their own, with the
//!   framing camera `lanecast -i mesh.obj` gives it.

use super::chunks::{self, BINARY_PROBE};
use super::mesh::{MeshFiles, mesh_from_bytes};
use super::{Scene, parse, range};
use crate::error::Result;
use crate::limits::MAX_PRIMITIVES;
use std::path::Path;

/// [`parse_scene`](super::parse_scene) for a scene's bytes in memory, its `mesh` files from
/// `meshes`: called with each `mesh` line's path joined to `file`'s folder (as
/// [`load_scene`](super::load_scene) would open it), it returns that file's bytes, or `None`,
/// which fails as a file that cannot be read, at the `mesh` line. The bytes are checked as
/// UTF-8 and for NULs with the command line's messages; `file` names the scene in them.
///
/// ```
/// use std::path::Path;
/// let text = b"camera eye 0 0 5 look 0 0 0 up 0 1 0\nsphere 0 0 0 1\nmesh m/tri.obj\n";
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
/// let get = |p: &Path| (p == Path::new("dir/m/tri.obj")).then(|| obj.clone());
/// let scene = lanecast::scene::parse_scene_with(text, Path::new("dir/a.sc"), &get)?;
/// assert_eq!(scene.shapes.len(), 2);
/// let e = lanecast::scene::parse_scene_with(text, Path::new("b.sc"), &get).unwrap_err();
/// assert!(e.to_string().starts_with("b.sc:3:"), "{e}");
/// # Ok::<(), lanecast::Error>(())
/// ```
pub fn parse_scene_with(
    bytes: &[u8],
    file: &Path,
    meshes: &dyn Fn(&Path) -> Option<Vec<u8>>,
) -> Result<Scene> {
    let head = &bytes[..bytes.len().min(BINARY_PROBE)];
    chunks::refuse_binary(file, head, "scene files")?;
    let chunk = chunks::chunk_bytes(bytes.len());
    let files = MeshFiles::Memory(meshes);
    let scene =
        parse::parse_bytes_meshes(bytes, file, MAX_PRIMITIVES, chunk, files, &mut Vec::new())?;
    range::f32_range_text(&scene, bytes)?;
    Ok(scene)
}

/// An OBJ or PLY file's bytes (the format by `file`'s extension: `.ply` is PLY, anything else
/// OBJ) as a scene of their own, as `lanecast -i mesh.obj` renders the file: its faces as
/// triangles in file order (ids from 0, scene line 0), seen by the mesh's framing camera
/// (`scene::parse::framing_camera`).
pub fn parse_mesh_bytes(bytes: &[u8], file: &Path) -> Result<Scene> {
    let scene = parse::mesh_scene(file, mesh_from_bytes(bytes, file, MAX_PRIMITIVES)?)?;
    range::f32_range(&scene)?;
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scene in memory (no file to read back) names the column of a range error as the
    /// file on disk does: the browser's messages are the command line's.
    #[test]
    fn range_errors_in_memory_give_the_files_column() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad/f32_tiny_radius.sc");
        let bytes = std::fs::read(&path).unwrap();
        let from_disk = crate::scene::load_scene(&path).unwrap_err().to_string();
        let in_memory = parse_scene_with(&bytes, &path.with_file_name("nowhere.sc"), &|_| None)
            .unwrap_err()
            .to_string();
        let col = |m: &str| m.split(':').nth(2).map(str::to_string);
        assert_eq!(
            col(&from_disk),
            col(&in_memory),
            "{from_disk} / {in_memory}"
        );
        assert!(
            col(&in_memory).is_some_and(|c| c.parse::<usize>().is_ok_and(|c| c > 1)),
            "{in_memory}"
        );
    }
    use std::path::PathBuf;

    fn repo(p: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join(p)
    }

    /// The file at `p`, read from disk: the lookup that makes memory loads match disk loads.
    fn from_disk(p: &Path) -> Option<Vec<u8>> {
        std::fs::read(p).ok()
    }

    #[test]
    fn memory_scenes_equal_disk_scenes() {
        for name in ["scene1.sc", "bunny.sc", "teapot.sc"] {
            let path = repo(&format!("scenes/{name}"));
            let disk = crate::scene::load_scene(&path).unwrap();
            let bytes = std::fs::read(&path).unwrap();
            let mem = parse_scene_with(&bytes, &path, &from_disk).unwrap();
            assert_eq!(mem, disk, "{name}");
        }
    }

    #[test]
    fn a_bare_mesh_equals_the_disk_loader() {
        let path = repo("scenes/meshes/teapot.obj");
        let disk = crate::scene::load_scene(&path).unwrap();
        let mem = parse_mesh_bytes(&std::fs::read(&path).unwrap(), &path).unwrap();
        assert_eq!(mem, disk);
        assert!(mem.shapes.len() > 100);
    }

    #[test]
    fn errors_read_as_the_command_lines() {
        let f = Path::new("s.sc");
        let none = |_: &Path| None;
        let e = parse_scene_with(
            b"camera eye 0 0 5 look 0 0 0 up 0 1 0\nsphere 0 0 0\n",
            f,
            &none,
        )
        .unwrap_err();
        let disk_text = "camera eye 0 0 5 look 0 0 0 up 0 1 0\nsphere 0 0 0\n";
        let disk = crate::scene::parse_scene(disk_text, f).unwrap_err();
        assert_eq!(e.to_string(), disk.to_string());
        assert!(e.to_string().starts_with("s.sc:2:"), "{e}");
        // a mesh that is not given fails at its line
        let e = parse_scene_with(
            b"camera eye 0 0 5 look 0 0 0 up 0 1 0\nmesh x.obj\n",
            f,
            &none,
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("s.sc:2:") && e.contains("x.obj"), "{e}");
        // a binary scene, and invalid UTF-8, as the command line words them
        let e = parse_scene_with(b"camera\0", f, &none)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("s.sc:1:7: binary data"), "{e}");
        let e = parse_scene_with(b"# \xff\n", f, &none)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("s.sc:1:3: not valid UTF-8"), "{e}");
        // a bad mesh names the mesh file and its line
        let obj = |_: &Path| Some(b"v 0 0 0\nf 1 2 3\n".to_vec());
        let e = parse_scene_with(
            b"camera eye 0 0 5 look 0 0 0 up 0 1 0\nmesh m.obj\n",
            f,
            &obj,
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("m.obj:2:"), "{e}");
        let e = parse_mesh_bytes(b"v 0 0 0\n", Path::new("m.obj"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no faces"), "{e}");
    }
}

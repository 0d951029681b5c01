//! `mesh PATH`: triangles from a Wavefront OBJ file, or a PLY file (`ply.rs`), by the file's
//! extension ([`load_mesh`]).
//!
//! Read here, by hand, rather than with an OBJ crate: only `v` and `f` lines matter, and every
//! error must name the OBJ file and line, which the crates' error types do not carry. `v x y z
//! [w]` adds a vertex (w ignored); `f i j k ...` adds a polygon, fan-triangulated from its first
//! vertex: (1,2,3), (1,3,4), ... Indices are 1-based, negative ones count back from the last
//! vertex, and `i/t/n` forms use the vertex index `i`. Every other statement (`vt`, `vn`, `o`,
//! `g`, `s`, `usemtl`, `mtllib`, ...) and `#` comments are ignored.
//!
//! Degenerate triangles (zero area, as real scans contain) are kept, so that the ids of the
//! others do not shift: they take their id and are never hit. The caller reports how many.
//!
//! # In parallel, with the answers of a sequential reader
//!
//! The file is read once into one buffer and cut at line ends into chunks that know the global
//! number of their first line (`chunks.rs`, as for `.sc` files). Each chunk is read in parallel
//! (`obj.rs`): its vertices, and its faces as the indices written. Whether an index is in range
//! depends on the vertices before it, in earlier chunks too, so once every chunk is read the
//! vertex and triangle counts are prefix-summed and every chunk is checked in parallel against
//! them; the first error in file order wins, worded and numbered as reading line by line would.
//! Then the vertices are joined into one list and the faces' vertex indices written in
//! parallel, in file order: the mesh stays indexed ([`Mesh`]), about 24 bytes a triangle. A shared budget bounds what chunks hold to the triangle limit (see `parse.rs`).

use super::chunks::{self, BINARY_PROBE, Budget, Chunk};
use super::obj::{self, Base, Halt, ObjChunk, Stop};
use super::shapes::Mesh;
use crate::error::{Error, Result};
use crate::limits::MAX_SCENE_BYTES;
use crate::par::prelude::*;
use glam::DVec3;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

pub use super::ply::{load_ply, parse_ply};

/// The mesh formats lanecast reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ ([`load_obj`]).
    Obj,
    /// PLY, ASCII or binary ([`load_ply`]).
    Ply,
}

impl MeshFormat {
    /// The format of the file at `path`, by its extension (case-insensitive): `.ply` is PLY,
    /// `.obj` is OBJ, anything else `None`.
    pub fn of(path: &Path) -> Option<MeshFormat> {
        let ext = path.extension().and_then(|e| e.to_str())?;
        if ext.eq_ignore_ascii_case("ply") {
            Some(MeshFormat::Ply)
        } else if ext.eq_ignore_ascii_case("obj") {
            Some(MeshFormat::Obj)
        } else {
            None
        }
    }
}

/// The triangles of the mesh file at `path`, in file order, and how many are degenerate: a
/// `.ply` file (any case) through [`load_ply`], any other through [`load_obj`]. The choice is
/// the extension's alone, made before the file is read: a binary PLY body holds NUL bytes, and
/// no check meant for text files sees it.
pub fn load_mesh(path: &Path, max_triangles: usize) -> Result<(Mesh, usize)> {
    match MeshFormat::of(path) {
        Some(MeshFormat::Ply) => load_ply(path, max_triangles),
        Some(MeshFormat::Obj) | None => load_obj(path, max_triangles),
    }
}

/// The bytes of the mesh file at `path`, its size checked against `MAX_SCENE_BYTES` first;
/// refused as binary when its first bytes hold a NUL and `text` names the text expected
/// ([`chunks::read_file`]).
pub(super) fn read_mesh_file(path: &Path, text: Option<&str>) -> Result<Vec<u8>> {
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, "read mesh", e))?;
    if meta.len() > MAX_SCENE_BYTES {
        return Err(Error::InputFile {
            file: path.to_path_buf(),
            msg: format!(
                "mesh file is {} bytes; the limit is {MAX_SCENE_BYTES}",
                meta.len()
            ),
        });
    }
    chunks::read_file(path, MAX_SCENE_BYTES, "read mesh", text)
}

/// The triangles of the OBJ file at `path`, in file order, and how many are degenerate.
pub fn load_obj(path: &Path, max_triangles: usize) -> Result<(Mesh, usize)> {
    let bytes = read_mesh_file(path, Some("OBJ files"))?;
    parse_obj(&bytes, path, max_triangles)
}

/// [`load_obj`] on bytes already read; `path` names them in messages.
pub fn parse_obj(bytes: &[u8], path: &Path, max_triangles: usize) -> Result<(Mesh, usize)> {
    parse_chunked(bytes, path, max_triangles, chunks::chunk_bytes(bytes.len()))
}

/// [`parse_obj`] with chunks of about `chunk_bytes`.
pub(super) fn parse_chunked(
    bytes: &[u8],
    path: &Path,
    max_triangles: usize,
    chunk_bytes: usize,
) -> Result<(Mesh, usize)> {
    parse_chunks(bytes, path, max_triangles, chunk_bytes).map_err(|e| obj::with_column(e, bytes))
}

/// [`parse_chunked`], its errors' columns not yet found.
fn parse_chunks(
    bytes: &[u8],
    path: &Path,
    max_triangles: usize,
    chunk_bytes: usize,
) -> Result<(Mesh, usize)> {
    let parts = chunks::split(bytes, chunk_bytes);
    let read =
        |c: &Chunk, budget: &Budget| obj::read(&bytes[c.range.clone()], c.first_line, path, budget);
    let budget = Budget::new(max_triangles);
    let chunks: Vec<ObjChunk> = parts.par_iter().map(|c| read(c, &budget)).collect();
    let line = match finish(chunks, path, max_triangles) {
        Ok(mesh) => return Ok(mesh),
        Err(Halt::Error(e)) => return Err(e),
        Err(Halt::Rerun(_)) => {
            // The budget ran out out of order: once more, one chunk after the other.
            let budget = Budget::new(max_triangles);
            let mut chunks = Vec::new();
            for c in &parts {
                let chunk = read(c, &budget);
                let stopped = chunk.stop.is_some();
                chunks.push(chunk);
                if stopped {
                    break;
                }
            }
            match finish(chunks, path, max_triangles) {
                Ok(mesh) => return Ok(mesh),
                Err(Halt::Error(e)) => return Err(e),
                // In order, the budget runs out only past the limit, which `obj::check` finds.
                Err(Halt::Rerun(line)) => line,
            }
        }
    };
    let msg = format!("too many triangles: a scene holds at most {max_triangles} primitives");
    Err(Error::input(path, line, 0, msg))
}

/// The chunks, read, joined in file order: every chunk checked in parallel (the first error in
/// file order wins), every vertex in one list, then the triangles built in parallel, each
/// written once, straight into the final list.
fn finish(
    mut chunks: Vec<ObjChunk>,
    path: &Path,
    max: usize,
) -> std::result::Result<(Mesh, usize), Halt> {
    // nothing after the first chunk that stopped matters
    if let Some(k) = chunks.iter().position(|c| c.stop.is_some()) {
        chunks.truncate(k + 1);
    }
    let mut bases = Vec::with_capacity(chunks.len());
    let (mut verts, mut tris) = (0, 0);
    for c in &chunks {
        bases.push(Base { verts, tris });
        verts += c.verts.len();
        tris += c.tris;
    }
    let stops: Vec<Option<Stop>> = chunks.iter_mut().map(|c| c.stop.take()).collect();
    let checked: Vec<_> = (chunks.par_iter().zip(stops).zip(&bases))
        .map(|((c, stop), &base)| obj::check(c, stop, base, max, path))
        .collect();
    checked
        .into_iter()
        .collect::<std::result::Result<(), Halt>>()?;
    // past the checks, every index is in range and there are at most `max` triangles
    let lens: Vec<usize> = chunks.iter().map(|c| c.verts.len()).collect();
    // the file is at most MAX_SCENE_BYTES (1 GiB), so vertex indices fit in 32 bits
    assert!(
        verts <= u32::MAX as usize,
        "vertex count under the file size limit"
    );
    let verts: Vec<DVec3> = chunks::gather(&lens, |p, j| chunks[p].verts[j]).collect();
    if chunks.iter().all(ObjChunk::triangles_only) {
        let zero = AtomicUsize::new(0);
        let lens: Vec<usize> = chunks.iter().map(|c| c.tris).collect();
        let faces = chunks::gather(&lens, |p, j| {
            let t = obj::triangle(&chunks[p], j, bases[p]);
            if obj::degenerate(&t.map(|i| verts[i as usize])) {
                zero.fetch_add(1, Ordering::Relaxed);
            }
            t
        });
        let faces = faces.collect();
        drop(chunks);
        let mesh = Mesh {
            vertices: verts,
            faces,
        };
        return Ok((mesh, zero.into_inner()));
    }
    // polygons: chunk j's triangles fill slice j of a zeroed list
    let mut out: Vec<[u32; 3]> = (0..tris).into_par_iter().map(|_| [0; 3]).collect();
    let mut slices = Vec::with_capacity(chunks.len());
    let mut rest = out.as_mut_slice();
    for c in &chunks {
        let (mine, after) = rest.split_at_mut(c.tris);
        slices.push(mine);
        rest = after;
    }
    let zero: usize = (chunks.par_iter().zip(&bases).zip(slices))
        .map(|((c, &base), slice)| obj::write(c, base, &verts, slice))
        .sum();
    let mesh = Mesh {
        vertices: verts,
        faces: out,
    };
    Ok((mesh, zero))
}

/// Where a scene's `mesh` files are read from.
#[derive(Clone, Copy)]
pub(super) enum MeshFiles<'a> {
    /// From disk ([`load_mesh`]).
    Disk,
    /// From a lookup function: `None` when it has no file at that path.
    Memory(&'a dyn Fn(&Path) -> Option<Vec<u8>>),
}

impl MeshFiles<'_> {
    /// The triangles of the mesh file at `path`, with room for `room` of them, and how many
    /// are degenerate.
    pub(super) fn load(self, path: &Path, room: usize) -> Result<(Mesh, usize)> {
        match self {
            MeshFiles::Disk => load_mesh(path, room),
            MeshFiles::Memory(get) => match get(path) {
                Some(bytes) => mesh_from_bytes(&bytes, path, room),
                None => Err(Error::io(
                    path,
                    "read mesh",
                    std::io::Error::new(
                        std::io::ErrorKind::NotFound,
                        "not among the files given with the scene",
                    ),
                )),
            },
        }
    }
}

/// A mesh file's bytes as [`load_mesh`] reads them from disk: the same size limit, the
/// format by `path`'s extension, an OBJ refused as binary when its first bytes hold a NUL.
pub(super) fn mesh_from_bytes(
    bytes: &[u8],
    path: &Path,
    max_triangles: usize,
) -> Result<(Mesh, usize)> {
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(Error::InputFile {
            file: path.to_path_buf(),
            msg: format!(
                "mesh file is {} bytes; the limit is {MAX_SCENE_BYTES}",
                bytes.len()
            ),
        });
    }
    match MeshFormat::of(path) {
        Some(MeshFormat::Ply) => parse_ply(bytes, path, max_triangles),
        Some(MeshFormat::Obj) | None => {
            let head = &bytes[..bytes.len().min(BINARY_PROBE)];
            chunks::refuse_binary(path, head, "OBJ files")?;
            parse_obj(bytes, path, max_triangles)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<(Vec<[DVec3; 3]>, usize)> {
        let (mesh, zero) = parse_obj(text.as_bytes(), Path::new("m.obj"), 1000)?;
        Ok(((0..mesh.len()).map(|f| mesh.triangle(f)).collect(), zero))
    }

    #[test]
    fn fan_triangulates_polygons_and_resolves_index_forms() {
        let (t, deg) = parse(
            "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1/1/1 2//1 3 4\nf -4 -3 -2\n",
        )
        .unwrap();
        assert_eq!(t.len(), 3);
        assert_eq!(deg, 0);
        assert_eq!(t[0], [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)]);
        assert_eq!(t[1], [DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0), DVec3::Y]);
        assert_eq!(t[2], t[0]);
    }

    #[test]
    fn degenerate_triangles_are_kept_and_counted() {
        let (t, deg) = parse("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n").unwrap();
        assert_eq!((t.len(), deg), (2, 1));
    }

    #[test]
    fn errors_name_file_and_line() {
        for (text, line, word) in [
            ("v 0 0 0\nv 1 0\n", 2, "3 coordinates"),
            ("v 0 0 0\nv 1 0 nan\n", 2, "finite"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n", 5, "out of range"),
            ("v 0 0 0\nf 0 1 1\n", 2, "index 0"),
            ("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "at least 3"),
            ("v 0 0 0\nf 1 x 1\n", 2, "vertex index"),
        ] {
            let e = parse(text).unwrap_err().to_string();
            assert!(e.starts_with(&format!("m.obj:{line}:")), "{e}");
            assert!(e.contains(word), "{e}");
        }
    }

    #[test]
    fn triangle_limit_is_enforced() {
        let e = parse_obj(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\n",
            Path::new("m.obj"),
            1,
        );
        assert!(e.unwrap_err().to_string().contains("too many"));
    }
}

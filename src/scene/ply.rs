//! `mesh PATH.ply` and `-i PATH.ply`: triangles from a PLY file (the Polygon File Format, or
//! Stanford Triangle Format, of Greg Turk, as described on Paul Bourke's page), in its three
//! encodings: `format ascii 1.0`, `format binary_little_endian 1.0` and
//! `format binary_big_endian 1.0`.
//!
//! The header (`header.rs`) is ASCII text, one statement a line, lines ending in `\n` or `\r\n`:
//! `ply`, one `format` line, then `element NAME COUNT` lines each followed by the
//! `property TYPE NAME` and `property list COUNT_TYPE ITEM_TYPE NAME` lines of its records, up to
//! `end_header`; `comment` and `obj_info` lines may come anywhere and are ignored. Types: `char`
//! `uchar` `short` `ushort` `int` `uint` `float` `double`, and their aliases `int8` `uint8`
//! `int16` `uint16` `int32` `uint32` `float32` `float64`. The body holds the records of every
//! element, in header order: one record per line in ASCII (`ascii.rs`), packed with no padding
//! in binary (`binary.rs`).
//!
//! lanecast reads the `x`, `y`, `z` properties of element `vertex` (any numeric types; its other
//! properties, normals and colours among them, are skipped) and the list `vertex_indices` (or
//! `vertex_index`, whichever comes first) of element `face`, whose items are 0-based vertex
//! indices of an integer type. Every other element (edges, materials, ...) is read past: in
//! ASCII line by line, in binary by the sizes of its properties, lists included. A face of n
//! vertices is fan-triangulated from its first vertex, (0,1,2), (0,2,3), ..., as the OBJ reader
//! does, and the mesh is the same indexed [`Mesh`] (about 24 bytes a triangle). Degenerate
//! triangles are kept, take their id and are never hit; the caller reports how many.
//!
//! Refused, with the file and the header or ASCII line, or the byte offset in a binary body: a
//! first line other than `ply`; a format other than the three above, or a version other than
//! 1.0; an unknown keyword or type; a list count of a float type; a missing `vertex` element, or
//! `x`, `y` or `z`, or one that is a list; a missing `face` element or index list, or indices of
//! a float type; an element with records but no properties; counts the file is too short for
//! (checked from the header alone, before anything is allocated for them); a body cut short; a
//! value that does not parse as its type (ASCII); a coordinate that is NaN or infinite; a face
//! of fewer than 3 vertices or a negative list count; an index out of range (the message names
//! the face, counted from 0); more triangles than the limit; and trailing data: anything after
//! the last record the header declares (in ASCII, anything but whitespace and blank lines), since
//! it means the counts do not describe the file.

mod ascii;
mod binary;
mod header;
mod walk;

#[cfg(test)]
mod tests;

use super::mesh::read_mesh_file;
use super::obj::degenerate;
use super::shapes::Mesh;
use crate::error::{Error, Result};
use crate::par::prelude::*;
use glam::DVec3;
use header::Format;
use std::path::{Path, PathBuf};

/// The triangles of the PLY file at `path`, in file order, and how many are degenerate.
pub fn load_ply(path: &Path, max_triangles: usize) -> Result<(Mesh, usize)> {
    let bytes = read_mesh_file(path, None)?; // a binary body holds NULs
    parse_ply(&bytes, path, max_triangles)
}

/// [`load_ply`] on bytes already read; `path` names them in messages.
pub fn parse_ply(bytes: &[u8], path: &Path, max_triangles: usize) -> Result<(Mesh, usize)> {
    let h = header::parse(bytes, path)?;
    let (v, f) = (&h.elements[h.vertex], &h.elements[h.face]);
    // every face is at least one triangle
    if f.count > max_triangles {
        let msg = format!("{} faces: {}", f.count, walk::too_many(max_triangles));
        return Err(Error::input(path, f.line, 0, msg));
    }
    // triangles hold their vertex indices in 32 bits
    if v.count > u32::MAX as usize {
        let msg = format!("{} vertices; a mesh holds at most {}", v.count, u32::MAX);
        return Err(Error::input(path, v.line, 0, msg));
    }
    let Body {
        vertices,
        faces,
        degenerate: counted,
    } = match h.format {
        Format::Ascii => ascii::read(bytes, &h, path, max_triangles)?,
        Format::Binary { big } => binary::read(bytes, &h, big, path, max_triangles)?,
    };
    let zero = counted.unwrap_or_else(|| {
        (faces.par_iter())
            .filter(|t| degenerate(&t.map(|i| vertices[i as usize])))
            .count()
    });
    Ok((Mesh { vertices, faces }, zero))
}

/// A body, read: the vertices, the triangles, and how many triangles are degenerate when the
/// reader counted them on the way.
struct Body {
    vertices: Vec<DVec3>,
    faces: Vec<[u32; 3]>,
    degenerate: Option<usize>,
}

/// An error at byte `offset` of the file `path` (in a binary body).
fn at_byte(path: &Path, offset: usize, msg: String) -> Error {
    Error::InputFile {
        file: PathBuf::from(path),
        msg: format!("at byte {offset}: {msg}"),
    }
}

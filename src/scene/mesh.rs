//! `mesh PATH`: triangles from a Wavefront OBJ file.
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

use crate::error::{Error, Result};
use crate::limits::{MAX_LINE_BYTES, MAX_SCENE_BYTES};
use glam::DVec3;
use std::path::Path;

/// The triangles of the OBJ file at `path`, in file order, and how many are degenerate.
pub fn load_obj(path: &Path, max_triangles: usize) -> Result<(Vec<[DVec3; 3]>, usize)> {
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
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, "read mesh", e))?;
    parse_obj(&bytes, path, max_triangles)
}

/// [`load_obj`] on bytes already read; `path` names them in messages.
pub fn parse_obj(
    bytes: &[u8],
    path: &Path,
    max_triangles: usize,
) -> Result<(Vec<[DVec3; 3]>, usize)> {
    let mut verts: Vec<DVec3> = Vec::new();
    let mut tris: Vec<[DVec3; 3]> = Vec::new();
    let mut degenerate = 0;
    let mut face: Vec<DVec3> = Vec::new();
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line_no = i + 1;
        let err = |msg: String| Error::input(path, line_no, 0, msg);
        if raw.len() > MAX_LINE_BYTES {
            return Err(err(format!(
                "line is {} bytes long; the limit is {MAX_LINE_BYTES}",
                raw.len()
            )));
        }
        let line = std::str::from_utf8(raw).map_err(|_| err("not valid UTF-8".into()))?;
        let line = line.split('#').next().unwrap_or("").trim();
        let mut toks = line.split_ascii_whitespace();
        match toks.next() {
            Some("v") => {
                let mut c = [0.0; 3];
                for (k, slot) in c.iter_mut().enumerate() {
                    let t = toks
                        .next()
                        .ok_or_else(|| err(format!("vertex needs 3 coordinates, got {k}")))?;
                    *slot =
                        number(t).ok_or_else(|| err(format!("'{t}' is not a finite number")))?;
                }
                verts.push(DVec3::from_array(c));
            }
            Some("f") => {
                face.clear();
                for t in toks {
                    let idx = t.split('/').next().unwrap_or("");
                    let n: i64 = idx
                        .parse()
                        .map_err(|_| err(format!("'{t}' is not a vertex index")))?;
                    let at = match n {
                        n if n > 0 => n - 1,
                        n if n < 0 => verts.len() as i64 + n,
                        _ => return Err(err("vertex index 0 (OBJ indices start at 1)".into())),
                    };
                    let v = usize::try_from(at)
                        .ok()
                        .and_then(|a| verts.get(a))
                        .ok_or_else(|| {
                            err(format!(
                                "vertex index {n} is out of range ({} vertices so far)",
                                verts.len()
                            ))
                        })?;
                    face.push(*v);
                }
                if face.len() < 3 {
                    return Err(err(format!(
                        "a face needs at least 3 vertices, got {}",
                        face.len()
                    )));
                }
                for k in 1..face.len() - 1 {
                    let t = [face[0], face[k], face[k + 1]];
                    if (t[1] - t[0]).cross(t[2] - t[0]).length_squared() == 0.0 {
                        degenerate += 1;
                    }
                    tris.push(t);
                }
                if tris.len() > max_triangles {
                    return Err(err(format!(
                        "too many triangles: a scene holds at most {max_triangles} primitives"
                    )));
                }
            }
            _ => {}
        }
    }
    Ok((tris, degenerate))
}

/// A finite decimal number (no `inf`, `nan` or hex, which `f64::from_str` would take).
fn number(t: &str) -> Option<f64> {
    let ok = t
        .bytes()
        .all(|b| b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'e' | b'E'));
    let v: f64 = t.parse().ok()?;
    (ok && v.is_finite()).then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<(Vec<[DVec3; 3]>, usize)> {
        parse_obj(text.as_bytes(), Path::new("m.obj"), 1000)
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

//! One chunk of an OBJ file, in two passes (`mesh.rs` splits the file and joins the chunks).
//!
//! [`read`] needs nothing from other chunks: it parses `v` lines into the chunk's vertices and
//! `f` lines into their indices as written, each face with its line and the number of vertices
//! the chunk had before it, and stops at the first error it can judge alone. Whether an index
//! is in range depends on the vertices of the chunks before, so [`check`] judges it once every
//! chunk is read and the counts are prefix-summed, and reports the chunk's first error in line
//! order (an out-of-range index in a face before the error `read` stopped at, or in the same
//! face before the bad token, comes first, as it would reading line by line). Checked chunks
//! become triangles with [`triangle`] (faces that are all triangles, one by one) or [`write`]
//! (polygons, fan-triangulated into the chunk's slice of the final list).

use super::chunks::{self, Budget};
use super::number::{finite, finite_token};
use crate::error::Error;
use crate::limits::MAX_LINE_BYTES;
use glam::DVec3;
use std::path::Path;

/// A face: its line and the chunk's vertex count before it (both counted within the chunk),
/// and where its indices end in `ObjChunk::corners` (they start where the previous face's end).
/// A chunk holds a few MiB, so these fit in 32 bits.
pub struct Face {
    line: u32,
    verts_before: u32,
    end: u32,
}

/// What [`read`] found in one chunk.
pub struct ObjChunk {
    first_line: usize,
    pub verts: Vec<DVec3>,
    faces: Vec<Face>,
    /// Vertex indices as written (never 0; negative ones count back); 0 marks an index beyond
    /// 32 bits, kept in `big` with its position.
    corners: Vec<i32>,
    big: Vec<(usize, i64)>,
    /// Triangles of the complete faces.
    pub tris: usize,
    pub stop: Option<Stop>,
}

impl ObjChunk {
    fn face(&self, line: usize) -> Face {
        Face {
            line: (line - self.first_line) as u32,
            verts_before: self.verts.len() as u32,
            end: self.corners.len() as u32,
        }
    }

    fn corner(&mut self, n: i64) {
        match i32::try_from(n) {
            Ok(k) => self.corners.push(k),
            Err(_) => {
                self.big.push((self.corners.len(), n));
                self.corners.push(0);
            }
        }
    }

    /// The index at position `at` of `corners`, as written.
    fn written(&self, at: usize) -> i64 {
        match self.corners[at] {
            0 => self
                .big
                .binary_search_by_key(&at, |b| b.0)
                .map_or(0, |k| self.big[k].1),
            k => i64::from(k),
        }
    }
}

/// Where a chunk stopped.
pub enum Stop {
    Error(Error),
    /// A face line with a bad token (or too few): `pending` is its error unless an index before
    /// it is out of range. Its good indices are the last ones in `corners`.
    Face(Face, String),
    /// The triangle budget ran out at this line.
    Budget(usize),
}

/// Why a chunk gives no triangles.
pub enum Halt {
    Error(Error),
    /// The budget ran out while chunks were read in parallel: read again in order.
    Rerun(usize),
}

/// Reads the chunk `bytes`, whose first line is line `first_line` of the OBJ file `path`.
pub fn read(bytes: &[u8], first_line: usize, path: &Path, budget: &Budget) -> ObjChunk {
    // a generated grid has a vertex line (~32 bytes) for every two face lines (~22 bytes)
    let guess = bytes.len().min(8 << 20) / 24;
    let mut c = ObjChunk {
        first_line,
        verts: Vec::with_capacity(guess / 3),
        faces: Vec::with_capacity(guess),
        corners: Vec::with_capacity(3 * guess),
        big: Vec::new(),
        tris: 0,
        stop: None,
    };
    let mut unrecorded = 0;
    let utf8 = std::str::from_utf8(bytes).is_ok();
    let mut line = |i: usize, raw: &[u8], c: &mut ObjChunk| {
        let line = first_line + i;
        let err = |msg: String| Stop::Error(Error::input(path, line, 0, msg));
        if raw.len() > MAX_LINE_BYTES {
            let n = raw.len();
            return Err(err(format!(
                "line is {n} bytes long; the limit is {MAX_LINE_BYTES}"
            )));
        }
        if !utf8 && std::str::from_utf8(raw).is_err() {
            return Err(err("not valid UTF-8".into()));
        }
        let tris_before = c.tris;
        if fast_line(raw, line, c).is_none() {
            general_line(raw, line, c, path)?;
        }
        unrecorded += c.tris - tris_before;
        if unrecorded >= budget.batch && !budget.take(std::mem::take(&mut unrecorded)) {
            return Err(Stop::Budget(line));
        }
        Ok(())
    };
    let mut lines = chunks::lines(bytes).enumerate();
    c.stop = lines.find_map(|(i, r)| line(i, &bytes[r], &mut c).err());
    c
}

fn blank(x: u8) -> bool {
    x == b' ' || x == b'\t'
}

/// A `v` or `f` line in the usual form, or a line with nothing to read, taken without building
/// tokens; `None` (and the chunk as before) for anything else, which takes the general path.
/// It takes only lines on which the general path agrees: tokens made of printable ASCII and
/// separated by spaces or tabs, with at most a `\r` at the end.
fn fast_line(raw: &[u8], line: usize, c: &mut ObjChunk) -> Option<()> {
    let b = match raw {
        [b @ .., b'\r'] => b,
        b => b,
    };
    let end = b.len();
    let mut i = 0;
    let skip_blanks = |i: &mut usize| {
        while *i < end && blank(b[*i]) {
            *i += 1;
        }
    };
    // the end of the token from `i`: a blank, a comment or the end of the line
    let token_end = |mut i: usize| {
        while i < end && !blank(b[i]) && b[i] != b'#' {
            i += 1;
        }
        i
    };
    skip_blanks(&mut i);
    if i == end || b[i] == b'#' {
        return Some(()); // a blank line or a comment
    }
    let kw_end = token_end(i);
    // (patterns of bytes, not b"v": a byte string pattern compares through `memcmp`)
    match &b[i..kw_end] {
        [b'v'] => {
            i = kw_end;
            let mut xyz = [0.0; 3];
            for x in &mut xyz {
                skip_blanks(&mut i);
                let (value, len) = finite_token(&b[i..])?;
                *x = value;
                i += len;
            }
            c.verts.push(DVec3::from_array(xyz));
        }
        [b'f'] => {
            i = kw_end;
            let start = c.corners.len();
            loop {
                skip_blanks(&mut i);
                if i == end || b[i] == b'#' {
                    break;
                }
                match index(&b[i..]) {
                    Some((k, len)) => {
                        c.corners.push(k);
                        i += len;
                    }
                    None => {
                        c.corners.truncate(start);
                        return None;
                    }
                }
            }
            let n = c.corners.len() - start;
            if n < 3 {
                c.corners.truncate(start);
                return None;
            }
            let face = c.face(line);
            c.faces.push(face);
            c.tris += n - 2;
        }
        kw if kw.iter().all(u8::is_ascii_graphic) => {} // another statement: ignored
        _ => return None,
    }
    Some(())
}

/// The face token at the start of `t`: `i`, `i/t`, `i//n` or `i/t/n` in printable ASCII, ending
/// at a space, a tab, a `#` or the end, whose `i` is a non-zero integer of at most 9 digits; and
/// its length.
fn index(t: &[u8]) -> Option<(i32, usize)> {
    let (negative, mut k) = match t.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let digits = k;
    let mut n: i32 = 0;
    while let Some(d) = t.get(k).map(|c| c.wrapping_sub(b'0')).filter(|&d| d < 10) {
        if k - digits == 9 {
            return None;
        }
        n = n * 10 + i32::from(d);
        k += 1;
    }
    if k == digits || n == 0 {
        return None;
    }
    if t.get(k) == Some(&b'/') {
        while k < t.len() && !matches!(t[k], b' ' | b'\t' | b'#') {
            if !t[k].is_ascii_graphic() {
                return None;
            }
            k += 1;
        }
    }
    let ends = t.get(k).is_none_or(|&c| matches!(c, b' ' | b'\t' | b'#'));
    ends.then_some((if negative { -n } else { n }, k))
}

/// Any line, as a line-by-line reader takes it (and the only path that words errors).
fn general_line(
    raw: &[u8],
    line: usize,
    c: &mut ObjChunk,
    path: &Path,
) -> std::result::Result<(), Stop> {
    let err = |msg: String| Stop::Error(Error::input(path, line, 0, msg));
    let text = std::str::from_utf8(raw).map_err(|_| err("not valid UTF-8".into()))?;
    let text = text.split('#').next().unwrap_or("").trim();
    let mut toks = text.split_ascii_whitespace();
    match toks.next() {
        Some("v") => {
            let mut xyz = [0.0; 3];
            for (k, x) in xyz.iter_mut().enumerate() {
                let t = toks
                    .next()
                    .ok_or_else(|| err(format!("vertex needs 3 coordinates, got {k}")))?;
                *x = finite(t.as_bytes())
                    .ok_or_else(|| err(format!("'{t}' is not a finite number")))?;
            }
            c.verts.push(DVec3::from_array(xyz));
        }
        Some("f") => {
            let start = c.corners.len();
            let face = |c: &ObjChunk| c.face(line);
            for t in toks {
                let idx = t.split('/').next().unwrap_or("");
                match idx.parse::<i64>() {
                    Err(_) => {
                        return Err(Stop::Face(face(c), format!("'{t}' is not a vertex index")));
                    }
                    Ok(0) => {
                        let msg = "vertex index 0 (OBJ indices start at 1)".to_string();
                        return Err(Stop::Face(face(c), msg));
                    }
                    Ok(n) => c.corner(n),
                }
            }
            let n = c.corners.len() - start;
            if n < 3 {
                let msg = format!("a face needs at least 3 vertices, got {n}");
                return Err(Stop::Face(face(c), msg));
            }
            c.faces.push(face(c));
            c.tris += n - 2;
        }
        _ => {}
    }
    Ok(())
}

/// Where a chunk stands in the file: its first vertex and triangle have these global indices.
#[derive(Clone, Copy)]
pub struct Base {
    pub verts: usize,
    pub tris: usize,
}

impl ObjChunk {
    /// Whether every face is a triangle: then face `j` is triangle `j`, its indices at `3 j`.
    pub fn triangles_only(&self) -> bool {
        self.corners.len() == 3 * self.faces.len()
    }
}

/// The chunk's first error in line order, if any: an index out of range, the triangle limit
/// (`max` for the whole mesh) passed, or the error [`read`] stopped at. Needs only the vertex
/// counts, not the vertices.
pub fn check(
    c: &ObjChunk,
    stop: Option<Stop>,
    base: Base,
    max: usize,
    path: &Path,
) -> std::result::Result<(), Halt> {
    let mut start = 0;
    let mut n = base.tris;
    for f in &c.faces {
        let at = Corners::new(c, f, start, base.verts);
        start = f.end as usize;
        if let Some(k) = (0..at.len).find(|&k| at.index(k).is_none()) {
            return Err(Halt::Error(at.error(k, path)));
        }
        n += at.len - 2;
        if n > max {
            let line = c.first_line + f.line as usize;
            let msg = format!("too many triangles: a scene holds at most {max} primitives");
            return Err(Halt::Error(Error::input(path, line, 0, msg)));
        }
    }
    match stop {
        None => Ok(()),
        Some(Stop::Error(e)) => Err(Halt::Error(e)),
        Some(Stop::Face(f, pending)) => {
            let at = Corners::new(c, &f, start, base.verts);
            if let Some(k) = (0..at.len).find(|&k| at.index(k).is_none()) {
                return Err(Halt::Error(at.error(k, path)));
            }
            let line = c.first_line + f.line as usize;
            Err(Halt::Error(Error::input(path, line, 0, pending)))
        }
        Some(Stop::Budget(line)) => Err(Halt::Rerun(line)),
    }
}

/// Whether a triangle has zero area (it keeps its id and is never hit).
pub fn degenerate(t: &[DVec3; 3]) -> bool {
    (t[1] - t[0]).cross(t[2] - t[0]).length_squared() == 0.0
}

/// A checked chunk's faces, fan-triangulated into `out` (its slice of the final face list, as
/// vertex indices), and how many of those triangles are degenerate. `verts`: the vertices of
/// the file.
pub fn write(c: &ObjChunk, base: Base, verts: &[DVec3], out: &mut [[u32; 3]]) -> usize {
    let (mut start, mut n, mut zero) = (0, 0, 0);
    for f in &c.faces {
        let at = Corners::new(c, f, start, base.verts);
        start = f.end as usize;
        let v = |k: usize| at.index(k).expect("indices are checked") as u32;
        let (a, mut b) = (v(0), v(1));
        for k in 2..at.len {
            let t = [a, b, v(k)];
            zero += usize::from(degenerate(&t.map(|i| verts[i as usize])));
            out[n] = t;
            n += 1;
            b = t[2];
        }
    }
    zero
}

/// Triangle `j` of a checked chunk whose faces are all triangles, as vertex indices.
pub fn triangle(c: &ObjChunk, j: usize, base: Base) -> [u32; 3] {
    let at = Corners::new(c, &c.faces[j], 3 * j, base.verts);
    [0, 1, 2].map(|k| at.index(k).expect("indices are checked") as u32)
}

/// A face's indices, resolved against the vertices before its line.
struct Corners<'a> {
    c: &'a ObjChunk,
    face: &'a Face,
    start: usize,
    len: usize,
    so_far: usize,
}

impl<'a> Corners<'a> {
    fn new(c: &'a ObjChunk, face: &'a Face, start: usize, base: usize) -> Self {
        Corners {
            c,
            face,
            start,
            len: face.end as usize - start,
            so_far: base + face.verts_before as usize,
        }
    }

    /// The global vertex index of index `k`, if in range.
    fn index(&self, k: usize) -> Option<usize> {
        let n = self.c.written(self.start + k);
        let at = if n > 0 { n - 1 } else { self.so_far as i64 + n };
        usize::try_from(at).ok().filter(|&a| a < self.so_far)
    }

    /// The message for index `k`, out of range.
    fn error(&self, k: usize, path: &Path) -> Error {
        let n = self.c.written(self.start + k);
        let so_far = self.so_far;
        let line = self.c.first_line + self.face.line as usize;
        let so_far = crate::words::count(so_far, "vertex", "vertices");
        let msg = format!("vertex index {n} is out of range ({so_far} so far)");
        Error::input(path, line, 0, msg)
    }
}

/// `e` with a column where it names a line of the OBJ `bytes` without one: the offending
/// token's (the one a message quotes, or the vertex index it names), the first invalid byte's
/// (not UTF-8), else the line's first token's (the statement as a whole). The readers keep
/// lines, not columns, so the line is looked at again here: an error's cost only.
pub(super) fn with_column(e: Error, bytes: &[u8]) -> Error {
    let Error::Input {
        file,
        line,
        col: 0,
        msg,
    } = e
    else {
        return e;
    };
    let body = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
    let col = chunks::lines(body)
        .nth(line.saturating_sub(1))
        .map_or(0, |r| column(&body[r], &msg));
    Error::Input {
        file,
        line,
        col,
        msg,
    }
}

/// The 1-based column on the OBJ line `raw` that the message `msg` is about ([`with_column`]).
fn column(raw: &[u8], msg: &str) -> usize {
    let text = match std::str::from_utf8(raw) {
        Ok(t) => t,
        Err(e) => {
            return String::from_utf8_lossy(&raw[..e.valid_up_to()])
                .chars()
                .count()
                + 1;
        }
    };
    let content = text.split('#').next().unwrap_or("");
    let toks: Vec<&str> = content.split_ascii_whitespace().collect();
    let quoted = (msg.strip_prefix('\''))
        .and_then(|m| m.split_once('\''))
        .map(|(t, _)| t);
    let index = (msg.strip_prefix("vertex index "))
        .and_then(|m| m.split(' ').next())
        .filter(|n| !n.is_empty());
    let named = |t: &&str| Some(*t) == quoted || (index.is_some() && t.split('/').next() == index);
    let first = toks.first().copied();
    match toks.iter().skip(1).find(|t| named(t)).copied().or(first) {
        Some(t) => {
            text[..t.as_ptr() as usize - text.as_ptr() as usize]
                .chars()
                .count()
                + 1
        }
        None => 1,
    }
}

//! The body of a binary PLY file, little- or big-endian: the records of each element back to
//! back, in header order, each property's values in its declared type with no padding, a list
//! being its count followed by that many items.
//!
//! Two fast paths read records in parallel, straight from the bytes with `from_le_bytes` /
//! `from_be_bytes`: an element whose properties are all scalars has records of one size, so
//! record `i` starts at `i * size` (the vertex element as nearly every file writes it, and
//! skipped elements, passed over in one step); and a face element whose only list is the vertex
//! index list, with every count 3 (`3 i j k`, as scans and most writers give them), has records
//! of one size too. That is checked while the records are read: at a count other than 3 the
//! element is read again record by record (`walk.rs`), as is anything else. The parallel passes
//! note the lowest bad record, which is read again to word the message, so the error reported
//! is the first in the file either way. When the vertices come before the faces (as nearly
//! always), the fast path for faces also counts the degenerate triangles, while their vertices
//! are at hand.

use super::super::obj::degenerate;
use super::header::{Element, Header, Kind, Type};
use super::walk::{self, Bad, Source};
use super::{Body, at_byte};
use crate::error::Error;
use crate::par::prelude::*;
use glam::DVec3;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A PLY value type as the Rust type of the same size and kind.
trait Scalar {
    /// The value at the start of `b`, big-endian when `BIG`, exactly as an f64.
    fn get<const BIG: bool>(b: &[u8]) -> f64;
    /// The same as an i64: exact for the integer types (vertex indices).
    fn int<const BIG: bool>(b: &[u8]) -> i64;
}

macro_rules! scalar {
    ($($t:ty),*) => {$(
        impl Scalar for $t {
            #[inline(always)]
            fn get<const BIG: bool>(b: &[u8]) -> f64 {
                const N: usize = std::mem::size_of::<$t>();
                let a: [u8; N] = b[..N].try_into().expect("N bytes");
                (if BIG { <$t>::from_be_bytes(a) } else { <$t>::from_le_bytes(a) }) as f64
            }

            #[inline(always)]
            fn int<const BIG: bool>(b: &[u8]) -> i64 {
                const N: usize = std::mem::size_of::<$t>();
                let a: [u8; N] = b[..N].try_into().expect("N bytes");
                (if BIG { <$t>::from_be_bytes(a) } else { <$t>::from_le_bytes(a) }) as i64
            }
        }
    )*};
}
scalar!(i8, u8, i16, u16, i32, u32, f32, f64);

/// `$body` with the type `$T` standing for the PLY type `$t`.
macro_rules! with_type {
    ($t:expr, $T:ident => $body:expr) => {
        match $t {
            Type::I8 => {
                type $T = i8;
                $body
            }
            Type::U8 => {
                type $T = u8;
                $body
            }
            Type::I16 => {
                type $T = i16;
                $body
            }
            Type::U16 => {
                type $T = u16;
                $body
            }
            Type::I32 => {
                type $T = i32;
                $body
            }
            Type::U32 => {
                type $T = u32;
                $body
            }
            Type::F32 => {
                type $T = f32;
                $body
            }
            Type::F64 => {
                type $T = f64;
                $body
            }
        }
    };
}

/// The value of type `t` at the start of `b` (at least `t.size()` bytes).
pub fn value(t: Type, big: bool, b: &[u8]) -> f64 {
    with_type!(t, T => if big { T::get::<true>(b) } else { T::get::<false>(b) })
}

/// The body read one value at a time; marks are byte offsets in the file.
struct Walk<'a> {
    bytes: &'a [u8],
    at: usize,
    big: bool,
    path: &'a Path,
}

const CUT: &str = "the file ends within this record (is it cut short?)";

impl Source for Walk<'_> {
    fn begin(&mut self) -> Result<(), Bad> {
        Ok(())
    }

    fn mark(&self) -> usize {
        self.at
    }

    fn value(&mut self, t: Type) -> Result<f64, Bad> {
        let at = self.at;
        let b = (self.bytes.get(at..at + t.size())).ok_or_else(|| self.cut())?;
        self.at += t.size();
        Ok(value(t, self.big, b))
    }

    fn skip(&mut self, t: Type, n: usize) -> Result<(), Bad> {
        let end = (n.checked_mul(t.size()))
            .and_then(|len| self.at.checked_add(len))
            .filter(|&end| end <= self.bytes.len());
        self.at = end.ok_or_else(|| self.cut())?;
        Ok(())
    }

    fn end(&mut self) -> Result<(), Bad> {
        Ok(())
    }

    fn error_at(&self, mark: usize, what: &str, r: usize, msg: String) -> Error {
        at_byte(self.path, mark, format!("{what} {r}: {msg}"))
    }
}

impl Walk<'_> {
    fn cut(&self) -> Bad {
        Bad {
            mark: self.bytes.len(),
            msg: CUT.into(),
        }
    }

    /// Passes over `el`, whose records are `size` bytes each, in one step.
    fn skip_fixed(&mut self, el: &Element, size: usize) -> Result<(), Error> {
        let left = self.bytes.len() - self.at;
        if size * el.count > left {
            // `check_sizes` leaves this to elements after one with lists
            let (len, r) = (self.bytes.len(), left / size);
            return Err(self.error_at(len, &el.name, r, CUT.into()));
        }
        self.at += size * el.count;
        Ok(())
    }
}

/// The vertices and triangles of the binary body of `bytes` (big-endian when `big`), with at
/// most `max` triangles, and how many triangles are degenerate when the fast path for faces
/// counted them on the way (it does when the vertices come first). The header is checked
/// (`header::parse`).
pub fn read(bytes: &[u8], h: &Header, big: bool, path: &Path, max: usize) -> Result<Body, Error> {
    let mut w = Walk {
        bytes,
        at: h.body,
        big,
        path,
    };
    let (mut verts, mut faces, mut degenerate) = (Vec::new(), Vec::new(), None);
    for (e, el) in h.elements.iter().enumerate() {
        let size = el.fixed_size();
        if e == h.vertex {
            match size {
                Some(size) => {
                    let start = w.at;
                    w.skip_fixed(el, size)?;
                    verts = fixed_vertices(&w, start, el, size, h.xyz)?;
                }
                None => walk::vertices(&mut w, el, h.xyz, &mut verts)?,
            }
        } else if e == h.face {
            let read = (e > h.vertex).then_some(&verts[..]);
            match uniform_faces(&w, el, h.list, h.vertices(), read)? {
                Some(fast) => {
                    faces = fast.faces;
                    degenerate = fast.degenerate;
                    let size = fast.size;
                    w.at += size * el.count;
                }
                None => walk::faces(&mut w, el, h.list, h.vertices(), max, &mut faces)?,
            }
        } else {
            match size {
                Some(size) => w.skip_fixed(el, size)?,
                None => walk::skip(&mut w, el)?,
            }
        }
    }
    if w.at < bytes.len() {
        let n = bytes.len() - w.at;
        let msg = format!(
            "{} after the last element the header declares",
            crate::words::count(n, "byte", "bytes")
        );
        return Err(at_byte(path, w.at, msg));
    }
    Ok(Body {
        vertices: verts,
        faces,
        degenerate,
    })
}

/// The `el.count` vertex records of `size` bytes from `bytes[start..]` (all there), in
/// parallel: `xyz` are the indices of the coordinates among the (all scalar) properties.
fn fixed_vertices(
    w: &Walk,
    start: usize,
    el: &Element,
    size: usize,
    xyz: [usize; 3],
) -> Result<Vec<DVec3>, Error> {
    let body = &w.bytes[start..start + size * el.count];
    let at = xyz.map(|k| el.offset(k).expect("scalar properties"));
    let types = xyz.map(|k| match el.props[k].kind {
        Kind::Scalar(t) => t,
        Kind::List { .. } => unreachable!("scalar properties"),
    });
    let bad = AtomicUsize::new(usize::MAX);
    let verts = if types[1] == types[0] && types[2] == types[0] {
        with_type!(types[0], T => if w.big {
            records(body, size, &bad, |r| at.map(|o| T::get::<true>(&r[o..])))
        } else {
            records(body, size, &bad, |r| at.map(|o| T::get::<false>(&r[o..])))
        })
    } else {
        let big = w.big;
        records(body, size, &bad, |r| {
            [0, 1, 2].map(|k| value(types[k], big, &r[at[k]..]))
        })
    };
    let r = bad.into_inner();
    if r == usize::MAX {
        return Ok(verts);
    }
    // the first coordinate that is not finite, in the record's property order
    let mut axes = [0, 1, 2];
    axes.sort_by_key(|&a| xyz[a]);
    let rec = &body[r * size..];
    let (axis, v) = (axes.into_iter())
        .map(|a| (a, value(types[a], w.big, &rec[at[a]..])))
        .find(|(_, v)| !v.is_finite())
        .expect("a coordinate is not finite");
    let mark = start + r * size + at[axis];
    Err(w.error_at(mark, "vertex", r, walk::not_finite(axis, v)))
}

/// The records of `size` bytes in `body`, each made a point by `get`, in parallel; the lowest
/// record whose point is not finite goes to `bad`.
fn records(
    body: &[u8],
    size: usize,
    bad: &AtomicUsize,
    get: impl Fn(&[u8]) -> [f64; 3] + Sync,
) -> Vec<DVec3> {
    (body.par_chunks_exact(size).enumerate())
        .with_min_len(1 << 12)
        .map(|(i, r)| {
            let p = DVec3::from_array(get(r));
            if !p.is_finite() {
                bad.fetch_min(i, Ordering::Relaxed);
            }
            p
        })
        .collect()
}

/// The faces of `el` when every one is a triangle and its only list is the index list `list`:
/// the triangles, in parallel, the record size, and how many triangles are degenerate when the
/// `verts` are given (read already); `None` when they are not all triangles (or the file is too
/// short for it), for the walk to read. An index out of range is an error here already when no
/// face before it has another count.
fn uniform_faces(
    w: &Walk,
    el: &Element,
    list: usize,
    vertices: usize,
    verts: Option<&[DVec3]>,
) -> Result<Option<Fast>, Error> {
    let Kind::List { count, item } = el.props[list].kind else {
        unreachable!("the header checks the list")
    };
    let scalar = |p: &super::header::Property| match p.kind {
        Kind::Scalar(t) => Some(t.size()),
        Kind::List { .. } => None,
    };
    let (Some(pre), Some(post)) = (
        el.props[..list].iter().map(scalar).sum::<Option<usize>>(),
        el.props[list + 1..]
            .iter()
            .map(scalar)
            .sum::<Option<usize>>(),
    ) else {
        return Ok(None);
    };
    let (cs, is) = (count.size(), item.size());
    let size = pre + cs + 3 * is + post;
    if size * el.count > w.bytes.len() - w.at {
        return Ok(None);
    }
    let body = &w.bytes[w.at..w.at + size * el.count];
    // whether a count is 3, compared as a whole word (not through `memcmp`)
    let is_three = |c: &[u8]| match *c {
        [n] => n == 3,
        [a, b] => u16::from_be_bytes([a, b]) == if w.big { 3 } else { 3 << 8 },
        [a, b, c, d] => u32::from_be_bytes([a, b, c, d]) == if w.big { 3 } else { 3 << 24 },
        _ => unreachable!("integer counts are 1, 2 or 4 bytes"),
    };
    let (odd, bad) = (AtomicUsize::new(usize::MAX), AtomicUsize::new(usize::MAX));
    let zero = AtomicUsize::new(0);
    let first = pre + cs;
    let at = Uniform {
        size,
        count: pre,
        first,
        item: is,
        vertices: vertices as u64,
    };
    let faces = with_type!(item, T => if w.big {
        at.triangles::<T, true>(body, &is_three, verts, [&odd, &bad, &zero])
    } else {
        at.triangles::<T, false>(body, &is_three, verts, [&odd, &bad, &zero])
    });
    let (odd, bad) = (odd.into_inner(), bad.into_inner());
    if bad < odd {
        // every record before `odd` is a triangle, so record `bad` is where it was read
        let rec = &body[bad * size..];
        let (k, i) = ((0..3).map(|k| (k, value(item, w.big, &rec[first + k * is..]))))
            .find(|&(_, i)| !(i >= 0.0 && i < vertices as f64))
            .expect("an index out of range");
        let mark = w.at + bad * size + first + k * is;
        let msg = walk::out_of_range(i, vertices);
        return Err(w.error_at(mark, "face", bad, msg));
    }
    let degenerate = verts.map(|_| zero.into_inner());
    Ok((odd == usize::MAX).then_some(Fast {
        faces,
        size,
        degenerate,
    }))
}

/// Faces read by the fast path: the triangles, the record size, and how many triangles are
/// degenerate when the vertices were at hand.
struct Fast {
    faces: Vec<[u32; 3]>,
    size: usize,
    degenerate: Option<usize>,
}

/// Where the parts of a face record of one size are: the count at `count`, the three indices
/// of `item` bytes each from `first`.
struct Uniform {
    size: usize,
    count: usize,
    first: usize,
    item: usize,
    vertices: u64,
}

impl Uniform {
    /// The triangles of `body`, indices of type `T`, in parallel. Notes the first record whose
    /// count is not 3 in `odd`, the first with an index out of range in `bad` (their triangles
    /// are left zero), and counts the degenerate triangles in `zero` when given the `verts`.
    fn triangles<T: Scalar, const BIG: bool>(
        &self,
        body: &[u8],
        is_three: &(impl Fn(&[u8]) -> bool + Sync),
        verts: Option<&[DVec3]>,
        [odd, bad, zero]: [&AtomicUsize; 3],
    ) -> Vec<[u32; 3]> {
        (body.par_chunks_exact(self.size).enumerate())
            .with_min_len(1 << 12)
            .map(|(f, r)| {
                if !is_three(&r[self.count..self.first]) {
                    odd.fetch_min(f, Ordering::Relaxed);
                    return [0; 3];
                }
                let t = [0, 1, 2].map(|k| T::int::<BIG>(&r[self.first + k * self.item..]));
                // a negative index wraps to beyond any vertex count
                if !t.iter().all(|&i| (i as u64) < self.vertices) {
                    bad.fetch_min(f, Ordering::Relaxed);
                    return [0; 3];
                }
                let t = t.map(|i| i as u32);
                if verts.is_some_and(|v| degenerate(&t.map(|i| v[i as usize]))) {
                    zero.fetch_add(1, Ordering::Relaxed);
                }
                t
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::header;
    use super::*;

    /// Triangles with counts of every integer type, in both byte orders, take the fast path.
    #[test]
    fn triangle_counts_of_every_integer_type_take_the_fast_path() {
        let int = [
            Type::I8,
            Type::U8,
            Type::I16,
            Type::U16,
            Type::I32,
            Type::U32,
        ];
        for big in [false, true] {
            for count in int {
                let order = if big { "big" } else { "little" };
                let mut b = format!(
                    "ply\nformat binary_{order}_endian 1.0\nelement vertex 3\n\
                     property uchar x\nproperty uchar y\nproperty uchar z\nelement face 2\n\
                     property list {} ushort vertex_indices\nend_header\n",
                    count.name()
                )
                .into_bytes();
                b.extend([0, 0, 0, 1, 0, 0, 0, 1, 0]);
                for _ in 0..2 {
                    let mut three = vec![0; count.size()];
                    three[if big { count.size() - 1 } else { 0 }] = 3;
                    b.extend(three);
                    for i in [0u16, 1, 2] {
                        b.extend(if big {
                            i.to_be_bytes()
                        } else {
                            i.to_le_bytes()
                        });
                    }
                }
                let path = Path::new("t.ply");
                let h = header::parse(&b, path).unwrap();
                let w = Walk {
                    bytes: &b,
                    at: h.body + 9,
                    big,
                    path,
                };
                let el = &h.elements[h.face];
                let fast = uniform_faces(&w, el, h.list, 3, None).unwrap();
                let fast = fast.unwrap_or_else(|| panic!("{count:?} big {big}"));
                assert_eq!(fast.faces, vec![[0, 1, 2]; 2]);
                assert_eq!(fast.size, count.size() + 6);
            }
        }
    }
}

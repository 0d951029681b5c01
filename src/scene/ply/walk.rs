//! Record by record, the same for both encodings: an ASCII body and the parts of a binary one
//! that its fast paths (`binary.rs`) do not take. A [`Source`] gives the values in file order
//! and says where an error is (a line, or a byte offset); the walkers here know what the values
//! mean and word the errors, so both encodings refuse the same things in the same words.

use super::header::{Element, Kind, Type};
use crate::error::Error;
use glam::DVec3;

/// Something wrong at `mark` (see [`Source::mark`]), not yet placed in a record.
pub struct Bad {
    pub mark: usize,
    pub msg: String,
}

/// Values in file order.
pub trait Source {
    /// Starts the next record (ASCII: takes its line).
    fn begin(&mut self) -> Result<(), Bad>;
    /// Where the next value starts.
    fn mark(&self) -> usize;
    /// The next value, of type `t`, exactly (integers as whole numbers).
    fn value(&mut self, t: Type) -> Result<f64, Bad>;
    /// Passes over the next `n` values of type `t`.
    fn skip(&mut self, t: Type, n: usize) -> Result<(), Bad>;
    /// Ends the record (ASCII: nothing may follow on its line).
    fn end(&mut self) -> Result<(), Bad>;
    /// `msg` about the value that started at `mark`, in record `r` of the element `what`.
    fn error_at(&self, mark: usize, what: &str, r: usize, msg: String) -> Error;
}

/// Runs `f` on the source, placing what goes wrong in record `r` of `what`.
fn within<S: Source, T>(
    s: &mut S,
    what: &str,
    r: usize,
    f: impl FnOnce(&mut S) -> Result<T, Bad>,
) -> Result<T, Error> {
    f(s).map_err(|b| s.error_at(b.mark, what, r, b.msg))
}

/// A list's count: a whole number (its type is an integer type), never negative.
fn count<S: Source>(s: &mut S, t: Type) -> Result<usize, Bad> {
    let mark = s.mark();
    let c = s.value(t)?;
    if c < 0.0 {
        let msg = format!("negative list count {c}");
        return Err(Bad { mark, msg });
    }
    Ok(c as usize)
}

/// The records of an element read for nothing but their place in the file.
pub fn skip<S: Source>(s: &mut S, el: &Element) -> Result<(), Error> {
    for r in 0..el.count {
        within(s, &el.name, r, |s| {
            s.begin()?;
            for p in &el.props {
                match p.kind {
                    Kind::Scalar(t) => s.skip(t, 1)?,
                    Kind::List { count: ct, item } => {
                        let n = count(s, ct)?;
                        s.skip(item, n)?;
                    }
                }
            }
            s.end()
        })?;
    }
    Ok(())
}

/// The vertex records: properties `xyz` of each, which must be finite, into `out`.
pub fn vertices<S: Source>(
    s: &mut S,
    el: &Element,
    xyz: [usize; 3],
    out: &mut Vec<DVec3>,
) -> Result<(), Error> {
    out.reserve_exact(el.count);
    for r in 0..el.count {
        let p = within(s, "vertex", r, |s| {
            s.begin()?;
            let mut p = [0.0; 3];
            for (k, prop) in el.props.iter().enumerate() {
                match prop.kind {
                    Kind::Scalar(t) => match xyz.iter().position(|&a| a == k) {
                        Some(axis) => {
                            let mark = s.mark();
                            p[axis] = s.value(t)?;
                            if !p[axis].is_finite() {
                                let msg = not_finite(axis, p[axis]);
                                return Err(Bad { mark, msg });
                            }
                        }
                        None => s.skip(t, 1)?,
                    },
                    Kind::List { count: ct, item } => {
                        let n = count(s, ct)?;
                        s.skip(item, n)?;
                    }
                }
            }
            s.end()?;
            Ok(p)
        })?;
        out.push(DVec3::from_array(p));
    }
    Ok(())
}

/// Why coordinate `axis` (0, 1, 2: x, y, z) with value `v` is refused.
pub fn not_finite(axis: usize, v: f64) -> String {
    let what = if v.is_nan() { "NaN" } else { "infinite" };
    format!(
        "{} is {what} (coordinates must be finite)",
        ["x", "y", "z"][axis]
    )
}

/// The face records: list property `list` of each, fan-triangulated from its first vertex
/// ((0,1,2), (0,2,3), ...), into `out`, each index checked against the `vertices` the file
/// declares; at most `max` triangles in `out`.
pub fn faces<S: Source>(
    s: &mut S,
    el: &Element,
    list: usize,
    vertices: usize,
    max: usize,
    out: &mut Vec<[u32; 3]>,
) -> Result<(), Error> {
    // the header check keeps `count` within `max` (a face is at least one triangle)
    out.reserve(el.count);
    for r in 0..el.count {
        within(s, "face", r, |s| {
            s.begin()?;
            for (k, prop) in el.props.iter().enumerate() {
                match prop.kind {
                    Kind::Scalar(t) => s.skip(t, 1)?,
                    Kind::List { count: ct, item } if k == list => {
                        let mark = s.mark();
                        let n = count(s, ct)?;
                        if n < 3 {
                            let msg = format!("a face needs at least 3 vertices, got {n}");
                            return Err(Bad { mark, msg });
                        }
                        if n - 2 > max - out.len() {
                            let msg = too_many(max);
                            return Err(Bad { mark, msg });
                        }
                        let mut index = || {
                            let mark = s.mark();
                            let i = s.value(item)?;
                            if i >= 0.0 && i < vertices as f64 {
                                Ok(i as u32)
                            } else {
                                let msg = out_of_range(i, vertices);
                                Err(Bad { mark, msg })
                            }
                        };
                        let a = index()?;
                        let mut b = index()?;
                        for _ in 2..n {
                            let c = index()?;
                            out.push([a, b, c]);
                            b = c;
                        }
                    }
                    Kind::List { count: ct, item } => {
                        let n = count(s, ct)?;
                        s.skip(item, n)?;
                    }
                }
            }
            s.end()
        })?;
    }
    Ok(())
}

pub fn too_many(max: usize) -> String {
    format!("too many triangles: a scene holds at most {max} primitives")
}

pub fn out_of_range(i: f64, vertices: usize) -> String {
    let n = crate::words::count(vertices, "vertex", "vertices");
    format!("vertex index {i} is out of range (the file has {n}, numbered from 0)")
}

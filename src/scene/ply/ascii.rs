//! The body of an ASCII PLY file: one record per line, its values in header order separated by
//! spaces or tabs (a list: its count, then that many items), the line ending in `\n` or
//! `\r\n`. Read line by line, in order (`walk.rs` gives the values their meaning).
//!
//! Values are read as the decimal numbers they are, whatever their declared type: a `float`
//! coordinate keeps the precision it is written with (as the OBJ reader keeps it), so the same
//! text gives the same mesh through either reader. An integer type takes only integers within
//! its range (`uchar`: 0 to 255). Coordinates use the scene number grammar (`number.rs`); other
//! float values may also be `nan` or `inf`, as some writers put them in normals. A line with
//! fewer or more values than its element declares is refused, as is any text after the last
//! record, whitespace and blank lines aside.

use super::super::number;
use super::Body;
use super::header::{Header, Type, clip};
use super::walk::{self, Bad, Source};
use crate::error::Error;
use std::ops::Range;
use std::path::Path;

/// The body's lines, read a value at a time; errors name the current line.
struct Lines<'a, I> {
    body: &'a [u8],
    lines: I,
    /// The current line's number in the file, and what is left of it.
    line: usize,
    rest: &'a [u8],
    path: &'a Path,
}

fn blank(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

impl<'a, I: Iterator<Item = Range<usize>>> Lines<'a, I> {
    /// The next token on the line, if any.
    fn token(&mut self) -> Option<&'a [u8]> {
        let start = self.rest.iter().position(|&b| !blank(b))?;
        let rest = &self.rest[start..];
        let end = rest.iter().position(|&b| blank(b)).unwrap_or(rest.len());
        self.rest = &rest[end..];
        Some(&rest[..end])
    }

    /// Takes the next line; false at the end of the body.
    fn next_line(&mut self) -> bool {
        // the empty piece after the body's last line end is no line
        let Some(r) = self.lines.next().filter(|r| r.start < self.body.len()) else {
            return false;
        };
        let raw = &self.body[r];
        self.rest = raw.strip_suffix(b"\r").unwrap_or(raw);
        self.line += 1;
        true
    }
}

impl<'a, I: Iterator<Item = Range<usize>>> Source for Lines<'a, I> {
    fn begin(&mut self) -> Result<(), Bad> {
        if self.next_line() {
            return Ok(());
        }
        let msg = "the file ends before this record (is it cut short?)";
        Err(Bad {
            mark: 0,
            msg: msg.into(),
        })
    }

    fn mark(&self) -> usize {
        0
    }

    fn value(&mut self, t: Type) -> Result<f64, Bad> {
        let Some(tok) = self.token() else {
            let msg = "the line ends before all the values its element declares";
            return Err(Bad {
                mark: 0,
                msg: msg.into(),
            });
        };
        let v = if t.is_int() {
            integer(tok, t)
        } else {
            // NaN and infinities are told apart from typos; `walk` refuses them as coordinates
            number::decimal(tok).or_else(|| std::str::from_utf8(tok).ok()?.parse().ok())
        };
        v.ok_or_else(|| {
            let tok = clip(&String::from_utf8_lossy(tok));
            let msg = match t.int_range() {
                (lo, hi) if t.is_int() => {
                    format!(
                        "'{tok}' is not a valid {} (an integer from {lo} to {hi})",
                        t.name()
                    )
                }
                _ => format!("'{tok}' is not a number"),
            };
            Bad { mark: 0, msg }
        })
    }

    fn skip(&mut self, t: Type, n: usize) -> Result<(), Bad> {
        for _ in 0..n {
            self.value(t)?;
        }
        Ok(())
    }

    fn end(&mut self) -> Result<(), Bad> {
        match self.token() {
            None => Ok(()),
            Some(tok) => {
                let tok = clip(&String::from_utf8_lossy(tok));
                let msg = format!("more values than its element declares ('{tok}')");
                Err(Bad { mark: 0, msg })
            }
        }
    }

    fn error_at(&self, _: usize, what: &str, r: usize, msg: String) -> Error {
        Error::input(self.path, self.line, 0, format!("{what} {r}: {msg}"))
    }
}

/// An integer token (optional sign, digits) within the range of `t`.
fn integer(tok: &[u8], t: Type) -> Option<f64> {
    let (negative, digits) = match tok {
        [b'-', d @ ..] => (true, d),
        [b'+', d @ ..] => (false, d),
        d => (false, d),
    };
    if digits.is_empty() || digits.len() > 18 || !digits.iter().all(u8::is_ascii_digit) {
        return None;
    }
    let n = digits
        .iter()
        .fold(0i64, |n, &d| n * 10 + i64::from(d - b'0'));
    let n = if negative { -n } else { n };
    let (lo, hi) = t.int_range();
    (lo..=hi).contains(&n).then_some(n as f64)
}

/// The vertices and triangles of the ASCII body of `bytes`, with at most `max` triangles. The
/// header is checked (`header::parse`).
pub fn read(bytes: &[u8], h: &Header, path: &Path, max: usize) -> Result<Body, Error> {
    let body = &bytes[h.body..];
    let mut s = Lines {
        body,
        lines: super::super::chunks::lines(body),
        line: h.lines,
        rest: &[],
        path,
    };
    let (mut verts, mut faces) = (Vec::new(), Vec::new());
    for (e, el) in h.elements.iter().enumerate() {
        if e == h.vertex {
            walk::vertices(&mut s, el, h.xyz, &mut verts)?;
        } else if e == h.face {
            walk::faces(&mut s, el, h.list, h.vertices(), max, &mut faces)?;
        } else {
            walk::skip(&mut s, el)?;
        }
    }
    while s.next_line() {
        if let Some(tok) = s.token() {
            let tok = clip(&String::from_utf8_lossy(tok));
            let msg = format!("'{tok}' after the last element the header declares");
            return Err(Error::input(path, s.line, 0, msg));
        }
    }
    Ok(Body {
        vertices: verts,
        faces,
        degenerate: None,
    })
}

//! One chunk of a `.sc` file, parsed on its own (`parse.rs` splits the file and joins the
//! chunks in file order).
//!
//! A chunk does everything a line-by-line reader does except what depends on earlier chunks:
//! primitives are parsed and validated (kept compactly until the join builds the scene),
//! `camera` and `mesh` lines become events for the join, and the chunk stops at its first
//! error, which the join reports unless something earlier in the file (the primitive limit, a
//! camera in an earlier chunk) decides otherwise.

use super::CameraSpec;
use super::chunks::{self, Budget, Chunk};
use super::statement::{
    Ctx, KEYWORDS, Tok, fast_shape, first_token_col, parse_camera, parse_shape, quote, tokenize,
};
use super::{KINDS, Shape};
use crate::error::Error;
use crate::limits::MAX_LINE_BYTES;
use std::path::Path;

/// What one chunk found, in line order.
pub struct ChunkOut<'a> {
    /// The chunk's primitives, compactly (a sphere takes 40 bytes here, 112 in the scene):
    /// their numbers one after the other, 4, 9 or 12 by type...
    nums: Vec<f64>,
    /// ...and for each, where its numbers start and its line, counted from `first_line`.
    prims: Vec<Prim>,
    first_line: usize,
    pub events: Vec<Event<'a>>,
    /// Where and why the chunk stopped early (its first error).
    pub stop: Option<Stop>,
}

/// A line whose meaning depends on the lines before it. `at`: how many of the chunk's shapes
/// precede it.
pub enum Event<'a> {
    /// The chunk's first camera (a second one in the same chunk stops the chunk).
    Camera {
        line: usize,
        col: usize,
        at: usize,
        spec: CameraSpec,
    },
    Mesh {
        line: usize,
        /// 1-based column of the path.
        col: usize,
        at: usize,
        path: &'a str,
    },
}

/// One primitive of a chunk (both fields fit: a chunk's lines and numbers are fewer than its
/// bytes, a few MiB).
#[derive(Clone, Copy)]
struct Prim {
    num_at: u32,
    line: u32,
}

impl ChunkOut<'_> {
    pub fn len(&self) -> usize {
        self.prims.len()
    }

    pub fn line(&self, k: usize) -> usize {
        self.first_line + self.prims[k].line as usize
    }

    fn push(&mut self, shape: &Shape, line: usize) {
        self.prims.push(Prim {
            num_at: self.nums.len() as u32,
            line: (line - self.first_line) as u32,
        });
        shape.write_numbers(&mut self.nums);
    }

    /// Primitive `k` as a shape again.
    pub fn shape(&self, k: usize) -> Shape {
        let at = self.prims[k].num_at as usize;
        let end = self
            .prims
            .get(k + 1)
            .map_or(self.nums.len(), |p| p.num_at as usize);
        let x = &self.nums[at..end];
        // (the kinds' counts of numbers differ: the count tells the kind)
        let kind = (0..KINDS.len()).find(|&k| Shape::numbers_of(k) == Some(x.len()));
        kind.and_then(|k| Shape::from_numbers(k, x))
            .expect("a chunk holds whole shapes")
    }
}

pub struct Stop {
    pub line: usize,
    /// How many of the chunk's shapes precede the line.
    pub at: usize,
    pub kind: StopKind,
}

pub enum StopKind {
    Error(Error),
    /// An error on a primitive line: the primitive limit, checked first, may win over it.
    Primitive(Error),
    /// The chunk's first camera line is bad: unless a camera came before, in another chunk.
    Camera {
        col: usize,
        err: Error,
    },
    /// The budget ran out.
    Budget,
}

/// Checks the chunk `body[c.range]` as UTF-8 (`Err`: the offset of its first bad byte in
/// `body`) and parses it, stopping at its first error.
pub fn parse_chunk<'a>(
    body: &'a [u8],
    c: &Chunk,
    file: &'a Path,
    budget: &Budget,
) -> std::result::Result<ChunkOut<'a>, usize> {
    let bytes = &body[c.range.clone()];
    let text = std::str::from_utf8(bytes).map_err(|e| c.range.start + e.valid_up_to())?;
    // about 48 bytes a line in large generated scenes
    let guess = bytes.len().min(8 << 20) / 40;
    let mut out = ChunkOut {
        nums: Vec::with_capacity(4 * guess),
        prims: Vec::with_capacity(guess),
        first_line: c.first_line,
        events: Vec::new(),
        stop: None,
    };
    let mut toks = Vec::new();
    let mut first_camera = None;
    let mut unrecorded = 0;
    for (i, r) in chunks::lines(bytes).enumerate() {
        let raw = &text[r];
        let line_no = c.first_line + i;
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        let shape = if line.len() > MAX_LINE_BYTES {
            let n = line.len();
            let msg = format!("line is {n} bytes long; the limit is {MAX_LINE_BYTES}");
            let col = first_token_col(line);
            Err(StopKind::Error(Error::input(file, line_no, col, msg)))
        } else if let Some(s) = fast_shape(line.as_bytes()) {
            Ok(Some(s))
        } else {
            let ctx = Ctx {
                file,
                line: line_no,
                text: line,
            };
            general_line(&ctx, &mut toks, &mut out, &mut first_camera)
        };
        let kind = match shape {
            Ok(None) => continue,
            Ok(Some(s)) => {
                out.push(&s, line_no);
                unrecorded += 1;
                if unrecorded < budget.batch || budget.take(std::mem::take(&mut unrecorded)) {
                    continue;
                }
                StopKind::Budget
            }
            Err(kind) => kind,
        };
        out.stop = Some(Stop {
            line: line_no,
            at: out.len(),
            kind,
        });
        break;
    }
    Ok(out)
}

/// Any line the fast path did not take: a primitive (`Some`), or a camera or mesh line, which
/// become events, or nothing.
fn general_line<'a>(
    ctx: &Ctx<'a>,
    toks: &mut Vec<Tok<'a>>,
    out: &mut ChunkOut<'a>,
    first_camera: &mut Option<usize>,
) -> std::result::Result<Option<Shape>, StopKind> {
    let line = ctx.text;
    let content = line.find('#').map_or(line, |k| &line[..k]);
    tokenize(content, toks);
    let Some(first) = toks.first() else {
        return Ok(None);
    };
    let at = out.len();
    match first.s {
        "camera" => {
            let col = ctx.col(first);
            if let Some(first_line) = *first_camera {
                let e = second_camera(ctx.file, ctx.line, col, first_line);
                return Err(StopKind::Error(e));
            }
            *first_camera = Some(ctx.line);
            let spec = parse_camera(ctx, toks).map_err(|err| StopKind::Camera { col, err })?;
            out.events.push(Event::Camera {
                line: ctx.line,
                col,
                at,
                spec,
            });
            Ok(None)
        }
        "mesh" => {
            let path = content[first.off + first.s.len()..].trim();
            if path.is_empty() {
                let e = ctx.at(first, "mesh needs a path: `mesh PATH`".to_string());
                return Err(StopKind::Error(e));
            }
            out.events.push(Event::Mesh {
                line: ctx.line,
                col: ctx.col(&toks[1]),
                at,
                path,
            });
            Ok(None)
        }
        kind if KINDS.iter().any(|&(keyword, _)| keyword == kind) => parse_shape(ctx, toks)
            .map(Some)
            .map_err(StopKind::Primitive),
        other => {
            let msg = format!(
                "unknown keyword {}: expected one of {KEYWORDS}",
                quote(other)
            );
            Err(StopKind::Error(ctx.at(first, msg)))
        }
    }
}

pub fn second_camera(file: &Path, line: usize, col: usize, first_line: usize) -> Error {
    let msg = format!(
        "second camera line (the first is on line {first_line}); a scene has exactly one camera"
    );
    Error::input(file, line, col, msg)
}

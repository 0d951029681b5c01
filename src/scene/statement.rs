//! One `.sc` line at a time: tokens, numbers, shapes and the camera, and the messages that
//! point at `FILE:LINE:COL` (the column counted in characters: the offending token's, or
//! the statement's first token's for a rule about the statement as a whole, `Ctx::whole`).
//!
//! [`fast_shape`] reads the common line, a well-formed primitive, without building tokens; on
//! anything unusual it gives up and the caller takes the general path ([`tokenize`],
//! [`parse_shape`], [`parse_camera`]), which accepts exactly the same lines with the same values
//! and words every error.

use super::number::{decimal, finite_token, is_decimal};
use super::{CameraSpec, Intrinsics, Lens, Shape, validate};
use crate::error::{Error, Result};
use glam::DVec3;
use std::path::Path;

pub const KEYWORDS: &str = "camera, sphere, triangle, quad, mesh";
pub const CAMERA_SYNTAX: &str =
    "camera eye X Y Z look X Y Z up X Y Z [fov DEGREES | K FX FY CX CY]";
const CAMERA_WORDS: [&str; 5] = ["eye", "look", "up", "fov", "K"];

/// A token and its byte offset in its line.
pub struct Tok<'a> {
    pub s: &'a str,
    pub off: usize,
}

/// Splits `s` on spaces and tabs into `out` (cleared first).
pub fn tokenize<'a>(s: &'a str, out: &mut Vec<Tok<'a>>) {
    out.clear();
    let mut start = None;
    for (i, b) in s.bytes().enumerate() {
        let sep = b == b' ' || b == b'\t';
        match (sep, start) {
            (true, Some(st)) => {
                out.push(Tok {
                    s: &s[st..i],
                    off: st,
                });
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(st) = start {
        out.push(Tok {
            s: &s[st..],
            off: st,
        });
    }
}

/// The 1-based character column of the first token of `line` (past leading spaces and tabs;
/// 1 for a blank line).
pub fn first_token_col(line: &str) -> usize {
    line.chars().take_while(|&c| c == ' ' || c == '\t').count() + 1
}

/// Where errors on the current line point.
pub struct Ctx<'a> {
    pub file: &'a Path,
    pub line: usize,
    pub text: &'a str,
}

impl Ctx<'_> {
    /// The 1-based character column of a token.
    pub fn col(&self, t: &Tok) -> usize {
        self.text[..t.off].chars().count() + 1
    }

    /// An error at a token's 1-based character column.
    pub fn at(&self, t: &Tok, msg: impl Into<String>) -> Error {
        Error::input(self.file, self.line, self.col(t), msg)
    }

    /// An error about the statement as a whole (too few numbers, a shape or camera breaking a
    /// geometric rule), at the column of its first token: README "Scene format (.sc)", every
    /// message has a column.
    pub fn whole(&self, msg: impl Into<String>) -> Error {
        Error::input(self.file, self.line, first_token_col(self.text), msg)
    }

    /// A token as a finite decimal number.
    pub fn number(&self, t: &Tok) -> Result<f64> {
        let Some(x) = decimal(t.s.as_bytes()) else {
            let msg = format!(
                "{} is not a number (expected a finite decimal such as 1, -2.5 or 1e-3)",
                quote(t.s)
            );
            return Err(self.at(t, msg));
        };
        if !x.is_finite() {
            return Err(self.at(
                t,
                format!("{} is out of range: it overflows f64", quote(t.s)),
            ));
        }
        Ok(x)
    }
}

/// A token quoted for a message, escaped and cut to a readable length.
pub fn quote(s: &str) -> String {
    const MAX: usize = 40;
    let cut: String = s.chars().take(MAX).collect();
    let more = if s.chars().nth(MAX).is_some() {
        "..."
    } else {
        ""
    };
    format!("'{}{more}'", cut.escape_debug())
}

/// The numbers a primitive takes, and what they are, for messages.
fn arity(kw: &str) -> (usize, &'static str) {
    match kw {
        "sphere" => (4, "center x y z, radius"),
        "triangle" => (9, "x y z of 3 vertices"),
        _ => (12, "x y z of 4 vertices in perimeter order"),
    }
}

/// The shape of keyword `kw` (`sphere`, `triangle` or `quad`) from its numbers, validated (`Err`: the message, and whether it is
/// about the radius, the 4th number, rather than the whole line).
fn shape(kw: &[u8], x: &[f64; 12]) -> std::result::Result<Shape, (String, bool)> {
    let p = |i: usize| DVec3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    match kw.len() {
        6 => {
            validate::sphere_radius(x[3]).map_err(|m| (m, true))?;
            Ok(Shape::Sphere {
                center: p(0),
                radius: x[3],
            })
        }
        8 => {
            let v = [p(0), p(1), p(2)];
            validate::triangle(&v).map_err(|m| (m, false))?;
            Ok(Shape::Triangle(v))
        }
        _ => {
            let v = [p(0), p(1), p(2), p(3)];
            validate::quad(&v).map_err(|m| (m, false))?;
            Ok(Shape::Quad(v))
        }
    }
}

/// A primitive line (`\r` already removed) that is well formed and valid, read in one pass over
/// its bytes; `None` for any other line, which then takes the general path.
pub fn fast_shape(line: &[u8]) -> Option<Shape> {
    let blanks = |mut i: usize| {
        while i < line.len() && matches!(line[i], b' ' | b'\t') {
            i += 1;
        }
        i
    };
    let start = blanks(0);
    let mut i = start;
    while i < line.len() && !matches!(line[i], b' ' | b'\t' | b'#') {
        i += 1;
    }
    let kw = &line[start..i];
    // (patterns of bytes, not b"quad": a byte string pattern compares through `memcmp`)
    let n = match kw {
        [b's', b'p', b'h', b'e', b'r', b'e'] => 4,
        [b't', b'r', b'i', b'a', b'n', b'g', b'l', b'e'] => 9,
        [b'q', b'u', b'a', b'd'] => 12,
        _ => return None,
    };
    let mut x = [0.0; 12];
    for slot in &mut x[..n] {
        i = blanks(i);
        let (value, len) = finite_token(&line[i..])?;
        *slot = value;
        i += len;
    }
    // nothing more than blanks, then perhaps a comment
    i = blanks(i);
    if i < line.len() && line[i] != b'#' {
        return None;
    }
    shape(kw, &x).ok()
}

/// A primitive line: numbers, their count, then the shape's own rules.
pub fn parse_shape(ctx: &Ctx, toks: &[Tok]) -> Result<Shape> {
    let kw = toks[0].s;
    let (n, what) = arity(kw);
    let args = &toks[1..];
    let mut x = [0.0; 12];
    for (k, t) in args.iter().take(n).enumerate() {
        x[k] = ctx.number(t)?;
    }
    let got = args.len();
    if got < n {
        return Err(ctx.whole(format!(
            "too few numbers: {kw} expects {n} ({what}), got {got}"
        )));
    }
    if got > n {
        let msg = format!("too many numbers: {kw} expects {n} ({what}), got {got}");
        return Err(ctx.at(&args[n], msg));
    }
    shape(kw.as_bytes(), &x).map_err(|(m, radius)| {
        if radius {
            ctx.at(&args[3], m)
        } else {
            ctx.whole(m)
        }
    })
}

/// `got` numbers given where `name` takes `expects`: the numbers are counted from `toks`.
fn too_many(ctx: &Ctx, toks: &[Tok], name: &str, expects: usize) -> Error {
    let extra = toks.iter().take_while(|t| is_decimal(t.s)).count();
    let got = expects + extra;
    ctx.at(
        &toks[0],
        format!("too many numbers: camera '{name}' expects {expects}, got {got}"),
    )
}

/// What may follow a camera's pose, from token `i` to the end of the line: nothing, `fov
/// DEGREES` or `K FX FY CX CY` (`validate::fov`, `validate::intrinsics`). `pose` names the
/// pose's last word and how many numbers it takes, for messages.
pub fn parse_lens(
    ctx: &Ctx,
    toks: &[Tok],
    mut i: usize,
    pose: (&str, usize),
) -> Result<Option<Lens>> {
    let mut lens = None;
    let mut last = pose;
    match toks.get(i).map(|t| t.s) {
        Some("fov") => {
            i += 1;
            let Some(t) = toks.get(i) else {
                return Err(ctx.whole("too few numbers: camera 'fov' expects 1, got 0"));
            };
            let deg = ctx.number(t)?;
            validate::fov(deg).map_err(|m| ctx.at(t, m))?;
            lens = Some(Lens::Fov(deg));
            last = ("fov", 1);
            i += 1;
        }
        Some("K") => {
            let word = i;
            i += 1;
            let mut x = [0.0; 4];
            for (k, v) in x.iter_mut().enumerate() {
                match toks.get(i) {
                    Some(t) if !CAMERA_WORDS.contains(&t.s) => *v = ctx.number(t)?,
                    _ => {
                        let few =
                            format!("too few numbers: camera 'K' expects 4 (FX FY CX CY), got {k}");
                        return Err(ctx.at(&toks[word], few));
                    }
                }
                i += 1;
            }
            let k = Intrinsics {
                fx: x[0],
                fy: x[1],
                cx: x[2],
                cy: x[3],
            };
            if let Err(m) = validate::intrinsics(&k) {
                // the focal length's own token where one is at fault
                let at = match (k.fx > 0.0, k.fy > 0.0) {
                    (false, _) => 1,
                    (true, false) => 2,
                    (true, true) => 0,
                };
                return Err(ctx.at(&toks[word + at], m));
            }
            lens = Some(Lens::Pinhole(k));
            last = ("K", 4);
        }
        _ => {}
    }
    if let Some(t) = toks.get(i) {
        if is_decimal(t.s) {
            return Err(too_many(ctx, &toks[i..], last.0, last.1));
        }
        let msg = match last.0 {
            "fov" => format!("camera: unexpected {} after 'fov DEGREES'", quote(t.s)),
            "K" => format!("camera: unexpected {} after 'K FX FY CX CY'", quote(t.s)),
            pose => format!(
                "camera: unexpected {} after '{pose}' (only `fov DEGREES` or `K FX FY CX CY` \
                 may follow)",
                quote(t.s)
            ),
        };
        return Err(ctx.at(t, msg));
    }
    Ok(lens)
}

pub fn parse_camera(ctx: &Ctx, toks: &[Tok]) -> Result<CameraSpec> {
    let mut i = 1;
    let mut groups = [DVec3::ZERO; 3];
    for (g, name) in ["eye", "look", "up"].into_iter().enumerate() {
        match toks.get(i) {
            None => {
                let msg = format!("camera: missing '{name}' (expected `{CAMERA_SYNTAX}`)");
                return Err(ctx.whole(msg));
            }
            Some(t) if t.s == name => {}
            Some(t) if g > 0 && is_decimal(t.s) => {
                return Err(too_many(ctx, &toks[i..], ["eye", "look"][g - 1], 3));
            }
            Some(t) => {
                let msg = format!(
                    "camera: expected '{name}', found {} (expected `{CAMERA_SYNTAX}`)",
                    quote(t.s)
                );
                return Err(ctx.at(t, msg));
            }
        }
        i += 1;
        let mut xyz = [0.0; 3];
        for (k, x) in xyz.iter_mut().enumerate() {
            let few = format!("too few numbers: camera '{name}' expects 3, got {k}");
            match toks.get(i) {
                None => return Err(ctx.whole(few)),
                Some(t) if CAMERA_WORDS.contains(&t.s) => return Err(ctx.at(t, few)),
                Some(t) => *x = ctx.number(t)?,
            }
            i += 1;
        }
        groups[g] = DVec3::from_array(xyz);
    }
    let lens = parse_lens(ctx, toks, i, ("up", 3))?;
    let [eye, look, up] = groups;
    let spec = CameraSpec {
        eye,
        look,
        up,
        lens,
    };
    validate::camera(&spec).map_err(|m| ctx.whole(m))?;
    Ok(spec)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quote_escapes_and_cuts() {
        assert_eq!(quote("a\tb"), "'a\\tb'");
        assert_eq!(quote(&"x".repeat(50)), format!("'{}...'", "x".repeat(40)));
    }

    /// The fast path takes a line only when the general path takes it, with the same shape.
    #[test]
    fn fast_path_agrees_with_the_general_path() {
        let lines = [
            "sphere 0 0 0 1",
            "  sphere\t1 2 3 0.5   # comment",
            "sphere 1 2 3 0.5#comment",
            "sphere 1 2 3 #0.5",
            "sphere# 1 2 3 0.5",
            "sphere 1 2 3 0.5 6",
            "sphere 1 2 3",
            "sphere 1 2 3 0",
            "sphere 1 2 3 -1",
            "sphere 1 2 3 1e400",
            "sphere 1 2 3 nan",
            "sphere 1 2 3 0x1",
            "sphere 1 2 3 １",
            "sphere 1 2 3 1\u{a0}",
            "Sphere 0 0 0 1",
            "spheres 0 0 0 1",
            "triangle 0 0 0 1 0 0 0 1 0",
            "triangle 0 0 0 1 0 0 2 0 0",
            "triangle 0 0 0 1 0 0 0 1",
            "quad 0 0 0 1 0 0 1 1 0 0 1 0",
            "quad 0 0 0 1 0 0 0 1 0 1 1 0",
            "quad -4 0 -4  4 0 -4  4 0 4  -4 0 4",
            "quad 0 0 0 1 0 0 1 1 0 0 1 1",
            "mesh a.obj",
            "camera eye 0 0 5 look 0 0 0 up 0 1 0",
            "",
            "# sphere 0 0 0 1",
        ];
        let mut toks = Vec::new();
        for line in lines {
            let ctx = Ctx {
                file: Path::new("t.sc"),
                line: 1,
                text: line,
            };
            let content = line.find('#').map_or(line, |k| &line[..k]);
            tokenize(content, &mut toks);
            let general = match toks.first().map(|t| t.s) {
                Some("sphere" | "triangle" | "quad") => parse_shape(&ctx, &toks).ok(),
                _ => None,
            };
            assert_eq!(fast_shape(line.as_bytes()), general, "{line:?}");
        }
    }
}

//! Reading `.sc` scene text into a `Scene`.
//!
//! UTF-8 text, one statement per line, `#` to end of line a comment, blank lines ignored,
//! tokens separated by spaces or tabs, a leading BOM and CRLF line ends accepted:
//!
//! ```text
//! camera eye EX EY EZ look LX LY LZ up UX UY UZ [fov DEGREES]
//! sphere CX CY CZ RADIUS
//! triangle AX AY AZ  BX BY BZ  CX CY CZ
//! quad AX AY AZ  BX BY BZ  CX CY CZ  DX DY DZ     # vertices in perimeter order
//! ```
//!
//! Exactly one camera line, anywhere; any number of primitives. Errors point at
//! `FILE:LINE:COL`, the column counted in characters (after the BOM), 0 for the whole line.

use super::{CameraSpec, Scene, Shape, mesh, validate};
use crate::error::{Error, Result};
use crate::limits::{MAX_LINE_BYTES, MAX_PRIMITIVES, MAX_SCENE_BYTES};
use glam::DVec3;
use std::fs::File;
use std::io::Read;
use std::path::Path;

const KEYWORDS: &str = "camera, sphere, triangle, quad, mesh";
const CAMERA_SYNTAX: &str = "camera eye X Y Z look X Y Z up X Y Z [fov DEGREES]";
const CAMERA_WORDS: [&str; 4] = ["eye", "look", "up", "fov"];

/// Reads and parses a scene file. The size is checked against `MAX_SCENE_BYTES` before
/// reading, and the text must be UTF-8.
pub fn load_scene(path: &Path) -> Result<Scene> {
    let io_err = |e| Error::io(path, "read scene", e);
    let meta = std::fs::metadata(path).map_err(io_err)?;
    if meta.len() > MAX_SCENE_BYTES {
        return Err(too_big(path, meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // `take` guards against files that grow after the check, and special files.
    let file = File::open(path).map_err(io_err)?;
    file.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io_err)?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(too_big(path, bytes.len() as u64));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let bytes = e.as_bytes();
        let bad = e.utf8_error().valid_up_to();
        let line_start = bytes[..bad]
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        let line = bytes[..line_start].iter().filter(|&&b| b == b'\n').count() + 1;
        // The prefix of the line up to the bad byte is valid UTF-8.
        let prefix = std::str::from_utf8(&bytes[line_start..bad]).unwrap_or("");
        let prefix = if line == 1 {
            prefix.strip_prefix('\u{feff}').unwrap_or(prefix)
        } else {
            prefix
        };
        let msg = format!(
            "not valid UTF-8 (byte 0x{:02x}); scene files must be UTF-8 text",
            bytes[bad]
        );
        Error::input(path, line, prefix.chars().count() + 1, msg)
    })?;
    parse_scene(&text, path)
}

fn too_big(path: &Path, len: u64) -> Error {
    Error::InputFile {
        file: path.to_path_buf(),
        msg: format!("scene file is {len} bytes; the limit is {MAX_SCENE_BYTES} bytes"),
    }
}

/// Parses and validates scene text. `file` only names the scene in messages and in
/// `Scene::source`.
pub fn parse_scene(text: &str, file: &Path) -> Result<Scene> {
    parse_with_limit(text, file, MAX_PRIMITIVES)
}

fn parse_with_limit(text: &str, file: &Path, max_primitives: usize) -> Result<Scene> {
    if text.len() as u64 > MAX_SCENE_BYTES {
        return Err(too_big(file, text.len() as u64));
    }
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut camera: Option<(CameraSpec, usize)> = None;
    let mut shapes = Vec::new();
    let mut lines = Vec::new();
    let mut warnings = Vec::new();
    let mut toks = Vec::new();
    for (i, raw) in text.split('\n').enumerate() {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        let ctx = Ctx {
            file,
            line: i + 1,
            text: line,
        };
        if line.len() > MAX_LINE_BYTES {
            let n = line.len();
            return Err(ctx.whole(format!(
                "line is {n} bytes long; the limit is {MAX_LINE_BYTES}"
            )));
        }
        let content = line.find('#').map_or(line, |k| &line[..k]);
        tokenize(content, &mut toks);
        let Some(first) = toks.first() else { continue };
        match first.s {
            "camera" => {
                if let Some((_, first_line)) = camera {
                    return Err(ctx.at(
                        first,
                        format!(
                            "second camera line (the first is on line {first_line}); a scene \
                             has exactly one camera"
                        ),
                    ));
                }
                camera = Some((parse_camera(&ctx, &toks)?, ctx.line));
            }
            "mesh" => {
                let rest = content[first.off + first.s.len()..].trim();
                if rest.is_empty() {
                    return Err(ctx.at(first, "mesh needs a path: `mesh PATH`".to_string()));
                }
                let path = file.parent().map_or_else(|| rest.into(), |d| d.join(rest));
                let room = max_primitives - shapes.len();
                let (tris, degenerate) = mesh::load_obj(&path, room).map_err(|e| match e {
                    Error::Io { source, .. } => {
                        ctx.whole(format!("cannot read mesh {}: {source}", path.display()))
                    }
                    other => other,
                })?;
                if degenerate > 0 {
                    warnings.push(format!(
                        "{}:{}: mesh {}: {degenerate} degenerate triangles kept (never hit)",
                        file.display(),
                        ctx.line,
                        path.display()
                    ));
                }
                lines.extend(std::iter::repeat_n(ctx.line, tris.len()));
                shapes.extend(tris.into_iter().map(Shape::Triangle));
            }
            "sphere" | "triangle" | "quad" => {
                if shapes.len() >= max_primitives {
                    let msg =
                        format!("too many primitives: a scene holds at most {max_primitives}");
                    return Err(ctx.whole(msg));
                }
                shapes.push(parse_shape(&ctx, &toks)?);
                lines.push(ctx.line);
            }
            other => {
                let msg = format!(
                    "unknown keyword {}: expected one of {KEYWORDS}",
                    quote(other)
                );
                return Err(ctx.at(first, msg));
            }
        }
    }
    let Some((camera, _)) = camera else {
        return Err(Error::InputFile {
            file: file.to_path_buf(),
            msg: format!("no camera line (expected `{CAMERA_SYNTAX}`)"),
        });
    };
    Ok(Scene {
        source: file.to_path_buf(),
        camera,
        shapes,
        lines,
        warnings,
    })
}

/// A token and its byte offset in its line.
struct Tok<'a> {
    s: &'a str,
    off: usize,
}

/// Splits `s` on spaces and tabs into `out` (cleared first).
fn tokenize<'a>(s: &'a str, out: &mut Vec<Tok<'a>>) {
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

/// Where errors on the current line point.
struct Ctx<'a> {
    file: &'a Path,
    line: usize,
    text: &'a str,
}

impl Ctx<'_> {
    /// An error at a token's 1-based character column.
    fn at(&self, t: &Tok, msg: impl Into<String>) -> Error {
        let col = self.text[..t.off].chars().count() + 1;
        Error::input(self.file, self.line, col, msg)
    }

    /// An error about the whole line (column 0).
    fn whole(&self, msg: impl Into<String>) -> Error {
        Error::input(self.file, self.line, 0, msg)
    }

    /// A token as a finite decimal number.
    fn number(&self, t: &Tok) -> Result<f64> {
        let not_number = || {
            let msg = format!(
                "{} is not a number (expected a finite decimal such as 1, -2.5 or 1e-3)",
                quote(t.s)
            );
            self.at(t, msg)
        };
        if !is_decimal(t.s) {
            return Err(not_number());
        }
        let x: f64 = t.s.parse().map_err(|_| not_number())?;
        if !x.is_finite() {
            return Err(self.at(
                t,
                format!("{} is out of range: it overflows f64", quote(t.s)),
            ));
        }
        Ok(x)
    }
}

/// Decimal float syntax: optional sign, digits with an optional fraction (at least one digit
/// in all), optional exponent (`e`/`E`, optional sign, at least one digit). Unlike
/// `f64::from_str` this rejects `inf`, `nan` and `infinity`.
fn is_decimal(s: &str) -> bool {
    let b = s.as_bytes();
    let digits_from = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut i = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    let int_end = digits_from(i);
    let mut mantissa_digits = int_end - i;
    i = int_end;
    if b.get(i) == Some(&b'.') {
        let frac_end = digits_from(i + 1);
        mantissa_digits += frac_end - (i + 1);
        i = frac_end;
    }
    if mantissa_digits == 0 {
        return false;
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let exp_end = digits_from(i);
        if exp_end == i {
            return false;
        }
        i = exp_end;
    }
    i == b.len()
}

/// A token quoted for a message, escaped and cut to a readable length.
fn quote(s: &str) -> String {
    const MAX: usize = 40;
    let cut: String = s.chars().take(MAX).collect();
    let more = if s.chars().nth(MAX).is_some() {
        "..."
    } else {
        ""
    };
    format!("'{}{more}'", cut.escape_debug())
}

fn parse_shape(ctx: &Ctx, toks: &[Tok]) -> Result<Shape> {
    let kw = toks[0].s;
    let (n, what) = match kw {
        "sphere" => (4, "center x y z, radius"),
        "triangle" => (9, "x y z of 3 vertices"),
        _ => (12, "x y z of 4 vertices in perimeter order"),
    };
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
    let p = |i: usize| DVec3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    match kw {
        "sphere" => {
            validate::sphere_radius(x[3]).map_err(|m| ctx.at(&args[3], m))?;
            Ok(Shape::Sphere {
                center: p(0),
                radius: x[3],
            })
        }
        "triangle" => {
            let v = [p(0), p(1), p(2)];
            validate::triangle(&v).map_err(|m| ctx.whole(m))?;
            Ok(Shape::Triangle(v))
        }
        _ => {
            let v = [p(0), p(1), p(2), p(3)];
            validate::quad(&v).map_err(|m| ctx.whole(m))?;
            Ok(Shape::Quad(v))
        }
    }
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

fn parse_camera(ctx: &Ctx, toks: &[Tok]) -> Result<CameraSpec> {
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
    let mut fov_deg = None;
    let mut last = "up";
    if toks.get(i).is_some_and(|t| t.s == "fov") {
        i += 1;
        let Some(t) = toks.get(i) else {
            return Err(ctx.whole("too few numbers: camera 'fov' expects 1, got 0"));
        };
        let deg = ctx.number(t)?;
        validate::fov(deg).map_err(|m| ctx.at(t, m))?;
        fov_deg = Some(deg);
        last = "fov";
        i += 1;
    }
    if let Some(t) = toks.get(i) {
        if is_decimal(t.s) {
            return Err(too_many(
                ctx,
                &toks[i..],
                last,
                if last == "up" { 3 } else { 1 },
            ));
        }
        let msg = if last == "up" {
            format!(
                "camera: unexpected {} after 'up' (only `fov DEGREES` may follow)",
                quote(t.s)
            )
        } else {
            format!("camera: unexpected {} after 'fov DEGREES'", quote(t.s))
        };
        return Err(ctx.at(t, msg));
    }
    let [eye, look, up] = groups;
    let spec = CameraSpec {
        eye,
        look,
        up,
        fov_deg,
    };
    validate::camera(&spec).map_err(|m| ctx.whole(m))?;
    Ok(spec)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_syntax() {
        for ok in [
            "0", "1", "-2.5", "+1", ".5", "5.", "1e-3", "1E3", "-.5e+7", "1e-400", "007",
        ] {
            assert!(is_decimal(ok), "{ok}");
        }
        let bad = [
            "", ".", "+", "-", "e5", "1e", "1e+", "inf", "nan", "infinity", "0x10", "1.2.3", "--1",
            "+-1", "1_000", "1,5", "1e5.0", " 1", "１",
        ];
        for b in bad {
            assert!(!is_decimal(b), "{b}");
        }
    }

    #[test]
    fn primitive_limit_counts_primitives_not_lines() {
        let text = "camera eye 0 0 5 look 0 0 0 up 0 1 0\n# c\nsphere 0 0 0 1\n\nsphere 0 0 0 1\n";
        let f = Path::new("s.sc");
        assert_eq!(parse_with_limit(text, f, 2).unwrap().shapes.len(), 2);
        let more = format!("{text}triangle 0 0 0 1 0 0 0 1 0\n");
        let e = parse_with_limit(&more, f, 2).unwrap_err().to_string();
        assert!(e.starts_with("s.sc:6: too many primitives"), "{e}");
    }

    #[test]
    fn quote_escapes_and_cuts() {
        assert_eq!(quote("a\tb"), "'a\\tb'");
        assert_eq!(quote(&"x".repeat(50)), format!("'{}...'", "x".repeat(40)));
    }
}

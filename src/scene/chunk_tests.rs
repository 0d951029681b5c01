//! Chunked parsing gives exactly what a single chunk gives, and what the line-by-line readers
//! it replaced gave (kept here, verbatim but for names, as oracles): the same scenes and meshes,
//! the same first error with the same global line and column, wherever the file is cut.

use super::mesh::{parse_chunked, parse_obj};
use super::parse::parse_bytes;
use super::statement::{
    CAMERA_SYNTAX, Ctx, KEYWORDS, fast_shape, parse_camera, parse_shape, quote, tokenize,
};
use super::{CameraSpec, Mesh, Scene, Shape, Shapes};
use crate::error::{Error, Result};
use crate::limits::MAX_LINE_BYTES;
use glam::DVec3;
use proptest::prelude::*;
use std::path::Path;

/// The `.sc` reader before chunking (meshes left out).
fn sequential_scene(text: &str, file: &Path, max_primitives: usize) -> Result<Scene> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut camera: Option<(CameraSpec, usize)> = None;
    let mut camera_at = None;
    let (mut shapes, mut toks) = (Shapes::new(), Vec::new());
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
                camera_at = Some((ctx.line, ctx.col(&toks[0])));
            }
            "mesh" => {
                if content[first.off + first.s.len()..].trim().is_empty() {
                    return Err(ctx.at(first, "mesh needs a path: `mesh PATH`".to_string()));
                }
                return Err(Error::Failed("no meshes in this oracle".into()));
            }
            "sphere" | "triangle" | "quad" => {
                if shapes.len() >= max_primitives {
                    let msg =
                        format!("too many primitives: a scene holds at most {max_primitives}");
                    return Err(ctx.whole(msg));
                }
                shapes.push(parse_shape(&ctx, &toks)?, ctx.line);
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
    let (source, warnings) = (file.to_path_buf(), Vec::new());
    Ok(Scene {
        source,
        camera,
        camera_at,
        shapes,
        warnings,
    })
}

/// The OBJ reader before chunking.
fn sequential_obj(bytes: &[u8], path: &Path, max: usize) -> Result<(Vec<[DVec3; 3]>, usize)> {
    let number = |t: &str| {
        let ok = t
            .bytes()
            .all(|b| b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'e' | b'E'));
        let v: f64 = t.parse().ok()?;
        (ok && v.is_finite()).then_some(v)
    };
    let (mut verts, mut tris, mut degenerate, mut face) = (Vec::new(), Vec::new(), 0, Vec::new());
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let err = |msg: String| Error::input(path, i + 1, 0, msg);
        if raw.len() > MAX_LINE_BYTES {
            let n = raw.len();
            return Err(err(format!(
                "line is {n} bytes long; the limit is {MAX_LINE_BYTES}"
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
                                "vertex index {n} is out of range ({} so far)",
                                crate::words::count(verts.len(), "vertex", "vertices")
                            ))
                        })?;
                    face.push(*v);
                }
                if face.len() < 3 {
                    let n = face.len();
                    return Err(err(format!("a face needs at least 3 vertices, got {n}")));
                }
                for k in 1..face.len() - 1 {
                    let t = [face[0], face[k], face[k + 1]];
                    if (t[1] - t[0]).cross(t[2] - t[0]).length_squared() == 0.0 {
                        degenerate += 1;
                    }
                    tris.push(t);
                }
                if tris.len() > max {
                    return Err(err(format!(
                        "too many triangles: a scene holds at most {max} primitives"
                    )));
                }
            }
            _ => {}
        }
    }
    Ok((tris, degenerate))
}

/// A mesh as the list of its triangles, as the old reader gave them.
fn triangles(r: Result<(Mesh, usize)>) -> Result<(Vec<[DVec3; 3]>, usize)> {
    r.map(|(m, zero)| ((0..m.len()).map(|f| m.triangle(f)).collect(), zero))
}

/// A result as a comparable value: the scene or mesh, or the error's full message.
fn show<T: std::fmt::Debug>(r: Result<T>) -> String {
    match r {
        Ok(v) => format!("{v:?}"),
        Err(e) => format!("error: {e}"),
    }
}

/// Every chunk size from one line per chunk up to one chunk for the whole text gives what the
/// old reader gives; returns that.
fn scene_agrees(text: &[u8], max: usize) -> String {
    let f = Path::new("s.sc");
    let want = match std::str::from_utf8(text) {
        Ok(t) => show(sequential_scene(t, f, max)),
        Err(_) => show(parse_bytes(text, f, max, usize::MAX)),
    };
    for chunk in (1..=text.len() + 1).chain([usize::MAX]) {
        let got = show(parse_bytes(text, f, max, chunk));
        assert_eq!(got, want, "chunks of {chunk} bytes, text {text:?}");
    }
    want
}

fn obj_agrees(text: &[u8], max: usize) -> String {
    let f = Path::new("m.obj");
    // the columns are found after either reader, from the line (`obj::with_column`)
    let want = show(sequential_obj(text, f, max).map_err(|e| super::obj::with_column(e, text)));
    for chunk in (1..=text.len() + 1).chain([usize::MAX]) {
        let got = show(triangles(parse_chunked(text, f, max, chunk)));
        assert_eq!(got, want, "chunks of {chunk} bytes, text {text:?}");
    }
    assert_eq!(show(triangles(parse_obj(text, f, max))), want);
    want
}

const CAM: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0\n";

#[test]
fn scenes_agree_wherever_they_are_cut() {
    let ok = scene_agrees(
        format!("\u{feff}# bom\r\n{CAM}sphere 0 0 0 1\r\n\r\n  triangle 0 0 0 1 0 0 0 1 0 # c\nquad 0 0 0 1 0 0 1 1 0 0 1 0").as_bytes(),
        100,
    );
    assert!(ok.contains("lines: [3, 5, 6]"), "{ok}");
    // camera last, comments and blank lines everywhere
    scene_agrees(
        format!("#a\n\nsphere 1 2 3 4#x\n\t\n{CAM}#\n").as_bytes(),
        100,
    );
    scene_agrees(b"", 100);
}

#[test]
fn the_first_error_in_file_order_wins_with_its_global_line() {
    for (text, at) in [
        (
            format!("{CAM}sphere 0 0 0 1\nsphere 0 0 0 1\nsphere 0 0 0 x\nbad\n"),
            "s.sc:4:14:",
        ),
        (
            format!("{CAM}sphere 0 0 0 1\n\n\n\nsphere 0 0 0 0\n"),
            "s.sc:6:14:",
        ),
        (
            format!("sphere 0 0 0 1\n{CAM}\n\nsphere 0 0 0 1\n  {CAM}"),
            "s.sc:6:3: second camera line (the first is on line 2)",
        ),
        (
            format!("{CAM}\n\ncamera eye 1\nsphere nan 0 0 1\n"),
            "s.sc:4:1: second camera",
        ),
        (
            format!("\n\ncamera eye 1\n{CAM}"),
            "s.sc:3:1: too few numbers: camera 'eye' expects 3, got 1",
        ),
        (
            format!("{CAM}sphere 1 1 1 1\r\nsphere 1 1 1\r\nsphere 1 1 1 1 1\r\n"),
            "s.sc:3:1: too few",
        ),
        (
            format!("{CAM}sphere 0 0 0 1\nmesh\n"),
            "s.sc:3:1: mesh needs a path",
        ),
        (
            format!("{CAM}\n\n\n\n\n\n\n\nSphere 1 2 3 4\n"),
            "s.sc:10:1: unknown keyword 'Sphere'",
        ),
        (
            format!("{CAM}\n\nsphere {}\nbad\n", "1 ".repeat(3000)),
            "s.sc:4:1: line is 6007 bytes",
        ),
        ("sphere 0 0 0 1\n".to_string(), "s.sc: no camera line"),
    ] {
        let got = scene_agrees(text.as_bytes(), 100);
        assert!(got.starts_with(&format!("error: {at}")), "{got}");
    }
}

#[test]
fn invalid_utf8_is_reported_first_wherever_it_is() {
    let mut text = b"\xef\xbb\xbfbad keyword\n".to_vec();
    text.extend_from_slice(CAM.as_bytes());
    text.extend_from_slice("# café \u{2014} ".as_bytes());
    text.extend_from_slice(b"\xff\n");
    text.extend_from_slice(b"# ok\n# \xff\n");
    let got = scene_agrees(&text, 100);
    assert!(
        got.starts_with("error: s.sc:3:10: not valid UTF-8 (byte 0xff)"),
        "{got}"
    );
    let got = scene_agrees(b"\xef\xbb\xbf\xe9t\xc3\n", 100);
    assert!(
        got.starts_with("error: s.sc:1:1: not valid UTF-8 (byte 0xe9)"),
        "{got}"
    );
}

#[test]
fn the_primitive_limit_holds_across_chunks() {
    let spheres = "sphere 0 0 0 1\n".repeat(12);
    let got = scene_agrees(format!("{CAM}{spheres}").as_bytes(), 5);
    assert!(
        got.starts_with("error: s.sc:7:1: too many primitives: a scene holds at most 5"),
        "{got}"
    );
    // a bad primitive line past the limit reports the limit; one before it, itself
    let got = scene_agrees(
        format!("{CAM}{}sphere x\n{spheres}", "sphere 0 0 0 1\n".repeat(5)).as_bytes(),
        5,
    );
    assert!(
        got.starts_with("error: s.sc:7:1: too many primitives"),
        "{got}"
    );
    let got = scene_agrees(
        format!("{CAM}sphere 0 0 0 1\nsphere x\n{spheres}").as_bytes(),
        5,
    );
    assert!(got.starts_with("error: s.sc:3:8:"), "{got}");
    assert!(
        !scene_agrees(
            format!("{CAM}{}", "sphere 0 0 0 1\n".repeat(5)).as_bytes(),
            5
        )
        .starts_with("error")
    );
}

#[test]
fn meshes_splice_in_at_their_line_in_any_chunking() {
    let dir = std::env::temp_dir().join(format!("lanecast-chunks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("q.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 2 0\nf 1 2 3 4\n",
    )
    .unwrap();
    let sc = dir.join("s.sc");
    let text = format!("sphere 0 0 0 1\nmesh q.obj\n{CAM}mesh  q.obj \nsphere 0 0 0 2\n");
    let one = parse_bytes(text.as_bytes(), &sc, 100, usize::MAX).unwrap();
    let lines: Vec<usize> = (0..one.shapes.len()).map(|i| one.shapes.line(i)).collect();
    assert_eq!(lines, vec![1, 2, 2, 4, 4, 5]);
    assert_eq!(one.warnings.len(), 2, "{:?}", one.warnings);
    for chunk in 1..text.len() {
        assert_eq!(parse_bytes(text.as_bytes(), &sc, 100, chunk).unwrap(), one);
    }
    // the limit counts mesh triangles; a mesh past it fails inside the OBJ
    for chunk in [1, 7, usize::MAX] {
        let e = parse_bytes(text.as_bytes(), &sc, 5, chunk)
            .unwrap_err()
            .to_string();
        assert!(
            e.ends_with("s.sc:5:1: too many primitives: a scene holds at most 5"),
            "{e}"
        );
        let e = parse_bytes(text.as_bytes(), &sc, 3, chunk)
            .unwrap_err()
            .to_string();
        assert!(e.contains("q.obj:5:1: too many triangles"), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn meshes_agree_wherever_they_are_cut() {
    let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    for text in [
        format!(
            "# quad\r\n{quad}vn 0 0 1\r\nf 1/1/1 2//1 3 4\r\n\nf -4 -3 -2 # c\n  v 2 2 2 \nf -1 1 2\n"
        ),
        format!("{quad}v 2 0 0\nf 1 2 5\nf 1 2 4\n\u{3000}v 5 5 5\nf\t1\t2\t-1\n"),
        format!("{quad}f 1 2 3\nf 1 2 9\nf 1 x 3\n"),
        format!("{quad}f 1 2 3\nf 1 9 x\n"),
        format!("{quad}f 1 2 3\nf 1 2 x -9\n"),
        format!("{quad}f 1 2 3\nf 1 2\nf 1 2 9\n"),
        format!("{quad}f 1 2 0\n"),
        format!("{quad}f 1 2 3 -5\n"),
        format!("{quad}v 1 2\nf 1 2 9\n"),
        format!("{quad}v 1 2 nan\n"),
        format!("{quad}f 1 2 3\x0c4\n"),
        format!("{quad}v 1 2 3\x0c\nf 1 2 3\x0b\n"),
        format!("{quad}f 1 2 99999999999999999999\n"),
        format!("{quad}f 1 2 +3 -1/2/3\n#{}\nf 1 2 3\n", "x".repeat(5000)),
    ] {
        obj_agrees(text.as_bytes(), 100);
    }
    // an error names the offending token's column, or the statement's first
    for (text, want) in [
        (
            format!("{quad}f 1 2 3\n  f 1 2 9\n"),
            "m.obj:6:9: vertex index 9 is out",
        ),
        (
            format!("{quad}v 1 2 nan\n"),
            "m.obj:5:7: 'nan' is not a finite number",
        ),
        (
            format!("{quad}f 1/1 x 3\n"),
            "m.obj:5:7: 'x' is not a vertex index",
        ),
        (
            format!("{quad}\tv 1 2\n"),
            "m.obj:5:2: vertex needs 3 coordinates",
        ),
    ] {
        let got = obj_agrees(text.as_bytes(), 100);
        assert!(got.starts_with(&format!("error: {want}")), "{got}");
    }
    let mut bad = quad.as_bytes().to_vec();
    bad.extend_from_slice(b"f 1 2 3\n# \xff\nf 1 2 9\n");
    let got = obj_agrees(&bad, 100);
    assert!(
        got.starts_with("error: m.obj:6:3: not valid UTF-8"),
        "{got}"
    );
    let got = obj_agrees(format!("{quad}{}", "f 1 2 3 4\n".repeat(9)).as_bytes(), 11);
    assert!(
        got.starts_with("error: m.obj:10:1: too many triangles"),
        "{got}"
    );
}

/// A line for random scenes: mostly valid statements, with the odd error.
fn sc_line() -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (-9i32..9, -9i32..9, 1u8..9).prop_map(|(x, y, r)| format!("sphere {x}.5 {y} -3 {r}e-1")),
        2 => Just("triangle 0 0 0 1 0 0 0 1 0".to_string()),
        2 => Just("  quad -4 0 -4  4 0 -4  4 0 4  -4 0 4 # floor".to_string()),
        2 => Just(CAM.trim_end().to_string()),
        2 => Just(String::new()),
        2 => Just("# comment".to_string()),
        1 => Just("sphere 0 0 0 -1".to_string()),
        1 => Just("sphere 0 0 0 1e400".to_string()),
        1 => Just("triangle 0 0 0 1 0 0".to_string()),
        1 => Just("cone 1".to_string()),
    ]
}

fn obj_line() -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (-9i32..9, -9i32..9, 0u8..9).prop_map(|(x, y, z)| format!("v {x}.25 {y} {z}")),
        6 => (1i64..12, 1i64..12, -4i64..4).prop_map(|(a, b, c)| format!("f {a} {b}/1 {}", if c == 0 { 1 } else { c })),
        2 => (1i64..12, 1i64..12).prop_map(|(a, b)| format!("f {a} {b} -1 -2 -3")),
        2 => Just("vn 0 0 1".to_string()),
        2 => Just(String::new()),
        1 => Just("f 1 2".to_string()),
        1 => Just("v 1 2 x".to_string()),
        1 => Just("f 1 0 2".to_string()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn random_scenes_agree(lines in prop::collection::vec(sc_line(), 0..24), crlf: bool, max in 1usize..16, chunk in 1usize..200) {
        let text = lines.join(if crlf { "\r\n" } else { "\n" });
        let f = Path::new("s.sc");
        prop_assert_eq!(show(parse_bytes(text.as_bytes(), f, max, chunk)), show(sequential_scene(&text, f, max)));
    }

    #[test]
    fn random_meshes_agree(lines in prop::collection::vec(obj_line(), 0..40), max in 1usize..40, chunk in 1usize..200) {
        let text = lines.join("\n");
        let f = Path::new("m.obj");
        prop_assert_eq!(show(triangles(parse_chunked(text.as_bytes(), f, max, chunk))), show(sequential_obj(text.as_bytes(), f, max).map_err(|e| super::obj::with_column(e, text.as_bytes()))));
    }

    /// The fast line reader takes a line only as the general reader would.
    #[test]
    fn fast_shapes_agree(line in sc_line()) {
        let ctx = Ctx { file: Path::new("s.sc"), line: 1, text: &line };
        let mut toks = Vec::new();
        tokenize(line.split('#').next().unwrap_or(""), &mut toks);
        let general: Option<Shape> = match toks.first().map(|t| t.s) {
            Some("sphere" | "triangle" | "quad") => parse_shape(&ctx, &toks).ok(),
            _ => None,
        };
        prop_assert_eq!(fast_shape(line.as_bytes()), general);
    }
}

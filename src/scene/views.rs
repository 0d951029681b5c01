//! Lists of cameras for many views of one scene: a views file (`--views FILE`, one camera a
//! line in the scene format's own camera syntax) and an orbit (`--orbit N`, a turntable about
//! the scene camera's up axis).
//!
//! A views file is parsed by the scene parser's own statement rules (`statement::parse_camera`),
//! so a line means there exactly what it means in a scene, with the same FILE:LINE:COL
//! messages. Blank lines and `#` comments are allowed; every other line must be a `camera`
//! line.

use super::CameraSpec;
use super::chunks;
use super::statement::{CAMERA_SYNTAX, Ctx, parse_camera, quote, tokenize};
use crate::error::{Error, Result};
use crate::limits::{MAX_LINE_BYTES, MAX_VIEWS};
use glam::DVec3;
use std::path::Path;

/// One camera of a views file, with its 1-based line (for messages).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewLine {
    /// The camera as written.
    pub camera: CameraSpec,
    /// Its line in the file.
    pub line: usize,
    /// The 1-based column of its first token (`camera`), where errors about the view as a
    /// whole point.
    pub col: usize,
}

/// Reads and parses the views file at `path` (at most `limits::MAX_SCENE_BYTES`, text).
pub fn load_views(path: &Path) -> Result<Vec<ViewLine>> {
    let bytes = chunks::read_file(
        path,
        crate::limits::MAX_SCENE_BYTES,
        "read views",
        Some("views files"),
    )?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        Error::input(
            path,
            line + 1,
            0,
            "not valid UTF-8; views files must be UTF-8 text",
        )
    })?;
    parse_views(text, path)
}

/// Parses views text; `file` names it in messages. Every camera is checked by the camera
/// line's rules (`validate::camera`); a file with no camera, or more than
/// `limits::MAX_VIEWS`, is refused.
pub fn parse_views(text: &str, file: &Path) -> Result<Vec<ViewLine>> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut views = Vec::new();
    let mut toks = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let ctx = Ctx {
            file,
            line: i + 1,
            text: line,
        };
        if line.len() > MAX_LINE_BYTES {
            return Err(ctx.whole(format!(
                "line is {} bytes; the limit is {MAX_LINE_BYTES}",
                line.len()
            )));
        }
        let content = line.find('#').map_or(line, |k| &line[..k]);
        tokenize(content, &mut toks);
        let Some(first) = toks.first() else { continue };
        if first.s != "camera" {
            return Err(ctx.at(
                first,
                format!(
                    "expected a camera line (`{CAMERA_SYNTAX}`), found {}",
                    quote(first.s)
                ),
            ));
        }
        if views.len() == MAX_VIEWS {
            return Err(ctx.whole(format!("more than {MAX_VIEWS} views")));
        }
        views.push(ViewLine {
            camera: parse_camera(&ctx, &toks)?,
            line: i + 1,
            col: ctx.col(first),
        });
    }
    if views.is_empty() {
        return Err(Error::InputFile {
            file: file.to_path_buf(),
            msg: format!("no camera lines (one view a line: `{CAMERA_SYNTAX}`)"),
        });
    }
    Ok(views)
}

/// `n` cameras on a turntable: the eye of `spec` turned about the axis through `look` along
/// `up`, by `2 pi k / n` for k = 0..n (view 0 is `spec` itself), counter-clockwise seen from
/// the tip of `up`. Distance to the axis and height along it stay those of `spec`; look, up and
/// fov are kept. Rodrigues' rotation of `e = eye - look` about the unit axis `a`:
/// `e cos + (a x e) sin + a (a . e)(1 - cos)`, in f64. Quarter turns use their exact sine and
/// cosine (0 and +-1, where `sin_cos` gives 6e-17 for 0): a camera orbiting a flat scene then
/// lies exactly in its plane at 90 degrees, where the scene is seen edge-on and not drawn,
/// rather than 1e-16 off it, where the f32 range rule (`range::f32_range`) refuses edges
/// that point at the eye.
pub fn orbit(spec: &CameraSpec, n: usize) -> Vec<CameraSpec> {
    let a = spec.up.normalize();
    let e = spec.eye - spec.look;
    (0..n)
        .map(|k| {
            let (sin, cos) = match (4 * k).is_multiple_of(n).then_some(4 * k / n) {
                Some(0) => (0.0, 1.0),
                Some(1) => (1.0, 0.0),
                Some(2) => (0.0, -1.0),
                Some(3) => (-1.0, 0.0),
                _ => (std::f64::consts::TAU * k as f64 / n as f64).sin_cos(),
            };
            let turned: DVec3 = e * cos + a.cross(e) * sin + a * a.dot(e) * (1.0 - cos);
            CameraSpec {
                eye: if k == 0 { spec.eye } else { spec.look + turned },
                ..*spec
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse_views(text, Path::new("v.txt"))
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn camera_lines_comments_and_blanks() {
        let text = "# a path\n\ncamera eye 0 0 5 look 0 0 0 up 0 1 0\n  camera eye 1 2 3 look 0 0 0 up 0 0 1 fov 30 # wide\n";
        let v = parse_views(text, Path::new("v.txt")).unwrap();
        assert_eq!(v.len(), 2);
        assert_eq!(v[0].line, 3);
        assert_eq!(v[0].camera.eye, DVec3::new(0.0, 0.0, 5.0));
        assert_eq!(v[0].camera.fov_deg, None);
        assert_eq!(v[1].line, 4);
        assert_eq!(v[1].camera.fov_deg, Some(30.0));
        assert_eq!(v[1].camera.up, DVec3::Z);
    }

    #[test]
    fn bad_lines_name_file_line_and_column() {
        let e = err("camera eye 0 0 5 look 0 0 0 up 0 1 0\nsphere 0 0 0 1\n");
        assert!(e.starts_with("v.txt:2:1:"), "{e}");
        assert!(e.contains("expected a camera line"), "{e}");
        let e = err("camera eye 0 0 5 look 0 0 0 up 0 1 0\ncamera eye 0 0 x look 0 0 0 up 0 1 0\n");
        assert!(e.starts_with("v.txt:2:16:"), "{e}");
        let e = err("camera eye 0 0 0 look 0 0 0 up 0 1 0\n");
        assert!(e.starts_with("v.txt:1:"), "{e}");
        assert!(e.contains("same point"), "{e}");
        let e = err("camera eye 0 5 0 look 0 0 0 up 0 1 0\n");
        assert!(e.contains("parallel"), "{e}");
        let e = err("camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 180\n");
        assert!(e.starts_with("v.txt:1:"), "{e}");
        let e = err("# nothing\n\n");
        assert!(e.contains("no camera lines"), "{e}");
    }

    #[test]
    fn quarter_turns_are_exact() {
        // scene 6's camera: a flat star in z = 0, seen from +z; the orbit about +y crosses the
        // star's plane at 90 and 270 degrees, exactly
        let spec = CameraSpec {
            eye: DVec3::new(0.0, 0.0, 7.0),
            look: DVec3::ZERO,
            up: DVec3::Y,
            fov_deg: None,
        };
        for n in [4, 12, 100] {
            let path = orbit(&spec, n);
            assert_eq!(path[n / 4].eye, DVec3::new(7.0, 0.0, 0.0), "{n}");
            assert_eq!(path[n / 2].eye, DVec3::new(0.0, 0.0, -7.0), "{n}");
            assert_eq!(path[3 * n / 4].eye, DVec3::new(-7.0, 0.0, 0.0), "{n}");
        }
    }

    #[test]
    fn an_orbit_keeps_distance_height_and_look() {
        // random cameras over scales 1e-6..1e6 and any up: the orbit keeps the eye's distance
        // from the axis and height along it (to rounding), and returns to the start
        let mut rng = crate::test_rng::Rng(0x2545_F491_4F6C_DD1D);
        let mut rnd = || rng.range(-1.0, 1.0);
        for _ in 0..200 {
            let scale = 10f64.powf(rnd() * 6.0);
            let v = |r: &mut dyn FnMut() -> f64| DVec3::new(r(), r(), r());
            let spec = CameraSpec {
                eye: v(&mut rnd) * scale,
                look: v(&mut rnd) * scale,
                up: v(&mut rnd),
                fov_deg: Some(45.0),
            };
            let n = 1 + (rnd().abs() * 40.0) as usize;
            let path = orbit(&spec, n);
            assert_eq!(path.len(), n);
            assert_eq!(path[0], spec);
            let a = spec.up.normalize();
            let split = |eye: DVec3| {
                let e = eye - spec.look;
                (a.dot(e), (e - a * a.dot(e)).length())
            };
            let (h0, r0) = split(spec.eye);
            let tol = 1e-12 * (spec.eye - spec.look).length().max(1e-300);
            for (k, c) in path.iter().enumerate() {
                let (h, r) = split(c.eye);
                assert!(
                    (h - h0).abs() <= tol && (r - r0).abs() <= tol,
                    "view {k} of {n}"
                );
                assert_eq!(
                    (c.look, c.up, c.fov_deg),
                    (spec.look, spec.up, spec.fov_deg)
                );
            }
            if n >= 4 && n.is_multiple_of(4) {
                // a quarter turn moves the eye by sqrt(2) r
                let d = (path[n / 4].eye - spec.eye).length();
                assert!((d - r0 * 2f64.sqrt()).abs() <= 4.0 * tol, "{d} {r0}");
            }
        }
    }
}

//! Lists of cameras for many views of one scene: a views file (`--views FILE`, one camera a
//! line in the scene format's own camera syntax) and an orbit (`--orbit N`, a turntable about
//! the scene camera's up axis).
//!
//! A views file is parsed by the scene parser's own statement rules (`statement::parse_camera`),
//! so a line means there exactly what it means in a scene, with the same FILE:LINE:COL
//! messages. Blank lines and `#` comments are allowed; every other line must be a `camera`
//! line, or a rig's pose: `extrinsic M00 M01 ... M33` (a 4x4 world-to-camera matrix, row-major,
//! OpenCV axes: `scene::pose`), followed, as a camera line's pose, by `K FX FY CX CY` or
//! `fov DEGREES` or nothing. [`write_views`] writes cameras back as camera lines that parse to
//! the same values, bit for bit.

use super::CameraSpec;
use super::chunks;
use super::statement::{CAMERA_SYNTAX, Ctx, Tok, parse_camera, parse_lens, quote, tokenize};
use super::{Lens, pose, validate};
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
        // the line and column of the first byte that is not UTF-8
        let valid = &bytes[..e.valid_up_to()];
        let start = valid.iter().rposition(|&b| b == b'\n').map_or(0, |k| k + 1);
        let line = valid.iter().filter(|&&b| b == b'\n').count() + 1;
        let col = String::from_utf8_lossy(&valid[start..]).chars().count() + 1;
        let msg = "not valid UTF-8; views files must be UTF-8 text";
        Error::input(path, line, col, msg)
    })?;
    parse_views(text, path)
}

/// A rig's view line.
pub const EXTRINSIC_SYNTAX: &str = "extrinsic M00 M01 ... M33 [K FX FY CX CY | fov DEGREES]";

/// An `extrinsic` line: 16 numbers (the world-to-camera matrix, row-major), then the lens as
/// a camera line's; the matrix must be a rigid transform (`pose::from_world_to_camera`).
fn parse_extrinsic(ctx: &Ctx, toks: &[Tok]) -> Result<CameraSpec> {
    let mut m = [[0.0; 4]; 4];
    for k in 0..16 {
        match toks.get(1 + k) {
            Some(t) if t.s != "K" && t.s != "fov" => {
                m[k / 4][k % 4] = ctx.number(t)?;
            }
            _ => {
                return Err(ctx.whole(format!(
                    "too few numbers: extrinsic expects 16 (a 4x4 world-to-camera matrix, \
                     row-major), got {k}"
                )));
            }
        }
    }
    let lens = parse_lens(ctx, toks, 17, ("extrinsic", 16))?;
    let spec = pose::from_world_to_camera(&m).map_err(|e| ctx.whole(e))?;
    let spec = CameraSpec { lens, ..spec };
    validate::camera(&spec).map_err(|e| ctx.whole(e))?;
    Ok(spec)
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
        let camera = match first.s {
            "camera" => parse_camera(&ctx, &toks)?,
            "extrinsic" => parse_extrinsic(&ctx, &toks)?,
            other => {
                return Err(ctx.at(
                    first,
                    format!(
                        "expected a camera line (`{CAMERA_SYNTAX}` or `{EXTRINSIC_SYNTAX}`), \
                         found {}",
                        quote(other)
                    ),
                ));
            }
        };
        if views.len() == MAX_VIEWS {
            return Err(ctx.whole(format!("more than {MAX_VIEWS} views")));
        }
        views.push(ViewLine {
            camera,
            line: i + 1,
            col: ctx.col(first),
        });
    }
    if views.is_empty() {
        return Err(Error::InputFile {
            file: file.to_path_buf(),
            msg: format!(
                "no camera lines (one view a line: `{CAMERA_SYNTAX}` or `{EXTRINSIC_SYNTAX}`)"
            ),
        });
    }
    Ok(views)
}

/// The views file of `cameras`: one camera line each (`camera eye .. look .. up ..`, then
/// `fov DEGREES` or `K FX FY CX CY` when it has a lens), every number written so that it
/// parses back to the same f64 (Rust's shortest round-trip form), so [`parse_views`] gives
/// back `cameras` exactly.
pub fn write_views(cameras: &[CameraSpec], header: &str) -> String {
    let mut out = String::new();
    for line in header.lines() {
        out.push_str("# ");
        out.push_str(line);
        out.push('\n');
    }
    for c in cameras {
        let v = |v: DVec3| format!("{} {} {}", num(v.x), num(v.y), num(v.z));
        out.push_str(&format!(
            "camera eye {} look {} up {}",
            v(c.eye),
            v(c.look),
            v(c.up)
        ));
        match c.lens {
            Some(Lens::Fov(f)) => out.push_str(&format!(" fov {}", num(f))),
            Some(Lens::Pinhole(k)) => out.push_str(&format!(
                " K {} {} {} {}",
                num(k.fx),
                num(k.fy),
                num(k.cx),
                num(k.cy)
            )),
            None => {}
        }
        out.push('\n');
    }
    out
}

/// `x` in the fewest digits that parse back to it: plain where that is short, else with an
/// exponent (`1e-300`, never 300 zeros).
pub fn num(x: f64) -> String {
    let plain = format!("{x}");
    if plain.len() <= 24 {
        plain
    } else {
        format!("{x:e}")
    }
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
        assert_eq!(v[0].camera.fov_deg(), None);
        assert_eq!(v[1].line, 4);
        assert_eq!(v[1].camera.fov_deg(), Some(30.0));
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
            lens: None,
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
                lens: Some(crate::scene::Lens::Fov(45.0)),
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
                    (c.look, c.up, c.fov_deg()),
                    (spec.look, spec.up, spec.fov_deg())
                );
            }
            if n >= 4 && n.is_multiple_of(4) {
                // a quarter turn moves the eye by sqrt(2) r
                let d = (path[n / 4].eye - spec.eye).length();
                assert!((d - r0 * 2f64.sqrt()).abs() <= 4.0 * tol, "{d} {r0}");
            }
        }
    }

    #[test]
    fn intrinsics_and_extrinsic_lines() {
        let text = "camera eye 0 0 5 look 0 0 0 up 0 1 0 K 500 520 319.5 -10\n\
                    extrinsic 1 0 0 0  0 -1 0 0  0 0 -1 5  0 0 0 1 K 400 400 320 240\n\
                    extrinsic 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n";
        let v = parse_views(text, Path::new("v.txt")).unwrap();
        let k = |fx, fy, cx, cy| Some(Lens::Pinhole(crate::scene::Intrinsics { fx, fy, cx, cy }));
        assert_eq!(v[0].camera.lens, k(500.0, 520.0, 319.5, -10.0));
        // OpenCV: z forward = -z world, y down = -y world: the camera at (0, 0, 5) looking
        // down -z with up +y
        assert_eq!(v[1].camera.eye, DVec3::new(0.0, 0.0, 5.0));
        assert_eq!(
            v[1].camera.look - v[1].camera.eye,
            DVec3::new(0.0, 0.0, -1.0)
        );
        assert_eq!(v[1].camera.up, DVec3::Y);
        assert_eq!(v[1].camera.lens, k(400.0, 400.0, 320.0, 240.0));
        assert_eq!(v[2].camera.lens, None);
    }

    #[test]
    fn bad_intrinsics_and_extrinsics_name_file_line_and_column() {
        let cam = "camera eye 0 0 5 look 0 0 0 up 0 1 0";
        let e = err(&format!("{cam}\n{cam} K 0 500 320 240\n"));
        assert!(
            e.starts_with("v.txt:2:40:") && e.contains("fx = 0 pixels"),
            "{e}"
        );
        let e = err(&format!("{cam} K 500 -2 320 240\n"));
        assert!(e.starts_with("v.txt:1:44:") && e.contains("fy = -2"), "{e}");
        let e = err(&format!("{cam} K 500 500 320\n"));
        assert!(
            e.starts_with("v.txt:1:38:") && e.contains("expects 4"),
            "{e}"
        );
        let e = err(&format!("{cam} K 500 500 320 240 1\n"));
        assert!(
            e.starts_with("v.txt:1:") && e.contains("too many numbers"),
            "{e}"
        );
        let e = err(&format!("{cam} K 500 500 320 240 fov 30\n"));
        assert!(e.contains("unexpected 'fov' after 'K FX FY CX CY'"), "{e}");
        let e = err(&format!("{cam} K 500 500 x 240\n"));
        assert!(
            e.starts_with("v.txt:1:48:") && e.contains("not a number"),
            "{e}"
        );
        let e = err("  extrinsic 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0\n");
        assert!(
            e.starts_with("v.txt:1:3:") && e.contains("expects 16"),
            "{e}"
        );
        let e = err("extrinsic 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 2\n");
        assert!(e.contains("too many numbers"), "{e}");
        let e = err("\nextrinsic 1.1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 K 5 5 2 2\n");
        assert!(
            e.starts_with("v.txt:2:1:") && e.contains("not a rigid transform"),
            "{e}"
        );
        let e = err("extrinsic 1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1\n");
        assert!(e.contains("last row must be 0 0 0 1"), "{e}");
        let e = err("extrinsic 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 K 5 0 2 2\n");
        assert!(e.contains("fy = 0"), "{e}");
    }

    /// `write_views` gives back, through `parse_views`, every camera bit for bit: random
    /// values over 1e-300 to 1e300, fields of view and intrinsics.
    #[test]
    fn written_views_parse_back_bit_for_bit() {
        let mut rng = crate::test_rng::Rng(99);
        let mut cams = Vec::new();
        while cams.len() < 300 {
            let x = |rng: &mut crate::test_rng::Rng| {
                let v = rng.log(-300.0, 300.0) * if rng.unit() < 0.5 { -1.0 } else { 1.0 };
                if rng.unit() < 0.5 {
                    v
                } else {
                    rng.range(-10.0, 10.0)
                }
            };
            let v = |rng: &mut crate::test_rng::Rng| DVec3::new(x(rng), x(rng), x(rng));
            let lens = match rng.below(3) {
                0 => None,
                1 => Some(Lens::Fov(rng.range(1e-3, 179.9))),
                _ => Some(Lens::Pinhole(crate::scene::Intrinsics {
                    fx: rng.log(-3.0, 5.0),
                    fy: rng.log(-3.0, 5.0),
                    cx: x(&mut rng),
                    cy: x(&mut rng),
                })),
            };
            let c = CameraSpec {
                eye: v(&mut rng),
                look: v(&mut rng),
                up: v(&mut rng),
                lens,
            };
            if crate::scene::validate::camera(&c).is_ok() {
                cams.push(c);
            }
        }
        let text = write_views(&cams, "made by a test\nsecond line");
        let back = parse_views(&text, Path::new("v.txt")).unwrap();
        assert_eq!(back.len(), cams.len());
        for (a, b) in back.iter().zip(&cams) {
            assert_eq!(format!("{:?}", a.camera), format!("{b:?}"));
            assert_eq!(a.camera, *b);
        }
    }
}

//! `lab-render`: one scene rendered with any of the lab's methods and compared with the f64
//! scalar oracle, pixel by pixel, as `lanecast compare` does for lanecast's own precisions:
//!
//! ```text
//! cargo run -p lanecast-lab --release --bin lab-render -- -i SCENE.sc [--method M]
//!     [-size WxH] [-fov DEG] [--accel A] [-o DIFF.png] [--image IMAGE.png]
//!     [--ids FILE.npy] [--depth FILE.npy] [--max-mismatch-ppm P]
//! ```
//!
//! `--method`: one of [`Method::ALL`]'s names (default `eplane+stable`, lanecast's kernels in
//! f32 through the lab's brute-force driver); `--accel` applies to `f64x4` and `auto` only (the
//! brute-force drivers test every primitive). Prints the report (mismatches split into ties,
//! edge band and unexcused, the first 20 unexcused pixels, the depth error); `-o` writes the
//! diff picture, `--image` the method's render (a colour per primitive), `--ids` and `--depth`
//! its ids and depths. Exits 1 when the unexcused mismatches exceed `--max-mismatch-ppm`
//! (default: never).

use crate::method::Method;
use lanecast::compare::{compare_frame, diff_picture};
use lanecast::experimental::render::f32_depth;
use lanecast::{Accel, Camera, ColorMode, Error, Result, Variation, load_scene};
use std::path::PathBuf;

/// What `lab-render` was asked for.
#[derive(Debug, Clone)]
pub struct RenderArgs {
    pub input: PathBuf,
    pub method: Method,
    pub size: (u32, u32),
    pub fov: Option<f64>,
    pub accel: Accel,
    pub diff: Option<PathBuf>,
    pub image: Option<PathBuf>,
    pub ids: Option<PathBuf>,
    pub depth: Option<PathBuf>,
    pub max_mismatch_ppm: f64,
}

/// The usage line, printed with `-h`.
pub const USAGE: &str = "usage: lab-render -i SCENE.sc [--method M] [-size WxH] [-fov DEG] \
[--accel auto|none|tiles|bvh|world] [-o DIFF.png] [--image IMAGE.png] [--ids FILE.npy] \
[--depth FILE.npy] [--max-mismatch-ppm P]; methods: eplane+stable mt watertight plane naive \
world-f32 f64x4 auto";

/// Parses `lab-render`'s arguments (program name left out); `None` for `-h`.
pub fn parse_args(args: impl IntoIterator<Item = String>) -> Result<Option<RenderArgs>> {
    let mut a = RenderArgs {
        input: PathBuf::new(),
        method: Method::Default,
        size: (640, 480),
        fov: None,
        accel: Accel::Auto,
        diff: None,
        image: None,
        ids: None,
        depth: None,
        max_mismatch_ppm: f64::INFINITY,
    };
    let mut input = None;
    let mut it = args.into_iter();
    while let Some(flag) = it.next() {
        if matches!(flag.as_str(), "-h" | "--help") {
            return Ok(None);
        }
        let value = it
            .next()
            .ok_or_else(|| Error::usage(format!("{flag} needs a value; {USAGE}")))?;
        let bad = |why: &str| Error::usage(format!("{flag} {value}: {why}"));
        match flag.as_str() {
            "-i" | "--input" => input = Some(PathBuf::from(&value)),
            "--method" => a.method = Method::parse(&value).ok_or_else(|| bad("unknown method"))?,
            "-size" | "--size" => {
                let (w, h) = value.split_once('x').ok_or_else(|| bad("expected WxH"))?;
                a.size = (
                    w.parse().map_err(|_| bad("expected WxH"))?,
                    h.parse().map_err(|_| bad("expected WxH"))?,
                );
            }
            "-fov" | "--fov" => a.fov = Some(value.parse().map_err(|_| bad("not a number"))?),
            "--accel" => {
                let all = [
                    Accel::Auto,
                    Accel::None,
                    Accel::Tiles,
                    Accel::Bvh,
                    Accel::World,
                ];
                a.accel = (all.into_iter().find(|x| x.name() == value))
                    .ok_or_else(|| bad("unknown acceleration"))?
            }
            "-o" | "--output" => a.diff = Some(value.into()),
            "--image" => a.image = Some(value.into()),
            "--ids" => a.ids = Some(value.into()),
            "--depth" => a.depth = Some(value.into()),
            "--max-mismatch-ppm" => {
                a.max_mismatch_ppm = value.parse().map_err(|_| bad("not a number"))?
            }
            _ => return Err(Error::usage(format!("unknown argument {flag}; {USAGE}"))),
        }
    }
    a.input = input.ok_or_else(|| Error::usage(format!("-i SCENE is required; {USAGE}")))?;
    if a.method.is_brute_force() && !matches!(a.accel, Accel::Auto | Accel::None) {
        return Err(Error::usage(format!(
            "--accel {}: method {} runs a brute-force driver, which tests every primitive",
            a.accel.name(),
            a.method.name()
        )));
    }
    Ok(Some(a))
}

/// Renders, compares, prints the report and writes the outputs asked for; fails (exit 1) past
/// `--max-mismatch-ppm`.
pub fn lab_render(a: &RenderArgs) -> Result<()> {
    let scene = load_scene(&a.input)?;
    let camera = Camera::for_scene(&scene, a.size.0, a.size.1, a.fov)?;
    let (frame, redecided) = a
        .method
        .prepare_with(&scene, &camera, a.accel)
        .render_marking();
    let frame = f32_depth(frame);
    let (mut r, oracle) = compare_frame(&scene, &camera, &frame);
    r.redecided = redecided;
    println!("scene       {}", a.input.display());
    println!("method      {} ({})", a.method.name(), a.method.describe());
    println!("against     the f64 scalar oracle");
    for line in r.lines(camera.width, camera.height, None, a.method == Method::Auto) {
        println!("{line}");
    }
    if let Some(p) = &a.diff {
        let picture = diff_picture(&r, &oracle);
        lanecast::output::write_image(p, camera.width, camera.height, &picture)?;
    }
    if let Some(p) = &a.image {
        let (mode, variation) = (ColorMode::Random, Variation::Linear);
        frame.write_image(p, (&scene, &camera), mode, variation, 0)?;
    }
    if let Some(p) = &a.ids {
        frame.write_ids(p)?;
    }
    if let Some(p) = &a.depth {
        frame.write_depth(p)?;
    }
    if r.unexcused_ppm() > a.max_mismatch_ppm {
        return Err(Error::Failed(format!(
            "{} unexcused id mismatches ({:.1} ppm) exceed --max-mismatch-ppm {}",
            r.unexcused,
            r.unexcused_ppm(),
            a.max_mismatch_ppm
        )));
    }
    Ok(())
}

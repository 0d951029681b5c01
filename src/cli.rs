//! The command line: raw arguments to validated settings in one step.
//!
//! The original assignment's single-dash long options (`-size`, `-fov`, `-cm`, `-cv`, `-time`)
//! are rewritten to their GNU long forms by [`SINGLE_DASH`] before clap sees them: clap has no
//! single-dash long options. Only whole tokens are rewritten, so values are never touched.
//!
//! After clap, the flags the user typed (clap's `ValueSource::CommandLine`, as opposed to
//! defaults) are checked against each other before any work: a flag that cannot apply to the
//! rest (an acceleration the method or kernel does not use, a precision the method or kernel
//! contradicts, threads a one-thread method cannot use, a seed the palette ignores) is a usage
//! error (exit 2) that names it and only flags that were typed. README "Valid flag
//! combinations" is the table of these rules.

mod views;

use crate::error::{Error, Result};
use crate::output::ImageFormat;
use crate::shade::{ColorMode, Variation};
use clap::parser::ValueSource;
use clap::{ArgMatches, Args, CommandFactory, FromArgMatches, Parser, Subcommand, ValueEnum};
use std::ffi::OsString;
use std::path::{Path, PathBuf};
pub use views::ViewSource;

/// The original's single-dash long options and their GNU long forms.
pub const SINGLE_DASH: [(&str, &str); 5] = [
    ("-size", "--size"),
    ("-fov", "--fov"),
    ("-cm", "--color-mode"),
    ("-cv", "--color-variation"),
    ("-time", "--time"),
];

/// Rewrites every token listed in [`SINGLE_DASH`] to its long form, and the `=` form of each
/// (`-fov=-30` to `--fov=-30`) likewise: left to clap, `-fov=-30` would read as `-f` with the
/// value `ov=-30`.
pub fn translate(args: impl IntoIterator<Item = OsString>) -> Vec<OsString> {
    args.into_iter().map(translate_one).collect()
}

fn translate_one(a: OsString) -> OsString {
    let Some(text) = a.to_str() else {
        return a;
    };
    for (short, long) in SINGLE_DASH {
        if text == short {
            return OsString::from(long);
        }
        if let Some(value) = text.strip_prefix(short).and_then(|v| v.strip_prefix('=')) {
            return OsString::from(format!("{long}={value}"));
        }
    }
    a
}

/// Whether `arg` is the single-dash option `short`, alone or in its `=` form.
fn is_single_dash(arg: &OsString, short: &str) -> bool {
    arg.to_str().is_some_and(|a| {
        a == short
            || a.strip_prefix(short)
                .is_some_and(|rest| rest.starts_with('='))
    })
}

const EXAMPLES: &str = "\
Examples:
  lanecast -i scenes/scene1.sc                      writes scenes/scene1.png (640x480)
  lanecast -i scene1.sc -o scene1.png -size 800x600 -fov 80
  lanecast -i scene1.sc -cm ordered -cv log -time
  lanecast -i scene1.sc --kernel scalar --threads 1 --ids ids.npy --depth depth.npy
  lanecast compare -i scene1.sc -size 1920x1080 -o diff.png

Exit codes: 0 success, 2 bad usage or bad input (message names the file and line, or the
argument), 75 an output folder another run kept locked longer than LANECAST_LOCK_WAIT seconds
(default 30; nothing written), 130 interrupted, 1 anything else (I/O errors, a failed
comparison).";

#[derive(Parser, Debug)]
#[command(
    name = "lanecast",
    version,
    about = "Ray-casts a .sc scene (camera, spheres, triangles, quads) to an image: \
             8-wide SIMD packets, with a scalar f64 oracle.",
    after_help = EXAMPLES,
    subcommand_negates_reqs = true,
    args_conflicts_with_subcommands = true
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Sub>,
    #[command(flatten)]
    render: RenderArgs,
}

#[derive(Subcommand, Debug)]
enum Sub {
    /// Renders with the packet kernel and the f64 scalar oracle and reports where they differ.
    #[command(
        after_help = "Example:\n  lanecast compare -i scenes/scene4.sc -size 1920x1080 -o diff.png"
    )]
    Compare(CompareArgs),
}

#[derive(Args, Debug)]
struct View {
    /// Scene file (.sc), or a mesh rendered alone with a framing camera (.obj, .ply)
    #[arg(short = 'i', long = "input", value_name = "SCENE.sc", required = true)]
    input: Option<PathBuf>,
    /// Camera position X,Y,Z, replacing the scene's eye (validated as the camera line is)
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    eye: Option<String>,
    /// Point the camera looks at, X,Y,Z, replacing the scene's look
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    look: Option<String>,
    /// Camera up direction X,Y,Z, replacing the scene's up
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    up: Option<String>,
    /// Image size WIDTHxHEIGHT, e.g. 800x600 (single-dash form: -size).
    #[arg(
        long,
        value_name = "WxH",
        default_value = "640x480",
        allow_hyphen_values = true
    )]
    size: String,
    /// Horizontal field of view in degrees, 0 < FOV < 180 [default: the scene's, else 60]
    /// (single-dash form: -fov).
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
    fov: Option<f64>,
    /// Worker threads [default: all cores]. The lab's brute-force methods (mt, watertight,
    /// plane, naive, world-f32) run on one thread and take no --threads above 1.
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// Acceleration: auto (tiles from 2 primitives on), none (test every primitive), tiles
    /// (primitives binned into screen tiles, nearest first), bvh (a bounding volume
    /// hierarchy). Every kernel and precision takes each; the lab's brute-force methods take
    /// none or auto.
    #[arg(long, value_enum, default_value = "auto")]
    accel: AccelArg,
    /// Intersection method of the simd kernel: eplane+stable (the default: edge planes through
    /// the eye, stable spheres), mt, watertight, plane, naive, world-f32, f64x4. f64x4 takes
    /// --accel and every thread; the others run the accuracy lab's brute-force packet driver
    /// on one thread.
    #[arg(long, value_name = "METHOD", default_value = "eplane+stable",
          value_parser = ["eplane+stable", "mt", "watertight", "plane", "naive", "world-f32", "f64x4"])]
    method: String,
    /// Precision of the simd kernel: auto (f32x8 lanes, and each hit f32 cannot hold to 1e-5
    /// relative decided again in f64), f32 (f32x8 alone) or f64 (f64x4, two per packet: the
    /// f64x4 method). With --kernel scalar or scalar-f32, only that kernel's own (f64, f32).
    #[arg(long, value_name = "BITS", default_value = "auto", value_parser = ["auto", "f32", "f64"])]
    precision: String,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelArg {
    Auto,
    None,
    Bvh,
    Tiles,
}

impl From<AccelArg> for crate::accel::Accel {
    fn from(a: AccelArg) -> crate::accel::Accel {
        match a {
            AccelArg::Auto => crate::accel::Accel::Auto,
            AccelArg::None => crate::accel::Accel::None,
            AccelArg::Bvh => crate::accel::Accel::Bvh,
            AccelArg::Tiles => crate::accel::Accel::Tiles,
        }
    }
}

#[derive(Args, Debug)]
struct RenderArgs {
    #[command(flatten)]
    view: View,
    /// Output image, .png or .bmp, or - for standard output [default: the input path with
    /// extension .png].
    #[arg(short = 'o', long = "output", value_name = "IMAGE")]
    output: Option<PathBuf>,
    /// Image format of -o - (standard output): png or bmp [default: png]. With a file name the
    /// extension decides, and a --format that disagrees is refused.
    #[arg(long, value_name = "FORMAT", value_parser = ["png", "bmp"])]
    format: Option<String>,
    /// Colour per primitive: random (seeded) or ordered (palette by first appearance)
    /// (single-dash form: -cm).
    #[arg(long = "color-mode", value_name = "MODE", default_value = "random",
          value_parser = ["random", "ordered"])]
    color_mode: String,
    /// Brightness against hit distance: linear or log (single-dash form: -cv).
    #[arg(long = "color-variation", value_name = "VARIATION", default_value = "linear",
          value_parser = ["linear", "log"])]
    color_variation: String,
    /// Print the time of each phase and primary rays per second to stderr (single-dash: -time).
    #[arg(long)]
    time: bool,
    /// Intersection kernel: simd (8-wide f32 packets), scalar (one ray at a time, f64: the
    /// oracle) or scalar-f32.
    #[arg(long, value_enum, default_value = "simd")]
    kernel: KernelArg,
    /// Seed of the random colour mode (refused with -cm ordered, which has no seed).
    #[arg(long, value_name = "N", default_value_t = 0)]
    seed: u64,
    /// Also write per-pixel primitive ids (int32, -1 = background) as a (H, W) .npy file.
    #[arg(long, value_name = "FILE.npy")]
    ids: Option<PathBuf>,
    /// Also write per-pixel hit distances (float32, +inf = background) as a (H, W) .npy file.
    #[arg(long, value_name = "FILE.npy")]
    depth: Option<PathBuf>,
    /// Render K times and report the best and median render time (-time, --stats).
    #[arg(long, value_name = "K", default_value_t = 1,
          value_parser = clap::value_parser!(u32).range(1..=10_000))]
    repeat: u32,
    /// Write a JSON record of the run: scene, size, primitives, kernel, method, acceleration,
    /// threads, SIMD width, phase times, best and median render, rays/s, peak memory.
    #[arg(long, value_name = "FILE.json")]
    stats: Option<PathBuf>,
    /// Render one view per camera line of FILE (`camera eye X Y Z look X Y Z up X Y Z [fov
    /// DEG]`), all from one load of the scene. Outputs take numbered names (-o
    /// frames/view_%05d.png, views counted from 0) or -o - (images one after another).
    #[arg(long, value_name = "FILE", conflicts_with = "orbit")]
    views: Option<PathBuf>,
    /// Render N views on a turntable: the camera turned about its up axis through its look
    /// point, at its distance and height. Outputs as with --views.
    #[arg(long, value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..=crate::limits::MAX_VIEWS as i64))]
    orbit: Option<u32>,
    /// With --views or --orbit: leave out every view whose outputs all exist (a rerun picks up
    /// where an interrupted run stopped).
    #[arg(long)]
    skip_existing: bool,
}

#[derive(Args, Debug)]
struct CompareArgs {
    #[command(flatten)]
    view: View,
    /// Write a diff image: the render dimmed, mismatches marked (red: unexcused, yellow: tie,
    /// cyan: within the edge band).
    #[arg(short = 'o', long = "output", value_name = "IMAGE")]
    output: Option<PathBuf>,
    /// Unexcused id mismatches allowed, in parts per million of the pixels, before the exit
    /// code turns to 1.
    #[arg(long, value_name = "PPM", default_value_t = 0.0)]
    max_mismatch_ppm: f64,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum KernelArg {
    Simd,
    Scalar,
    #[value(name = "scalar-f32")]
    ScalarF32,
}

impl KernelArg {
    pub fn name(self) -> &'static str {
        match self {
            KernelArg::Simd => "simd",
            KernelArg::Scalar => "scalar",
            KernelArg::ScalarF32 => "scalar-f32",
        }
    }

    /// The precision a scalar kernel computes in; `None` for the simd kernel, whose lanes
    /// `--precision` chooses.
    pub fn precision(self) -> Option<&'static str> {
        match self {
            KernelArg::Simd => None,
            KernelArg::Scalar => Some("f64"),
            KernelArg::ScalarF32 => Some("f32"),
        }
    }
}

/// What the shared options resolve to.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewSettings {
    pub input: PathBuf,
    pub width: u32,
    pub height: u32,
    /// From `-fov`; the scene's value or 60 applies when `None`.
    pub fov: Option<f64>,
    pub threads: Option<usize>,
    pub accel: crate::accel::Accel,
    /// Intersection method (`--method`, with `--precision f64` meaning `f64x4`).
    pub method: crate::render::Method,
    /// Camera overrides from `--eye`, `--look`, `--up`, each with the flag as typed.
    pub camera: CameraOverrides,
}

/// `--eye`, `--look` and `--up`: each replaces that part of the scene's camera.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CameraOverrides {
    pub eye: Option<glam::DVec3>,
    pub look: Option<glam::DVec3>,
    pub up: Option<glam::DVec3>,
}

impl CameraOverrides {
    /// `spec` with the overrides applied, checked by the camera line's own rules; an error
    /// names the flags typed.
    pub fn apply(&self, spec: &mut crate::scene::CameraSpec) -> Result<()> {
        if *self == CameraOverrides::default() {
            return Ok(());
        }
        spec.eye = self.eye.unwrap_or(spec.eye);
        spec.look = self.look.unwrap_or(spec.look);
        spec.up = self.up.unwrap_or(spec.up);
        crate::scene::validate::camera(spec).map_err(|m| {
            let flags: Vec<&str> = [
                ("--eye", self.eye),
                ("--look", self.look),
                ("--up", self.up),
            ]
            .iter()
            .filter(|(_, v)| v.is_some())
            .map(|(f, _)| *f)
            .collect();
            Error::usage(format!("{}: {m}", flags.join(", ")))
        })
    }
}

/// A point or direction `X,Y,Z` of `flag`: three finite decimal numbers.
fn parse_vec3(flag: &str, text: &str) -> Result<glam::DVec3> {
    let bad = || {
        Error::usage(format!(
            "{flag} {text}: expected three finite numbers X,Y,Z"
        ))
    };
    let v: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(bad)?;
    match v[..] {
        [x, y, z] => Ok(glam::DVec3::new(x, y, z)),
        _ => Err(bad()),
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct RenderSettings {
    pub view: ViewSettings,
    pub output: PathBuf,
    pub color_mode: ColorMode,
    pub variation: Variation,
    pub time: bool,
    /// `Some(format)` when the image goes to standard output (`-o -`).
    pub stdout_format: Option<ImageFormat>,
    pub kernel: KernelArg,
    pub seed: u64,
    pub ids: Option<PathBuf>,
    pub depth: Option<PathBuf>,
    pub repeat: u32,
    pub stats: Option<PathBuf>,
    /// Many views (`--views`, `--orbit`); `None` for the scene's one camera.
    pub views: Option<views::ViewSource>,
    /// `--skip-existing`.
    pub skip_existing: bool,
}

#[derive(Debug, Clone, PartialEq)]
pub struct CompareSettings {
    pub view: ViewSettings,
    pub output: Option<PathBuf>,
    pub max_mismatch_ppm: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    Render(RenderSettings),
    Compare(CompareSettings),
    /// `-h` / `--version`: text for stdout, exit 0.
    Info(String),
}

/// Parses the full argument list (program name first), then checks that every flag the user
/// typed applies to the others (`view`, `method`, `check_render`; README "Valid flag
/// combinations") before any work is done: a flag that cannot apply is a usage error naming
/// it, never dropped.
pub fn parse(args: impl IntoIterator<Item = OsString>) -> Result<Command> {
    let raw: Vec<OsString> = args.into_iter().collect();
    parse_raw(&raw).map_err(|e| match e {
        Error::Usage(msg) => Error::Usage(respell(&msg, &raw)),
        other => other,
    })
}

/// `msg` with each GNU long form of [`SINGLE_DASH`] written as the user spelled it: `-cm`
/// rather than `--color-mode` when the arguments hold `-cm` and not `--color-mode`, so that a
/// message names the flags as they were typed (clap's own messages included).
fn respell(msg: &str, raw: &[OsString]) -> String {
    let mut msg = msg.to_string();
    for (short, long) in SINGLE_DASH {
        let typed_long = raw.iter().any(|a| {
            a.to_str()
                .is_some_and(|a| a == long || a.starts_with(&format!("{long}=")))
        });
        if raw.iter().any(|a| is_single_dash(a, short)) && !typed_long {
            msg = msg.replace(long, short);
        }
    }
    msg
}

fn parse_raw(raw: &[OsString]) -> Result<Command> {
    let clap_error = |e: clap::Error| {
        use clap::error::ErrorKind::{DisplayHelp, DisplayVersion};
        match e.kind() {
            DisplayHelp | DisplayVersion => Ok(Command::Info(e.render().to_string())),
            _ => {
                let text = e.render().to_string();
                let text = text
                    .trim_end()
                    .strip_prefix("error: ")
                    .unwrap_or(text.trim_end());
                Err(Error::usage(text.to_string()))
            }
        }
    };
    let matches = match Cli::command().try_get_matches_from(translate(raw.iter().cloned())) {
        Ok(m) => m,
        Err(e) => return clap_error(e),
    };
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(c) => c,
        Err(e) => return clap_error(e),
    };
    match cli.command {
        Some(Sub::Compare(c)) => {
            let sub = matches
                .subcommand_matches("compare")
                .expect("clap matched the compare subcommand");
            let typed = Typed { matches: sub };
            if c.max_mismatch_ppm.is_nan() || c.max_mismatch_ppm < 0.0 {
                return Err(Error::usage(format!(
                    "--max-mismatch-ppm {}: must be a number of parts per million, 0 or more",
                    c.max_mismatch_ppm
                )));
            }
            Ok(Command::Compare(CompareSettings {
                // compare's render is the simd kernel's, against the f64 scalar oracle
                view: view(c.view, &typed, KernelArg::Simd)?,
                output: c.output,
                max_mismatch_ppm: c.max_mismatch_ppm,
            }))
        }
        None => {
            let typed = Typed { matches: &matches };
            let r = cli.render;
            let flag = method_flag(&r.view, &typed);
            let view = view(r.view, &typed, r.kernel)?;
            let source = views::source(r.views, r.orbit);
            let output = match r.output {
                Some(o) => o,
                None if source.is_some() => views::default_output(&view.input)?,
                None if view.input == Path::new(crate::scene::parse::STDIN) => {
                    return Err(Error::usage(
                        "-i -: a scene from standard input has no file name to put the image \
                         beside; give -o IMAGE",
                    ));
                }
                None => default_output(&view.input, raw)?,
            };
            let stdout_format = stdout_format(&output, r.format.as_deref())?;
            let settings = RenderSettings {
                view,
                output,
                color_mode: ColorMode::parse(&r.color_mode).expect("clap checked the value"),
                variation: Variation::parse(&r.color_variation).expect("clap checked the value"),
                time: r.time,
                kernel: r.kernel,
                seed: r.seed,
                ids: r.ids,
                depth: r.depth,
                repeat: r.repeat,
                stats: r.stats,
                stdout_format,
                views: source,
                skip_existing: r.skip_existing,
            };
            check_render(&settings, &typed, &flag)?;
            views::check(&settings, &typed)?;
            Ok(Command::Render(settings))
        }
    }
}

/// The image path when `-o` is not given: the input's with extension `.png`, refused when that
/// is the input itself (`-i scene.png`). The message names the input flag as typed and the
/// default, since no `-o` was typed.
fn default_output(input: &Path, raw: &[OsString]) -> Result<PathBuf> {
    let output = input.with_extension("png");
    if crate::output::same_file(&output, input) {
        let long = raw
            .iter()
            .any(|a| a.to_str().is_some_and(|a| a.starts_with("--input")));
        return Err(Error::usage(format!(
            "{} {}: the default output {} (the input's name with extension .png) would \
             overwrite the input scene; give -o IMAGE",
            if long { "--input" } else { "-i" },
            input.display(),
            output.display()
        )));
    }
    Ok(output)
}

/// The format of an image written to standard output (`-o -`, with `--format`, PNG by default),
/// or `None` for an image file, whose extension decides (a `--format` that disagrees is refused).
fn stdout_format(output: &Path, format: Option<&str>) -> Result<Option<ImageFormat>> {
    let named = |f: &str| match f {
        "bmp" => ImageFormat::Bmp,
        _ => ImageFormat::Png,
    };
    if output == Path::new("-") {
        return Ok(Some(format.map_or(ImageFormat::Png, named)));
    }
    if let Some(f) = format
        && crate::output::image_format(output).ok() != Some(named(f))
    {
        return Err(Error::usage(format!(
            "--format {f}: -o {} names a file of another format; --format chooses the format \
             of -o - (standard output) only",
            output.display()
        )));
    }
    Ok(None)
}

/// Which arguments the user typed (as opposed to clap's defaults).
struct Typed<'a> {
    /// The matches of the command being run (the top level, or `compare`).
    matches: &'a ArgMatches,
}

impl Typed<'_> {
    /// Whether the argument with clap id `id` (the field name) was given on the command line.
    fn has(&self, id: &str) -> bool {
        self.matches.value_source(id) == Some(ValueSource::CommandLine)
    }
}

/// `n` and `noun`, with an `s` unless `n` is 1.
fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// The shared options resolved for `kernel` (`simd` for `compare`), refusing the typed
/// `--accel` that the method or kernel cannot use.
fn view(v: View, typed: &Typed, kernel: KernelArg) -> Result<ViewSettings> {
    let (width, height) = parse_size(&v.size)?;
    if let Some(fov) = v.fov {
        crate::scene::validate::fov(fov).map_err(|m| Error::usage(format!("--fov {fov}: {m}")))?;
    }
    if v.threads == Some(0) {
        return Err(Error::usage("--threads 0: need at least one thread"));
    }
    if let Some(n) = v.threads
        && n > crate::limits::MAX_THREADS
    {
        return Err(Error::usage(format!(
            "--threads {n}: at most {} threads",
            crate::limits::MAX_THREADS
        )));
    }
    let method = method(&v, typed, kernel)?;
    let accel: crate::accel::Accel = v.accel.into();
    if method.is_brute_force()
        && typed.has("accel")
        && !matches!(v.accel, AccelArg::Auto | AccelArg::None)
    {
        return Err(Error::usage(format!(
            "--accel {}: {} runs the brute-force driver of the accuracy lab, which tests every \
             primitive with no acceleration; use --accel none (or auto), or the default method",
            accel.name(),
            method_flag(&v, typed),
        )));
    }
    Ok(ViewSettings {
        input: v.input.expect("clap requires --input"),
        width,
        height,
        fov: v.fov,
        threads: v.threads,
        accel,
        method,
        camera: CameraOverrides {
            eye: v
                .eye
                .as_deref()
                .map(|t| parse_vec3("--eye", t))
                .transpose()?,
            look: v
                .look
                .as_deref()
                .map(|t| parse_vec3("--look", t))
                .transpose()?,
            up: v.up.as_deref().map(|t| parse_vec3("--up", t)).transpose()?,
        },
    })
}

/// The typed flag that chose a method other than the default: `--method NAME`, or
/// `--precision f64` when only that was typed.
fn method_flag(v: &View, typed: &Typed) -> String {
    if typed.has("method") {
        format!("--method {}", v.method)
    } else {
        format!("--precision {} (the f64x4 method)", v.precision)
    }
}

/// The method named by `--method` and `--precision` for `kernel`, refusing the pairs that
/// contradict each other. The messages name only flags the user typed: a value left at its
/// default cannot contradict a typed one (the defaults, `simd`, `eplane+stable` and `f32`,
/// agree with every choice of the other two).
fn method(v: &View, typed: &Typed, kernel: KernelArg) -> Result<crate::render::Method> {
    use crate::render::Method;
    let m = Method::parse(&v.method).expect("clap checked the name");
    let precision = v.precision.as_str();
    if let Some(own) = kernel.precision() {
        // a scalar kernel (typed: the default is simd): it traces with the default method's
        // formulas in its own precision
        if m != Method::Default {
            return Err(Error::usage(format!(
                "--method {}: methods apply to --kernel simd only; --kernel {} traces one ray at \
                 a time with the default method ({}) in {own}",
                m.name(),
                kernel.name(),
                Method::Default.name()
            )));
        }
        if typed.has("precision") && precision != own {
            return Err(Error::usage(format!(
                "--precision {precision}: --kernel {} computes in {own} (--precision chooses the \
                 simd kernel's lanes)",
                kernel.name()
            )));
        }
        return Ok(Method::Default);
    }
    match m {
        Method::Default if precision == "f64" => Ok(Method::F64x4),
        Method::Default if precision == "auto" => Ok(Method::Auto),
        Method::Default => Ok(m),
        // a method computes in its own precision; a typed --precision must agree with it
        _ if typed.has("precision") && precision != m.precision() => {
            let hint = if precision == "f64" {
                "; f64 packets exist for the default method only (--method f64x4)"
            } else {
                ""
            };
            Err(Error::usage(format!(
                "--precision {precision}: contradicts --method {}, which computes in {}{hint}",
                m.name(),
                m.precision()
            )))
        }
        _ => Ok(m),
    }
}

/// Refuses the render command's flags that cannot apply to the rest of its settings.
/// `method_flag` names the typed flag that chose the method ([`method_flag`]).
fn check_render(s: &RenderSettings, typed: &Typed, method_flag: &str) -> Result<()> {
    let method = s.view.method;
    if let Some(n) = s.view.threads
        && n > 1
        && method.is_brute_force()
    {
        return Err(Error::usage(format!(
            "--threads {n}: {method_flag} renders on 1 thread, not on {} (it runs the \
             brute-force driver of the accuracy lab); use --threads 1, or the default method",
            count(n, "thread")
        )));
    }
    if typed.has("seed") && s.color_mode == ColorMode::Ordered {
        return Err(Error::usage(format!(
            "--seed {}: --color-mode ordered colours by the palette, with no seed; --seed applies to the \
             random colour mode only",
            s.seed,
        )));
    }
    Ok(())
}

/// `WIDTHxHEIGHT` within `limits::MAX_SIDE` and `limits::MAX_PIXELS`.
pub fn parse_size(s: &str) -> Result<(u32, u32)> {
    let bad = |why: &str| Error::usage(format!("--size {s}: {why}"));
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| bad("expected WIDTHxHEIGHT, e.g. 800x600"))?;
    let side = |v: &str| -> Result<u64> {
        let n: u64 = v
            .parse()
            .map_err(|_| bad("width and height must be whole numbers"))?;
        // each side alone first, so a bad width is named before the product is checked
        crate::limits::check_size(n, 1).map_err(|why| bad(&why))?;
        Ok(n)
    };
    let (w, h) = (side(w)?, side(h)?);
    crate::limits::check_size(w, h).map_err(|why| bad(&why))?;
    Ok((w as u32, h as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<OsString> {
        std::iter::once("lanecast")
            .chain(s.split_whitespace())
            .map(OsString::from)
            .collect()
    }

    fn render(s: &str) -> RenderSettings {
        match parse(args(s)).unwrap() {
            Command::Render(r) => r,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn original_invocations_parse() {
        let r = render("-i scene1.sc");
        assert_eq!(r.output, PathBuf::from("scene1.png"));
        assert_eq!((r.view.width, r.view.height), (640, 480));
        assert_eq!(r.color_mode, ColorMode::Random);
        assert_eq!(r.variation, Variation::Linear);
        assert_eq!(
            render("-i scene1.sc -o out.bmp").output,
            PathBuf::from("out.bmp")
        );
        let r = render("-i scene1.sc -size 800x600");
        assert_eq!((r.view.width, r.view.height), (800, 600));
        assert_eq!(render("-i scene1.sc -fov 80").view.fov, Some(80.0));
        assert_eq!(
            render("-i scene1.sc -cm ordered").color_mode,
            ColorMode::Ordered
        );
        assert_eq!(render("-i scene1.sc -cv log").variation, Variation::Log);
        assert!(render("-i scene1.sc -time").time);
    }

    #[test]
    fn long_forms_parse_the_same() {
        let a = render("-i s.sc -o o.png -size 320x200 -fov 45 -cm ordered -cv log -time");
        let b = render(
            "--input s.sc --output o.png --size 320x200 --fov 45 --color-mode ordered \
             --color-variation log --time",
        );
        assert_eq!(a, b);
    }

    #[test]
    fn bad_sizes_are_usage_errors() {
        for s in [
            "0x10",
            "10x0",
            "10",
            "axb",
            "100000x10",
            "65536x65536",
            "-5x10",
        ] {
            let e = parse(args(&format!("-i s.sc -size {s}"))).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{s}");
            assert!(e.to_string().contains("size"), "{s}: {e}");
        }
    }

    #[test]
    fn bad_fov_and_threads_are_usage_errors() {
        for a in [
            "-fov 0",
            "-fov 180",
            "-fov -3",
            "--threads 0",
            "--threads 1025",
            "--kernel gpu",
            "-cm rainbow",
        ] {
            let e = parse(args(&format!("-i s.sc {a}"))).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{a}: {e}");
        }
        assert!(parse(args("-o x.png")).is_err(), "-i is required");
    }

    #[test]
    fn help_is_info_and_lists_examples() {
        match parse(args("-h")).unwrap() {
            Command::Info(t) => assert!(t.contains("Examples:") && t.contains("--color-mode")),
            other => panic!("{other:?}"),
        }
    }

    /// The usage error of `s`, checking exit code 2.
    fn refused(s: &str) -> String {
        let e = parse(args(s)).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{s}: {e}");
        e.to_string()
    }

    #[test]
    fn combinations_that_cannot_apply_name_the_typed_flags() {
        for (s, words) in [
            (
                "-i s.sc --method mt --accel bvh",
                &["--accel bvh", "--method mt"][..],
            ),
            (
                "-i s.sc --method f64x4 --precision f32",
                &["--precision f32", "--method f64x4"],
            ),
            (
                "-i s.sc --method naive --precision f64",
                &["--precision f64", "--method naive"],
            ),
            (
                "-i s.sc --kernel scalar --precision f32",
                &["--precision f32", "--kernel scalar"],
            ),
            (
                "-i s.sc --kernel scalar-f32 --method mt",
                &["--method mt", "--kernel scalar-f32"],
            ),
            (
                "-i s.sc --method plane --threads 3",
                &["--threads 3", "--method plane"],
            ),
            ("-i s.sc -cm ordered --seed 2", &["--seed 2", "-cm ordered"]),
            (
                "compare -i s.sc --method mt --accel bvh",
                &["--accel bvh", "--method mt"],
            ),
        ] {
            let msg = refused(s);
            for w in words {
                assert!(msg.contains(w), "{s}: {msg}");
            }
        }
        // the default method is never named when --method was not typed
        assert!(!refused("-i s.sc --kernel scalar --precision f32").contains("--method"));
        assert!(!refused("-i s.sc --precision f64 --kernel scalar-f32").contains("--method"));
    }

    #[test]
    fn consistent_combinations_resolve() {
        use crate::accel::Accel;
        use crate::render::Method;
        let r = render("-i s.sc --kernel scalar --precision f64 --accel tiles");
        assert_eq!(
            (r.kernel, r.view.method),
            (KernelArg::Scalar, Method::Default)
        );
        assert_eq!(r.view.accel, Accel::Tiles);
        // every kernel and precision takes every acceleration and every thread
        for s in [
            "-i s.sc --kernel scalar --accel bvh --threads 2",
            "-i s.sc --kernel scalar-f32 --accel bvh",
            "-i s.sc --precision f64 --accel tiles --threads 2",
            "-i s.sc --method f64x4 --accel bvh",
        ] {
            assert!(parse(args(s)).is_ok(), "{s}");
        }
        let r = render("-i s.sc --kernel scalar-f32 --precision f32 --method eplane+stable");
        assert_eq!(r.view.method, Method::Default);
        assert_eq!(render("-i s.sc --precision f64").view.method, Method::F64x4);
        assert_eq!(render("-i s.sc --method f64x4").view.method, Method::F64x4);
        let r = render("-i s.sc --method mt --accel none --threads 1 --precision f32");
        assert_eq!((r.view.method, r.view.accel), (Method::Mt, Accel::None));
        assert_eq!(render("-i s.sc --seed 5 -cm random").seed, 5);
        assert_eq!(render("-i s.sc --threads 4").view.threads, Some(4));
    }

    #[test]
    fn messages_spell_single_dash_options_as_typed() {
        assert!(refused("-i s.sc -size 0x1").starts_with("-size 0x1:"));
        assert!(refused("-i s.sc --size 0x1").starts_with("--size 0x1:"));
        assert!(refused("-i s.sc -cm rainbow").contains("'-cm <MODE>'"));
        assert!(refused("-i s.sc --color-mode=ordered --seed 1").contains("--color-mode"));
    }

    #[test]
    fn compare_subcommand() {
        match parse(args(
            "compare -i s.sc -size 64x48 -o d.png --max-mismatch-ppm 5",
        ))
        .unwrap()
        {
            Command::Compare(c) => {
                assert_eq!((c.view.width, c.view.height), (64, 48));
                assert_eq!(c.output, Some(PathBuf::from("d.png")));
                assert_eq!(c.max_mismatch_ppm, 5.0);
            }
            other => panic!("{other:?}"),
        }
    }
}

//! The command line: raw arguments to validated settings in one step.
//!
//! The seed command line's single-dash long options (`-size`, `-fov`, `-cm`, `-cv`, `-time`)
//! are rewritten to their GNU long forms by [`SINGLE_DASH`] before clap sees them: clap has no
//! single-dash long options. Only whole tokens are rewritten, so values are never touched.
//!
//! After clap, the flags the user typed (clap's `ValueSource::CommandLine`, as opposed to
//! defaults) are checked against each other before any work: a flag that cannot apply to the
//! rest (an acceleration the kernel does not use, a precision the kernel contradicts, a seed
//! the palette ignores) is a usage
//! error (exit 2) that names it and only flags that were typed. README "Valid flag
//! combinations" is the table of these rules.

mod args;
mod camera;
mod spelling;
mod view_flags;

use crate::error::{Error, Result};
use crate::output::ImageFormat;
use crate::shade::{ColorMode, Variation};
pub use args::KernelArg;
use args::{Cli, Sub, View};
pub use camera::CameraOverrides;
use camera::parse_vec3;
use clap::parser::ValueSource;
use clap::{ArgMatches, CommandFactory, FromArgMatches};
use std::ffi::OsString;
use std::path::{Path, PathBuf};
pub use view_flags::ViewSource;

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

/// What the shared options resolve to.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewSettings {
    pub input: PathBuf,
    pub width: u32,
    pub height: u32,
    /// From `-fov`, replacing every lens; the scene's lens (or a views line's), else 60,
    /// applies when `None`.
    pub fov: Option<f64>,
    /// `-fov`'s flag and value as typed (`-fov 80`, `--fov 80`), for messages.
    pub fov_typed: Option<String>,
    pub threads: Option<usize>,
    pub accel: crate::accel::Accel,
    /// The precision (`--precision`; a scalar kernel's own).
    pub precision: crate::Precision,
    /// Camera overrides from `--eye`, `--look`, `--up`, each with the flag as typed.
    pub camera: CameraOverrides,
}

#[derive(Debug, Clone, PartialEq)]
pub struct RenderSettings {
    pub view: ViewSettings,
    /// The image: a file (or pattern), `-` for standard output, or `None` when no image is
    /// written (a many-view run that names only `.npy` outputs and no `-o`).
    pub output: Option<PathBuf>,
    pub color_mode: ColorMode,
    pub variation: Variation,
    pub time: bool,
    /// `Some(format)` when the image goes to standard output (`-o -`).
    pub stdout_format: Option<ImageFormat>,
    pub kernel: KernelArg,
    pub seed: u64,
    pub ids: Option<PathBuf>,
    pub depth: Option<PathBuf>,
    /// `--zdepth`: distances along the camera's forward axis (`Frame::z_depth`).
    pub zdepth: Option<PathBuf>,
    /// `--normals`: unit surface normals facing the camera (`Frame::normals`).
    pub normals: Option<PathBuf>,
    pub repeat: u32,
    pub stats: Option<PathBuf>,
    /// Many views (`--views`, `--orbit`); `None` for the scene's one camera.
    pub views: Option<view_flags::ViewSource>,
    /// `--skip-existing`.
    pub skip_existing: bool,
    /// `--save-views FILE` (with `--orbit`).
    pub save_views: Option<PathBuf>,
}

impl RenderSettings {
    /// The image file (or pattern) the run writes: `None` when the image goes to standard
    /// output or no image is written.
    pub fn image_file(&self) -> Option<&Path> {
        self.output
            .as_deref()
            .filter(|_| self.stdout_format.is_none())
    }

    /// Whether the run shades an image at all (to a file or to standard output).
    pub fn writes_image(&self) -> bool {
        self.output.is_some()
    }
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
/// typed applies to the others (`view`, `precision`, `check_render`; README "Valid flag
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
    let args = translate(raw.iter().cloned());
    let mut command = Cli::command();
    command.build();
    spelling::check(&args, &command)?;
    let matches = match command.try_get_matches_from(args) {
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
                view: view(c.view, &typed, KernelArg::Simd, raw)?,
                output: c.output,
                max_mismatch_ppm: c.max_mismatch_ppm,
            }))
        }
        None => {
            let typed = Typed { matches: &matches };
            let r = cli.render;
            let view = view(r.view, &typed, r.kernel, raw)?;
            let source = view_flags::source(r.views, r.orbit);
            let buffers = [&r.ids, &r.depth, &r.zdepth, &r.normals];
            let typed_output = r.output.is_some();
            let output = match r.output {
                Some(o) => Some(o),
                // many views: the outputs named, and images only when nothing else is
                None if source.is_some() && buffers.iter().any(|b| b.is_some()) => None,
                None if source.is_some() => Some(view_flags::default_output(&view.input)?),
                None if view.input == Path::new(crate::scene::STDIN) => {
                    return Err(Error::usage(
                        "-i -: a scene from standard input has no file name to put the image \
                         beside; give -o IMAGE",
                    ));
                }
                // one view: the image always, beside the input by default
                None => Some(default_output(&view.input, raw)?),
            };
            let stdout_format =
                stdout_format(output.as_deref(), typed_output, r.format.as_deref())?;
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
                zdepth: r.zdepth,
                normals: r.normals,
                repeat: r.repeat,
                stats: r.stats,
                stdout_format,
                views: source,
                skip_existing: r.skip_existing,
                save_views: r.save_views,
            };
            check_render(&settings, &typed)?;
            view_flags::check(&settings, &typed)?;
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
/// or `None` for an image file, whose extension decides (a `--format` that disagrees is refused,
/// naming `-o` when it was `typed`, else the default name), or for a run that writes no image.
fn stdout_format(
    output: Option<&Path>,
    typed: bool,
    format: Option<&str>,
) -> Result<Option<ImageFormat>> {
    let named = |f: &str| match f {
        "bmp" => ImageFormat::Bmp,
        _ => ImageFormat::Png,
    };
    let Some(output) = output else {
        return match format {
            Some(f) => Err(Error::usage(format!(
                "--format {f}: chooses the format of -o - (standard output); this run writes \
                 no image (give -o - or -o PATTERN.{f})"
            ))),
            None => Ok(None),
        };
    };
    if output == Path::new("-") {
        return Ok(Some(format.map_or(ImageFormat::Png, named)));
    }
    if let Some(f) = format
        && crate::output::image_format(output).ok() != Some(named(f))
    {
        let file = if typed {
            format!("-o {} names a file of another format", output.display())
        } else {
            format!(
                "with no -o the image goes to {}, whose extension gives another format",
                output.display()
            )
        };
        return Err(Error::usage(format!(
            "--format {f}: {file}; --format chooses the format of -o - (standard output) only"
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

/// The shared options resolved for `kernel` (`simd` for `compare`), refusing the typed
/// `--precision` that the kernel contradicts.
fn view(v: View, typed: &Typed, kernel: KernelArg, raw: &[OsString]) -> Result<ViewSettings> {
    let (width, height) = parse_size(&v.size)?;
    let fov = v
        .fov
        .as_deref()
        .map(|t| parse_fov(t, width, height))
        .transpose()?;
    let fov_typed = v
        .fov
        .as_deref()
        .map(|t| respell(&format!("--fov {t}"), raw));
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
    let precision = precision(&v, typed, kernel)?;
    let accel: crate::accel::Accel = v.accel.into();
    Ok(ViewSettings {
        input: v.input.expect("clap requires --input"),
        width,
        height,
        fov,
        fov_typed,
        threads: v.threads,
        accel,
        precision,
        camera: CameraOverrides {
            typed: [("--eye", &v.eye), ("--look", &v.look), ("--up", &v.up)]
                .iter()
                .filter_map(|(f, t)| t.as_deref().map(|t| format!("{f} {t}")))
                .collect(),
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

/// `--fov DEGREES`, `text` as typed: a finite number strictly between 0 and 180 whose screen
/// a `width` x `height` image can hold (the rule intrinsics meet too: `camera::check_lens`).
/// Messages echo the value as typed (`1e400`, `nan`), not as parsed.
fn parse_fov(text: &str, width: u32, height: u32) -> Result<f64> {
    let bad = |why: String| Error::usage(format!("--fov {text}: {why}"));
    let deg: f64 = text
        .trim()
        .parse()
        .ok()
        .filter(|d: &f64| d.is_finite())
        .ok_or_else(|| {
            bad("the field of view must be a finite number of degrees, 0 < FOV < 180".into())
        })?;
    if !(deg > 0.0 && deg < 180.0) {
        return Err(bad(
            "the field of view must lie strictly between 0 and 180 degrees".into(),
        ));
    }
    crate::camera::check_lens(&crate::scene::Lens::Fov(deg), width, height).map_err(bad)?;
    Ok(deg)
}

/// The precision `--precision` names for `kernel`, refusing one that contradicts a scalar
/// kernel's own. The message names only flags the user typed: a value left at its default
/// cannot contradict a typed one.
fn precision(v: &View, typed: &Typed, kernel: KernelArg) -> Result<crate::Precision> {
    let precision = crate::Precision::parse(&v.precision).expect("clap checked the name");
    match kernel.precision() {
        // a scalar kernel (typed: the default is simd) computes in its own precision
        Some(own) if typed.has("precision") && precision != own => Err(Error::usage(format!(
            "--precision {}: --kernel {} computes in {} (--precision chooses the simd \
                 kernel's lanes)",
            precision.name(),
            kernel.name(),
            own.name()
        ))),
        Some(own) => Ok(own),
        None => Ok(precision),
    }
}

/// Refuses the render command's flags that cannot apply to the rest of its settings.
fn check_render(s: &RenderSettings, typed: &Typed) -> Result<()> {
    if typed.has("seed") && s.color_mode != ColorMode::Random {
        let how = match s.color_mode {
            ColorMode::Ordered => "colours by the palette",
            _ => "shades every primitive the same grey",
        };
        return Err(Error::usage(format!(
            "--seed {}: --color-mode {} {how}, with no seed; --seed applies to the random \
             colour mode only",
            s.seed,
            s.color_mode.name(),
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
mod tests;

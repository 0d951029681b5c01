//! The command line as clap sees it: the flags, their help, defaults and value ranges. The
//! checks that tie flags to each other, and the settings they resolve to, are in `cli.rs`.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

pub(super) const EXAMPLES: &str = "\
Examples:
  lanecast -i scenes/scene1.sc                      writes scenes/scene1.png (640x480)
  lanecast -i scene1.sc -o scene1.png -size 800x600 -fov 80
  lanecast -i scene1.sc -cm ordered -cv log -time
  lanecast -i scene1.sc --kernel scalar --threads 1 --ids ids.npy --depth depth.npy
  lanecast -i scenes/bunny.sc -cm shade --zdepth z.npy --normals n.npy
  lanecast compare -i scene1.sc -size 1920x1080 -o diff.png

Exit codes: 0 success (also when the reader of stdout or stderr closes the pipe), 2 bad usage
or bad input (message names the file and line, or the argument), 75 an output folder another
run kept locked longer than LANECAST_LOCK_WAIT seconds (default 30; nothing written), 130
interrupted, 1 anything else (I/O errors, stdout or stderr full, a failed comparison).";

#[derive(Parser, Debug)]
#[command(
    name = "lanecast",
    version,
    about = "Ray-casts a .sc scene (camera, spheres, triangles, quads, OBJ and PLY meshes), or \
             an OBJ or PLY mesh alone, to an image: 8-wide SIMD packets, with a scalar f64 oracle.",
    after_help = EXAMPLES,
    subcommand_negates_reqs = true,
    args_conflicts_with_subcommands = true
)]
pub(super) struct Cli {
    #[command(subcommand)]
    pub(super) command: Option<Sub>,
    #[command(flatten)]
    pub(super) render: RenderArgs,
}

#[derive(Subcommand, Debug)]
pub(super) enum Sub {
    /// Renders with the packet kernel and the f64 scalar oracle and reports where they differ.
    #[command(
        after_help = "Example:\n  lanecast compare -i scenes/scene4.sc -size 1920x1080 -o diff.png"
    )]
    Compare(CompareArgs),
}

#[derive(Args, Debug)]
pub(super) struct View {
    /// Scene file (.sc), or a mesh rendered alone with a framing camera (.obj, .ply)
    #[arg(short = 'i', long = "input", value_name = "SCENE.sc", required = true)]
    pub(super) input: Option<PathBuf>,
    /// Camera position X,Y,Z, replacing the scene's eye (validated as the camera line is)
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(super) eye: Option<String>,
    /// Point the camera looks at, X,Y,Z, replacing the scene's look
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(super) look: Option<String>,
    /// Camera up direction X,Y,Z, replacing the scene's up
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(super) up: Option<String>,
    /// Image size WIDTHxHEIGHT, e.g. 800x600 (single-dash form: -size).
    #[arg(
        long,
        value_name = "WxH",
        default_value = "640x480",
        allow_hyphen_values = true
    )]
    pub(super) size: String,
    /// Horizontal field of view in degrees, 0 < FOV < 180, replacing every lens (the scene's,
    /// each --views line's; a replaced K is noted on stderr) [default: the scene's, else 60]
    /// (single-dash form: -fov).
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
    pub(super) fov: Option<String>,
    /// Worker threads [default: all cores].
    #[arg(long, value_name = "N")]
    pub(super) threads: Option<usize>,
    /// Acceleration: auto (tiles from 2 primitives on), none (test every primitive), tiles
    /// (primitives binned into screen tiles, nearest first), bvh (a bounding volume
    /// hierarchy), world (the scene prepared once for every view, each view rendered in
    /// object order and held to the f64 oracle). Every kernel and precision takes each but
    /// world, which takes the simd kernel only.
    #[arg(long, value_enum, default_value = "auto")]
    pub(super) accel: AccelArg,
    /// Precision of the simd kernel: auto (f32x8 lanes, and each hit f32 cannot hold to 1e-5
    /// relative decided again in f64), f32 (f32x8 alone) or f64 (f64x4, two per packet, equal to
    /// the oracle). With --kernel scalar or scalar-f32, only that kernel's own (f64, f32).
    #[arg(long, value_name = "BITS", default_value = "auto", value_parser = ["auto", "f32", "f64"])]
    pub(super) precision: String,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelArg {
    Auto,
    None,
    Bvh,
    Tiles,
    World,
}

impl From<AccelArg> for crate::accel::Accel {
    fn from(a: AccelArg) -> crate::accel::Accel {
        match a {
            AccelArg::Auto => crate::accel::Accel::Auto,
            AccelArg::None => crate::accel::Accel::None,
            AccelArg::Bvh => crate::accel::Accel::Bvh,
            AccelArg::Tiles => crate::accel::Accel::Tiles,
            AccelArg::World => crate::accel::Accel::World,
        }
    }
}

#[derive(Args, Debug)]
pub(super) struct RenderArgs {
    #[command(flatten)]
    pub(super) view: View,
    /// Output image, .png or .bmp, or - for standard output [default: the input path with
    /// extension .png].
    #[arg(short = 'o', long = "output", value_name = "IMAGE")]
    pub(super) output: Option<PathBuf>,
    /// Image format of -o - (standard output): png or bmp [default: png]. With a file name the
    /// extension decides, and a --format that disagrees is refused.
    #[arg(long, value_name = "FORMAT", value_parser = ["png", "bmp"])]
    pub(super) format: Option<String>,
    /// Colour: random (a seeded colour per primitive), ordered (palette by first appearance)
    /// or shade (grey lit by a headlight at the eye, |n . d|: the shape of a scan)
    /// (single-dash form: -cm).
    #[arg(long = "color-mode", value_name = "MODE", default_value = "random",
          value_parser = ["random", "ordered", "shade"])]
    pub(super) color_mode: String,
    /// Brightness against hit distance: linear or log (single-dash form: -cv).
    #[arg(long = "color-variation", value_name = "VARIATION", default_value = "linear",
          value_parser = ["linear", "log"])]
    pub(super) color_variation: String,
    /// Print the time of each phase and primary rays per second to stderr (single-dash: -time).
    #[arg(long)]
    pub(super) time: bool,
    /// Intersection kernel: simd (8-wide f32 packets), scalar (one ray at a time, f64: the
    /// oracle) or scalar-f32.
    #[arg(long, value_enum, default_value = "simd")]
    pub(super) kernel: KernelArg,
    /// Seed of the random colour mode (refused with -cm ordered and -cm shade, which have none).
    #[arg(long, value_name = "N", default_value_t = 0, allow_negative_numbers = true,
          value_parser = seed_value)]
    pub(super) seed: u64,
    /// Also write per-pixel primitive ids (int32, -1 = background) as a (H, W) .npy file.
    #[arg(long, value_name = "FILE.npy")]
    pub(super) ids: Option<PathBuf>,
    /// Also write per-pixel hit distances (float32, +inf = background) as a (H, W) .npy file.
    #[arg(long, value_name = "FILE.npy")]
    pub(super) depth: Option<PathBuf>,
    /// Also write per-pixel distances along the camera's forward axis (float32, +inf =
    /// background; depth times the ray's cosine with the axis) as a (H, W) .npy file.
    #[arg(long, value_name = "FILE.npy")]
    pub(super) zdepth: Option<PathBuf>,
    /// Also write per-pixel unit surface normals (float32, world space, facing the camera;
    /// 0, 0, 0 = background) as a (H, W, 3) .npy file.
    #[arg(long, value_name = "FILE.npy")]
    pub(super) normals: Option<PathBuf>,
    /// Render K times and report the best and median render time (-time, --stats).
    #[arg(long, value_name = "K", default_value_t = 1,
          value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub(super) repeat: u32,
    /// Write a JSON record of the run: scene, size, primitives, kernel, precision, acceleration,
    /// threads, SIMD width, phase times, best and median render, rays/s, peak memory.
    #[arg(long, value_name = "FILE.json")]
    pub(super) stats: Option<PathBuf>,
    /// Render one view per line of FILE (`camera eye X Y Z look X Y Z up X Y Z [fov DEG | K
    /// FX FY CX CY]`, or `extrinsic M00 .. M33 [fov DEG | K FX FY CX CY]`: a 4x4
    /// world-to-camera matrix, OpenCV axes), all from one load of the scene; -fov replaces
    /// every line's lens. Outputs take numbered names (-o
    /// frames/view_%05d.png, views counted from 0) or -o - (images one after another).
    #[arg(long, value_name = "FILE", conflicts_with = "orbit")]
    pub(super) views: Option<PathBuf>,
    /// Render N views on a turntable: the camera turned about its up axis through its look
    /// point, at its distance and height. Outputs as with --views.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = orbit_views)]
    pub(super) orbit: Option<u32>,
    /// With --orbit: write the views file of the orbit's cameras to FILE.txt (numbers in full,
    /// so --views FILE.txt renders the same views bit for bit); an existing file is replaced
    /// only when it is a views file.
    #[arg(long, value_name = "FILE.txt")]
    pub(super) save_views: Option<PathBuf>,
    /// With --views or --orbit: leave out every view whose files are whole and were made by
    /// this scene, camera, size, precision and output settings, as the record written beside
    /// them says (a rerun picks up where an interrupted run stopped).
    #[arg(long)]
    pub(super) skip_existing: bool,
}

#[derive(Args, Debug)]
pub(super) struct CompareArgs {
    #[command(flatten)]
    pub(super) view: View,
    /// Write a diff image: the render dimmed, mismatches marked (red: unexcused, yellow: tie,
    /// cyan: within the edge band).
    #[arg(short = 'o', long = "output", value_name = "IMAGE")]
    pub(super) output: Option<PathBuf>,
    /// Unexcused id mismatches allowed, in parts per million of the pixels, before the exit
    /// code turns to 1.
    #[arg(
        long,
        value_name = "PPM",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub(super) max_mismatch_ppm: f64,
}

/// `--seed N`'s value, with the reason a bad one is refused (clap's message names the flag and
/// the value as typed, a negative one included).
fn seed_value(s: &str) -> Result<u64, String> {
    s.parse().map_err(|_| {
        format!(
            "the seed must be a non-negative whole number, 0 to {}",
            u64::MAX
        )
    })
}

/// `--orbit N`'s value, with the reason a bad one is refused (clap's message names the flag
/// and the value as typed).
fn orbit_views(s: &str) -> Result<u32, String> {
    let max = crate::limits::MAX_VIEWS;
    let n: i128 = s.parse().map_err(|_| {
        format!("the number of views on the turntable must be a whole number, 1 to {max}")
    })?;
    match u32::try_from(n) {
        Ok(n) if (1..=max as u64).contains(&(n as u64)) => Ok(n),
        _ if n < 1 => Err(format!(
            "the number of views on the turntable must be at least 1 (views are \
             360/N degrees apart), at most {max}"
        )),
        _ => Err(format!("at most {max} views per run (limits::MAX_VIEWS)")),
    }
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
    pub fn precision(self) -> Option<crate::Precision> {
        match self {
            KernelArg::Simd => None,
            KernelArg::Scalar => Some(crate::Precision::F64),
            KernelArg::ScalarF32 => Some(crate::Precision::F32),
        }
    }

    /// The library's kernel: packets, or one ray at a time.
    pub fn kernel(self) -> crate::Kernel {
        match self {
            KernelArg::Simd => crate::Kernel::Packet,
            KernelArg::Scalar | KernelArg::ScalarF32 => crate::Kernel::Scalar,
        }
    }
}

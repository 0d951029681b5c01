//! lanecast: a ray caster. One primary ray per pixel from a pinhole camera, nearest hit among
//! spheres, triangles and quads, tested 8 rays at a time in `wide::f32x8` lanes against
//! structure-of-arrays primitives, with a plain scalar f64 path as the oracle.
//!
//! This library is the one way in, for the `lanecast` command line and for Rust callers alike:
//! load a scene, make a camera, prepare a [`Renderer`], render a [`Frame`] of ids and depths,
//! shade it to RGB.
//!
//! ```
//! use lanecast::{Camera, ColorMode, Options, Renderer, Variation};
//! use std::path::Path;
//!
//! let text = "camera eye 0 2 8 look 0 1 0 up 0 1 0 fov 60\n\
//!             sphere 0 1 0 1\n\
//!             quad -4 0 -4  4 0 -4  4 0 4  -4 0 4\n";
//! // `mesh` paths in the text would be relative to this path's folder.
//! let scene = lanecast::parse_scene(text, Path::new("inline.sc"))?;
//! assert!(scene.warnings.is_empty());
//! let camera = Camera::for_scene(&scene, 64, 48, None)?; // the scene's fov
//! let renderer = Renderer::new(&scene, &camera, &Options::default())?;
//! let frame = renderer.render(); // in the current rayon pool
//! let centre = 24 * 64 + 32;
//! assert_eq!(frame.ids[centre], 0); // the sphere, id 0
//! assert!(frame.depth[centre] > 6.0 && frame.depth[centre] < 8.0);
//! assert_eq!(frame.ids[0], -1); // top-left: background
//! let rgb = lanecast::shade(&frame.ids, &frame.depth, 64, ColorMode::Ordered, Variation::Linear, 0);
//! assert_eq!(rgb.len(), 64 * 48 * 3);
//! # Ok::<(), lanecast::Error>(())
//! ```
//!
//! Threads: rendering and shading use the rayon pool they are called in; wrap the calls in
//! `rayon::ThreadPool::install` to choose the thread count. Output is bit-identical at any
//! thread count.
//!
//! Build flags: the packet kernel is one AVX register per `f32x8` only when `wide` is compiled
//! with AVX enabled. lanecast's own `.cargo/config.toml` sets `target-cpu=native`, but that file
//! does not apply to a crate that depends on lanecast: set `RUSTFLAGS="-C target-cpu=native"`
//! (or a `[build] rustflags` entry in your own `.cargo/config.toml`) to get the AVX2 path.
//!
//! Modules, lowest layer first (lower layers never import higher ones): [`scene`] (parse,
//! validate, meshes) -> [`camera`], [`soa`] -> [`kernel`] (default kernels and the other
//! intersection methods) -> [`accel`] -> [`render`] -> [`shade`](mod@shade), [`output`] -> [`compare`] ->
//! the command line (private). [`error`], [`limits`] and [`real`] are shared by all.

#![warn(missing_docs)]

pub mod accel;
pub mod camera;
#[cfg(feature = "cli")]
pub(crate) mod cli;
pub mod compare;
pub mod error;
pub mod kernel;
pub mod limits;
pub mod output;
pub(crate) mod par;
#[cfg(feature = "cli")]
pub(crate) mod progress;
pub mod real;
pub mod render;
#[cfg(feature = "cli")]
pub(crate) mod run;
pub mod scene;
pub mod shade;
pub mod soa;
#[cfg(feature = "cli")]
pub(crate) mod stats;
pub(crate) mod words;

pub use accel::Accel;
pub use camera::Camera;
pub use error::{Error, Result};
pub use render::{Frame, Kernel, Method, Options, Renderer};
pub use scene::{Scene, load_scene, parse_scene};
pub use shade::{ColorMode, Variation, shade};

/// Runs the lanecast command line (feature `cli`) on a full argument list (program name first). Text for
/// stdout (help, reports) is printed here; errors are returned for `main` to print once, with
/// [`Error::exit_code`] as the process's exit code.
#[cfg(feature = "cli")]
pub fn run(args: impl IntoIterator<Item = std::ffi::OsString>) -> Result<()> {
    run::command(cli::parse(args)?)
}

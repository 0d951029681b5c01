//! lanecast: a ray caster. One primary ray per pixel from a pinhole camera, nearest hit among
//! spheres, triangles and quads, tested 8 rays at a time in `wide::f32x8` lanes against
//! structure-of-arrays primitives, with a plain scalar f64 path as the oracle.
//!
//! This library is the engine of the `lanecast` command line, for Rust callers too: load a
//! [`Scene`], make a [`Camera`], prepare a [`Renderer`], render a [`Frame`] of ids and depths,
//! then shade it to RGB or write it out.
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
//! let frame = renderer.render();
//! let centre = 24 * 64 + 32;
//! assert_eq!(frame.ids[centre], 0); // the sphere, id 0
//! assert!(frame.depth[centre] > 6.0 && frame.depth[centre] < 8.0);
//! assert_eq!(frame.ids[0], -1); // top-left: background
//! let rgb = frame.rgb(&scene, &camera, ColorMode::Shade, Variation::Linear, 0);
//! assert_eq!(rgb.len(), 64 * 48 * 3);
//! // Each file is written to a temporary file beside it, then renamed into place.
//! let dir = std::env::temp_dir();
//! let (mode, variation) = (ColorMode::Random, Variation::Linear);
//! frame.write_image(&dir.join("lanecast-doc.png"), (&scene, &camera), mode, variation, 0)?;
//! frame.write_ids(&dir.join("lanecast-doc-ids.npy"))?; // (48, 64) little-endian i32
//! frame.write_depth(&dir.join("lanecast-doc-depth.npy"))?; // (48, 64) little-endian f32
//! # for f in ["lanecast-doc.png", "lanecast-doc-ids.npy", "lanecast-doc-depth.npy"] {
//! #     std::fs::remove_file(dir.join(f)).unwrap();
//! # }
//! # Ok::<(), lanecast::Error>(())
//! ```
//!
//! # What is here
//!
//! - Scenes: [`load_scene`] (a `.sc` file, meshes included) and [`parse_scene`] (text), giving
//!   a [`Scene`]; its parts ([`scene::Shape`], [`scene::CameraSpec`], ...) are in [`scene`],
//!   with scenes from bytes in memory ([`scene::parse_scene_with`]) and from vertex and index
//!   arrays ([`scene::scene_from_arrays`]).
//! - The camera: [`Camera::for_scene`] for an image size, with [`DEFAULT_FOV`] when neither the
//!   caller nor the scene gives a field of view.
//! - Rendering: [`Renderer::new`] with [`Options`] ([`Precision`], [`Accel`], [`Kernel`])
//!   prepares a scene for a camera; [`Renderer::render`] gives a [`Frame`].
//! - Many views of one scene: [`Views::new`] once, then [`Views::render`] for each camera
//!   ([`Camera::look_at`] makes one from a [`CameraSpec`]); [`scene::cameras`] reads views files
//!   and makes orbits. Each view is bit-identical to a [`Renderer`] of its own.
//! - Shading: [`shade`] (or [`Frame::rgb`]) by [`ColorMode`] and [`Variation`]; what the
//!   hits' surfaces are: [`Frame::z_depth`] and [`Frame::normals`].
//! - Output files, each written atomically: [`Frame::write_image`] (PNG or BMP by extension),
//!   [`Frame::write_ids`] and [`Frame::write_depth`] (NumPy `.npy`), and the functions of
//!   [`output`] they call.
//! - Errors: one [`Error`] type (with [`Error::exit_code`], the command line's) and
//!   [`Result`]; bad input names its file, line and column.
//! - [`limits`]: every resource limit enforced; [`compare`]: the packet kernel against the
//!   f64 oracle, pixel by pixel (`lanecast compare`).
//!
//! Image sizes are `u32` throughout. The parts of the engine's inner layers (kernels,
//! primitive stores, ray tables, one kernel's setup) that the accuracy lab, the benches and
//! the tests use are named under [`experimental`], with no stability promise. The other intersection methods
//! (Möller–Trumbore, watertight, ...) are the lab's (`lab/`), not the engine's.
//!
//! # Features
//!
//! - `cli` (default): the `lanecast` binary and `lanecast::run`, with clap, ctrlc and
//!   serde_json. Implies `parallel`.
//! - `parallel` (default): scene loading, setup, rendering and shading spread over the current
//!   rayon pool; wrap the calls in `rayon::ThreadPool::install` to choose the thread count.
//!   Without it everything runs on the calling thread, and no thread is ever started.
//!
//! Output is bit-identical at any thread count, and with or without `parallel`.
//! `default-features = false` gives the engine alone (glam, image for PNG and BMP, wide), for
//! a target without threads too.
//!
//! # Build flags
//!
//! The packet kernel is one AVX register per `f32x8` only when `wide` is compiled with AVX
//! enabled. lanecast's own `.cargo/config.toml` sets `target-cpu=native`, but that file does not
//! apply to a crate that depends on lanecast: set `RUSTFLAGS="-C target-cpu=native"` (or a
//! `[build] rustflags` entry in your own `.cargo/config.toml`) to get the AVX2 path.
//!
//! # Inside
//!
//! The modules are layered, the scene lowest and the command line (`cli`, `run`, `progress`,
//! `stats`: feature `cli`) highest; lower layers never import higher ones. The order is the
//! table in docs/architecture.md ("Layers"), which `scripts/layers.py` checks in CI. Only
//! [`scene`], [`output`], [`limits`], [`compare`] and [`world`] are public as modules;
//! [`experimental`] names a few items of the others.

#![warn(missing_docs)]

pub(crate) mod accel;
pub(crate) mod basis;
pub(crate) mod camera;
#[cfg(feature = "cli")]
pub(crate) mod cli;
pub mod compare;
pub(crate) mod error;
pub mod experimental;
pub(crate) mod frame;
pub(crate) mod kernel;
pub mod limits;
pub mod output;
pub(crate) mod par;
pub(crate) mod precision;
#[cfg(feature = "cli")]
pub(crate) mod progress;
pub(crate) mod real;
pub(crate) mod render;
#[cfg(feature = "cli")]
pub(crate) mod run;
pub mod scene;
pub(crate) mod shade;
pub(crate) mod soa;
#[cfg(feature = "cli")]
pub(crate) mod stats;
pub(crate) mod surface;
#[cfg(test)]
mod test_rng;
pub(crate) mod words;
pub mod world;

/// The vector library of [`CameraSpec`] (`glam::DVec3`) and the rest of the API, re-exported
/// so that a caller need not depend on the same glam version: `lanecast::glam::DVec3`, or
/// [`DVec3`] itself.
pub use glam;
pub use glam::DVec3;

pub use accel::Accel;
pub use camera::{Camera, DEFAULT_FOV, intrinsics_of_matrix, spec_from_matrices};
pub use error::{Error, Result};
pub use frame::Frame;
pub use precision::Precision;
pub use render::{Kernel, Options, Rendered, Renderer, Views};
pub use scene::{CameraSpec, Intrinsics, Lens, Scene, load_scene, parse_scene};
pub use shade::{ColorMode, Variation, shade};

/// Runs the lanecast command line (feature `cli`) on a full argument list (program name
/// first). Text for stdout (help, reports) is printed here; errors are returned for `main` to
/// print once, with [`Error::exit_code`] as the process's exit code.
#[cfg(feature = "cli")]
pub fn run(args: impl IntoIterator<Item = std::ffi::OsString>) -> Result<()> {
    run::command(cli::parse(args)?)
}

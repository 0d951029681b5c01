//! End to end through the real binary: the original invocations and their GNU long forms,
//! `.npy` side outputs, known pixels, rejected input and arguments, `-h`, `compare`; and, a
//! module each, what were test binaries of their own (flags, outputs, meshes, PLY, standard
//! input, concurrent and stale runs, determinism, methods...): one binary links once, where each
//! file of its own cost a link with thin LTO. `tests/hardening/` and `tests/views_cli/` are the
//! other binaries that run the command line. Every test works in its own fresh temp folder,
//! with the scene copied into it.

#[path = "../common/mod.rs"]
mod common;

use common::*;
use image::{GenericImageView, RgbImage};
use std::fs;
use std::path::Path;

/// The decoded image at `path` as RGB8, checking its size.
fn image_of(path: &Path, w: u32, h: u32) -> RgbImage {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(img.dimensions(), (w, h), "{}", path.display());
    img.to_rgb8()
}

/// A temp folder holding a copy of seed scene 1 as `scene1.sc`.
fn with_scene1(name: &str) -> TempDir {
    let dir = TempDir::new(name);
    dir.copy_in(&seed_scene(1), "scene1.sc");
    dir
}

/// Runs the binary in `dir` and asserts success.
fn ok(dir: &TempDir, args: &[&str]) -> std::process::Output {
    let o = run(&dir.path, args);
    assert_success(&o, &args.join(" "));
    o
}

#[path = "../ply_write/mod.rs"]
mod ply_write;

mod binary_input;
mod camera_flags;
mod compare_cli;
mod concurrent;
mod determinism;
mod flags;
mod help_compare;
mod invocations;
mod library;
mod mesh;
mod messages;
mod methods;
mod npy;
mod outputs;
mod ply_cli;
mod rejected;
mod stale;
mod stats;
mod stdin;
mod streams;
mod surface_outputs;

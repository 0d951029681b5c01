//! lanecast: a command-line ray caster. One primary ray per pixel from a pinhole camera,
//! nearest hit among spheres, triangles and quads, tested 8 rays at a time in `wide::f32x8`
//! lanes against structure-of-arrays primitives, with a plain scalar path as the oracle.

pub mod accel;
pub mod camera;
pub mod cli;
pub mod compare;
pub mod error;
pub mod kernel;
pub mod lab;
pub mod limits;
pub mod output;
pub mod progress;
pub mod real;
pub mod render;
pub mod run;
pub mod scene;
pub mod shade;
pub mod soa;
pub mod stats;

pub use error::{Error, Result};

/// Runs lanecast on a full argument list (program name first). Text for stdout (help) is
/// printed here; errors are returned for `main` to print once.
pub fn run(args: impl IntoIterator<Item = std::ffi::OsString>) -> Result<()> {
    match cli::parse(args)? {
        cli::Command::Info(text) => {
            print!("{text}");
            Ok(())
        }
        cli::Command::Render(s) => run::render_command(&s),
        cli::Command::Compare(s) => compare::compare_command(&s),
    }
}

//! lanecast: a command-line ray caster. One primary ray per pixel from a pinhole camera,
//! nearest hit among spheres, triangles and quads, tested 8 rays at a time in `wide::f32x8`
//! lanes against structure-of-arrays primitives, with a plain scalar path as the oracle.

pub mod error;
pub mod limits;
pub mod scene;

pub use error::{Error, Result};

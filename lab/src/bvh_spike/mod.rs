//! A spike of the second many-view design: a world-space bounding volume hierarchy, built once
//! per scene, traversed by coherent 8x8 pixel tiles (docs/architecture.md, "Many views: object
//! order against a world-space BVH", gives the figures against `--accel world` and Embree).
//!
//! - [`build`]: binned SAH over the scene's triangles, in world space, f32 node bounds rounded
//!   outward from the f64 vertices, top-level splits in parallel (rayon).
//! - [`triangle`]: the triangle test for rays that share one origin (the eye): three edge
//!   planes through the eye, set up once per triangle and tile, then 8 rays a test.
//! - [`traverse`]: a tile's 64 rays (8 packets of 8, one per row) through the hierarchy, front
//!   to back, with two node tests: every packet's slab test ([`Variant::Packets`]), or one
//!   tile frustum and distance test, packets only at the leaves ([`Variant::Frustum`]).
//!
//! A spike, not an engine: triangles only (spheres and quads are refused), rays in f32 from the
//! library's f32 ray tables (`Camera::tables`), no f64 re-decision of pixels near an edge or a
//! tie (so no `--precision auto` contract: the mismatches against the f64 oracle are measured,
//! not bounded), no range check of the scene seen from each eye.

pub mod build;
pub mod traverse;
pub mod triangle;

pub use build::{Bvh, Node};
pub use traverse::{Counts, Variant, render};

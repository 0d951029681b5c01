//! Scenes as parsed from `.sc` files: one camera and a list of primitives in file order.
//!
//! A primitive's id is its index in `Scene::shapes`: its 0-based position among the primitive
//! lines of the file, whatever its type. Parsing (`parse.rs`) turns text into this form;
//! validation (`validate.rs`) holds the geometric rules and their tolerances, and `range.rs`
//! the f32 range check of a scene seen from an eye.

mod arrays;
pub mod cameras;
#[cfg(test)]
mod chunk_tests;
mod chunks;
mod memory;
pub(crate) mod mesh;
mod number;
mod obj;
pub(crate) mod parse;
mod ply;
pub mod pose;
pub(crate) mod range;
pub(crate) mod range_clusters;
mod scene_chunk;
mod shapes;
mod statement;
pub(crate) mod validate;

pub use arrays::scene_from_arrays;
use glam::DVec3;
pub use memory::{parse_mesh_bytes, parse_scene_with};
pub use range_clusters::RangeClusters;
pub use shapes::{Iter, Mesh, PartRef, Shapes};

/// The input path that means standard input (`-i -`).
pub const STDIN: &str = "-";
/// How a scene read from standard input is named in messages.
pub const STDIN_NAME: &str = "<stdin>";
use std::path::PathBuf;

use crate::error::Result;
use std::path::Path;

/// Reads, parses and validates a scene file, meshes included: every rule of the format
/// (README "Scene format") and the f32 range check of `range::f32_range`, so a scene this
/// accepts is one the command line renders. Errors name the file, line and column.
pub fn load_scene(path: &Path) -> Result<Scene> {
    let scene = parse::load_scene(path)?;
    range::f32_range(&scene)?;
    Ok(scene)
}

/// [`load_scene`], also returning every mesh file the scene read, in the order of its `mesh`
/// lines, each as resolved (joined to the scene's folder): with the scene file itself, every
/// file the load read. The command line refuses an output that names any of them.
pub fn load_scene_meshes(path: &Path) -> Result<(Scene, Vec<PathBuf>)> {
    let (scene, meshes) = parse::load_scene_meshes(path)?;
    range::f32_range(&scene)?;
    Ok((scene, meshes))
}

/// [`load_scene`] for scene text in memory; `file` names the scene in messages, and `mesh`
/// paths are relative to its folder.
pub fn parse_scene(text: &str, file: &Path) -> Result<Scene> {
    let scene = parse::parse_scene(text, file)?;
    range::f32_range_text(&scene, text.as_bytes())?;
    Ok(scene)
}

/// The `camera` statement, unvalidated values as written (validated by `validate::camera`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraSpec {
    /// Eye position: the origin of every ray.
    pub eye: DVec3,
    /// A point the camera looks at (the centre of the image).
    pub look: DVec3,
    /// Up direction, any length; need not be perpendicular to the view direction.
    pub up: DVec3,
    /// The lens, when the scene gives one: a horizontal field of view (`fov DEGREES`) or
    /// pinhole intrinsics in pixels (`K FX FY CX CY`).
    pub lens: Option<Lens>,
}

/// How a camera maps pixels to directions, as written: `camera::Camera` turns it into the one
/// pinhole formula (module `camera`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lens {
    /// Horizontal field of view in degrees, 0 < fov < 180: the centred pinhole with square
    /// pixels that spans the image's width.
    Fov(f64),
    /// Intrinsics in pixels of the rendered image (`-size`), skew 0.
    Pinhole(Intrinsics),
}

/// Pinhole intrinsics, in pixels of the rendered image: focal lengths `fx`, `fy` and principal
/// point `(cx, cy)`, where pixel (x, y) spans `[x, x + 1) x [y, y + 1)` (its centre at
/// `x + 0.5`, row 0 at the top): the 3x3 `K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intrinsics {
    /// Focal length along x, pixels.
    pub fx: f64,
    /// Focal length along y, pixels.
    pub fy: f64,
    /// Principal point x, pixels from the image's left edge.
    pub cx: f64,
    /// Principal point y, pixels from the image's top edge.
    pub cy: f64,
}

impl CameraSpec {
    /// The field of view in degrees when the lens is given as one (`None` for no lens and for
    /// intrinsics).
    pub fn fov_deg(&self) -> Option<f64> {
        match self.lens {
            Some(Lens::Fov(f)) => Some(f),
            _ => None,
        }
    }
}

/// One primitive, in the scene's own f64 coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A sphere (`sphere CX CY CZ RADIUS`).
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius (positive in a validated scene).
        radius: f64,
    },
    /// A triangle with vertices A, B, C (`triangle` lines and mesh faces).
    Triangle([DVec3; 3]),
    /// A planar convex quad, vertices in perimeter order: the union of (A,B,C) and (A,C,D).
    Quad([DVec3; 4]),
}

/// A parsed, validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Where the scene came from, for messages.
    pub source: PathBuf,
    /// The scene's `camera` statement.
    pub camera: CameraSpec,
    /// Where that statement is: the 1-based line and column of its first token, for the
    /// camera's messages that depend on the image size (`Camera::for_scene`); `None` for a
    /// camera no file wrote (a mesh rendered alone, a scene from arrays).
    pub camera_at: Option<(usize, usize)>,
    /// Every primitive in file order, a mesh's triangles at its place; the index is the id.
    /// Each with its 1-based source line for messages (`Shapes::line`): a mesh's triangles all
    /// carry the line of their `mesh` statement. Meshes are kept indexed (see [`Shapes`]).
    pub shapes: Shapes,
    /// Things worth telling the user that do not stop the render (e.g. degenerate mesh
    /// triangles), each a full message naming file and line.
    pub warnings: Vec<String>,
}

/// The kinds of primitive, in the one order every per-kind list follows (the counts, the
/// stores, the acceleration structures' kind tags): each kind's keyword in the scene format
/// and its plural.
pub const KINDS: [(&str, &str); 3] = [
    ("sphere", "spheres"),
    ("triangle", "triangles"),
    ("quad", "quads"),
];

impl Shape {
    /// The shape's kind: its index in [`KINDS`].
    #[inline(always)]
    pub fn kind(&self) -> usize {
        match self {
            Shape::Sphere { .. } => 0,
            Shape::Triangle(_) => 1,
            Shape::Quad(_) => 2,
        }
    }

    /// The shape's keyword in the scene format (`sphere`, `triangle`, `quad`).
    pub fn keyword(&self) -> &'static str {
        KINDS[self.kind()].0
    }

    /// The shape's numbers as the scene format writes them, appended to `out`: a sphere's
    /// centre and radius (4), a polygon's vertices' x, y, z in order (9, 12).
    pub fn write_numbers(&self, out: &mut Vec<f64>) {
        match self {
            Shape::Sphere { center, radius } => {
                out.extend_from_slice(&center.to_array());
                out.push(*radius);
            }
            Shape::Triangle(v) => v.iter().for_each(|p| out.extend(p.to_array())),
            Shape::Quad(v) => v.iter().for_each(|p| out.extend(p.to_array())),
        }
    }

    /// How many numbers [`Shape::write_numbers`] writes for a shape of kind `kind`.
    pub fn numbers_of(kind: usize) -> Option<usize> {
        [4, 9, 12].get(kind).copied()
    }

    /// The shape of kind `kind` from the numbers [`Shape::write_numbers`] wrote; `None` when
    /// `x` does not hold that kind's count of numbers.
    pub fn from_numbers(kind: usize, x: &[f64]) -> Option<Shape> {
        if Shape::numbers_of(kind) != Some(x.len()) {
            return None;
        }
        let p = |i: usize| DVec3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
        Some(match kind {
            0 => Shape::Sphere {
                center: p(0),
                radius: x[3],
            },
            1 => Shape::Triangle([p(0), p(1), p(2)]),
            _ => Shape::Quad([p(0), p(1), p(2), p(3)]),
        })
    }

    /// Where the shape lies and which way it faces, as `range_clusters` groups shapes: its
    /// centroid (a sphere's centre) and a normal not normalised (a triangle's
    /// (B - A) x (C - A), a quad's diagonals' (C - A) x (D - B); `None` for a sphere).
    pub fn centre_and_normal(&self) -> (DVec3, Option<DVec3>) {
        match self {
            Shape::Sphere { center, .. } => (*center, None),
            Shape::Triangle(v) => (
                (v[0] + v[1] + v[2]) / 3.0,
                Some((v[1] - v[0]).cross(v[2] - v[0])),
            ),
            Shape::Quad(v) => (
                (v[0] + v[1] + v[2] + v[3]) / 4.0,
                Some((v[2] - v[0]).cross(v[3] - v[1])),
            ),
        }
    }

    /// The shape's box relative to `origin`, as (min, max): a sphere's `centre - origin` plus
    /// and minus its radius, a polygon's least and greatest `vertex - origin` per axis (each
    /// difference rounded once, so the box holds every rounded vertex).
    pub fn bounds(&self, origin: DVec3) -> (DVec3, DVec3) {
        let points = |v: &[DVec3]| {
            (v.iter()).fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
                let p = p - origin;
                (lo.min(p), hi.max(p))
            })
        };
        match self {
            Shape::Sphere { center, radius } => {
                let c = *center - origin;
                (c - DVec3::splat(*radius), c + DVec3::splat(*radius))
            }
            Shape::Triangle(v) => points(v),
            Shape::Quad(v) => points(v),
        }
    }
}

impl Scene {
    /// How many primitives of each kind, in [`KINDS`] order.
    pub fn counts(&self) -> [usize; KINDS.len()] {
        let mut n = [0; KINDS.len()];
        for s in self.shapes.loose() {
            n[s.kind()] += 1;
        }
        // (a mesh's faces are triangles)
        n[Shape::Triangle([DVec3::ZERO; 3]).kind()] +=
            self.shapes.meshes().map(|(m, _)| m.len()).sum::<usize>();
        n
    }
}

#[cfg(test)]
mod shape_tests {
    use super::{KINDS, Shape};
    use crate::test_rng::Rng;
    use glam::DVec3;

    /// Random shapes of every kind, at every scale the format accepts (coordinates up to
    /// 1e12, radii from 1e-6): the numbers written give the same shape back bit for bit, and
    /// only for their own kind's count; the keyword is the kind's; the box from any origin
    /// holds every vertex (a sphere: its centre and radius) and is exact, the least and
    /// greatest of the rounded differences.
    #[test]
    fn numbers_round_trip_and_boxes_hold_the_shape() {
        let mut rng = Rng(0x5EA5);
        let mut seen = [false; KINDS.len()];
        for case in 0..3000 {
            let scale = rng.log(-3.0, 12.0);
            let mut p = || rng.point(scale);
            let shape = match case % 3 {
                0 => Shape::Sphere {
                    center: p(),
                    radius: scale * 1e-6 + scale * 0.5,
                },
                1 => Shape::Triangle([p(), p(), p()]),
                _ => Shape::Quad([p(), p(), p(), p()]),
            };
            let kind = shape.kind();
            seen[kind] = true;
            assert_eq!(shape.keyword(), KINDS[kind].0);
            let mut x = Vec::new();
            shape.write_numbers(&mut x);
            assert_eq!(Some(x.len()), Shape::numbers_of(kind));
            assert_eq!(Shape::from_numbers(kind, &x), Some(shape), "case {case}");
            for other in (0..KINDS.len()).filter(|&k| k != kind) {
                assert_eq!(Shape::from_numbers(other, &x), None);
            }
            let origin = rng.point(scale);
            let (lo, hi) = shape.bounds(origin);
            let corners: Vec<DVec3> = match shape {
                Shape::Sphere { center, radius } => {
                    let c = center - origin;
                    vec![c - DVec3::splat(radius), c + DVec3::splat(radius)]
                }
                Shape::Triangle(v) => v.iter().map(|&v| v - origin).collect(),
                Shape::Quad(v) => v.iter().map(|&v| v - origin).collect(),
            };
            for c in &corners {
                assert!(lo.cmple(*c).all() && hi.cmpge(*c).all(), "case {case}");
            }
            // each face of the box touches a corner: the box is the least one
            for axis in 0..3 {
                assert!(corners.iter().any(|c| c[axis] == lo[axis]), "case {case}");
                assert!(corners.iter().any(|c| c[axis] == hi[axis]), "case {case}");
            }
        }
        assert!(seen.iter().all(|&s| s));
    }
}

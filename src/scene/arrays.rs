//! Scenes from arrays, for a front that holds its geometry in memory (the Python package's
//! `Scene.from_arrays`, numpy arrays) rather than in a `.sc` file.
//!
//! The rules are the format's, from `validate.rs` and the mesh readers, never restated here:
//! triangles are a mesh's faces (three indices into the vertices; zero-area ones kept, never
//! hit, and counted in a warning, as in an OBJ or PLY file), quads go through
//! `validate::quad`, sphere radii through `validate::sphere_radius`, a given camera through
//! `validate::camera`, and the whole scene through `range::f32_range`. What a file format
//! rules out by its syntax is checked here: every number finite, every index in range.
//!
//! Every error names the array and its 0-based row (`quads row 3: quad is not planar: ...`),
//! as an [`Error::Usage`].

use super::parse::framing_camera_of;
use super::{CameraSpec, Mesh, Scene, Shape, Shapes, obj, range, validate};
use crate::error::{Error, Result};
use crate::limits::MAX_PRIMITIVES;
use glam::DVec3;
use std::path::Path;

/// A scene of `triangles` and `quads` (rows of indices into `vertices`) and `spheres` (rows
/// of centre x, y, z and radius), seen from `camera`, or when it is `None` from the framing
/// camera `lanecast -i mesh.obj` uses for a mesh alone (README "Rendering an OBJ directly"),
/// made for the bounding box of every primitive: the triangles' vertices, the quads' corners
/// and the spheres' bounding boxes. Every row is validated before the camera is made, so a
/// bad row reports its own error. `source` names the scene in messages.
///
/// Ids: the triangles first, in row order (0 to M-1), then the quads, then the spheres. The
/// triangles are kept indexed, as one mesh (line 0, so a later range check names a face by
/// its 1-based id); each quad and sphere carries its id + 1 as its line, so a message about
/// it names its 1-based id too.
///
/// Fails with an [`Error::Usage`] naming the array and row of the first bad entry: a
/// non-finite number, an index out of range, a quad or radius the format refuses, a camera the
/// format refuses (or, with none given, primitives with no extent to frame), a primitive the
/// f32 kernels cannot represent from the eye, or more than `limits::MAX_PRIMITIVES`
/// primitives in all.
pub fn scene_from_arrays(
    source: &Path,
    camera: Option<CameraSpec>,
    vertices: &[[f64; 3]],
    triangles: &[[i64; 3]],
    quads: &[[i64; 4]],
    spheres: &[[f64; 4]],
) -> Result<Scene> {
    let at =
        |array: &str, row: usize, msg: String| Error::usage(format!("{array} row {row}: {msg}"));
    let total = triangles.len() + quads.len() + spheres.len();
    if total > MAX_PRIMITIVES {
        return Err(Error::usage(format!(
            "{total} primitives (triangles, quads and spheres); the limit is {MAX_PRIMITIVES}"
        )));
    }
    if vertices.len() > u32::MAX as usize {
        return Err(Error::usage(format!(
            "vertices: {} rows; at most {} can be indexed",
            vertices.len(),
            u32::MAX
        )));
    }
    if let Some(i) = vertices
        .iter()
        .position(|v| !v.iter().all(|x| x.is_finite()))
    {
        return Err(at(
            "vertices",
            i,
            format!("{:?} is not finite", vertices[i]),
        ));
    }
    let index = |array: &str, row: usize, k: i64| -> Result<u32> {
        if (0..vertices.len() as i64).contains(&k) {
            Ok(k as u32)
        } else {
            Err(at(
                array,
                row,
                format!("index {k} is out of range for {} vertices", vertices.len()),
            ))
        }
    };
    let vertex: Vec<DVec3> = vertices.iter().map(|&v| DVec3::from_array(v)).collect();

    let mut faces = Vec::with_capacity(triangles.len());
    let mut degenerate = 0;
    for (row, t) in triangles.iter().enumerate() {
        let face = [
            index("triangles", row, t[0])?,
            index("triangles", row, t[1])?,
            index("triangles", row, t[2])?,
        ];
        degenerate += usize::from(obj::degenerate(&face.map(|i| vertex[i as usize])));
        faces.push(face);
    }
    let mesh = Mesh {
        vertices: vertex,
        faces,
    };

    let mut shapes = Shapes::new();
    let mut loose = Vec::with_capacity(quads.len() + spheres.len());
    for (row, q) in quads.iter().enumerate() {
        let mut v = [DVec3::ZERO; 4];
        for k in 0..4 {
            v[k] = mesh.vertices[index("quads", row, q[k])? as usize];
        }
        validate::quad(&v).map_err(|m| at("quads", row, m))?;
        loose.push(Shape::Quad(v));
    }
    for (row, s) in spheres.iter().enumerate() {
        if !s.iter().all(|x| x.is_finite()) {
            return Err(at("spheres", row, format!("{s:?} is not finite")));
        }
        validate::sphere_radius(s[3]).map_err(|m| at("spheres", row, m))?;
        loose.push(Shape::Sphere {
            center: DVec3::new(s[0], s[1], s[2]),
            radius: s[3],
        });
    }
    // Every primitive is valid before a camera is made for them: a bad row's own error comes
    // first, and the framing camera sees every primitive.
    let camera = match camera {
        Some(c) => {
            validate::camera(&c).map_err(|m| Error::usage(format!("camera: {m}")))?;
            c
        }
        None => framing_camera_of(framed_points(&mesh, &loose)).ok_or_else(|| {
            Error::usage(
                "camera: none given, and the primitives have no extent to frame (no \
                 primitives, or all at one point): give a camera",
            )
        })?,
    };
    let mut warnings = Vec::new();
    if degenerate > 0 {
        warnings.push(format!(
            "{}: {degenerate} degenerate triangle{} kept (never hit)",
            source.display(),
            if degenerate == 1 { "" } else { "s" }
        ));
    }
    let m = triangles.len();
    shapes.push_mesh(mesh, 0);
    for (j, shape) in loose.into_iter().enumerate() {
        shapes.push(shape, m + j + 1);
    }
    let scene = Scene {
        camera_at: None,
        source: source.to_path_buf(),
        camera,
        shapes,
        warnings,
    };
    // The range rule names a primitive by line (quads, spheres: id + 1) or, for the mesh at
    // line 0, as "face ID+1"; both turn back into an array and row.
    let row_of = |id: usize| {
        if id < m {
            ("triangles", id)
        } else if id < m + quads.len() {
            ("quads", id - m)
        } else {
            ("spheres", id - m - quads.len())
        }
    };
    range::f32_range(&scene).map_err(|e| match e {
        Error::Input { line, msg, .. } if line >= 1 => {
            let (array, row) = row_of(line - 1);
            at(array, row, msg)
        }
        Error::InputFile { msg, .. } => {
            let face = msg.strip_prefix("face ").and_then(|r| r.split_once(": "));
            match face.and_then(|(n, msg)| Some((n.parse::<usize>().ok()?, msg))) {
                Some((n, msg)) if n >= 1 => at("triangles", n - 1, msg.to_string()),
                _ => Error::usage(msg),
            }
        }
        other => Error::usage(other.to_string()),
    })?;
    Ok(scene)
}

/// The points whose bounding box the framing camera frames: the triangles' vertices (those
/// the faces use), the quads' corners, and the eight corners of each sphere's bounding box
/// (so the sphere is framed whole, whatever the framing rule).
fn framed_points<'a>(mesh: &'a Mesh, loose: &'a [Shape]) -> impl Iterator<Item = DVec3> + 'a {
    let triangles = mesh
        .faces
        .iter()
        .flatten()
        .map(|&i| mesh.vertices[i as usize]);
    let shapes = loose.iter().flat_map(|s| match *s {
        Shape::Quad(v) => v.to_vec(),
        Shape::Sphere { center, radius } => (0..8)
            .map(|k| {
                let corner = DVec3::new(
                    if k & 1 == 0 { -1.0 } else { 1.0 },
                    if k & 2 == 0 { -1.0 } else { 1.0 },
                    if k & 4 == 0 { -1.0 } else { 1.0 },
                );
                center + corner * radius
            })
            .collect(),
        Shape::Triangle(v) => v.to_vec(),
    });
    triangles.chain(shapes)
}

#[cfg(test)]
mod tests {
    use super::*;

    const V: [[f64; 3]; 5] = [
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [0.0, 0.0, 0.0],
    ];

    fn cam() -> Option<CameraSpec> {
        Some(CameraSpec {
            eye: DVec3::new(0.0, 0.0, 5.0),
            look: DVec3::ZERO,
            up: DVec3::Y,
            lens: Some(crate::scene::Lens::Fov(60.0)),
        })
    }

    fn err(r: Result<Scene>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn ids_run_triangles_then_quads_then_spheres() {
        let p = Path::new("<arrays>");
        let s = scene_from_arrays(
            p,
            cam(),
            &V,
            &[[0, 1, 2], [0, 2, 3]],
            &[[0, 1, 2, 3]],
            &[[0.0, 0.0, -3.0, 1.0]],
        )
        .unwrap();
        assert_eq!(s.shapes.len(), 4);
        assert_eq!(
            s.shapes.get(1),
            Shape::Triangle([V[0], V[2], V[3]].map(DVec3::from_array))
        );
        assert!(matches!(s.shapes.get(2), Shape::Quad(_)));
        assert_eq!(
            s.shapes.get(3),
            Shape::Sphere {
                center: DVec3::new(0.0, 0.0, -3.0),
                radius: 1.0
            }
        );
        assert_eq!(
            (s.shapes.line(0), s.shapes.line(2), s.shapes.line(3)),
            (0, 3, 4)
        );
        assert!(s.warnings.is_empty());
        // No camera: the framing camera of the triangles, looking at their centre along -z.
        let framed = scene_from_arrays(p, None, &V, &[[0, 1, 2]], &[], &[]).unwrap();
        assert_eq!(framed.camera.look, DVec3::ZERO);
        assert!(framed.camera.eye.z > 0.0 && framed.camera.eye.x == 0.0);
    }

    #[test]
    fn bad_rows_are_named_by_array_and_row() {
        let p = Path::new("<arrays>");
        let mut nan = V;
        nan[3][1] = f64::NAN;
        let e = err(scene_from_arrays(p, cam(), &nan, &[], &[], &[]));
        assert!(e.starts_with("vertices row 3: "), "{e}");
        let e = err(scene_from_arrays(
            p,
            cam(),
            &V,
            &[[0, 1, 2], [0, 1, 5]],
            &[],
            &[],
        ));
        assert!(
            e.starts_with("triangles row 1: index 5 is out of range"),
            "{e}"
        );
        let e = err(scene_from_arrays(p, cam(), &V, &[], &[[0, 1, 2, -1]], &[]));
        assert!(e.starts_with("quads row 0: index -1"), "{e}");
        // the same rule as a `quad` line: a bow-tie
        let e = err(scene_from_arrays(
            p,
            cam(),
            &V,
            &[],
            &[[0, 1, 2, 3], [0, 2, 1, 3]],
            &[],
        ));
        assert!(e.starts_with("quads row 1: quad is not convex"), "{e}");
        let e = err(scene_from_arrays(
            p,
            cam(),
            &V,
            &[],
            &[],
            &[[0.0, 0.0, 0.0, -1.0]],
        ));
        assert!(
            e.starts_with("spheres row 0: sphere radius must be positive"),
            "{e}"
        );
        let e = err(scene_from_arrays(
            p,
            cam(),
            &V,
            &[],
            &[],
            &[[0.0, f64::INFINITY, 0.0, 1.0]],
        ));
        assert!(e.starts_with("spheres row 0: "), "{e}");
        let e = err(scene_from_arrays(p, None, &V, &[], &[], &[]));
        assert!(e.starts_with("camera: none given"), "{e}");
        let on_look = CameraSpec {
            look: DVec3::new(0.0, 0.0, 5.0),
            ..cam().unwrap()
        };
        let e = err(scene_from_arrays(
            p,
            Some(on_look),
            &V,
            &[[0, 1, 2]],
            &[],
            &[],
        ));
        assert!(
            e.starts_with("camera: camera eye and look are the same point"),
            "{e}"
        );
    }

    #[test]
    fn without_a_camera_bad_rows_get_their_own_error() {
        // Validation comes before framing: no "nothing to frame" in place of the real error.
        let p = Path::new("<arrays>");
        for r in [0.0, -1.0, f64::NAN] {
            let e = err(scene_from_arrays(
                p,
                None,
                &V,
                &[],
                &[],
                &[[0.0, 0.0, 0.0, r]],
            ));
            assert!(e.starts_with("spheres row 0: "), "{r}: {e}");
        }
        let mut bent = V;
        bent[2][2] = 0.5;
        let e = err(scene_from_arrays(p, None, &bent, &[], &[[0, 1, 2, 3]], &[]));
        assert!(e.starts_with("quads row 0: quad is not planar"), "{e}");
        let e = err(scene_from_arrays(p, None, &V, &[], &[[0, 2, 1, 3]], &[]));
        assert!(e.starts_with("quads row 0: quad is not convex"), "{e}");
        let e = err(scene_from_arrays(
            p,
            None,
            &V,
            &[[0, 1, 2]],
            &[[0, 2, 1, 3]],
            &[],
        ));
        assert!(e.starts_with("quads row 0: quad is not convex"), "{e}");
    }

    #[test]
    fn without_a_camera_every_primitive_is_framed() {
        let p = Path::new("<arrays>");
        let frame = |quads: &[[i64; 4]], spheres: &[[f64; 4]]| {
            scene_from_arrays(p, None, &V, &[[0, 1, 2]], quads, spheres)
                .unwrap()
                .camera
        };
        let alone = frame(&[], &[]);
        // A sphere far to the right: the camera looks at the middle of both, from further.
        let with_sphere = frame(&[], &[[10.0, 0.0, 0.0, 1.0]]);
        assert_eq!(with_sphere.look, DVec3::new(5.0, 0.0, 0.0));
        assert!(with_sphere.eye.z > alone.eye.z, "{with_sphere:?}");
        // Spheres alone, and quads alone, are framed too (the box of a sphere: centre +- r).
        let s = scene_from_arrays(p, None, &V, &[], &[], &[[0.0, 2.0, 0.0, 1.0]]).unwrap();
        assert_eq!(s.camera.look, DVec3::new(0.0, 2.0, 0.0));
        let sphere_box = (0..8).map(|k| {
            let pick = |bit: usize, lo: f64, hi: f64| if k & bit == 0 { lo } else { hi };
            DVec3::new(pick(1, -1.0, 1.0), pick(2, 1.0, 3.0), pick(4, -1.0, 1.0))
        });
        assert_eq!(Some(s.camera), framing_camera_of(sphere_box));
        let mut far = V.to_vec();
        far.extend([
            [9.0, 9.0, 0.0],
            [11.0, 9.0, 0.0],
            [11.0, 11.0, 0.0],
            [9.0, 11.0, 0.0],
        ]);
        let q = scene_from_arrays(p, None, &far, &[], &[[5, 6, 7, 8]], &[]).unwrap();
        assert_eq!(q.camera.look, DVec3::new(10.0, 10.0, 0.0));
        let both = scene_from_arrays(p, None, &far, &[[0, 1, 2]], &[[5, 6, 7, 8]], &[]).unwrap();
        assert_eq!(both.camera.look, DVec3::new(5.0, 5.0, 0.0));
        assert!(both.camera.eye.z > q.camera.eye.z);
    }

    #[test]
    fn the_range_rule_names_the_row() {
        let p = Path::new("<arrays>");
        let far = [[0.0, 0.0, -1e19], [1e18, 0.0, -1e19], [0.0, 1e18, -1e19]];
        let mut v = V.to_vec();
        v.extend(far);
        let e = err(scene_from_arrays(
            p,
            cam(),
            &v,
            &[[0, 1, 2], [5, 6, 7]],
            &[],
            &[],
        ));
        assert!(
            e.starts_with("triangles row 1: triangle vertex A is"),
            "{e}"
        );
        let e = err(scene_from_arrays(
            p,
            cam(),
            &v,
            &[[0, 1, 2]],
            &[[0, 1, 2, 3]],
            &[[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, -1e19, 1.0]],
        ));
        assert!(e.starts_with("spheres row 1: sphere reaches"), "{e}");
    }

    #[test]
    fn zero_area_triangles_are_kept_and_counted() {
        let p = Path::new("<arrays>");
        let s =
            scene_from_arrays(p, cam(), &V, &[[0, 1, 2], [0, 4, 2], [0, 0, 1]], &[], &[]).unwrap();
        assert_eq!(s.shapes.len(), 3);
        assert_eq!(
            s.warnings,
            ["<arrays>: 2 degenerate triangles kept (never hit)"]
        );
    }
}

//! Pickling: a scene by value, compactly (its primitives as runs of loose shapes and meshes),
//! and back, its structure checked.

use crate::errors::value_error;
use lanecast::scene::{Mesh, Shape, Shapes};
use lanecast::{CameraSpec, Scene};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyList, PyTuple};
use std::path::PathBuf;

/// One loose shape's kind (its index in `lanecast::scene::KINDS`) and numbers, for pickling
/// (`Shape::write_numbers`).
fn shape_numbers(s: &Shape, out: &mut Vec<f64>) -> u8 {
    s.write_numbers(out);
    s.kind() as u8
}

/// A scene's primitives in id order, as runs: loose shapes (kinds, numbers, lines) and meshes
/// (vertices, faces, line). Runs are found from the public `Shapes::address` (where each id's
/// data lies: in the loose shapes or in a mesh's faces).
enum Run<'a> {
    Loose(Vec<u8>, Vec<f64>, Vec<u32>),
    Mesh(&'a Mesh, usize),
}

fn runs(shapes: &Shapes) -> Vec<Run<'_>> {
    let loose = shapes.loose();
    let lo = loose.as_ptr() as usize;
    let hi = lo + std::mem::size_of_val(loose);
    let meshes: Vec<(&Mesh, usize)> = shapes.meshes().filter(|(m, _)| !m.is_empty()).collect();
    let (mut out, mut id, mut k) = (Vec::new(), 0, 0);
    while id < shapes.len() {
        let at = shapes.address(id).0 as usize;
        if (lo..hi).contains(&at) {
            let shape = loose[(at - lo) / std::mem::size_of::<Shape>()];
            if !matches!(out.last(), Some(Run::Loose(..))) {
                out.push(Run::Loose(Vec::new(), Vec::new(), Vec::new()));
            }
            if let Some(Run::Loose(kinds, nums, lines)) = out.last_mut() {
                kinds.push(shape_numbers(&shape, nums));
                lines.push(shapes.line(id) as u32);
            }
            id += 1;
        } else {
            let (mesh, line) = meshes[k];
            debug_assert_eq!(at, mesh.faces.as_ptr() as usize);
            out.push(Run::Mesh(mesh, line));
            id += mesh.len();
            k += 1;
        }
    }
    out
}

/// Item `i` of a pickled part as a C-contiguous, aligned array of `dtype`: a pickle's buffers
/// may come back misaligned (out-of-band buffers, as Dask sends them).
fn aligned<'py>(part: &Bound<'py, PyTuple>, i: usize, dtype: &str) -> PyResult<Bound<'py, PyAny>> {
    let np = part.py().import("numpy")?;
    let kw = pyo3::types::PyDict::new(part.py());
    kw.set_item("requirements", "CA")?;
    np.call_method("require", (part.get_item(i)?, dtype), Some(&kw))
}

fn corrupt(what: &str) -> PyErr {
    value_error(format!("not a pickled lanecast.Scene: {what}"))
}

/// A scene's `_state` (see `Scene._state`).
pub(crate) fn state<'py>(py: Python<'py>, s: &Scene) -> PyResult<Bound<'py, PyTuple>> {
    let mut parts = Vec::new();
    for run in runs(&s.shapes) {
        let part = match run {
            Run::Loose(kinds, nums, lines) => (
                "loose",
                PyBytes::new(py, &kinds).into_any(),
                PyArray1::from_vec(py, nums).into_any(),
                PyArray1::from_vec(py, lines).into_any(),
            )
                .into_pyobject(py)?,
            Run::Mesh(mesh, line) => {
                let v: Vec<f64> = mesh.vertices.iter().flat_map(|p| p.to_array()).collect();
                let f: Vec<u32> = mesh.faces.iter().flatten().copied().collect();
                let v = Array2::from_shape_vec((mesh.vertices.len(), 3), v).expect("n * 3");
                let f = Array2::from_shape_vec((mesh.faces.len(), 3), f).expect("m * 3");
                (
                    "mesh",
                    v.into_pyarray(py).into_any(),
                    f.into_pyarray(py).into_any(),
                    line.into_pyobject(py)?.into_any(),
                )
                    .into_pyobject(py)?
            }
        };
        parts.push(part);
    }
    let c = s.camera;
    let lens = match c.lens {
        Some(lanecast::Lens::Fov(f)) => Some(vec![f]),
        Some(lanecast::Lens::Pinhole(k)) => Some(vec![k.fx, k.fy, k.cx, k.cy]),
        None => None,
    };
    (
        2u32,
        s.source.clone(),
        (c.eye.to_array(), c.look.to_array(), c.up.to_array()),
        lens,
        s.warnings.clone(),
        PyList::new(py, parts)?,
    )
        .into_pyobject(py)
}

/// What `Scene._state` gives: version, source, (eye, look, up), lens ([fov] or [fx, fy, cx,
/// cy], or None), warnings, runs.
pub(crate) type SceneState<'py> = (
    u32,
    PathBuf,
    ([f64; 3], [f64; 3], [f64; 3]),
    Option<Vec<f64>>,
    Vec<String>,
    Vec<Bound<'py, PyTuple>>,
);

/// The scene a `_state` gave, its structure checked (see `Scene._from_state`).
pub(crate) fn from_state(state: SceneState<'_>) -> PyResult<Scene> {
    let (version, source, (eye, look, up), lens, warnings, parts) = state;
    if version != 2 {
        return Err(corrupt(&format!("version {version}")));
    }
    let lens = match lens.as_deref() {
        None => None,
        Some(&[f]) => Some(lanecast::Lens::Fov(f)),
        Some(&[fx, fy, cx, cy]) => Some(lanecast::Lens::Pinhole(lanecast::Intrinsics {
            fx,
            fy,
            cx,
            cy,
        })),
        Some(_) => return Err(corrupt("lens")),
    };
    let mut shapes = Shapes::new();
    for part in parts {
        let kind: String = part.get_item(0)?.extract()?;
        match kind.as_str() {
            "loose" => {
                let kinds: Vec<u8> = part.get_item(1)?.extract()?;
                let nums: PyReadonlyArray1<f64> = aligned(&part, 2, "float64")?.extract()?;
                let lines: PyReadonlyArray1<u32> = aligned(&part, 3, "uint32")?.extract()?;
                let (nums, lines) = (nums.as_slice()?, lines.as_slice()?);
                if lines.len() != kinds.len() {
                    return Err(corrupt("lines"));
                }
                let mut at = 0;
                for (k, &line) in kinds.iter().zip(lines) {
                    let n = Shape::numbers_of(*k as usize).ok_or_else(|| corrupt("kind"))?;
                    let x = nums.get(at..at + n).ok_or_else(|| corrupt("numbers"))?;
                    at += n;
                    let shape =
                        Shape::from_numbers(*k as usize, x).ok_or_else(|| corrupt("kind"))?;
                    shapes.push(shape, line as usize);
                }
                if at != nums.len() {
                    return Err(corrupt("numbers"));
                }
            }
            "mesh" => {
                let v: PyReadonlyArray2<f64> = aligned(&part, 1, "float64")?.extract()?;
                let f: PyReadonlyArray2<u32> = aligned(&part, 2, "uint32")?.extract()?;
                let line: usize = part.get_item(3)?.extract()?;
                let (v, f) = (v.as_slice()?, f.as_slice()?);
                let vertices: Vec<glam::DVec3> = v
                    .as_chunks::<3>()
                    .0
                    .iter()
                    .map(|&p| glam::DVec3::from_array(p))
                    .collect();
                let faces = f.as_chunks::<3>().0.to_vec();
                if faces
                    .iter()
                    .flatten()
                    .any(|&i| i as usize >= vertices.len())
                {
                    return Err(corrupt("face index"));
                }
                shapes.push_mesh(Mesh { vertices, faces }, line);
            }
            _ => return Err(corrupt("part")),
        }
    }
    Ok(Scene {
        camera_at: None,
        source,
        camera: CameraSpec {
            eye: glam::DVec3::from_array(eye),
            look: glam::DVec3::from_array(look),
            up: glam::DVec3::from_array(up),
            lens,
        },
        shapes,
        warnings,
    })
}

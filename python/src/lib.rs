//! lanecast for Python: the extension module `lanecast._lanecast`, wrapped by the package in
//! `python/lanecast/`.
//!
//! This crate converts and delegates, nothing more: numpy arrays in (checked at the border for
//! shape, dtype and finite values, with errors naming the argument and row), numpy arrays out
//! (the library's buffers moved into numpy without a copy where the shape allows), and every
//! rule and every ray from the `lanecast` library: `load_scene`, `scene_from_arrays`,
//! `Camera::look_at`, `Views`, `shade`. The GIL is released around every load, validation and
//! render; `threads=` picks a rayon pool.

use lanecast::scene::{Mesh, Shape, Shapes};
use lanecast::{CameraSpec, ColorMode, Method, Options, Scene, Variation, Views};
use numpy::ndarray::{Array2, Array3};
use numpy::{
    IntoPyArray, PyArray1, PyArray3, PyArrayDescrMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyReadonlyArray3, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyList, PyTuple};
use rayon::ThreadPool;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

// ------------------------------------------------------------------------------------------
// Errors

/// A library error as the Python exception a caller expects: bad content in a scene or mesh
/// file (with its file, line and column) as `lanecast.SceneError`, a file that cannot be read
/// as `OSError`, a bad argument as `ValueError`.
fn py_err(py: Python<'_>, e: lanecast::Error) -> PyErr {
    use lanecast::Error as E;
    let text = e.to_string();
    let scene_error = |file: &Path, line: Option<usize>, col: Option<usize>| {
        let class = py
            .import("lanecast._errors")
            .and_then(|m| m.getattr("SceneError"));
        match class.and_then(|c| c.call1((text.clone(), file.to_path_buf(), line, col))) {
            Ok(obj) => PyErr::from_value(obj),
            Err(err) => err,
        }
    };
    match &e {
        E::Input {
            file, line, col, ..
        } => scene_error(file, Some(*line), Some(*col)),
        E::InputFile { file, .. } => scene_error(file, None, None),
        E::IoAt { file, line, .. } => scene_error(file, Some(*line), Some(0)),
        E::Io { source, path, .. } => match source.raw_os_error() {
            Some(code) => PyOSError::new_err((code, text, path.clone())),
            None => PyOSError::new_err(text),
        },
        E::Usage(_) => PyValueError::new_err(text),
        _ => PyRuntimeError::new_err(text),
    }
}

fn value_error(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

// ------------------------------------------------------------------------------------------
// Thread pools and precision

/// The rayon pool for `threads` (None: rayon's global pool, every core). Pools are kept, one
/// per thread count asked for, so a loop of renders does not start threads every call.
fn pool(threads: Option<usize>) -> PyResult<Option<Arc<ThreadPool>>> {
    static POOLS: Mutex<BTreeMap<usize, Arc<ThreadPool>>> = Mutex::new(BTreeMap::new());
    let Some(n) = threads else { return Ok(None) };
    if n == 0 || n > lanecast::limits::MAX_THREADS {
        return Err(value_error(format!(
            "threads={n}: must be 1 to {}",
            lanecast::limits::MAX_THREADS
        )));
    }
    let mut pools = POOLS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(p) = pools.get(&n) {
        return Ok(Some(p.clone()));
    }
    let p = rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("threads={n}: {e}")))?;
    let p = Arc::new(p);
    pools.insert(n, p.clone());
    Ok(Some(p))
}

/// Runs `f` with the GIL released, in the pool `threads` names.
fn run<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    f: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    let pool = pool(threads)?;
    Ok(py.detach(|| match pool {
        Some(p) => p.install(f),
        None => f(),
    }))
}

/// The precisions of `--precision`, as indices into a scene's prepared views.
const PRECISIONS: [(&str, Method); 3] = [
    ("auto", Method::Auto),
    ("f32", Method::Default),
    ("f64", Method::F64x4),
];

fn precision_index(name: &str) -> PyResult<usize> {
    PRECISIONS
        .iter()
        .position(|(n, _)| *n == name)
        .ok_or_else(|| {
            value_error(format!(
                "precision={name:?}: must be \"auto\", \"f32\" or \"f64\""
            ))
        })
}

// ------------------------------------------------------------------------------------------
// Arrays in

/// `obj` as a C-contiguous 2-D array of `K` columns converted to `dtype` ("float64",
/// "int64", "uint64"), or `None` for no rows. Errors name `name` and say what was expected.
fn as_rows<'py>(
    py: Python<'py>,
    name: &str,
    obj: &Bound<'py, PyAny>,
    k: usize,
    integers: bool,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let np = py.import("numpy")?;
    let arr = np
        .call_method1("asarray", (obj,))
        .map_err(|e| value_error(format!("{name}: not an array of numbers ({e})")))?;
    let arr = arr
        .cast::<PyUntypedArray>()
        .map_err(|_| value_error(format!("{name}: not an array")))?
        .clone();
    let shape = arr.shape().to_vec();
    if arr.len() == 0 && (shape.len() == 1 || (shape.len() == 2 && shape[1] == k)) {
        return Ok(None);
    }
    if shape.len() != 2 || shape[1] != k {
        return Err(value_error(format!(
            "{name}: shape {}, expected (N, {k})",
            py_shape(&shape)
        )));
    }
    let kind = arr.dtype().kind();
    let ok = match kind {
        b'i' | b'u' => true,
        b'f' => !integers,
        _ => false,
    };
    if !ok {
        let want = if integers {
            "integer indices"
        } else {
            "real numbers"
        };
        return Err(value_error(format!(
            "{name}: dtype {}, expected {want}",
            arr.dtype()
        )));
    }
    let dtype = match (integers, kind) {
        (false, _) => "float64",
        (true, b'u') => "uint64",
        (true, _) => "int64",
    };
    let c = np.call_method1("ascontiguousarray", (arr, dtype))?;
    Ok(Some(c))
}

/// A shape as Python writes it: (5, 2), (3,).
fn py_shape(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

fn float_rows<const K: usize>(
    py: Python<'_>,
    name: &str,
    obj: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<[f64; K]>> {
    let Some(obj) = obj else {
        return Ok(Vec::new());
    };
    let Some(a) = as_rows(py, name, obj, K, false)? else {
        return Ok(Vec::new());
    };
    let a: PyReadonlyArray2<f64> = a.extract()?;
    let flat = a.as_slice()?;
    Ok(flat.as_chunks::<K>().0.to_vec())
}

/// Index rows as i64; a uint64 index past i64's range becomes i64::MAX, which is out of range
/// for any vertex array (so it is refused by row like any other).
fn index_rows<const K: usize>(
    py: Python<'_>,
    name: &str,
    obj: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<[i64; K]>> {
    let Some(obj) = obj else {
        return Ok(Vec::new());
    };
    let Some(a) = as_rows(py, name, obj, K, true)? else {
        return Ok(Vec::new());
    };
    if let Ok(u) = a.extract::<PyReadonlyArray2<u64>>() {
        let flat = u.as_slice()?;
        return Ok(flat
            .as_chunks::<K>()
            .0
            .iter()
            .map(|r| r.map(|x| i64::try_from(x).unwrap_or(i64::MAX)))
            .collect());
    }
    let a: PyReadonlyArray2<i64> = a.extract()?;
    Ok(a.as_slice()?.as_chunks::<K>().0.to_vec())
}

fn vec3(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<glam::DVec3> {
    let v: Vec<f64> = obj
        .extract()
        .map_err(|_| value_error(format!("{name}: expected 3 numbers")))?;
    match v[..] {
        [x, y, z] => Ok(glam::DVec3::new(x, y, z)),
        _ => Err(value_error(format!(
            "{name}: expected 3 numbers, got {}",
            v.len()
        ))),
    }
}

// ------------------------------------------------------------------------------------------
// Camera

/// Tolerance of `Camera.from_intrinsics`, relative: the principal point's distance from the
/// image centre (to the image's size), fx against fy and the skew (to fx), and how far the
/// extrinsic's rotation is from orthonormal (entries of R Rᵀ - I).
const INTRINSICS_TOL: f64 = 1e-6;

/// What a pickled camera holds: eye, look, up, fov, size.
type CameraState = ([f64; 3], [f64; 3], [f64; 3], f64, Option<(u32, u32)>);

/// A pinhole camera: eye, look, up and horizontal field of view in degrees, as a scene's
/// `camera` line (README "Camera"); optionally tied to an image size (`from_intrinsics`).
#[pyclass(frozen, from_py_object, module = "lanecast._lanecast", name = "Camera")]
#[derive(Clone, Copy)]
struct PyCamera {
    spec: CameraSpec,
    size: Option<(u32, u32)>,
}

impl PyCamera {
    /// The library's camera for a `width` x `height` image: the size given, else the camera's
    /// own (from intrinsics), else 640x480 as the command line.
    fn resolve(&self, width: Option<u32>, height: Option<u32>) -> PyResult<lanecast::Camera> {
        let (w, h) = match (self.size, width, height) {
            (Some((cw, ch)), w, h) => {
                let (w, h) = (w.unwrap_or(cw), h.unwrap_or(ch));
                if (w, h) != (cw, ch) {
                    return Err(value_error(format!(
                        "this camera is for {cw}x{ch} images (its intrinsics); asked for {w}x{h}"
                    )));
                }
                (w, h)
            }
            (None, w, h) => (w.unwrap_or(640), h.unwrap_or(480)),
        };
        lanecast::Camera::look_at(&self.spec, w, h).map_err(|e| value_error(e.to_string()))
    }

    fn checked(spec: CameraSpec, size: Option<(u32, u32)>) -> PyResult<PyCamera> {
        let cam = PyCamera { spec, size };
        cam.resolve(None, None)?;
        Ok(cam)
    }

    fn from_matrices(
        k: [[f64; 3]; 3],
        e: [[f64; 4]; 4],
        width: u32,
        height: u32,
    ) -> Result<PyCamera, String> {
        let tol = INTRINSICS_TOL;
        let finite = k
            .iter()
            .flatten()
            .chain(e.iter().flatten())
            .all(|x| x.is_finite());
        if !finite {
            return Err("K and extrinsic must be finite".into());
        }
        let (fx, fy, cx, cy) = (k[0][0], k[1][1], k[0][2], k[1][2]);
        if k[1][0] != 0.0 || k[2] != [0.0, 0.0, 1.0] {
            return Err(format!(
                "K must be [[fx, s, cx], [0, fy, cy], [0, 0, 1]], got {k:?}"
            ));
        }
        if fx <= 0.0 || fy <= 0.0 {
            return Err(format!("K: fx and fy must be positive, got {fx} and {fy}"));
        }
        if (fx - fy).abs() > tol * fx {
            return Err(format!(
                "K: fx = {fx} and fy = {fy} differ; lanecast's pixels are square (tolerance \
                 {tol:e} relative)"
            ));
        }
        if k[0][1].abs() > tol * fx {
            return Err(format!("K: skew {} is not 0", k[0][1]));
        }
        let (w, h) = (width as f64, height as f64);
        if (cx - w / 2.0).abs() > tol * w || (cy - h / 2.0).abs() > tol * h {
            return Err(format!(
                "K: principal point ({cx}, {cy}) is not the image centre ({}, {}) of a \
                 {width}x{height} image; lanecast's camera has its principal point at the \
                 centre (pixel x's centre is x + 0.5, as in Open3D's create_rays_pinhole; \
                 tolerance {tol:e} of the size)",
                w / 2.0,
                h / 2.0
            ));
        }
        if e[3] != [0.0, 0.0, 0.0, 1.0] {
            return Err(format!(
                "extrinsic: last row must be [0, 0, 0, 1], got {:?}",
                e[3]
            ));
        }
        let r = |i: usize| glam::DVec3::new(e[i][0], e[i][1], e[i][2]);
        let (x, y, z) = (r(0), r(1), r(2));
        let off = [
            x.dot(x) - 1.0,
            y.dot(y) - 1.0,
            z.dot(z) - 1.0,
            x.dot(y),
            y.dot(z),
            x.dot(z),
        ];
        if off.iter().any(|o| o.abs() > tol) || x.cross(y).dot(z) <= 0.0 {
            return Err(
                "extrinsic: the 3x3 rotation must be orthonormal with determinant +1 \
                 (world-to-camera, OpenCV axes: x right, y down, z forward)"
                    .into(),
            );
        }
        let t = glam::DVec3::new(e[0][3], e[1][3], e[2][3]);
        // X_cam = R X_world + t: the centre is -Rᵀ t; the camera's axes in the world are R's
        // rows; lanecast's up is -y (OpenCV's y points down).
        let eye = -(x * t.x + y * t.y + z * t.z);
        let spec = CameraSpec {
            eye,
            look: eye + z,
            up: -y,
            fov_deg: Some((2.0 * (w / (2.0 * fx)).atan()).to_degrees()),
        };
        Ok(PyCamera {
            spec,
            size: Some((width, height)),
        })
    }
}

#[pymethods]
impl PyCamera {
    /// Camera(eye, look, up=(0, 1, 0), fov=60.0): a pinhole at `eye` looking at `look`, `up`
    /// giving the image's up, `fov` the horizontal field of view in degrees (README "Camera").
    #[new]
    #[pyo3(signature = (eye, look, up = None, fov = 60.0))]
    fn new(
        eye: &Bound<'_, PyAny>,
        look: &Bound<'_, PyAny>,
        up: Option<&Bound<'_, PyAny>>,
        fov: f64,
    ) -> PyResult<PyCamera> {
        let up = match up {
            Some(u) => vec3("up", u)?,
            None => glam::DVec3::Y,
        };
        let spec = CameraSpec {
            eye: vec3("eye", eye)?,
            look: vec3("look", look)?,
            up,
            fov_deg: Some(fov),
        };
        PyCamera::checked(spec, None)
    }

    /// Camera.from_intrinsics(K, extrinsic, width, height): the camera of a 3x3 intrinsic
    /// matrix and a 4x4 world-to-camera extrinsic matrix, OpenCV/Open3D convention (x right,
    /// y down, z forward; pixel x's centre at x + 0.5, as Open3D's `create_rays_pinhole`).
    /// lanecast's camera has square pixels and its principal point at the image centre, so K
    /// must have fx == fy, no skew, and (cx, cy) == (width / 2, height / 2), each within 1e-6
    /// relative; anything else raises ValueError. `extrinsic` of shape (V, 4, 4) (and K
    /// (3, 3) or (V, 3, 3)) gives a list of V cameras. The camera keeps its image size.
    #[staticmethod]
    #[allow(non_snake_case)]
    fn from_intrinsics(
        py: Python<'_>,
        K: &Bound<'_, PyAny>,
        extrinsic: &Bound<'_, PyAny>,
        width: u32,
        height: u32,
    ) -> PyResult<Py<PyAny>> {
        let np = py.import("numpy")?;
        let k = np.call_method1("ascontiguousarray", (K, "float64"))?;
        let e = np.call_method1("ascontiguousarray", (extrinsic, "float64"))?;
        let ks: PyReadonlyArray3<f64> = match k.getattr("ndim")?.extract::<usize>()? {
            2 => k.call_method1("reshape", ((1, 3, 3),))?.extract()?,
            3 => k.extract()?,
            _ => return Err(value_error("K: expected shape (3, 3) or (V, 3, 3)")),
        };
        let batch = e.getattr("ndim")?.extract::<usize>()? == 3;
        let es: PyReadonlyArray3<f64> = if batch {
            e.extract()?
        } else {
            e.call_method1("reshape", ((1, 4, 4),))
                .map_err(|_| value_error("extrinsic: expected shape (4, 4) or (V, 4, 4)"))?
                .extract()?
        };
        let (ksh, esh) = (ks.shape().to_vec(), es.shape().to_vec());
        if ksh[1..] != [3, 3] {
            return Err(value_error(format!(
                "K: shape {}, expected (3, 3) or (V, 3, 3)",
                py_shape(&ksh)
            )));
        }
        if esh[1..] != [4, 4] {
            return Err(value_error(format!(
                "extrinsic: shape {}, expected (4, 4) or (V, 4, 4)",
                py_shape(&esh)
            )));
        }
        if ksh[0] != 1 && ksh[0] != esh[0] {
            return Err(value_error(format!(
                "K: {} matrices for {} extrinsics",
                ksh[0], esh[0]
            )));
        }
        let (kf, ef) = (ks.as_slice()?, es.as_slice()?);
        let mut cams = Vec::with_capacity(esh[0]);
        for v in 0..esh[0] {
            let kv = if ksh[0] == 1 { 0 } else { v };
            let km: [[f64; 3]; 3] =
                std::array::from_fn(|i| std::array::from_fn(|j| kf[kv * 9 + i * 3 + j]));
            let em: [[f64; 4]; 4] =
                std::array::from_fn(|i| std::array::from_fn(|j| ef[v * 16 + i * 4 + j]));
            let cam = PyCamera::from_matrices(km, em, width, height)
                .map_err(|m| value_error(if batch { format!("view {v}: {m}") } else { m }))?;
            cam.resolve(None, None)
                .map_err(|e| value_error(format!("view {v}: {e}")))?;
            cams.push(cam);
        }
        if batch {
            Ok(PyList::new(py, cams)?.into_any().unbind())
        } else {
            Ok(Py::new(py, cams[0])?.into_any())
        }
    }

    /// The eye (ray origin), as (x, y, z).
    #[getter]
    fn eye(&self) -> [f64; 3] {
        self.spec.eye.to_array()
    }

    /// The point looked at (the image centre).
    #[getter]
    fn look(&self) -> [f64; 3] {
        self.spec.look.to_array()
    }

    /// The up direction as given.
    #[getter]
    fn up(&self) -> [f64; 3] {
        self.spec.up.to_array()
    }

    /// Horizontal field of view, degrees.
    #[getter]
    fn fov(&self) -> f64 {
        self.spec.fov_deg.unwrap_or(lanecast::DEFAULT_FOV)
    }

    /// (width, height) for a camera made from intrinsics, else None.
    #[getter]
    fn size(&self) -> Option<(u32, u32)> {
        self.size
    }

    /// The camera's rays for a `width` x `height` image, shape (H, W, 6), float64: origin then
    /// unit direction, row 0 at the top, as lanecast's camera makes them (the f64 direction
    /// tables); the layout of Open3D's `create_rays_pinhole` (whose directions are not unit).
    #[pyo3(signature = (width = None, height = None))]
    fn rays<'py>(
        &self,
        py: Python<'py>,
        width: Option<u32>,
        height: Option<u32>,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let cam = self.resolve(width, height)?;
        let (w, h) = (cam.width as usize, cam.height as usize);
        let tables = cam.tables::<f64>(1, 1);
        let mut out = Vec::with_capacity(w * h * 6);
        for y in 0..h {
            for x in 0..w {
                out.extend(cam.eye.to_array());
                out.extend(tables.dir_x1(x, y));
            }
        }
        let a = Array3::from_shape_vec((h, w, 6), out).expect("h * w * 6 values");
        Ok(a.into_pyarray(py))
    }

    fn __repr__(&self) -> String {
        let size = match self.size {
            Some((w, h)) => format!(", size=({w}, {h})"),
            None => String::new(),
        };
        format!(
            "Camera(eye={:?}, look={:?}, up={:?}, fov={}{size})",
            self.eye(),
            self.look(),
            self.up(),
            self.fov()
        )
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.extract::<PyCamera>() {
            Ok(o) => o.spec == self.spec && o.size == self.size,
            Err(_) => false,
        }
    }

    /// (eye, look, up, fov, size): what pickling keeps.
    fn _state(&self) -> CameraState {
        (self.eye(), self.look(), self.up(), self.fov(), self.size)
    }

    #[staticmethod]
    fn _from_state(state: CameraState) -> PyResult<PyCamera> {
        let (eye, look, up, fov, size) = state;
        let spec = CameraSpec {
            eye: glam::DVec3::from_array(eye),
            look: glam::DVec3::from_array(look),
            up: glam::DVec3::from_array(up),
            fov_deg: Some(fov),
        };
        PyCamera::checked(spec, size)
    }
}

/// A camera argument: a `Camera`, or None for the scene's own.
fn camera_arg(scene: &Scene, camera: Option<&Bound<'_, PyAny>>) -> PyResult<PyCamera> {
    match camera {
        None => Ok(PyCamera {
            spec: scene.camera,
            size: None,
        }),
        Some(c) => c
            .extract::<PyCamera>()
            .map_err(|_| value_error("camera: expected a lanecast.Camera")),
    }
}

// ------------------------------------------------------------------------------------------
// Scene

// A scene and its prepared views for one precision, in one value: `Views` borrows the scene.
self_cell::self_cell!(
    struct Prepared {
        owner: Arc<Scene>,
        #[not_covariant]
        dependent: Views,
    }
);

/// A loaded, validated scene, and its prepared views (one per precision, made on first use and
/// kept for every later render).
#[pyclass(frozen, module = "lanecast._lanecast", name = "Scene")]
struct PyScene {
    scene: Arc<Scene>,
    prepared: Mutex<[Option<Arc<Prepared>>; 3]>,
}

impl PyScene {
    fn new(scene: Scene) -> PyScene {
        PyScene {
            scene: Arc::new(scene),
            prepared: Mutex::new([None, None, None]),
        }
    }

    fn prepared(&self, precision: usize) -> PyResult<Arc<Prepared>> {
        let mut slots = self.prepared.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(p) = &slots[precision] {
            return Ok(p.clone());
        }
        let options = Options {
            method: PRECISIONS[precision].1,
            ..Options::default()
        };
        let p = Prepared::try_new(self.scene.clone(), |s| Views::new(s, &options))
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        let p = Arc::new(p);
        slots[precision] = Some(p.clone());
        Ok(p)
    }
}

/// One loose shape's kind and numbers, for pickling: 0 sphere (cx cy cz r), 1 triangle (9),
/// 2 quad (12).
fn shape_numbers(s: &Shape, out: &mut Vec<f64>) -> u8 {
    match s {
        Shape::Sphere { center, radius } => {
            out.extend(center.to_array());
            out.push(*radius);
            0
        }
        Shape::Triangle(v) => {
            v.iter().for_each(|p| out.extend(p.to_array()));
            1
        }
        Shape::Quad(v) => {
            v.iter().for_each(|p| out.extend(p.to_array()));
            2
        }
    }
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

#[pymethods]
impl PyScene {
    /// Scene.load(path): a `.sc` scene (meshes included), or a `.obj` / `.ply` mesh alone
    /// seen by the command line's framing camera. Every rule of the command line applies;
    /// bad content raises lanecast.SceneError with file, line and column.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<PyScene> {
        let scene = run(py, None, || lanecast::load_scene(&path))?.map_err(|e| py_err(py, e))?;
        Ok(PyScene::new(scene))
    }

    /// Scene.from_arrays(vertices=(N, 3), triangles=(M, 3), quads=(Q, 4), spheres=(K, 4),
    /// camera=None): triangles and quads index `vertices` (any integer dtype); spheres are
    /// rows of centre and radius. Ids: triangles first, then quads, then spheres. Without a
    /// camera, the triangles are framed as `lanecast mesh.obj` frames a mesh. Bad arrays raise
    /// ValueError naming the array and row.
    #[staticmethod]
    #[pyo3(signature = (vertices = None, triangles = None, quads = None, spheres = None, camera = None, name = "<arrays>"))]
    fn from_arrays(
        py: Python<'_>,
        vertices: Option<&Bound<'_, PyAny>>,
        triangles: Option<&Bound<'_, PyAny>>,
        quads: Option<&Bound<'_, PyAny>>,
        spheres: Option<&Bound<'_, PyAny>>,
        camera: Option<&Bound<'_, PyAny>>,
        name: &str,
    ) -> PyResult<PyScene> {
        let v = float_rows::<3>(py, "vertices", vertices)?;
        let t = index_rows::<3>(py, "triangles", triangles)?;
        let q = index_rows::<4>(py, "quads", quads)?;
        let s = float_rows::<4>(py, "spheres", spheres)?;
        let cam = match camera {
            None => None,
            Some(c) => Some(
                c.extract::<PyCamera>()
                    .map_err(|_| value_error("camera: expected a lanecast.Camera"))?
                    .spec,
            ),
        };
        let source = PathBuf::from(name);
        let scene = run(py, None, || {
            lanecast::scene::scene_from_arrays(&source, cam, &v, &t, &q, &s)
        })?
        .map_err(|e| py_err(py, e))?;
        Ok(PyScene::new(scene))
    }

    /// Where the scene came from (its file, or the name given to from_arrays).
    #[getter]
    fn source(&self) -> PathBuf {
        self.scene.source.clone()
    }

    /// Warnings that did not stop the load (degenerate mesh triangles), each a full message.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scene.warnings.clone()
    }

    /// The scene's own camera (its `camera` line, or the framing camera).
    #[getter]
    fn camera(&self) -> PyCamera {
        PyCamera {
            spec: CameraSpec {
                fov_deg: Some(self.scene.camera.fov_deg.unwrap_or(lanecast::DEFAULT_FOV)),
                ..self.scene.camera
            },
            size: None,
        }
    }

    /// How many primitives of each type: (spheres, triangles, quads).
    #[getter]
    fn counts(&self) -> (usize, usize, usize) {
        self.scene.counts()
    }

    fn __len__(&self) -> usize {
        self.scene.shapes.len()
    }

    fn __repr__(&self) -> String {
        let (s, t, q) = self.scene.counts();
        format!(
            "lanecast.Scene({:?}: {s} spheres, {t} triangles, {q} quads)",
            self.scene.source
        )
    }

    /// scene.render(camera=None, width=None, height=None, precision="auto", threads=None,
    /// zdepth=False): one view, as a `Render` with `ids` (H, W) int32 (-1: background) and
    /// `depth` (H, W) float32 (distance along the unit ray, +inf: background), and `zdepth`
    /// (distance along the optical axis) when asked for. `camera` None is the scene's own;
    /// the size is the camera's (from intrinsics), else 640x480. The ids and depth buffers
    /// are the library's, moved into numpy without a copy. The GIL is released while the
    /// view renders, on `threads` threads (None: all cores).
    #[pyo3(signature = (camera = None, width = None, height = None, precision = "auto", threads = None, zdepth = false))]
    #[allow(clippy::too_many_arguments)]
    fn render(
        &self,
        py: Python<'_>,
        camera: Option<&Bound<'_, PyAny>>,
        width: Option<u32>,
        height: Option<u32>,
        precision: &str,
        threads: Option<usize>,
        zdepth: bool,
    ) -> PyResult<Render> {
        let cam = camera_arg(&self.scene, camera)?.resolve(width, height)?;
        let prepared = self.prepared(precision_index(precision)?)?;
        let (frame, z) = run(py, threads, || {
            prepared.with_dependent(|_, views| {
                let frame = views.render(&cam)?;
                let z = zdepth.then(|| z_depth(&cam, &frame.depth));
                Ok::<_, lanecast::Error>((frame, z))
            })
        })?
        .map_err(|e| py_err(py, e))?;
        let (h, w) = (frame.height as usize, frame.width as usize);
        let ids = Array2::from_shape_vec((h, w), frame.ids).expect("h * w ids");
        let depth = Array2::from_shape_vec((h, w), frame.depth).expect("h * w depths");
        let z = z.map(|z| {
            let z = Array2::from_shape_vec((h, w), z).expect("h * w");
            z.into_pyarray(py).into_any().unbind()
        });
        Ok(Render {
            ids: ids.into_pyarray(py).into_any().unbind(),
            depth: depth.into_pyarray(py).into_any().unbind(),
            z,
        })
    }

    /// scene.render_views(cameras, width=None, height=None, precision="auto", threads=None,
    /// zdepth=False): many views from the scene's prepared views, as one `Render` whose arrays
    /// are stacked (V, H, W), view v from cameras[v]; every camera must give the same size.
    /// Each view is rendered by the library into its recycled frame and copied into the
    /// stacked arrays. The GIL is released for the whole batch.
    #[pyo3(signature = (cameras, width = None, height = None, precision = "auto", threads = None, zdepth = false))]
    #[allow(clippy::too_many_arguments)]
    fn render_views(
        &self,
        py: Python<'_>,
        cameras: &Bound<'_, PyAny>,
        width: Option<u32>,
        height: Option<u32>,
        precision: &str,
        threads: Option<usize>,
        zdepth: bool,
    ) -> PyResult<Render> {
        let mut cams = Vec::new();
        for (v, c) in cameras.try_iter()?.enumerate() {
            let c = c?;
            let cam = c
                .extract::<PyCamera>()
                .map_err(|_| value_error(format!("cameras[{v}]: expected a lanecast.Camera")))?;
            let cam = cam
                .resolve(width, height)
                .map_err(|e| value_error(format!("cameras[{v}]: {e}")))?;
            if let Some(first) = cams.first().map(|c: &lanecast::Camera| (c.width, c.height))
                && first != (cam.width, cam.height)
            {
                return Err(value_error(format!(
                    "cameras[{v}]: {}x{} images, but cameras[0] {}x{}",
                    cam.width, cam.height, first.0, first.1
                )));
            }
            cams.push(cam);
        }
        let (w, h) = match cams.first() {
            Some(c) => (c.width as usize, c.height as usize),
            None => (
                width.unwrap_or(640) as usize,
                height.unwrap_or(480) as usize,
            ),
        };
        let prepared = self.prepared(precision_index(precision)?)?;
        let n = w * h;
        let out = run(py, threads, || {
            prepared.with_dependent(|_, views| {
                let mut ids = Vec::with_capacity(cams.len() * n);
                let mut depth = Vec::with_capacity(cams.len() * n);
                let mut zd = Vec::with_capacity(if zdepth { cams.len() * n } else { 0 });
                for (v, cam) in cams.iter().enumerate() {
                    let frame = views.render(cam).map_err(|e| (v, e))?;
                    ids.extend_from_slice(&frame.ids);
                    depth.extend_from_slice(&frame.depth);
                    if zdepth {
                        zd.extend(z_depth(cam, &frame.depth));
                    }
                    views.recycle(frame);
                }
                Ok::<_, (usize, lanecast::Error)>((ids, depth, zd))
            })
        })?;
        let (ids, depth, zd) = out.map_err(|(v, e)| {
            let err = py_err(py, e);
            let msg = format!("cameras[{v}]: {}", err.value(py));
            match err.is_instance_of::<PyValueError>(py) {
                true if !err.is_instance(py, &scene_error_class(py)) => value_error(msg),
                _ => err,
            }
        })?;
        let v = cams.len();
        let arr = |x| Array3::from_shape_vec((v, h, w), x).expect("v * h * w");
        let ids = Array3::from_shape_vec((v, h, w), ids).expect("v * h * w");
        let z = zdepth.then(|| arr(zd).into_pyarray(py).into_any().unbind());
        Ok(Render {
            ids: ids.into_pyarray(py).into_any().unbind(),
            depth: arr(depth).into_pyarray(py).into_any().unbind(),
            z,
        })
    }

    /// The scene by value, compactly, for pickling: (version, source, camera, fov or None,
    /// warnings, runs), each run ("loose", kinds uint8, numbers float64, lines uint32) or
    /// ("mesh", vertices float64 (n, 3), faces uint32 (m, 3), line).
    fn _state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let s = &self.scene;
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
        (
            1u32,
            s.source.clone(),
            (c.eye.to_array(), c.look.to_array(), c.up.to_array()),
            c.fov_deg,
            s.warnings.clone(),
            PyList::new(py, parts)?,
        )
            .into_pyobject(py)
    }

    /// The scene `_state` gave. The state is trusted as any pickle is (it was a validated
    /// scene), but its structure is checked, so a damaged one raises ValueError.
    #[staticmethod]
    #[allow(clippy::type_complexity)]
    fn _from_state(
        state: (
            u32,
            PathBuf,
            ([f64; 3], [f64; 3], [f64; 3]),
            Option<f64>,
            Vec<String>,
            Vec<Bound<'_, PyTuple>>,
        ),
    ) -> PyResult<PyScene> {
        let (version, source, (eye, look, up), fov_deg, warnings, parts) = state;
        if version != 1 {
            return Err(corrupt(&format!("version {version}")));
        }
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
                        let n = [4, 9, 12].get(*k as usize).ok_or_else(|| corrupt("kind"))?;
                        let x = nums.get(at..at + n).ok_or_else(|| corrupt("numbers"))?;
                        at += n;
                        let p = |i: usize| glam::DVec3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
                        let shape = match k {
                            0 => Shape::Sphere {
                                center: p(0),
                                radius: x[3],
                            },
                            1 => Shape::Triangle([p(0), p(1), p(2)]),
                            _ => Shape::Quad([p(0), p(1), p(2), p(3)]),
                        };
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
        Ok(PyScene::new(Scene {
            source,
            camera: CameraSpec {
                eye: glam::DVec3::from_array(eye),
                look: glam::DVec3::from_array(look),
                up: glam::DVec3::from_array(up),
                fov_deg,
            },
            shapes,
            warnings,
        }))
    }
}

/// A render's buffers: `ids` and `depth`, (H, W) for one view or (V, H, W) for a batch, and
/// `zdepth` when the render asked for it.
#[pyclass(frozen, module = "lanecast._lanecast", name = "Render")]
struct Render {
    /// Primitive id per pixel, int32, -1 for background; row 0 at the top.
    #[pyo3(get)]
    ids: Py<PyAny>,
    /// Distance along the unit ray per pixel, float32, +inf for background.
    #[pyo3(get)]
    depth: Py<PyAny>,
    z: Option<Py<PyAny>>,
}

#[pymethods]
impl Render {
    /// Distance along the camera's forward axis (the z of OpenCV's camera frame), float32,
    /// +inf for background: `depth` times the cosine between each pixel's ray and the axis.
    /// Only when rendered with `zdepth=True`.
    #[getter]
    fn zdepth(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        match &self.z {
            Some(z) => Ok(z.clone_ref(py)),
            None => Err(pyo3::exceptions::PyAttributeError::new_err(
                "zdepth: render with zdepth=True (depth is the distance along the ray)",
            )),
        }
    }

    /// The image the command line writes for this render, uint8 (H, W, 3) (or (V, H, W, 3)):
    /// a colour per primitive, dimmed with distance (README "Colour").
    #[pyo3(signature = (color_mode = "random", variation = "linear", seed = 0))]
    fn image<'py>(
        &self,
        py: Python<'py>,
        color_mode: &str,
        variation: &str,
        seed: u64,
    ) -> PyResult<Bound<'py, PyAny>> {
        shade(
            py,
            self.ids.bind(py),
            self.depth.bind(py),
            color_mode,
            variation,
            seed,
        )
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let shape = self.ids.bind(py).getattr("shape")?.repr()?;
        Ok(format!("lanecast.Render(shape={shape})"))
    }
}

fn scene_error_class(py: Python<'_>) -> Bound<'_, PyAny> {
    py.import("lanecast._errors")
        .and_then(|m| m.getattr("SceneError"))
        .unwrap_or_else(|_| py.get_type::<PyValueError>().into_any())
}

/// Depth along the optical axis: each pixel's distance along its unit ray times the cosine
/// between that ray (the camera's f64 direction tables) and the forward axis. Background stays
/// +inf.
fn z_depth(cam: &lanecast::Camera, depth: &[f32]) -> Vec<f32> {
    let tables = cam.tables::<f64>(1, 1);
    let f = cam.f.to_array();
    let w = cam.width as usize;
    depth
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let d = tables.dir_x1(i % w, i / w);
            (t as f64 * (d[0] * f[0] + d[1] * f[1] + d[2] * f[2])) as f32
        })
        .collect()
}

// ------------------------------------------------------------------------------------------
// Shading

/// shade(ids, depth, color_mode="random", variation="linear", seed=0): the image the command
/// line writes for these buffers (README "Colour"), uint8 (H, W, 3); (V, H, W) buffers give
/// (V, H, W, 3), each view shaded on its own.
#[pyfunction]
#[pyo3(signature = (ids, depth, color_mode = "random", variation = "linear", seed = 0))]
fn shade<'py>(
    py: Python<'py>,
    ids: &Bound<'py, PyAny>,
    depth: &Bound<'py, PyAny>,
    color_mode: &str,
    variation: &str,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let mode = ColorMode::parse(color_mode).ok_or_else(|| {
        value_error(format!(
            "color_mode={color_mode:?}: must be \"random\" or \"ordered\""
        ))
    })?;
    let var = Variation::parse(variation).ok_or_else(|| {
        value_error(format!(
            "variation={variation:?}: must be \"linear\" or \"log\""
        ))
    })?;
    let np = py.import("numpy")?;
    let ids = np.call_method1("ascontiguousarray", (ids, "int32"))?;
    let depth = np.call_method1("ascontiguousarray", (depth, "float32"))?;
    let shape: Vec<usize> = ids.getattr("shape")?.extract()?;
    let dshape: Vec<usize> = depth.getattr("shape")?.extract()?;
    if shape != dshape || !(shape.len() == 2 || shape.len() == 3) {
        return Err(value_error(format!(
            "ids {shape:?} and depth {dshape:?}: expected the same shape, (H, W) or (V, H, W)"
        )));
    }
    let ids = ids.call_method1("reshape", (-1,))?;
    let depth = depth.call_method1("reshape", (-1,))?;
    let ids: PyReadonlyArray1<i32> = ids.extract()?;
    let depth: PyReadonlyArray1<f32> = depth.extract()?;
    let (hw, w) = (
        shape[shape.len() - 2] * shape[shape.len() - 1],
        shape[shape.len() - 1],
    );
    let (ids, depth) = (ids.as_slice()?, depth.as_slice()?);
    let mut out = Vec::with_capacity(ids.len() * 3);
    if hw > 0 {
        for (i, d) in ids.chunks(hw).zip(depth.chunks(hw)) {
            out.extend(lanecast::shade(i, d, w as u32, mode, var, seed));
        }
    }
    let mut full = shape.clone();
    full.push(3);
    let flat = out.into_pyarray(py);
    flat.call_method1("reshape", (PyTuple::new(py, full)?,))
}

/// The extension module; `lanecast/__init__.py` is the public face.
#[pymodule]
fn _lanecast(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_class::<PyCamera>()?;
    m.add_class::<Render>()?;
    m.add_function(wrap_pyfunction!(shade, m)?)?;
    m.add("INTRINSICS_TOL", INTRINSICS_TOL)?;
    Ok(())
}

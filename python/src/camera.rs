//! Cameras: `lanecast.Camera` (eye, look, up, fov; or from intrinsics and extrinsics), and the
//! camera arguments of a render.

use crate::args;
use crate::arrays::{py_shape, vec3};
use crate::errors::value_error;
use lanecast::{CameraSpec, Scene};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyList;

/// Tolerance of `Camera.from_intrinsics`, relative: the principal point's distance from the
/// image centre (to the image's size), fx against fy and the skew (to fx), and how far the
/// extrinsic's rotation is from orthonormal (entries of R Rᵀ - I).
pub(crate) const INTRINSICS_TOL: f64 = 1e-6;

/// What a pickled camera holds: eye, look, up, fov, size.
type CameraState = ([f64; 3], [f64; 3], [f64; 3], f64, Option<(u32, u32)>);

/// A pinhole camera: eye, look, up and horizontal field of view in degrees, as a scene's
/// `camera` line (README "Camera"); optionally tied to an image size (`from_intrinsics`).
#[pyclass(frozen, from_py_object, module = "lanecast._lanecast", name = "Camera")]
#[derive(Clone, Copy)]
pub(crate) struct PyCamera {
    pub(crate) spec: CameraSpec,
    pub(crate) size: Option<(u32, u32)>,
}

impl PyCamera {
    /// The library's camera for a `width` x `height` image: the size given (both, or one
    /// that agrees with the camera's own), else the camera's own (from intrinsics), else
    /// 640x480 as the command line. One size without the other, for a camera without its
    /// own, is a ValueError: no aspect ratio is guessed.
    pub(crate) fn resolve(
        &self,
        width: Option<u32>,
        height: Option<u32>,
    ) -> PyResult<lanecast::Camera> {
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
            (None, w, h) => both_or_neither(w, h)?,
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
        #[pyo3(from_py_with = args::width)] width: u32,
        #[pyo3(from_py_with = args::height)] height: u32,
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
    /// The size as for `Scene.render`: both, or neither.
    #[pyo3(signature = (width = None, height = None))]
    fn rays<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = args::opt_width)] width: Option<u32>,
        #[pyo3(from_py_with = args::opt_height)] height: Option<u32>,
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

/// An image size of a camera without its own: `width` and `height` together, or neither for
/// 640x480 (the command line's default); one alone is refused rather than completed.
pub(crate) fn both_or_neither(width: Option<u32>, height: Option<u32>) -> PyResult<(u32, u32)> {
    match (width, height) {
        (Some(w), Some(h)) => Ok((w, h)),
        (None, None) => Ok((640, 480)),
        (w, h) => {
            let given = match (w, h) {
                (Some(w), _) => format!("width={w}"),
                (_, h) => format!("height={}", h.unwrap_or_default()),
            };
            Err(value_error(format!(
                "width and height: give both, or neither for 640x480 (got {given} alone; the \
                 camera's field of view is horizontal, so no height follows from a width)"
            )))
        }
    }
}

/// A camera argument: a `Camera`, or None for the scene's own.
pub(crate) fn camera_arg(scene: &Scene, camera: Option<&Bound<'_, PyAny>>) -> PyResult<PyCamera> {
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

/// A `cameras` argument: each a `Camera`, resolved for the size given, all of one size.
pub(crate) fn cameras_arg(
    cameras: &Bound<'_, PyAny>,
    width: Option<u32>,
    height: Option<u32>,
) -> PyResult<Vec<lanecast::Camera>> {
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
    Ok(cams)
}

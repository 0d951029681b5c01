//! Cameras: `lanecast.Camera` (eye, look, up, fov; or from intrinsics and extrinsics), and the
//! camera arguments of a render.

use crate::args;
use crate::arrays::{py_shape, vec3};
use crate::errors::value_error;
use lanecast::{CameraSpec, Lens, Scene};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray2, PyArray3, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyList;

/// What a pickled camera holds: eye, look, up, fov, size, intrinsics (fx, fy, cx, cy) or None.
type CameraState = (
    [f64; 3],
    [f64; 3],
    [f64; 3],
    f64,
    Option<(u32, u32)>,
    Option<(f64, f64, f64, f64)>,
);

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

    /// The camera of K (3x3) and a world-to-camera extrinsic (4x4, OpenCV axes) for a
    /// `width` x `height` image: the library's `camera::spec_from_matrices`, then its checks
    /// for that size (`Camera::look_at`).
    fn from_matrices(
        k: [[f64; 3]; 3],
        e: [[f64; 4]; 4],
        width: u32,
        height: u32,
    ) -> Result<PyCamera, String> {
        let spec = lanecast::spec_from_matrices(&k, &e).map_err(|e| e.to_string())?;
        lanecast::Camera::look_at(&spec, width, height).map_err(|e| e.to_string())?;
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
            lens: Some(lanecast::Lens::Fov(fov)),
        };
        PyCamera::checked(spec, None)
    }

    /// Camera.from_intrinsics(K, extrinsic, width, height): the camera of a 3x3 intrinsic
    /// matrix and a 4x4 world-to-camera extrinsic matrix, OpenCV/Open3D convention (x right,
    /// y down, z forward; pixel x's centre at x + 0.5, as Open3D's `create_rays_pinhole`).
    /// K is any pinhole: positive fx and fy (not necessarily equal), any principal point (cx,
    /// cy) within `limits::MAX_PRINCIPAL_OFFSET` image sizes of the centre, skew 0; the
    /// extrinsic's 3x3 a rotation within RIGID_TOL. Anything else raises ValueError.
    /// `extrinsic` of shape (V, 4, 4) (and K (3, 3) or (V, 3, 3)) gives a list of V cameras.
    /// The camera keeps its image size.
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

    /// Horizontal field of view, degrees: as given, or for intrinsics `2 atan(W / (2 fx))` of
    /// the camera's image (the field of view its principal point is centred in, when it is).
    #[getter]
    fn fov(&self) -> f64 {
        match (self.spec.lens, self.size) {
            (Some(Lens::Pinhole(k)), Some((w, _))) => {
                (2.0 * (w as f64 / (2.0 * k.fx)).atan()).to_degrees()
            }
            _ => self.spec.fov_deg().unwrap_or(lanecast::DEFAULT_FOV),
        }
    }

    /// (fx, fy, cx, cy) in pixels for a camera made from intrinsics, else None.
    #[getter]
    fn intrinsics(&self) -> Option<(f64, f64, f64, f64)> {
        match self.spec.lens {
            Some(Lens::Pinhole(k)) => Some((k.fx, k.fy, k.cx, k.cy)),
            _ => None,
        }
    }

    /// The 3x3 K of the camera for a `width` x `height` image (its own size when it has one),
    /// float64: `[[fx, 0, cx], [0, fy, cy], [0, 0, 1]]`, a field of view's
    /// `fx = fy = W / (2 tan(fov/2))`, `cx = W/2`, `cy = H/2` (README "Camera").
    #[pyo3(name = "K", signature = (width = None, height = None))]
    fn k_matrix<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = args::opt_width)] width: Option<u32>,
        #[pyo3(from_py_with = args::opt_height)] height: Option<u32>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let cam = self.resolve(width, height)?;
        Ok(PyArray2::from_owned_array(py, matrix(cam.k_matrix())))
    }

    /// The 4x4 world-to-camera matrix, OpenCV axes (x right, y down, z forward), float64.
    fn extrinsic<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (w, h) = self.size.unwrap_or((640, 480));
        let cam =
            lanecast::Camera::look_at(&self.spec, w, h).map_err(|e| value_error(e.to_string()))?;
        Ok(PyArray2::from_owned_array(
            py,
            matrix(cam.world_to_camera()),
        ))
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
        let lens = match self.intrinsics() {
            Some(k) => format!("intrinsics={k:?}"),
            None => format!("fov={}", self.fov()),
        };
        format!(
            "Camera(eye={:?}, look={:?}, up={:?}, {lens}{size})",
            self.eye(),
            self.look(),
            self.up(),
        )
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.extract::<PyCamera>() {
            Ok(o) => o.spec == self.spec && o.size == self.size,
            Err(_) => false,
        }
    }

    /// (eye, look, up, fov, size, intrinsics): what pickling keeps.
    fn _state(&self) -> CameraState {
        (
            self.eye(),
            self.look(),
            self.up(),
            self.fov(),
            self.size,
            self.intrinsics(),
        )
    }

    #[staticmethod]
    fn _from_state(state: CameraState) -> PyResult<PyCamera> {
        let (eye, look, up, fov, size, k) = state;
        let lens = match k {
            Some((fx, fy, cx, cy)) => Lens::Pinhole(lanecast::Intrinsics { fx, fy, cx, cy }),
            None => Lens::Fov(fov),
        };
        let spec = CameraSpec {
            eye: glam::DVec3::from_array(eye),
            look: glam::DVec3::from_array(look),
            up: glam::DVec3::from_array(up),
            lens: Some(lens),
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

/// A row-major matrix as an ndarray.
pub(crate) fn matrix<const R: usize, const C: usize>(m: [[f64; C]; R]) -> Array2<f64> {
    Array2::from_shape_vec((R, C), m.into_iter().flatten().collect()).expect("R x C values")
}

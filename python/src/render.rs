//! Rendering and results: views rendered from a scene's prepared views into `lanecast.Render`
//! (ids, depth, z-depth as numpy arrays), and `shade`.

use crate::errors::{py_err, scene_error_class, value_error};
use crate::scene::Prepared;
use crate::threads::run;
use lanecast::{ColorMode, Variation};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// A render's buffers: `ids` and `depth`, (H, W) for one view or (V, H, W) for a batch, and
/// `zdepth` when the render asked for it.
#[pyclass(frozen, module = "lanecast._lanecast", name = "Render")]
pub(crate) struct Render {
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

/// One view from `prepared` through `cam`, the GIL released on `threads` threads: the
/// library's ids and depth buffers moved into numpy without a copy, and the optical-axis
/// depth when `zdepth`.
pub(crate) fn one(
    py: Python<'_>,
    prepared: &Prepared,
    cam: &lanecast::Camera,
    threads: Option<usize>,
    zdepth: bool,
) -> PyResult<Render> {
    let (frame, z) = run(py, threads, || {
        prepared.with_dependent(|_, views| {
            let frame = views.render(cam)?;
            let z = zdepth.then(|| z_depth(cam, &frame.depth));
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

/// Many views from `prepared`, `cams` all `w` x `h`, the GIL released for the whole batch:
/// each view rendered by the library into its recycled frame and copied into the stacked
/// (V, H, W) arrays; an error names the camera it came from.
pub(crate) fn views(
    py: Python<'_>,
    prepared: &Prepared,
    cams: &[lanecast::Camera],
    (w, h): (usize, usize),
    threads: Option<usize>,
    zdepth: bool,
) -> PyResult<Render> {
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

/// shade(ids, depth, color_mode="random", variation="linear", seed=0): the image the command
/// line writes for these buffers (README "Colour"), uint8 (H, W, 3); (V, H, W) buffers give
/// (V, H, W, 3), each view shaded on its own.
#[pyfunction]
#[pyo3(signature = (ids, depth, color_mode = "random", variation = "linear", seed = 0))]
pub(crate) fn shade<'py>(
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

//! Rendering and results: views rendered from a scene's prepared views into `lanecast.Render`
//! (ids, depth, and on request z-depth and normals, as numpy arrays), and `shade`.

use crate::args;
use crate::errors::{py_err, scene_error_class, value_error};
use crate::threads::run;
use lanecast::Frame;
use lanecast::scene::RangeClusters;
use lanecast::world::{self, World};
use lanecast::{ColorMode, Precision, Scene, Variation, Views};
use numpy::ndarray::{ArrayD, IxDyn};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::sync::Arc;

// A scene and its prepared views for one precision, in one value: `Views` borrows the scene.
self_cell::self_cell!(
    pub(crate) struct Prepared {
        owner: Arc<Scene>,
        #[not_covariant]
        dependent: Views,
    }
);

/// A render's buffers: `ids` and `depth`, (H, W) for one view or (V, H, W) for a batch, and
/// `zdepth` and `normals` when the render asked for them.
#[pyclass(frozen, module = "lanecast._lanecast", name = "Render")]
pub(crate) struct Render {
    /// Primitive id per pixel, int32, -1 for background; row 0 at the top.
    #[pyo3(get)]
    ids: Py<PyAny>,
    /// Distance along the unit ray per pixel, float32, +inf for background.
    #[pyo3(get)]
    depth: Py<PyAny>,
    z: Option<Py<PyAny>>,
    n: Option<Py<PyAny>>,
    /// Each view's 3x3 intrinsic matrix, float64: (3, 3), or (V, 3, 3) for a batch
    /// (`Camera::k_matrix`: a field of view's too).
    #[pyo3(get, name = "K")]
    k: Py<PyAny>,
    /// Each view's 4x4 world-to-camera matrix, OpenCV axes (x right, y down, z forward),
    /// float64: (4, 4), or (V, 4, 4) for a batch.
    #[pyo3(get)]
    extrinsics: Py<PyAny>,
}

/// What a render computes beside ids and depth (the library's `Frame::z_depth`,
/// `Frame::normals`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Extras {
    pub(crate) zdepth: bool,
    pub(crate) normals: bool,
}

#[pymethods]
impl Render {
    /// Distance along the camera's forward axis (the z of OpenCV's camera frame), float32,
    /// +inf for background: `depth` times the cosine between each pixel's ray and the axis.
    /// Only when rendered with `zdepth=True`.
    #[getter]
    fn zdepth(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        asked(
            py,
            &self.z,
            "zdepth: render with zdepth=True (depth is the distance along the ray)",
        )
    }

    /// Unit surface normal of each pixel's hit, world coordinates, facing the camera, float32
    /// (H, W, 3) (or (V, H, W, 3)); (0, 0, 0) for background. Only when rendered with
    /// `normals=True`.
    #[getter]
    fn normals(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        asked(py, &self.n, "normals: render with normals=True")
    }

    /// The image the command line writes for this render, uint8 (H, W, 3) (or (V, H, W, 3)):
    /// a colour per primitive, dimmed with distance (README "Colour").
    #[pyo3(signature = (color_mode = "random", variation = "linear", seed = 0))]
    fn image<'py>(
        &self,
        py: Python<'py>,
        color_mode: &str,
        variation: &str,
        #[pyo3(from_py_with = args::seed)] seed: u64,
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

/// An extra the render computed, or an `AttributeError` saying how to ask for it.
fn asked(py: Python<'_>, extra: &Option<Py<PyAny>>, how: &str) -> PyResult<Py<PyAny>> {
    match extra {
        Some(x) => Ok(x.clone_ref(py)),
        None => Err(pyo3::exceptions::PyAttributeError::new_err(how.to_string())),
    }
}

/// `data` as a numpy array of shape `shape`, moved without a copy.
fn array<T: numpy::Element>(py: Python<'_>, data: Vec<T>, shape: &[usize]) -> Py<PyAny> {
    let a = ArrayD::from_shape_vec(IxDyn(shape), data).expect("the buffer fills the shape");
    a.into_pyarray(py).into_any().unbind()
}

impl Render {
    /// The buffers of one view (`lead` empty) or of a batch (`lead` = [V]), each view `h` x
    /// `w`, moved into numpy arrays: ids and depth (lead, H, W), z-depth likewise and normals
    /// (lead, H, W, 3) when computed.
    fn from_buffers(
        py: Python<'_>,
        lead: &[usize],
        cams: &[lanecast::Camera],
        (h, w): (usize, usize),
        (ids, depth): (Vec<i32>, Vec<f32>),
        z: Option<Vec<f32>>,
        n: Option<Vec<[f32; 3]>>,
    ) -> Render {
        let shape = [lead, &[h, w]].concat();
        let ks: Vec<f64> = cams
            .iter()
            .flat_map(|c| c.k_matrix().into_iter().flatten())
            .collect();
        let es: Vec<f64> = (cams.iter())
            .flat_map(|c| c.world_to_camera().into_iter().flatten())
            .collect();
        Render {
            ids: array(py, ids, &shape),
            depth: array(py, depth, &shape),
            z: z.map(|z| array(py, z, &shape)),
            n: n.map(|n| array(py, n.into_flattened(), &[&shape[..], &[3]].concat())),
            k: array(py, ks, &[lead, &[3, 3]].concat()),
            extrinsics: array(py, es, &[lead, &[4, 4]].concat()),
        }
    }
}

/// What renders a scene's views: its per-eye views (`accel="auto"`), or the world engine's
/// prepared scene (`accel="world"`), held directly, with the range check's cluster bounds.
pub(crate) enum Engine {
    Views(Arc<Prepared>),
    World {
        scene: Arc<lanecast::Scene>,
        world: Arc<World>,
        range: Arc<RangeClusters>,
        precision: Precision,
    },
}

impl Engine {
    /// Runs `f` with a renderer of single views (`cam`, the spare frame to fill) and the scene.
    fn with<R>(
        &self,
        f: impl FnOnce(
            &mut dyn FnMut(
                &lanecast::Camera,
                Option<Frame<f32>>,
            ) -> Result<Frame<f32>, lanecast::Error>,
            &lanecast::Scene,
        ) -> R,
    ) -> R {
        match self {
            Engine::Views(prepared) => prepared.with_dependent(|_, views| {
                let mut one = |cam: &lanecast::Camera, spare: Option<Frame<f32>>| {
                    if let Some(spare) = spare {
                        views.recycle(spare);
                    }
                    views.render(cam)
                };
                f(&mut one, views.scene())
            }),
            Engine::World {
                scene,
                world,
                range,
                precision,
            } => {
                let mut scratch = world::Scratch::default();
                let mut one = |cam: &lanecast::Camera, spare: Option<Frame<f32>>| {
                    // the command line's f32 range check of the scene from this eye
                    if cam.eye != scene.camera.eye {
                        range.check(scene, cam.eye)?;
                    }
                    Ok(world.render_marking(cam, *precision, &mut scratch, spare).0)
                };
                f(&mut one, scene)
            }
        }
    }
}

/// One view from `prepared` through `cam`, the GIL released on `threads` threads: the
/// library's ids and depth buffers moved into numpy without a copy, and the extras asked for.
pub(crate) fn one(
    py: Python<'_>,
    engine: &Engine,
    cam: &lanecast::Camera,
    threads: Option<usize>,
    extras: Extras,
) -> PyResult<Render> {
    let (frame, z, n) = run(py, threads, || {
        engine.with(|render, scene| {
            let frame = render(cam, None)?;
            let z = extras.zdepth.then(|| frame.z_depth(cam));
            let n = extras.normals.then(|| frame.normals(scene, cam));
            Ok::<_, lanecast::Error>((frame, z, n))
        })
    })?
    .map_err(|e| py_err(py, e))?;
    let size = (frame.height as usize, frame.width as usize);
    let buffers = (frame.ids, frame.depth);
    Ok(Render::from_buffers(
        py,
        &[],
        std::slice::from_ref(cam),
        size,
        buffers,
        z,
        n,
    ))
}

/// Many views from `prepared`, `cams` all `w` x `h`, the GIL released for the whole batch:
/// each view rendered by the library into its recycled frame and copied into the stacked
/// (V, H, W) arrays; an error names the camera it came from.
pub(crate) fn views(
    py: Python<'_>,
    engine: &Engine,
    cams: &[lanecast::Camera],
    (w, h): (usize, usize),
    threads: Option<usize>,
    extras: Extras,
) -> PyResult<Render> {
    let n = w * h;
    let room = |on: bool, per: usize| if on { cams.len() * per } else { 0 };
    let out = run(py, threads, || {
        engine.with(|render, scene| {
            let mut ids = Vec::with_capacity(cams.len() * n);
            let mut depth = Vec::with_capacity(cams.len() * n);
            let mut zd = Vec::with_capacity(room(extras.zdepth, n));
            let mut nd: Vec<[f32; 3]> = Vec::with_capacity(room(extras.normals, n));
            let mut spare = None;
            for (v, cam) in cams.iter().enumerate() {
                let frame = render(cam, spare.take()).map_err(|e| (v, e))?;
                ids.extend_from_slice(&frame.ids);
                depth.extend_from_slice(&frame.depth);
                if extras.zdepth {
                    zd.extend(frame.z_depth(cam));
                }
                if extras.normals {
                    nd.extend(frame.normals(scene, cam));
                }
                spare = Some(frame);
            }
            Ok::<_, (usize, lanecast::Error)>((ids, depth, zd, nd))
        })
    })?;
    let (ids, depth, zd, nd) = out.map_err(|(v, e)| {
        let err = py_err(py, e);
        let msg = format!("cameras[{v}]: {}", err.value(py));
        match err.is_instance_of::<PyValueError>(py) {
            true if !err.is_instance(py, &scene_error_class(py)) => value_error(msg),
            _ => err,
        }
    })?;
    let z = extras.zdepth.then_some(zd);
    let n = extras.normals.then_some(nd);
    Ok(Render::from_buffers(
        py,
        &[cams.len()],
        cams,
        (h, w),
        (ids, depth),
        z,
        n,
    ))
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
    #[pyo3(from_py_with = args::seed)] seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let mode = ColorMode::parse(color_mode)
        .filter(|m| !m.needs_light())
        .ok_or_else(|| {
            value_error(format!(
                "color_mode={color_mode:?}: must be \"random\" or \"ordered\" (the command \
                 line's -cm shade lights each hit by its surface normal, which ids and depth \
                 alone do not give)"
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
            out.extend(lanecast::shade(i, d, None, w as u32, mode, var, seed));
        }
    }
    let mut full = shape.clone();
    full.push(3);
    let flat = out.into_pyarray(py);
    flat.call_method1("reshape", (PyTuple::new(py, full)?,))
}

//! Scenes: `lanecast.Scene`, loaded from a file or from arrays, with its prepared views (one
//! per precision); renders and pickling delegate to `render` and `pickle`.

use crate::args;
use crate::arrays::{float_rows, index_rows};
use crate::camera::{PyCamera, camera_arg, cameras_arg};
use crate::errors::{py_err, value_error};
use crate::pickle::{self, SceneState};
use crate::render::{self, Engine, Extras, Prepared, Render};
use crate::threads::run;
use lanecast::scene::RangeClusters;
use lanecast::world::World;
use lanecast::{CameraSpec, Options, Precision, Scene, Views};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};

/// The index of `--precision`'s `name` in `Precision::ALL`: a slot of a scene's prepared views.
fn precision_index(name: &str) -> PyResult<usize> {
    Precision::ALL
        .iter()
        .position(|p| p.name() == name)
        .ok_or_else(|| {
            value_error(format!(
                "precision={name:?}: must be \"auto\", \"f32\" or \"f64\""
            ))
        })
}

/// A loaded, validated scene, and what is prepared from it once: its per-eye views (one per
/// precision) and, for `accel="world"`, the world engine's prepared scene with the range
/// check's cluster bounds; each made on first use and kept for every later render.
#[pyclass(frozen, module = "lanecast._lanecast", name = "Scene")]
pub(crate) struct PyScene {
    scene: Arc<Scene>,
    prepared: Mutex<[Option<Arc<Prepared>>; 3]>,
    world: OnceLock<(Arc<World>, Arc<RangeClusters>)>,
}

impl PyScene {
    fn new(scene: Scene) -> PyScene {
        PyScene {
            scene: Arc::new(scene),
            prepared: Mutex::new([None, None, None]),
            world: OnceLock::new(),
        }
    }

    /// What renders with `accel` (`"auto"`: the command line's default, the per-eye views;
    /// `"world"`: the world engine, `--accel world`) in `precision`; built on first use with
    /// the GIL released, on `threads` threads.
    fn engine(
        &self,
        py: Python<'_>,
        accel: &str,
        precision: &str,
        threads: Option<usize>,
    ) -> PyResult<Engine> {
        let p = precision_index(precision)?;
        match accel {
            "auto" => Ok(Engine::Views(self.prepared(p)?)),
            "world" => {
                let (world, range) = match self.world.get() {
                    Some(w) => w.clone(),
                    None => {
                        let scene = &self.scene;
                        let made = run(py, threads, || {
                            (
                                Arc::new(World::new(scene)),
                                Arc::new(RangeClusters::new(scene)),
                            )
                        })?;
                        self.world.get_or_init(|| made).clone()
                    }
                };
                Ok(Engine::World {
                    scene: self.scene.clone(),
                    world,
                    range,
                    precision: Precision::ALL[p],
                })
            }
            _ => Err(value_error(format!(
                "accel={accel:?}: must be \"auto\" or \"world\""
            ))),
        }
    }

    fn prepared(&self, precision: usize) -> PyResult<Arc<Prepared>> {
        let mut slots = self.prepared.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(p) = &slots[precision] {
            return Ok(p.clone());
        }
        let options = Options {
            precision: Precision::ALL[precision],
            ..Options::default()
        };
        let p = Prepared::try_new(self.scene.clone(), |s| Views::new(s, &options))
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        let p = Arc::new(p);
        slots[precision] = Some(p.clone());
        Ok(p)
    }
}

#[pymethods]
impl PyScene {
    /// Scene.load(path): a `.sc` scene (meshes included), or a `.obj` / `.ply` mesh alone
    /// seen by the command line's framing camera. Every rule of the command line applies;
    /// bad content raises lanecast.SceneError with file, line and column.
    /// `path`: str, bytes or os.PathLike; a file that cannot be read raises OSError (errno and
    /// filename set; FileNotFoundError when missing).
    #[staticmethod]
    fn load(py: Python<'_>, #[pyo3(from_py_with = args::path)] path: PathBuf) -> PyResult<PyScene> {
        let scene = run(py, None, || lanecast::load_scene(&path))?.map_err(|e| py_err(py, e))?;
        Ok(PyScene::new(scene))
    }

    /// Scene.from_arrays(vertices=(N, 3), triangles=(M, 3), quads=(Q, 4), spheres=(K, 4),
    /// camera=None): triangles and quads index `vertices` (any integer dtype); spheres are
    /// rows of centre and radius. Ids: triangles first, then quads, then spheres. Every row is
    /// validated first; then, without a camera, every primitive (triangles, quads, spheres) is
    /// framed as `lanecast -i mesh.obj` frames a mesh. Bad arrays raise ValueError naming the
    /// array and row.
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
                lens: Some(
                    (self.scene.camera.lens).unwrap_or(lanecast::Lens::Fov(lanecast::DEFAULT_FOV)),
                ),
                ..self.scene.camera
            },
            size: None,
        }
    }

    /// How many primitives of each kind, in `lanecast::scene::KINDS` order (spheres,
    /// triangles, quads).
    #[getter]
    fn counts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, self.scene.counts())
    }

    fn __len__(&self) -> usize {
        self.scene.shapes.len()
    }

    fn __repr__(&self) -> String {
        let counts = (lanecast::scene::KINDS.iter().zip(self.scene.counts()))
            .map(|(&(_, many), n)| format!("{n} {many}"))
            .collect::<Vec<_>>();
        format!(
            "lanecast.Scene({:?}: {})",
            self.scene.source,
            counts.join(", ")
        )
    }

    /// scene.render(camera=None, width=None, height=None, precision="auto", threads=None,
    /// zdepth=False, normals=False, accel="auto"): one view, as a `Render` with `ids` (H, W)
    /// int32 (-1: background) and `depth` (H, W) float32 (distance along the unit ray, +inf:
    /// background), and when asked for, `zdepth` (distance along the optical axis) and
    /// `normals` (H, W, 3). `accel`: "auto" (the command line's default) or "world" (the
    /// scene prepared once for every camera, kept by the scene: `--accel world`'s bytes).
    /// `camera` None is the scene's own. The size: `width` and `height` together, or neither
    /// for the camera's own (from intrinsics; one of the two, if given, must agree with it),
    /// else 640x480; one without the other is a ValueError, never a guessed size. The ids
    /// and depth buffers are the library's, moved into numpy without a copy. The GIL is
    /// released while the view renders, on `threads` threads (None: all cores). An integer
    /// argument out of range (`threads=-1`, `width=0`) is a ValueError naming it.
    #[pyo3(signature = (camera = None, width = None, height = None, precision = "auto", threads = None, zdepth = false, normals = false, accel = "auto"))]
    #[allow(clippy::too_many_arguments)]
    fn render(
        &self,
        py: Python<'_>,
        camera: Option<&Bound<'_, PyAny>>,
        #[pyo3(from_py_with = args::opt_width)] width: Option<u32>,
        #[pyo3(from_py_with = args::opt_height)] height: Option<u32>,
        precision: &str,
        #[pyo3(from_py_with = args::threads)] threads: Option<usize>,
        zdepth: bool,
        normals: bool,
        accel: &str,
    ) -> PyResult<Render> {
        let cam = camera_arg(&self.scene, camera)?.resolve(width, height)?;
        let engine = self.engine(py, accel, precision, threads)?;
        render::one(py, &engine, &cam, threads, Extras { zdepth, normals })
    }

    /// scene.render_views(cameras, width=None, height=None, precision="auto", threads=None,
    /// zdepth=False, normals=False, accel="auto"): many views from the scene's prepared views
    /// (`accel` as for `render`), as one
    /// `Render` whose arrays are stacked (V, H, W), view v from cameras[v]; every camera must
    /// give the same size (`width` and `height` as for `render`).
    /// Each view is rendered by the library into its recycled frame and copied into the
    /// stacked arrays. The GIL is released for the whole batch. Each view's setup fills the
    /// buffers of the view before; the scene keeps one view's buffers, per precision used,
    /// until it is freed.
    #[pyo3(signature = (cameras, width = None, height = None, precision = "auto", threads = None, zdepth = false, normals = false, accel = "auto"))]
    #[allow(clippy::too_many_arguments)]
    fn render_views(
        &self,
        py: Python<'_>,
        cameras: &Bound<'_, PyAny>,
        #[pyo3(from_py_with = args::opt_width)] width: Option<u32>,
        #[pyo3(from_py_with = args::opt_height)] height: Option<u32>,
        precision: &str,
        #[pyo3(from_py_with = args::threads)] threads: Option<usize>,
        zdepth: bool,
        normals: bool,
        accel: &str,
    ) -> PyResult<Render> {
        let cams = cameras_arg(cameras, width, height)?;
        let (w, h) = match cams.first() {
            Some(c) => (c.width as usize, c.height as usize),
            None => {
                let (w, h) = crate::camera::both_or_neither(width, height)?;
                (w as usize, h as usize)
            }
        };
        let engine = self.engine(py, accel, precision, threads)?;
        render::views(
            py,
            &engine,
            &cams,
            (w, h),
            threads,
            Extras { zdepth, normals },
        )
    }

    /// The scene by value, compactly, for pickling: (version, source, camera, fov or None,
    /// warnings, runs), each run ("loose", kinds uint8, numbers float64, lines uint32) or
    /// ("mesh", vertices float64 (n, 3), faces uint32 (m, 3), line).
    fn _state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        pickle::state(py, &self.scene)
    }

    /// The scene `_state` gave. The state is trusted as any pickle is (it was a validated
    /// scene), but its structure is checked, so a damaged one raises ValueError.
    #[staticmethod]
    fn _from_state(state: SceneState<'_>) -> PyResult<PyScene> {
        pickle::from_state(state).map(PyScene::new)
    }
}

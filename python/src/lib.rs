//! lanecast for Python: the extension module `lanecast._lanecast`, wrapped by the package in
//! `python/lanecast/`.
//!
//! This crate converts and delegates, nothing more: numpy arrays in (checked at the border for
//! shape, dtype and finite values, with errors naming the argument and row), numpy arrays out
//! (the library's buffers moved into numpy without a copy where the shape allows), and every
//! rule and every ray from the `lanecast` library: `load_scene`, `scene_from_arrays`,
//! `Camera::look_at`, `Views`, `shade`. The GIL is released around every load, validation and
//! render; `threads=` picks a rayon pool.

mod args;
mod arrays;
mod camera;
mod errors;
mod pickle;
mod render;
mod scene;
mod threads;

use camera::PyCamera;
use pyo3::prelude::*;
use render::{Render, shade};
use scene::PyScene;

/// The extension module; `lanecast/__init__.py` is the public face.
#[pymodule]
fn _lanecast(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_class::<PyCamera>()?;
    m.add_class::<Render>()?;
    m.add_function(wrap_pyfunction!(shade, m)?)?;
    m.add("RIGID_TOL", lanecast::scene::pose::RIGID_TOL)?;
    m.add("MAX_THREADS", lanecast::limits::MAX_THREADS)?;
    m.add("MAX_SIDE", lanecast::limits::MAX_SIDE)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

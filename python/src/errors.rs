//! Errors: the library's errors as the Python exceptions a caller expects.

use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::path::Path;

/// A library error as the Python exception a caller expects: bad content in a scene or mesh
/// file (with its file, line and column) as `lanecast.SceneError`, a file that cannot be read
/// as `OSError`, a bad argument as `ValueError`.
pub(crate) fn py_err(py: Python<'_>, e: lanecast::Error) -> PyErr {
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
        // OSError(errno, strerror, filename), the filename a str as open()'s: Python's str()
        // appends it, so the message is the library's without its path ("[Errno 2] cannot
        // read scene: No such file or directory: 'x.sc'").
        E::Io {
            source,
            path,
            action,
        } => match source.raw_os_error() {
            Some(code) => {
                let why = source.to_string();
                let why = why
                    .strip_suffix(&format!(" (os error {code})"))
                    .unwrap_or(&why);
                let why = format!("cannot {action}: {why}");
                PyOSError::new_err((code, why, path.as_os_str().to_os_string()))
            }
            None => PyOSError::new_err(text),
        },
        E::Usage(_) => PyValueError::new_err(text),
        _ => PyRuntimeError::new_err(text),
    }
}

pub(crate) fn value_error(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

pub(crate) fn scene_error_class(py: Python<'_>) -> Bound<'_, PyAny> {
    py.import("lanecast._errors")
        .and_then(|m| m.getattr("SceneError"))
        .unwrap_or_else(|_| py.get_type::<PyValueError>().into_any())
}

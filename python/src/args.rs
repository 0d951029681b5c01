//! Arguments that are not arrays: integers (image sizes, thread counts, seeds) and paths,
//! checked at the border with errors naming the argument.
//!
//! An integer is anything Python takes as one (`int`, numpy's integers: `__index__`); one out
//! of range, negative or huge, is a `ValueError` naming the argument, its value and the range
//! (`threads=-1: must be 1 to 1024`), never an `OverflowError`; anything else (a float, a
//! string) is a `TypeError` naming the argument.

use crate::errors::value_error;
use pyo3::exceptions::{PyOverflowError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyString};
use std::path::PathBuf;

/// `obj` as an integer in `lo..=hi` (`what` follows the range in the message).
fn int_in(name: &str, obj: &Bound<'_, PyAny>, lo: i128, hi: i128, what: &str) -> PyResult<i128> {
    let v = match obj.extract::<i128>() {
        Ok(v) => Some(v),
        Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => None,
        Err(_) => {
            let ty = obj.get_type().name()?;
            return Err(PyTypeError::new_err(format!(
                "{name}: expected an integer, not {ty}"
            )));
        }
    };
    match v {
        Some(v) if (lo..=hi).contains(&v) => Ok(v),
        _ => Err(value_error(format!(
            "{name}={}: must be {lo} to {hi}{what}",
            obj.str()?
        ))),
    }
}

fn side(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<u32> {
    let max = lanecast::limits::MAX_SIDE as i128;
    Ok(int_in(name, obj, 1, max, " pixels")? as u32)
}

fn optional<T>(
    obj: &Bound<'_, PyAny>,
    f: impl FnOnce(&Bound<'_, PyAny>) -> PyResult<T>,
) -> PyResult<Option<T>> {
    if obj.is_none() {
        Ok(None)
    } else {
        f(obj).map(Some)
    }
}

/// A `width=` argument: 1 to `limits::MAX_SIDE` pixels.
pub(crate) fn width(obj: &Bound<'_, PyAny>) -> PyResult<u32> {
    side("width", obj)
}

/// A `height=` argument: 1 to `limits::MAX_SIDE` pixels.
pub(crate) fn height(obj: &Bound<'_, PyAny>) -> PyResult<u32> {
    side("height", obj)
}

/// A `width=` argument or None.
pub(crate) fn opt_width(obj: &Bound<'_, PyAny>) -> PyResult<Option<u32>> {
    optional(obj, width)
}

/// A `height=` argument or None.
pub(crate) fn opt_height(obj: &Bound<'_, PyAny>) -> PyResult<Option<u32>> {
    optional(obj, height)
}

/// A `threads=` argument or None (all cores): 1 to `limits::MAX_THREADS`.
pub(crate) fn threads(obj: &Bound<'_, PyAny>) -> PyResult<Option<usize>> {
    let max = lanecast::limits::MAX_THREADS as i128;
    optional(obj, |o| Ok(int_in("threads", o, 1, max, "")? as usize))
}

/// A `seed=` argument: 0 to 2**64 - 1.
pub(crate) fn seed(obj: &Bound<'_, PyAny>) -> PyResult<u64> {
    Ok(int_in("seed", obj, 0, u64::MAX as i128, "")? as u64)
}

/// A path argument: `str`, `bytes` (any bytes the file system takes, as `os.fsencode` gives)
/// or an `os.PathLike` returning either.
pub(crate) fn path(obj: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    let os = obj.py().import("os")?;
    let fspath = os.call_method1("fspath", (obj,)).map_err(|_| {
        let ty = obj.get_type().name().map_or("?".into(), |n| n.to_string());
        PyTypeError::new_err(format!(
            "path: expected str, bytes or os.PathLike, not {ty}"
        ))
    })?;
    if let Ok(b) = fspath.cast::<PyBytes>() {
        // os.fsdecode: the file system's encoding, surrogateescape for bytes it cannot decode,
        // which PathBuf's extraction turns back into the same bytes.
        let s = os.call_method1("fsdecode", (b,))?;
        return s.extract();
    }
    match fspath.cast::<PyString>() {
        Ok(s) => s.extract(),
        Err(_) => Err(PyTypeError::new_err(
            "path: os.fspath gave neither str nor bytes",
        )),
    }
}

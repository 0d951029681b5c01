//! Arrays in: numpy arrays (and sequences) as the library's rows and vectors, checked at the
//! border for shape and dtype, with errors naming the argument.

use crate::errors::value_error;
use numpy::{PyArrayDescrMethods, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::prelude::*;

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
pub(crate) fn py_shape(shape: &[usize]) -> String {
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

pub(crate) fn float_rows<const K: usize>(
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
pub(crate) fn index_rows<const K: usize>(
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

pub(crate) fn vec3(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<glam::DVec3> {
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

//! Thread pools: the rayon pool `threads=` names, and running work in it with the GIL
//! released.

use crate::errors::value_error;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use rayon::ThreadPool;
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

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
pub(crate) fn run<T: Send>(
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

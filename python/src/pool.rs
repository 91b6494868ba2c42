//! The threads batches run on, also in a process forked from one that used them.
//!
//! Batches run on rayon's global pool. A process forked from one whose pool had started
//! inherits the pool without its threads (a fork copies only the thread that called it), so a
//! batch there would wait forever for workers that do not exist — as happens with Python's
//! `multiprocessing` on Linux, which forks by default. The package registers
//! [`after_fork_in_child`] with `os.register_at_fork`; from then on each calling thread runs
//! its batches on a pool of its own, made in the child.

use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How many forks this process descends from (0: not forked since the module was loaded).
static FORKS: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// The pool this thread made in its process (tagged by the fork count it was made at).
    static OWN_POOL: RefCell<Option<(u64, rayon::ThreadPool)>> = const { RefCell::new(None) };
}

/// Called by Python in the child after a fork (registered by `meshq/__init__.py`).
#[pyfunction]
pub fn after_fork_in_child() {
    FORKS.fetch_add(1, Ordering::SeqCst);
}

/// Runs `work` on the global pool, or, in a forked process, on a pool of this thread's own.
pub fn run<R: Send>(work: impl FnOnce() -> R + Send) -> PyResult<R> {
    let forks = FORKS.load(Ordering::SeqCst);
    if forks == 0 {
        return Ok(work());
    }
    OWN_POOL.with(|cell| {
        let mut own = cell.borrow_mut();
        if own.as_ref().is_none_or(|(made, _)| *made != forks) {
            // A pool made before the fork has no threads here: leave it (dropping it would
            // signal threads that are gone), make a new one.
            if let Some(stale) = own.take() {
                std::mem::forget(stale);
            }
            let pool = rayon::ThreadPoolBuilder::new().build().map_err(|e| {
                PyRuntimeError::new_err(format!("could not start threads after a fork: {e}"))
            })?;
            *own = Some((forks, pool));
        }
        match own.as_ref() {
            Some((_, pool)) => Ok(pool.install(work)),
            None => Err(PyRuntimeError::new_err("no thread pool")),
        }
    })
}

/// Runs `work` with the GIL released, on the threads [`run`] picks.
pub fn detached<R: Send>(py: Python<'_>, work: impl FnOnce() -> R + Send) -> PyResult<R> {
    py.detach(|| run(work))
}

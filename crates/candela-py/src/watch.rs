//! Long Rust work that Python can interrupt.
//!
//! The work runs on a scoped thread with the GIL released; the calling thread
//! wakes every few milliseconds to run Python's signal handlers
//! (`PyErr_CheckSignals`). When one raises (Ctrl-C: `KeyboardInterrupt`),
//! the cancellation flag tells the work to stop, and the Python error is
//! returned once it has. Off the main thread (e.g. in a Dask worker) signal
//! checks do nothing, so the work simply runs to the end.

use candela_render::render::Cancel;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::time::Duration;

/// How often the waiting thread looks for signals.
const POLL: Duration = Duration::from_millis(20);

/// Runs `work` without the GIL, raising `cancel` if a Python signal handler
/// raises meanwhile.
pub fn run_interruptible<T: Send>(
    py: Python<'_>,
    cancel: &Cancel,
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    std::thread::scope(|s| {
        let handle = s.spawn(work);
        let mut interrupted = None;
        while !handle.is_finished() {
            py.detach(|| {
                let step = POLL / 10;
                for _ in 0..10 {
                    if handle.is_finished() {
                        break;
                    }
                    std::thread::sleep(step);
                }
            });
            if interrupted.is_none() {
                if let Err(e) = py.check_signals() {
                    cancel.cancel();
                    interrupted = Some(e);
                }
            }
        }
        let result = py
            .detach(|| handle.join())
            .map_err(|_| PyRuntimeError::new_err("the render thread panicked"));
        match interrupted {
            Some(e) => Err(e),
            None => result,
        }
    })
}

//! Running a long computation from Python: on a worker thread of its own with the GIL
//! released, on a rayon pool made for the call (rayon's global pool would not survive a
//! `fork` of the host process), while the calling thread wakes every [`POLL`] to run Python's
//! signal handlers (Ctrl-C) and the user's progress callback. A signal handler's exception
//! (`KeyboardInterrupt`) or a callback that raises or returns `False` sets the computation's
//! cancel token; the worker stops at its next checkpoint without writing anything, and the
//! exception is raised once it has stopped.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Mutex;
use std::time::Duration;

use pyo3::prelude::*;
use wingcheck_app::{AppError, Cancel};

/// How often the calling thread serves signals and progress while the worker runs.
const POLL: Duration = Duration::from_millis(20);

/// The latest progress of the worker: (fraction done in [0, 1], stage), taken by the poller.
#[derive(Default)]
pub struct Progress(Mutex<Option<(f64, String)>>);

impl Progress {
    /// Record the fraction done of `stage`.
    pub fn set(&self, fraction: f64, stage: &str) {
        if let Ok(mut g) = self.0.lock() {
            *g = Some((fraction, stage.to_string()));
        }
    }

    fn take(&self) -> Option<(f64, String)> {
        self.0.lock().ok().and_then(|mut g| g.take())
    }
}

/// Run `work` (given the cancel token and the progress sink) as described above; its error
/// becomes the matching Python exception.
pub fn run<T: Send>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    threads: Option<usize>,
    work: impl FnOnce(&Cancel, &Progress) -> Result<T, AppError> + Send,
) -> PyResult<T> {
    let cancel = Cancel::new();
    let sink = Progress::default();
    let mut stop: Option<PyErr> = None;
    let (tx, mut rx) = std::sync::mpsc::channel::<()>();
    let result = std::thread::scope(|s| {
        let (cancel, sink) = (&cancel, &sink);
        let worker = s.spawn(move || {
            let r = catch_unwind(AssertUnwindSafe(|| wingcheck_app::ops::in_own_pool(threads, || work(cancel, sink))));
            let _ = tx.send(());
            r
        });
        loop {
            let (done, back) = py.detach(move || (rx.recv_timeout(POLL), rx));
            rx = back;
            if !matches!(done, Err(std::sync::mpsc::RecvTimeoutError::Timeout)) {
                break;
            }
            if stop.is_some() {
                continue;
            }
            if let Err(e) = py.check_signals() {
                stop = Some(e);
            } else if let (Some(cb), Some((fraction, stage))) = (progress, sink.take()) {
                match cb.call1((fraction, stage)) {
                    Ok(v) if v.is_instance_of::<pyo3::types::PyBool>() && !v.is_truthy().unwrap_or(true) => {
                        stop = Some(crate::errors::cancelled(py, "stopped by the progress callback"));
                    }
                    Ok(_) => {}
                    Err(e) => stop = Some(e),
                }
            }
            if stop.is_some() {
                cancel.cancel();
            }
        }
        worker.join()
    });
    if let Some(e) = stop {
        return Err(e);
    }
    match result {
        Ok(Ok(r)) => r.map_err(|e| crate::errors::to_py(py, &e)),
        Ok(Err(panic)) | Err(panic) => Err(crate::errors::to_py(py, &AppError::Internal(panic_text(&panic)))),
    }
}

fn panic_text(p: &Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<String>()
        .cloned()
        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_else(|| "a panic without a message".into())
}

//! Running a long computation from Python: on a worker thread of its own with the GIL
//! released, on a rayon pool made for the call (rayon's global pool would not survive a
//! `fork` of the host process), while the calling thread wakes every [`POLL`] to run Python's
//! signal handlers (Ctrl-C) and the user's progress callback. A signal handler's exception
//! (`KeyboardInterrupt`) or a callback that raises or returns `False` sets the computation's
//! cancel token; the worker stops at its next checkpoint without writing anything.
//!
//! A computation that writes files as it goes ([`Writes::Files`]: a search directory, a run
//! with a Python controller) is waited for before the exception is raised, so nothing of it can appear
//! afterwards. One that moves its output into place through the cancel token's gate
//! ([`Writes::Gated`]: simulate's output, report, certify; [`Cancel::commit`]) or writes nothing
//! ([`Writes::Nothing`]: check, modes, verify) is left to finish its current stretch in the
//! background (exact arithmetic without a checkpoint can take seconds) and the exception is
//! raised at once: once `cancel` has returned, a gated output never appears. A gated worker
//! still removes its staging directory when it reaches its next checkpoint, so it is kept in
//! [`STOPPED`] and joined by [`join_stopped`] (registered with `atexit`): the interpreter does not
//! exit with a staging directory left behind.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use pyo3::prelude::*;
use wingcheck_app::{AppError, Cancel};

/// How often the calling thread serves signals and progress while the worker runs.
const POLL: Duration = Duration::from_millis(20);

/// Whether a computation writes files (then a stop waits for it to end).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Writes {
    /// It writes files: wait for it after a stop.
    Files,
    /// It moves its output into place through [`Cancel::commit`]: raise at once after a stop,
    /// join the worker at exit.
    Gated,
    /// It writes nothing: raise at once after a stop.
    Nothing,
}

/// Workers stopped while they may still hold a staging directory ([`Writes::Gated`]).
static STOPPED: Mutex<Vec<std::thread::JoinHandle<()>>> = Mutex::new(Vec::new());

/// Wait (GIL released) for every stopped gated worker to end, so its staging directory is
/// removed. Called at interpreter exit.
#[pyfunction]
pub fn join_stopped(py: Python<'_>) {
    let workers = std::mem::take(&mut *STOPPED.lock().unwrap_or_else(std::sync::PoisonError::into_inner));
    py.detach(move || {
        for w in workers {
            let _ = w.join();
        }
    });
}

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

type Outcome<T> = std::thread::Result<Result<T, AppError>>;

/// Run `work` (given the cancel token and the progress sink) as described above; its error
/// becomes the matching Python exception.
pub fn run<T: Send + 'static>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    writes: Writes,
    work: impl FnOnce(&Cancel, &Progress) -> Result<T, AppError> + Send + 'static,
) -> PyResult<T> {
    let cancel = Cancel::new();
    let sink = Arc::new(Progress::default());
    let (tx, rx) = channel::<Outcome<T>>();
    let (c, s) = (cancel.clone(), sink.clone());
    let worker = std::thread::Builder::new()
        .name("wingcheck".into())
        .spawn(move || {
            let r = catch_unwind(AssertUnwindSafe(|| wingcheck_app::ops::in_own_pool(None, || work(&c, &s))));
            let _ = tx.send(r);
        })
        .map_err(|e| crate::errors::to_py(py, &AppError::Internal(format!("cannot start a thread: {e}"))))?;
    let (outcome, stop) = poll(py, progress, &cancel, &sink, rx, writes);
    if outcome.is_some() || writes == Writes::Files {
        let _ = worker.join();
    } else if writes == Writes::Gated {
        STOPPED.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push(worker);
    }
    if let Some(e) = stop {
        return Err(e);
    }
    match outcome {
        Some(Ok(r)) => r.map_err(|e| crate::errors::to_py(py, &e)),
        Some(Err(panic)) => Err(crate::errors::to_py(py, &AppError::Internal(panic_text(&panic)))),
        None => Err(crate::errors::to_py(py, &AppError::Internal("the worker thread ended without a result".into()))),
    }
}

/// Wait for the worker's outcome, serving signals and progress; after a stop, wait on only if
/// it writes files. Returns the outcome (if it came) and the exception that stopped it.
fn poll<T: Send>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    cancel: &Cancel,
    sink: &Progress,
    mut rx: Receiver<Outcome<T>>,
    writes: Writes,
) -> (Option<Outcome<T>>, Option<PyErr>) {
    let mut stop: Option<PyErr> = None;
    loop {
        let (got, back) = py.detach(move || (rx.recv_timeout(POLL), rx));
        rx = back;
        match got {
            Ok(outcome) => return (Some(outcome), stop),
            Err(RecvTimeoutError::Disconnected) => return (None, stop),
            Err(RecvTimeoutError::Timeout) => {}
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
            // for a gated computation: once this returns, its output never appears
            cancel.cancel();
            if writes != Writes::Files {
                return (None, stop);
            }
        }
    }
}

fn panic_text(p: &Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<String>()
        .cloned()
        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_else(|| "a panic without a message".into())
}

//! [`AppError`] → the exception classes of `wingcheck.errors` (defined in Python, where a class
//! can also be a `ValueError` or an `OSError`), chosen by [`AppError::kind`].

use pyo3::prelude::*;
use pyo3::types::PyDict;
use wingcheck_app::{AppError, ErrorKind};

/// The exception `class_name` of `wingcheck.errors` with `message` and `attrs` set on it.
fn raise(py: Python<'_>, class_name: &str, message: &str, attrs: &[(&str, Py<PyAny>)]) -> PyErr {
    let made = (|| -> PyResult<PyErr> {
        let cls = py.import("wingcheck.errors")?.getattr(class_name)?;
        let exc = cls.call1((message,))?;
        for (k, v) in attrs {
            exc.setattr(*k, v.bind(py))?;
        }
        Ok(PyErr::from_value(exc))
    })();
    made.unwrap_or_else(|e| e)
}

/// `wingcheck.errors.Cancelled` (a `KeyboardInterrupt`) with `why`.
pub fn cancelled(py: Python<'_>, why: &str) -> PyErr {
    raise(py, "Cancelled", why, &[])
}

/// The message as the command line prints it: the error and its causes joined by ": ", each
/// cause once.
fn message(e: &AppError) -> String {
    let mut out = String::new();
    let mut cause: Option<&dyn std::error::Error> = Some(e);
    while let Some(c) = cause {
        let text = c.to_string();
        if !out.contains(&text) {
            if !out.is_empty() {
                out.push_str(": ");
            }
            out.push_str(&text);
        }
        cause = c.source();
    }
    out
}

/// The Python exception for `e`.
pub fn to_py(py: Python<'_>, e: &AppError) -> PyErr {
    let msg = message(e);
    let none = || py.None();
    match e.kind() {
        ErrorKind::Config => raise(py, "ConfigError", &msg, &[]),
        ErrorKind::WorkLimit => {
            let est = match e {
                AppError::WorkLimit(w) => Some(&w.estimate),
                _ => None,
            };
            let num = |f: fn(&wingcheck_model::work::WorkEstimate) -> f64| {
                est.map_or_else(none, |e| {
                    f(e).into_pyobject(py).map(|v| v.into_any().unbind()).unwrap_or_else(|_| none())
                })
            };
            raise(
                py,
                "WorkLimitError",
                &msg,
                &[
                    ("estimated_seconds", num(|e| e.seconds)),
                    ("estimated_memory_bytes", num(|e| e.memory_bytes)),
                    ("estimated_output_bytes", num(|e| e.output_bytes)),
                    ("estimated_steps", num(|e| e.steps)),
                ],
            )
        }
        ErrorKind::Numerical => raise(py, "NumericalError", &msg, &[]),
        ErrorKind::Diverged { t } => {
            let t = t.into_pyobject(py).map(|v| v.into_any().unbind()).unwrap_or_else(|_| none());
            raise(py, "DivergedError", &msg, &[("t", t)])
        }
        ErrorKind::Search => raise(py, "SearchError", &msg, &[]),
        ErrorKind::Input => raise(py, "InputError", &msg, &[]),
        ErrorKind::Output => raise(py, "OutputError", &msg, &[]),
        ErrorKind::Verification => raise(py, "VerificationError", &msg, &[]),
        ErrorKind::Cancelled => cancelled(py, &msg),
        ErrorKind::Internal => raise(py, "InternalError", &msg, &[]),
    }
}

/// A bad argument of a Python call (`name` and why) as `ConfigError`.
pub fn argument(py: Python<'_>, name: &'static str, why: impl std::fmt::Display) -> PyErr {
    to_py(py, &AppError::Argument { name, message: format!("{name}: {why}") })
}

/// A dict from pairs (for the Python layer).
pub fn dict<'py>(py: Python<'py>, pairs: Vec<(&str, Bound<'py, PyAny>)>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in pairs {
        d.set_item(k, v)?;
    }
    Ok(d)
}

//! A controller written in Python as a [`Controller`]: the Rust loop runs on the worker thread
//! with the GIL released and takes it only for each call of the user's object (once per sample
//! period T_s, plus `reset()` before each run).
//!
//! The object is called `f(t, tip)` with `tip` a `wingcheck.Tip` (the measurements at t_k of
//! Remark 2 and the period's integrals of τ and w, SI units) and returns the held inputs
//! (tau1 (N), tau2 (N m)), added to the continuous part (k1, k2, a, b) of law (15) that the
//! Python layer read from the object's `continuous` attribute. An exception inside the object
//! stops the run; it is kept in [`Shared::error`] and raised by `simulate` with its traceback.

use std::sync::{Arc, Mutex};

use pyo3::prelude::*;
use wingcheck_control::{BoundaryLaw, ControlError, Controller, Held, PeriodIntegrals, TipMeasurement};
use wingcheck_model::Config;
use wingcheck_sim::BoxedController;

/// What every run's controller shares: the user's object, the record class and the first
/// Python exception raised inside the object.
pub struct Shared {
    /// The user's callable (or object with `__call__`).
    obj: Py<PyAny>,
    /// `wingcheck.Tip`.
    tip: Py<PyAny>,
    /// Whether the object has a `reset()` to call before each run.
    has_reset: bool,
    /// The continuous part (zero gains for a plain callable).
    law: BoundaryLaw,
    /// The Python exception that stopped the run, if any.
    pub error: Mutex<Option<PyErr>>,
}

impl Shared {
    /// The user's object `obj` with the continuous part (k1, k2, a, b) (N/m, N m/rad, –, s).
    pub fn new(py: Python<'_>, obj: Py<PyAny>, continuous: [f64; 4]) -> PyResult<Arc<Shared>> {
        let tip = py.import("wingcheck._control")?.getattr("Tip")?.unbind();
        let has_reset = obj.bind(py).hasattr("reset")?;
        let [k1, k2, a, b] = continuous;
        let law = BoundaryLaw { gains: [k1, k2], a, b };
        Ok(Arc::new(Shared { obj, tip, has_reset, law, error: Mutex::new(None) }))
    }

    /// A controller for one run.
    pub fn controller(self: &Arc<Shared>) -> BoxedController {
        Box::new(PyController { shared: self.clone(), integrals: PeriodIntegrals::default() })
    }

    /// Keep the first Python exception and describe it for the Rust error.
    fn failed(&self, py: Python<'_>, t: f64, e: PyErr) -> ControlError {
        let message = e.value(py).repr().map(|r| r.to_string()).unwrap_or_else(|_| e.to_string());
        let mut slot = self.error.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        slot.get_or_insert(e);
        ControlError::Failed { t, message }
    }

    /// The Python exception that stopped the run, taken.
    pub fn take_error(&self) -> Option<PyErr> {
        self.error.lock().unwrap_or_else(std::sync::PoisonError::into_inner).take()
    }
}

/// Run `f` on this thread with a Python thread state kept for it and the GIL released: each
/// controller call on this thread then takes the GIL by restoring that state instead of
/// creating and destroying one (`PyGILState_Ensure` on a thread without one), which was most of
/// a trivial controller's cost per call (bench_controller.py).
pub fn with_thread_state<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    Python::attach(|py| py.detach(f))
}

/// One run's controller: the shared object and the integrals of the current sample period.
struct PyController {
    shared: Arc<Shared>,
    integrals: PeriodIntegrals,
}

/// (tau1, tau2) from the object's return value, or why not.
fn pair(t: f64, out: &Bound<'_, PyAny>) -> Result<[f64; 2], ControlError> {
    let shape = |found: String| ControlError::Shape { t, found };
    let describe = || out.repr().map(|r| r.to_string()).unwrap_or_else(|_| "an unprintable value".into());
    let items: Vec<Bound<'_, PyAny>> = match out.try_iter() {
        Ok(it) => it.take(3).collect::<PyResult<_>>().map_err(|_| shape(describe()))?,
        Err(_) => return Err(shape(format!("{} (not a sequence)", describe()))),
    };
    if items.len() != 2 {
        let n = if items.len() > 2 { "3 or more".to_string() } else { items.len().to_string() };
        return Err(shape(format!("{} ({n} items)", describe())));
    }
    let mut v = [0.0; 2];
    for (i, item) in items.iter().enumerate() {
        v[i] = item.extract::<f64>().map_err(|_| shape(format!("{} (item {i} is not a number)", describe())))?;
        if !v[i].is_finite() {
            return Err(ControlError::NonFinite { t, name: ["tau1", "tau2"][i], value: v[i] });
        }
    }
    Ok(v)
}

impl Controller for PyController {
    type Error = ControlError;

    fn continuous(&self) -> BoundaryLaw {
        self.shared.law
    }

    fn reset(&mut self, _cfg: &Config) -> Result<(), ControlError> {
        self.integrals = PeriodIntegrals::default();
        if !self.shared.has_reset {
            return Ok(());
        }
        Python::attach(|py| match self.shared.obj.bind(py).call_method0("reset") {
            Ok(_) => Ok(()),
            Err(e) => Err(self.shared.failed(py, 0.0, e)),
        })
    }

    fn integrate(&mut self, h: f64, tau_mean: [f64; 2], w_mean: [f64; 2]) {
        self.integrals.add(h, tau_mean, w_mean);
    }

    fn sample(&mut self, tip: &TipMeasurement) -> Result<Held, ControlError> {
        let i = self.integrals.take();
        let t = tip.t;
        Python::attach(|py| {
            let args =
                (t, tip.x[0], tip.x[1], tip.v[0], tip.v[1], tip.w[0], tip.w[1], i.tau[0], i.tau[1], i.w[0], i.w[1]);
            let record = self.shared.tip.bind(py).call1(args).map_err(|e| self.shared.failed(py, t, e))?;
            let out = self.shared.obj.bind(py).call1((t, record)).map_err(|e| self.shared.failed(py, t, e))?;
            let input = pair(t, &out)?;
            Ok(Held { input, sigma: [0.0; 2] })
        })
    }
}

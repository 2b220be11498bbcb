//! The closed loop driven one sample period at a time from Python (`wingcheck.Wing`): the same
//! stepper as `simulate(config, controller=f)` in the nodal basis, with the held inputs given by
//! each `step` instead of returned by a callback, so the two forms give the same bits.
//!
//! Each call is one sample period (`observer.sample_period` integrator steps' worth, ≈ µs at
//! the paper's grid) and keeps the GIL: releasing it would cost more than the step.

use pyo3::prelude::*;
use wingcheck_app::{AppError, ConfigSource};
use wingcheck_control::{BoundaryLaw, ControlError, Controller, Held, PeriodIntegrals, TipMeasurement};
use wingcheck_model::Config;
use wingcheck_sim::{check_sample, nodal_only, Discretisation, SimError, Stepper};

use crate::errors::to_py;

/// A controller whose held inputs are set from outside ([`Wing::step`]).
struct Driven {
    law: BoundaryLaw,
    input: [f64; 2],
    integrals: PeriodIntegrals,
}

impl Controller for Driven {
    type Error = ControlError;
    fn continuous(&self) -> BoundaryLaw {
        self.law
    }
    fn reset(&mut self, _cfg: &Config) -> Result<(), ControlError> {
        self.integrals = PeriodIntegrals::default();
        self.input = [0.0; 2];
        Ok(())
    }
    fn integrate(&mut self, h: f64, tau_mean: [f64; 2], w_mean: [f64; 2]) {
        self.integrals.add(h, tau_mean, w_mean);
    }
    fn sample(&mut self, _tip: &TipMeasurement) -> Result<Held, ControlError> {
        Ok(Held { input: self.input, sigma: [0.0; 2] })
    }
}

/// The loop of a configuration, stepped from Python.
#[pyclass(unsendable, module = "wingcheck._wingcheck")]
pub struct WingLoop {
    cfg: Config,
    law: BoundaryLaw,
    stepper: Option<Stepper<Driven>>,
    e0: f64,
}

type Obs = (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);

fn observation(st: &mut Stepper<Driven>) -> Obs {
    let m = st.measurement();
    let i = st.controller_mut().integrals.take();
    (m.t, m.x[0], m.x[1], m.v[0], m.v[1], m.w[0], m.w[1], i.tau[0], i.tau[1], i.w[0], i.w[1])
}

fn sim_err(py: Python<'_>, e: SimError) -> PyErr {
    to_py(py, &AppError::Sim(e))
}

#[pymethods]
impl WingLoop {
    /// The loop of the configuration (JSON text or file, overrides) with the continuous part
    /// (k1, k2, a, b) of law (15).
    #[new]
    #[pyo3(signature = (continuous, config_text=None, config_path=None, set=Vec::new()))]
    fn new(
        py: Python<'_>,
        continuous: [f64; 4],
        config_text: Option<String>,
        config_path: Option<std::path::PathBuf>,
        set: Vec<String>,
    ) -> PyResult<WingLoop> {
        let cfg = ConfigSource { file: config_path, text: config_text, set }.load().map_err(|e| to_py(py, &e))?;
        cfg.validate().map_err(|e| sim_err(py, e.into()))?;
        nodal_only(&cfg).map_err(|e| sim_err(py, e))?;
        let [k1, k2, a, b] = continuous;
        let law = BoundaryLaw { gains: [k1, k2], a, b };
        Ok(WingLoop { cfg, law, stepper: None, e0: 0.0 })
    }

    /// Start at t = 0; the measurements there (the fields of `wingcheck.Tip`).
    fn reset(&mut self, py: Python<'_>) -> PyResult<Obs> {
        let driven = Driven { law: self.law, input: [0.0; 2], integrals: PeriodIntegrals::default() };
        let disc = Discretisation::new(&self.cfg);
        let mut st = py.detach(|| Stepper::with_controller(&self.cfg, disc, driven)).map_err(|e| sim_err(py, e))?;
        self.e0 = st.sample().energy;
        let obs = observation(&mut st);
        self.stepper = Some(st);
        Ok(obs)
    }

    /// Hold (tau1 (N), tau2 (N m)) over [t_k, t_k + T_s), advance, and return the measurements
    /// at t_{k+1} with (t (s), energy (J)); a diverged loop raises `DivergedError`.
    fn step(&mut self, py: Python<'_>, tau1: f64, tau2: f64) -> PyResult<(Obs, f64, f64)> {
        let Some(st) = self.stepper.as_mut() else {
            return Err(to_py(py, &AppError::Argument { name: "step", message: "step: call reset() first".into() }));
        };
        let t = st.time();
        for (name, v) in [("tau1", tau1), ("tau2", tau2)] {
            if !v.is_finite() {
                return Err(sim_err(py, SimError::Control(ControlError::NonFinite { t, name, value: v })));
            }
        }
        st.controller_mut().input = [tau1, tau2];
        st.resample().and_then(|()| st.try_advance_sample()).map_err(|e| sim_err(py, e.into()))?;
        let sample = st.sample();
        check_sample(&sample, self.e0).map_err(|e| sim_err(py, e))?;
        Ok((observation(st), sample.t, sample.energy))
    }

    /// The sample period T_s (s) and the horizon's end t_end (s).
    fn timing(&self) -> (f64, f64) {
        (self.cfg.observer.sample_period, self.cfg.horizon.t_end)
    }
}

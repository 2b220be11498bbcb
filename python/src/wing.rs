//! The closed loop driven one sample period at a time from Python (`wingcheck.Wing`): the run
//! of `simulate(config, controller=f)` itself ([`SteppedRun`]: the same basis and scheme the
//! configuration resolves to, modal by default), with the held inputs given by each `step`
//! instead of returned by a callback, so the two forms give the same bits.
//!
//! Each call is one sample period (`observer.sample_period` integrator steps' worth) plus one
//! hand-over to the run's thread, with the GIL released while the run steps.

use pyo3::prelude::*;
use wingcheck_app::{AppError, ConfigSource};
use wingcheck_control::BoundaryLaw;
use wingcheck_model::Config;
use wingcheck_sim::{SimError, SteppedRun, SteppedSample};

use crate::errors::to_py;

/// The loop of a configuration, stepped from Python.
#[pyclass(unsendable, module = "wingcheck._wingcheck")]
pub struct WingLoop {
    cfg: Config,
    law: BoundaryLaw,
    run: Option<SteppedRun>,
}

type Obs = (f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64);

fn observation(s: &SteppedSample) -> Obs {
    let (m, i) = (&s.tip, &s.integrals);
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
        let [k1, k2, a, b] = continuous;
        let law = BoundaryLaw { gains: [k1, k2], a, b };
        law.check().map_err(|e| sim_err(py, e.into()))?;
        Ok(WingLoop { cfg, law, run: None })
    }

    /// Start at t = 0 (ending any run in progress); the measurements there (the fields of
    /// `wingcheck.Tip`).
    fn reset(&mut self, py: Python<'_>) -> PyResult<Obs> {
        self.run = None;
        let (cfg, law) = (&self.cfg, self.law);
        let (run, first) = py.detach(|| SteppedRun::start(cfg, law)).map_err(|e| sim_err(py, e))?;
        self.run = Some(run);
        Ok(observation(&first))
    }

    /// Hold (tau1 (N), tau2 (N m)) over [t_k, t_k + T_s), advance, and return the measurements
    /// at t_{k+1} with (t (s), energy (J)); a diverged loop raises `DivergedError`, a step past
    /// t_end `ConfigError`.
    fn step(&mut self, py: Python<'_>, tau1: f64, tau2: f64) -> PyResult<(Obs, f64, f64)> {
        let Some(run) = self.run.as_mut() else {
            return Err(to_py(py, &AppError::Argument { name: "step", message: "step: call reset() first".into() }));
        };
        let sample = py.detach(|| run.step([tau1, tau2])).map_err(|e| sim_err(py, e))?;
        Ok((observation(&sample), sample.tip.t, sample.energy))
    }

    /// The sample period T_s (s) and the horizon's end t_end (s).
    fn timing(&self) -> (f64, f64) {
        (self.cfg.observer.sample_period, self.cfg.horizon.t_end)
    }
}

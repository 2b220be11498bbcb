//! The study layer: every distinct closed-loop simulation a `check` (or `report`) needs runs
//! once, cached by the SHA-256 of the simulated configuration (thread-safe; a cached value is a
//! pure function of its key, so caching never changes a result).

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use wingcheck_model::{Config, ControllerKind};
use wingcheck_sim::{simulate, RunOptions, SimOutput};

use crate::theory::{g_hmax, DisturbanceBounds};
use crate::{config_sha256, ClaimsError};

/// Cache of simulations, keyed by configuration hash.
#[derive(Default)]
pub struct Study {
    runs: Mutex<HashMap<String, Arc<SimOutput>>>,
    performed: Mutex<usize>,
}

impl Study {
    /// An empty study.
    pub fn new() -> Self {
        Study::default()
    }

    /// The simulation of `cfg` with q(z,t), θ(z,t) on the output grid (run once per config).
    pub fn simulate(&self, cfg: &Config) -> Result<Arc<SimOutput>, ClaimsError> {
        let key = config_sha256(cfg);
        if let Some(out) = self.runs.lock().expect("study lock").get(&key) {
            return Ok(out.clone());
        }
        let out = Arc::new(simulate(cfg, RunOptions { fields: true, progress: None })?);
        *self.performed.lock().expect("study lock") += 1;
        self.runs.lock().expect("study lock").entry(key).or_insert(out.clone());
        Ok(out)
    }

    /// The configuration with the FTDO controller (the paper's design), simulated once.
    pub fn ftdo(&self, cfg: &Config) -> Result<Arc<SimOutput>, ClaimsError> {
        let mut c = cfg.clone();
        c.control.kind = ControllerKind::Ftdo;
        self.simulate(&c)
    }

    /// Number of simulations actually run (cache misses).
    pub fn simulations_run(&self) -> usize {
        *self.performed.lock().expect("study lock")
    }

    /// Disturbance bounds of (29)–(32): g_hmax ([`g_hmax`]) and ζ3, ζ4 = sup_t |g̃1|, |g̃2| of
    /// the FTDO run of the configuration.
    pub fn disturbance_bounds(&self, cfg: &Config) -> Result<DisturbanceBounds, ClaimsError> {
        let out = self.ftdo(cfg)?;
        let s = &out.series;
        let sup = |g: &[f64], h: &[f64]| g.iter().zip(h).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        Ok(DisturbanceBounds { g_hmax: g_hmax(cfg), zeta3: sup(&s.g1, &s.g1_hat), zeta4: sup(&s.g2, &s.g2_hat) })
    }
}

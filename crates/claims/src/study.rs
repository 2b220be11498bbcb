//! The study layer: every distinct closed-loop simulation a `check` (or `report`) needs runs
//! once, cached by the SHA-256 of the simulated configuration. Thread-safe, and a run that is
//! in flight is waited for rather than started twice, so the ledger and the report can share
//! one study from several threads. A cached value is a pure function of its key, so caching
//! never changes a result.

pub mod refine;

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use wingcheck_model::{Config, ControllerKind};
use wingcheck_sim::{simulate, RunOptions, SimOutput};

use crate::{config_sha256, ClaimsError};
use wingcheck_theory::{g_hmax, DisturbanceBounds};

/// A run's outcome, shared by everyone who asked for it.
type Shared = Arc<OnceLock<Result<Arc<SimOutput>, Arc<wingcheck_sim::SimError>>>>;

/// Cache of simulations, keyed by configuration hash.
#[derive(Default)]
pub struct Study {
    runs: Mutex<HashMap<String, Shared>>,
    /// The statistics-only runs ([`Study::statistics`]), apart from the full ones.
    statistics: Mutex<HashMap<String, Shared>>,
    /// The refinement runs ([`Study::refinement`]).
    refinements: Mutex<HashMap<String, Shared>>,
    performed: Mutex<usize>,
    /// Handed to every run: once set, the runs stop with `SimError::Cancelled`.
    cancel: wingcheck_model::Cancel,
}

impl Study {
    /// An empty study.
    pub fn new() -> Self {
        Study::default()
    }

    /// An empty study whose runs stop once `cancel` is set ([`check_all_cancellable`]).
    pub fn with_cancel(cancel: wingcheck_model::Cancel) -> Self {
        Study { cancel, ..Study::default() }
    }

    /// The study's cancel token (a fresh one unless made [`Study::with_cancel`]).
    pub fn cancel(&self) -> &wingcheck_model::Cancel {
        &self.cancel
    }

    /// The simulation of `cfg` with q(z,t), θ(z,t) on the output grid (run once per config;
    /// a second caller of a run in flight waits for it).
    pub fn simulate(&self, cfg: &Config) -> Result<Arc<SimOutput>, ClaimsError> {
        self.cached(&self.runs, cfg, || {
            simulate(cfg, RunOptions { fields: true, cancel: self.cancel.clone(), ..Default::default() })
        })
    }

    /// A run of `cfg` for its whole-run statistics only (RMS τ over [0, t_end], the final tip
    /// values): one output interval ([`wingcheck_model::work::one_output_interval`]: the series holds t = 0
    /// and t_end, and the interval's ∫τ² is the run's: the per-step values summed, nothing is
    /// reconstructed at intermediate outputs), no fields, no initial-layer re-run, no sub-step
    /// probe (peaks at the recorded instants), and the exponential scheme in the closed loop's
    /// eigenbasis where its round-off estimate is at most
    /// [`wingcheck_sim::MAX_EIGENBASIS_ROUNDOFF`] (`stats.eigenbasis_roundoff` then states it;
    /// whoever uses the run adds it to the quantity's error: the explicit FTDO's RMS τ errors it
    /// serves are of order 1e-2 relative; on a doubled grid of 576 unknowns the estimate reaches
    /// 3.1e-3 and widens that ± visibly). Its whole-run RMS τ is that
    /// of [`Study::simulate`] within that estimate (the layer and the probe change peaks only).
    /// Divergence is checked at its outputs, so at the end: the error runs' configurations differ
    /// from a full run's only in dt, the grid or ν(0), and that run checks every output.
    pub fn statistics(&self, cfg: &Config) -> Result<Arc<SimOutput>, ClaimsError> {
        let one_interval = wingcheck_model::work::one_output_interval(cfg);
        self.cached(&self.statistics, &one_interval, || {
            let opts = RunOptions {
                sub_step_probe: wingcheck_sim::SubStepProbe::Off,
                eigenbasis: Some(wingcheck_sim::MAX_EIGENBASIS_ROUNDOFF),
                cancel: self.cancel.clone(),
                ..Default::default()
            };
            wingcheck_sim::simulate_base(&one_interval, opts)
        })
    }

    /// A run of `cfg` for its series only, as a refinement of another run's metrics (the
    /// comparison's ± from the doubled grid and dt/2): every output sample of the tip values,
    /// τ and the observer ([`RunOptions::series_only`]: the energy column is an upper bound, the
    /// tip boundary states are not recorded; no metric reads them), no fields, no
    /// initial-layer re-run, no sub-step probe, and the exponential scheme in the closed loop's
    /// eigenbasis where its round-off estimate is at most
    /// [`wingcheck_sim::MAX_EIGENBASIS_ROUNDOFF`] (`stats.eigenbasis_roundoff` states it; the
    /// user adds it to the error). Its series are those of [`Study::simulate`] within that
    /// estimate; its peaks lack what the layer and the probe add.
    pub fn refinement(&self, cfg: &Config) -> Result<Arc<SimOutput>, ClaimsError> {
        self.cached(&self.refinements, cfg, || {
            let opts = RunOptions {
                sub_step_probe: wingcheck_sim::SubStepProbe::Off,
                eigenbasis: Some(wingcheck_sim::MAX_EIGENBASIS_ROUNDOFF),
                series_only: true,
                cancel: self.cancel.clone(),
                ..Default::default()
            };
            wingcheck_sim::simulate_base(cfg, opts)
        })
    }

    /// The refinement runs of `cfg` ([`refine::refinements`], [`Study::refinement`]): the
    /// doubled grid's, dt/2's, and the larger of their eigenbasis round-off estimates (relative;
    /// 0 where neither stepped in the eigenbasis).
    pub fn refined_runs(&self, cfg: &Config) -> Result<(Arc<SimOutput>, Arc<SimOutput>, f64), ClaimsError> {
        let [fine, half_dt] = refine::refinements(cfg);
        let (fine, half_dt) = (self.refinement(&fine)?, self.refinement(&half_dt)?);
        let roundoff = [&fine, &half_dt].iter().filter_map(|o| o.stats.eigenbasis_roundoff).fold(0.0, f64::max);
        Ok((fine, half_dt, roundoff))
    }

    fn cached(
        &self,
        map: &Mutex<HashMap<String, Shared>>,
        cfg: &Config,
        run: impl FnOnce() -> Result<SimOutput, wingcheck_sim::SimError>,
    ) -> Result<Arc<SimOutput>, ClaimsError> {
        let key = config_sha256(cfg);
        let cell = map.lock().expect("study lock").entry(key).or_default().clone();
        let out = cell.get_or_init(|| {
            *self.performed.lock().expect("study lock") += 1;
            run().map(Arc::new).map_err(Arc::new)
        });
        out.clone().map_err(ClaimsError::Sim)
    }

    /// The configuration with the FTDO controller (the paper's design), simulated once.
    pub fn ftdo(&self, cfg: &Config) -> Result<Arc<SimOutput>, ClaimsError> {
        let mut c = cfg.clone();
        c.control.kind = ControllerKind::Ftdo;
        self.simulate(&c)
    }

    /// The configuration hashes of every run asked for (in any order).
    pub fn keys(&self) -> Vec<String> {
        let mut keys: Vec<String> = self.runs.lock().expect("study lock").keys().cloned().collect();
        keys.extend(self.statistics.lock().expect("study lock").keys().cloned());
        keys.extend(self.refinements.lock().expect("study lock").keys().cloned());
        keys.sort();
        keys.dedup();
        keys
    }

    /// Number of simulations actually run (cache misses).
    pub fn simulations_run(&self) -> usize {
        *self.performed.lock().expect("study lock")
    }

    /// Disturbance bounds of (29)–(32): g_hmax ([`g_hmax`]) and ζ3, ζ4 = sup_t |g̃1|, |g̃2| of
    /// the FTDO run of the configuration, at full rate ([`wingcheck_sim::metrics::observer_error_sup`]).
    pub fn disturbance_bounds(&self, cfg: &Config) -> Result<DisturbanceBounds, ClaimsError> {
        let out = self.ftdo(cfg)?;
        Ok(DisturbanceBounds {
            g_hmax: g_hmax(cfg),
            zeta3: wingcheck_sim::metrics::observer_error_sup(&out, 0),
            zeta4: wingcheck_sim::metrics::observer_error_sup(&out, 1),
        })
    }

    /// The errors of ζ3, ζ4 ([`Study::disturbance_bounds`]) from the FTDO run's refinements on
    /// the doubled grid and at dt/2 ([`refine::refinement_error`]; the same runs as
    /// the comparison's FTDO refinements at the configured rule, so no extra simulation there).
    pub fn zeta_errors(&self, cfg: &Config) -> Result<[f64; 2], ClaimsError> {
        let mut c = cfg.clone();
        c.control.kind = ControllerKind::Ftdo;
        let base = self.simulate(&c)?;
        let (fine, half_dt, roundoff) = self.refined_runs(&c)?;
        let sup = wingcheck_sim::metrics::observer_error_sup;
        Ok([0, 1].map(|ch| refine::refinement_error(sup(&base, ch), sup(&fine, ch), sup(&half_dt, ch), roundoff)))
    }
}

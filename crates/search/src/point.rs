//! One point of a search: config = base + the axis overrides, the closed-loop simulation and
//! its metrics, and the theory ([`crate::theory`]).

use std::time::Instant;

use serde::{Deserialize, Serialize};
use wingcheck_model::{apply_overrides, Config, ControllerKind};
use wingcheck_sim::{metrics, simulate, ControllerFactory, RunOptions, SimError};

use crate::axis::Grid;
use crate::metric::Metric;
use crate::modal::{RunCache, TipTrace};
use crate::theory::{Theory, TheoryCache};

/// Outcome of a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Simulation and theory completed.
    Ok,
    /// The simulation diverged (theory columns still filled).
    Diverged,
    /// The config, the simulation or the theory failed (see the message).
    Error,
}

impl Status {
    /// Name in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Diverged => "diverged",
            Status::Error => "error",
        }
    }
}

/// Result of one point (everything but the timings is deterministic).
#[derive(Debug, Clone, PartialEq)]
pub struct PointResult {
    /// Point index (row-major, first axis slowest).
    pub index: usize,
    /// Swept values as applied (`key=text`), in axis order.
    pub values: Vec<String>,
    /// Outcome.
    pub status: Status,
    /// Why a point is not `ok` (empty otherwise).
    pub message: String,
    /// W ≻ 0 on the Galerkin space.
    pub w_positive_definite: Option<bool>,
    /// (29)–(32) satisfiable.
    pub feasible_32: Option<bool>,
    /// Values of [`Metric::ALL`], same order; None where not available.
    pub metrics: Vec<Option<f64>>,
    /// Wall time in simulation (s) — not deterministic, kept out of the result files.
    pub sim_seconds: f64,
    /// Wall time in theory (eigen, SOCPs) (s) — not deterministic.
    pub theory_seconds: f64,
}

/// The two theory verdicts of a point (2 bytes): what boundaries and heatmap marks need.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PointVerdicts {
    /// W ≻ 0 on the Galerkin space.
    pub w_positive_definite: Option<bool>,
    /// (29)–(32) satisfiable.
    pub feasible_32: Option<bool>,
}

impl PointVerdicts {
    /// Both hypotheses of Theorem 2: W ≻ 0 and (32) feasible.
    pub fn theorem_feasible(&self) -> Option<bool> {
        Some(self.w_positive_definite? && self.feasible_32?)
    }
}

impl PointResult {
    /// Both hypotheses of Theorem 2: W ≻ 0 and (32) feasible.
    pub fn theorem_feasible(&self) -> Option<bool> {
        self.verdicts().theorem_feasible()
    }

    /// The two theory verdicts.
    pub fn verdicts(&self) -> PointVerdicts {
        PointVerdicts { w_positive_definite: self.w_positive_definite, feasible_32: self.feasible_32 }
    }

    /// A metric's value (None where not available).
    pub fn metric(&self, metric: Metric) -> Option<f64> {
        self.metrics[metric.index()]
    }
}

/// Metric window [t0, t1] (s): `Some` as given, else the second half of the horizon
/// ([10, 20] s for T = 20 s).
pub fn window(cfg: &Config, w: Option<(f64, f64)>) -> (f64, f64) {
    w.unwrap_or((0.5 * cfg.horizon.t_end, cfg.horizon.t_end))
}

/// Joint settling time of the tip ([`metrics::joint_tip_settle_time`], [`Metric::SettlingTime`])
/// in the ledger's band ([`settle_fraction`]).
pub fn settling_time(s: &TipTrace) -> Option<f64> {
    metrics::joint_tip_settle_time(&s.t, &s.q_tip, &s.theta_tip, settle_fraction())
}

/// The settling band of [`Metric::SettlingTime`] as a fraction of the tip's initial values: the
/// ledger's ([`wingcheck_claims::CheckSettings::settle_fraction`], its default), so that a
/// point's settling time and the ftdo-vs-dobc row's agree.
pub fn settle_fraction() -> f64 {
    wingcheck_claims::CheckSettings::default().settle_fraction
}

/// The simulation metrics ([`Metric::SIMULATION`], in order).
fn sim_metrics(s: &TipTrace, win: (f64, f64)) -> [Option<f64>; 12] {
    let w = metrics::window_indices(&s.t, metrics::Window { t0: win.0, t1: win.1 });
    let (q, th) = (&s.q_tip[w.clone()], &s.theta_tip[w.clone()]);
    [
        metrics::rms(q),
        metrics::max_abs(q),
        metrics::rms(th),
        metrics::max_abs(th),
        settling_time(s),
        (!s.t.is_empty()).then_some(s.tau_peak[0]),
        (!s.t.is_empty()).then_some(s.tau_rms[0]),
        (!s.t.is_empty()).then_some(s.tau_peak[1]),
        (!s.t.is_empty()).then_some(s.tau_rms[1]),
        metrics::rms(&s.g1_tilde[w.clone()]),
        metrics::rms(&s.g2_tilde[w]),
        (!s.t.is_empty()).then_some(s.energy_end),
    ]
}

/// The closed loop of `cfg`: the simulator's modal driver on the shared basis and observer
/// signal, or the simulator itself where the modal basis is not available (mass matrix not
/// positive definite). Under a controller of the user's (`controller`, made for this run) the
/// modal driver samples it from the state ([`crate::modal::run_controlled`]), and the
/// simulator runs it where the basis is nodal.
pub fn closed_loop(
    cfg: &Config,
    runs: &RunCache,
    controller: Option<ControllerFactory<'_>>,
) -> Result<TipTrace, SimError> {
    match (&*runs.basis(cfg), controller) {
        (Some(basis), None) => crate::modal::run(cfg, basis, &runs.signal(cfg)),
        (Some(basis), Some(make)) => crate::modal::run_controlled(cfg, basis, make),
        (None, controller) => {
            simulate(cfg, RunOptions { controller, ..Default::default() }).map(|o| TipTrace::from_output(&o))
        }
    }
}

fn sim_message(e: &SimError) -> (Status, String) {
    match e {
        SimError::Diverged { .. } => (Status::Diverged, e.to_string()),
        _ => (Status::Error, format!("simulation: {e}")),
    }
}

/// Evaluate point `p` of `grid` on `base`. Never panics on a bad point: failures are a status.
pub fn evaluate(
    grid: &Grid,
    base: &Config,
    win: Option<(f64, f64)>,
    cache: &TheoryCache,
    runs: &RunCache,
    controller: Option<ControllerFactory<'_>>,
    p: usize,
) -> PointResult {
    let mut r = PointResult {
        index: p,
        values: grid.texts(p),
        status: Status::Ok,
        message: String::new(),
        w_positive_definite: None,
        feasible_32: None,
        metrics: vec![None; Metric::ALL.len()],
        sim_seconds: 0.0,
        theory_seconds: 0.0,
    };
    let cfg = match apply_overrides(base, &grid.overrides(p)) {
        Ok(c) => c,
        Err(e) => {
            r.status = Status::Error;
            r.message = format!("config: {e}");
            return r;
        }
    };
    let start = Instant::now();
    match closed_loop(&cfg, runs, controller) {
        Ok(trace) => r.metrics[Metric::SIMULATION].copy_from_slice(&sim_metrics(&trace, window(&cfg, win))),
        Err(e) => (r.status, r.message) = sim_message(&e),
    }
    // ζ3, ζ4 are sup |g̃| of the FTDO run; g̃ does not depend on the plant, so they come from
    // the shared FTDO observer signal, whatever the point's controller (the theory columns are
    // the paper's, about its FTDO, under a controller of the user's too).
    let mut ftdo = cfg.clone();
    ftdo.control.kind = ControllerKind::Ftdo;
    let zetas = Some(runs.sup_tilde(&ftdo));
    r.sim_seconds = start.elapsed().as_secs_f64();

    let start = Instant::now();
    let g_hmax = cache.g_hmax(&cfg);
    let bounds = zetas.map(|(z3, z4)| (g_hmax, z3, z4));
    match cache.evaluate(&cfg, bounds) {
        Ok(t) => fill_theory(&mut r, &t, g_hmax, zetas),
        Err(e) => {
            // keep what the theory did decide (W ≻ 0, (32)) when only λ, ε failed
            if let Ok(v) = cache.verdicts(&cfg) {
                fill_theory(&mut r, &Theory::decided(&v), g_hmax, zetas);
            }
            if r.status == Status::Ok {
                r.status = Status::Error;
            }
            r.message = if r.message.is_empty() { e.to_string() } else { format!("{}; {e}", r.message) };
        }
    }
    r.theory_seconds += start.elapsed().as_secs_f64();
    r
}

fn fill_theory(r: &mut PointResult, t: &Theory, g_hmax: f64, zetas: Option<(f64, f64)>) {
    r.w_positive_definite = t.w_pd;
    r.feasible_32 = t.feasible_32;
    let th = [
        t.lambda2,
        t.lambda1,
        t.lambda3_max,
        t.lambda,
        t.epsilon,
        t.uub_bound_q,
        Some(g_hmax),
        zetas.map(|z| z.0),
        zetas.map(|z| z.1),
    ];
    r.metrics[Metric::THEORY].copy_from_slice(&th);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn series(q: &[f64], th: &[f64]) -> TipTrace {
        TipTrace {
            t: (0..q.len()).map(|k| k as f64 * 0.5).collect(),
            q_tip: q.to_vec(),
            theta_tip: th.to_vec(),
            ..Default::default()
        }
    }

    #[test]
    fn settling_time_definition() {
        // thresholds 5 % of |q(0)| = 0.05 and of |θ(0)| = 0.1 (hand-made series, t = 0.5 k)
        let s = series(&[1.0, 0.5, 0.04, 0.06, 0.01, 0.0], &[2.0, 0.05, 0.05, 0.05, 0.05, 0.05]);
        assert_eq!(settling_time(&s), Some(2.0)); // last excursion at k = 3 (q = 0.06 > 0.05)
        let s = series(&[1.0, 0.01, 0.2], &[0.0, 0.0, 0.0]); // θ starts at 0: ignored
        assert_eq!(settling_time(&s), None); // still outside at T
        let s = series(&[0.0, 0.0], &[0.0, 0.0]);
        assert_eq!(settling_time(&s), None);
    }

    #[test]
    fn window_metrics() {
        // window [0.5, 1.0] holds samples k = 1, 2: q = 3, −4 → RMS √12.5, max 4
        let mut s = series(&[1.0, 3.0, -4.0], &[1.0, 1.0, 1.0]);
        for c in [&mut s.tau1, &mut s.tau2] {
            *c = vec![0.0, 1.0, 2.0];
        }
        (s.g1_tilde, s.g2_tilde, s.energy_end) = (vec![0.0; 3], vec![0.0; 3], 2.0);
        s.tau_peak = [2.5, 3.0]; // full rate: above every output sample's |τ|
        let m = sim_metrics(&s, (0.5, 1.0));
        assert_eq!(m[0], Some(12.5f64.sqrt()));
        assert_eq!(m[1], Some(4.0));
        assert_eq!(m[5], Some(2.5)); // τ1 peak over [0, T], the full-rate one
        assert_eq!(m[9], Some(0.0)); // g̃1 = 0
        assert_eq!(m[11], Some(2.0)); // E(T)
    }
}

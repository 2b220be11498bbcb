//! The closed loop of one search point, run in the modal basis of the wing
//! ([`wingcheck_sim::modal`]: the simulator's scheme in another basis, O(n) work per step),
//! with everything that does not change across points computed once per search: the modal
//! basis per wing, and the observer signal per observer/disturbance ([`InputSignal`]: σ obeys
//! σ_{n+1} − σ_n = h(ḡ − ĝ_k) whatever the plant, so ĝ_k and the tip input of every step are
//! the same at every point of a sweep over plant, control-law or scheme keys).
//!
//! Same equations, so the results agree with `wingcheck_sim::simulate` in the nodal basis to
//! round-off (tests/modal.rs). Only the tip quantities the metrics need are recorded.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use serde::Serialize;
use wingcheck_model::Config;
use wingcheck_sim::modal::{ModalLoop, ModalState, ObserverSignal, SampleInput, StepInput};
use wingcheck_sim::{check_sample, SimError, SquareIntegral};

pub use wingcheck_sim::modal::ModalBasis;

/// Entries kept per cache before it is cleared (bounds memory on sweeps over wing keys; the
/// search's memory estimate counts them).
pub const CACHE_ENTRIES: usize = 16;

/// The plant-independent inputs of a run: per integrator step the load factor φ̄ and the
/// tip inputs ḡ − ĝ; per observer sample ĝ_k and g(t_k).
#[derive(Debug)]
pub struct InputSignal {
    /// φ̄ over each step (dimensionless time factor of g_h).
    phi_mean: Vec<f64>,
    /// ḡ − ĝ over each step: N (bending), N m (torsion).
    tip_input: [Vec<f64>; 2],
    /// ĝ_k held from t_k, k = 0..=K.
    pub g_hat: [Vec<f64>; 2],
    /// g(t_k), k = 0..=K.
    pub g: [Vec<f64>; 2],
}

impl InputSignal {
    /// The signal of `cfg` (its observer, disturbances, initial tip states, horizon), collected
    /// from [`ObserverSignal`].
    pub fn new(cfg: &Config) -> InputSignal {
        let (m, total) = (cfg.steps_per_sample(), cfg.total_samples());
        let mut phi_mean = Vec::with_capacity(total * m);
        let mut tip_input = [Vec::with_capacity(total * m), Vec::with_capacity(total * m)];
        let mut g_hat = [Vec::with_capacity(total + 1), Vec::with_capacity(total + 1)];
        let mut g = [Vec::with_capacity(total + 1), Vec::with_capacity(total + 1)];
        let mut signal = ObserverSignal::new(cfg);
        for k in 0..=total {
            let now = signal.current();
            for c in 0..2 {
                g_hat[c].push(now.g_hat[c]);
                g[c].push(now.g[c]);
            }
            if k == total {
                break;
            }
            signal.advance(|_, input| {
                phi_mean.push(input.phi);
                tip_input[0].push(input.tip_input[0]);
                tip_input[1].push(input.tip_input[1]);
            });
        }
        InputSignal { phi_mean, tip_input, g_hat, g }
    }

    /// sup |g(t_k) − ĝ_k| over the output samples of `cfg` (k a multiple of
    /// `samples_per_output`, and k = K), per channel: ζ3 (N), ζ4 (N m) of (32) as
    /// `wingcheck_claims::mu::disturbance_bounds` defines them (sup over the FTDO run's series).
    pub fn sup_tilde(&self, cfg: &Config) -> (f64, f64) {
        let (every, total) = (cfg.samples_per_output(), cfg.total_samples());
        let sup = |c: usize| {
            (0..=total)
                .filter(|k| k % every == 0 || *k == total)
                .map(|k| (self.g[c][k] - self.g_hat[c][k]).abs())
                .fold(0.0, f64::max)
        };
        (sup(0), sup(1))
    }
}

/// What the metrics need of a run, at the output samples: t (s), q(s,t) (m), θ(s,t) (rad),
/// τ1 (N), τ2 (N m), g̃ = g − ĝ per channel, and E(T) (J).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct TipTrace {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// q(s,t) (m).
    pub q_tip: Vec<f64>,
    /// θ(s,t) (rad).
    pub theta_tip: Vec<f64>,
    /// τ1 (N).
    pub tau1: Vec<f64>,
    /// τ2 (N m).
    pub tau2: Vec<f64>,
    /// Full-rate RMS of τ1 over each output interval (N), as `wingcheck_sim::Series::tau1_rms`.
    pub tau1_rms: Vec<f64>,
    /// The same for τ2 (N m).
    pub tau2_rms: Vec<f64>,
    /// Full-rate max |τ1| (N), |τ2| (N m) over [0, T]: every integrator step's end and both
    /// sides of every sample's jump, as `wingcheck_sim::Peaks` (never the output samples, which
    /// are phase-locked to the explicit observer's chatter).
    pub tau_peak: [f64; 2],
    /// g1 − ĝ1 (N).
    pub g1_tilde: Vec<f64>,
    /// g2 − ĝ2 (N m).
    pub g2_tilde: Vec<f64>,
    /// Mechanical energy at T (J).
    pub energy_end: f64,
}

impl TipTrace {
    /// The trace of a full simulator run (fallback path and tests).
    pub fn from_output(o: &wingcheck_sim::SimOutput) -> TipTrace {
        let s = &o.series;
        let tilde = |g: &[f64], h: &[f64]| g.iter().zip(h).map(|(a, b)| a - b).collect();
        TipTrace {
            tau_peak: [o.peaks.tau1.abs_max, o.peaks.tau2.abs_max],
            t: s.t.clone(),
            q_tip: s.q_tip.clone(),
            theta_tip: s.theta_tip.clone(),
            tau1: s.tau1.clone(),
            tau2: s.tau2.clone(),
            tau1_rms: s.tau1_rms.clone(),
            tau2_rms: s.tau2_rms.clone(),
            g1_tilde: tilde(&s.g1, &s.g1_hat),
            g2_tilde: tilde(&s.g2, &s.g2_hat),
            energy_end: s.energy.last().copied().unwrap_or(0.0),
        }
    }
}

/// Run the closed loop of `cfg` on a shared basis and signal (built from configurations that
/// agree with `cfg` on the keys they read; [`RunCache`] guarantees it), with the scheme
/// `cfg.time_scheme(true)` selects (`discretisation.stepper`, `auto` resolved).
pub fn run(cfg: &Config, basis: &ModalBasis, signal: &InputSignal) -> Result<TipTrace, SimError> {
    cfg.validate().map_err(SimError::Config)?;
    let lp = ModalLoop::new(cfg, basis)?;
    let mut st = lp.initial_state(cfg, basis);
    let (m, total, every) = (cfg.steps_per_sample(), cfg.total_samples(), cfg.samples_per_output());
    let period = cfg.observer.sample_period;
    let mut trace = TipTrace::default();
    let mut e0 = 0.0;
    let h = cfg.discretisation.dt;
    let mut squares = SquareIntegral::default();
    let mut record = |k: usize, st: &ModalState, rms: [f64; 2], tr: &mut TipTrace| {
        let gh = [signal.g_hat[0][k], signal.g_hat[1][k]];
        // σ is not recorded by the search (0 in the sample)
        let obs = SampleInput { g_hat: gh, sigma: [0.0; 2], g: [signal.g[0][k], signal.g[1][k]] };
        let sample = lp.sample(basis, st, k as f64 * period, &obs);
        let e = sample.energy;
        if k == 0 {
            e0 = e;
        }
        check_sample(&sample, e0)?;
        tr.t.push(sample.t);
        tr.q_tip.push(sample.q_tip);
        tr.theta_tip.push(sample.theta_tip);
        tr.tau1.push(sample.tau1);
        tr.tau2.push(sample.tau2);
        tr.tau1_rms.push(rms[0]);
        tr.tau2_rms.push(rms[1]);
        tr.g1_tilde.push(sample.g1 - gh[0]);
        tr.g2_tilde.push(sample.g2 - gh[1]);
        tr.energy_end = e;
        Ok::<(), SimError>(())
    };
    // full-rate ∫τ² dt: after every step with the held estimate, and after each sample's jump
    let taus = |st: &ModalState, gh: [f64; 2]| [0, 1].map(|c| lp.tau(c, st.x_tip[c], st.v_tip[c], gh[c]));
    let mut peak = [0.0f64; 2];
    let fold = |peak: &mut [f64; 2], tau: [f64; 2]| {
        for c in 0..2 {
            peak[c] = peak[c].max(tau[c].abs());
        }
        tau
    };
    squares.update(0.0, fold(&mut peak, taus(&st, [signal.g_hat[0][0], signal.g_hat[1][0]])));
    record(0, &st, squares.take_rms(), &mut trace)?;
    wingcheck_sim::cpu::clear_upper_vector_state();
    let mut step = 0;
    for k in 1..=total {
        let g_hat = [signal.g_hat[0][k - 1], signal.g_hat[1][k - 1]];
        let t0 = (k - 1) as f64 * period;
        for j in 0..m {
            let input = StepInput {
                phi: signal.phi_mean[step],
                tip_input: [signal.tip_input[0][step], signal.tip_input[1][step]],
                g_hat,
            };
            step += 1;
            let exact = lp.step(&mut st, &input);
            squares.update_step(t0 + (j + 1) as f64 * h, fold(&mut peak, taus(&st, g_hat)), exact);
        }
        squares.update(k as f64 * period, fold(&mut peak, taus(&st, [signal.g_hat[0][k], signal.g_hat[1][k]])));
        if k % every == 0 || k == total {
            st.sync_tip(basis);
            record(k, &st, squares.take_rms(), &mut trace)?;
        }
    }
    trace.tau_peak = peak;
    Ok(trace)
}

fn cache_get<T>(map: &Mutex<HashMap<String, Arc<T>>>, key: String, make: impl FnOnce() -> T) -> Arc<T> {
    if let Some(v) = map.lock().expect("cache lock").get(&key) {
        return v.clone();
    }
    let v = Arc::new(make());
    let mut m = map.lock().expect("cache lock");
    if m.len() >= CACHE_ENTRIES {
        m.clear();
    }
    m.entry(key).or_insert(v).clone()
}

/// Shared modal bases and input signals of a search (thread-safe; values are pure functions
/// of their keys, so caching never changes a result).
#[derive(Default)]
pub struct RunCache {
    bases: Mutex<HashMap<String, Arc<Result<ModalBasis, String>>>>,
    signals: Mutex<HashMap<String, Arc<InputSignal>>>,
}

impl RunCache {
    /// Empty caches.
    pub fn new() -> Self {
        Self::default()
    }

    /// Modal basis of the wing: keyed by everything `Discretisation::new` reads.
    pub fn basis(&self, cfg: &Config) -> Arc<Result<ModalBasis, String>> {
        let key = serde_json::to_string(&(
            &cfg.wing,
            &cfg.discretisation.method,
            &cfg.discretisation.basis,
            cfg.discretisation.elements,
            cfg.discretisation.fd_points,
            cfg.discretisation.grading,
            &cfg.initial,
            &cfg.disturbance.distributed,
            cfg.horizon.field_points,
        ))
        .expect("serialises");
        cache_get(&self.bases, key, || {
            // the simulator's own choice of basis (`discretisation.basis`), so a point is run
            // in the modal basis exactly when `simulate` would be
            let disc = wingcheck_sim::Discretisation::new(cfg);
            match wingcheck_sim::resolved_basis(cfg, &disc) {
                Ok((_, Some(basis))) => Ok(basis),
                Ok((basis, None)) => Err(format!("the {} basis is selected", basis.name())),
                Err(e) => Err(e.to_string()),
            }
        })
    }

    /// Input signal of `cfg` (its control kind); keyed by everything [`InputSignal::new`] reads.
    pub fn signal(&self, cfg: &Config) -> Arc<InputSignal> {
        let key = serde_json::to_string(&(
            &cfg.observer,
            &cfg.disturbance,
            &cfg.control.kind,
            &cfg.initial,
            (cfg.wing.span, cfg.wing.ei, cfg.wing.gj, cfg.wing.xi),
            cfg.discretisation.dt,
            &cfg.horizon,
        ))
        .expect("serialises");
        cache_get(&self.signals, key, || InputSignal::new(cfg))
    }
}

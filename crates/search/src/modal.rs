//! The closed loop of one search point: the simulator's own modal loop and driver
//! ([`wingcheck_sim::modal::drive`], the same code `simulate` runs), with everything that does
//! not change across points computed once per search and shared: the modal basis per wing and
//! the observer signal per observer/disturbance ([`RecordedSignal`]: σ obeys
//! σ_{n+1} − σ_n = h(ḡ − ĝ_k) whatever the plant, so ĝ_k and the tip input of every step are
//! the same at every point of a sweep over plant, control-law or scheme keys), each under the
//! key the simulator defines for it ([`ModalBasis::key`], [`ObserverSignal::key`]).
//!
//! The search only chooses what to record ([`TipTrace`]): the results are those of
//! `wingcheck_sim::simulate` for the same point, bit for bit in the modal basis
//! (tests/modal.rs), and to round-off against the nodal stepper.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use serde::Serialize;
use wingcheck_model::Config;
use wingcheck_sim::modal::{
    controlled_loop, drive, ModalLoop, ModalState, ObserverSignal, Reads, RecordedSignal, Recorder, Signal,
};
use wingcheck_sim::{ControllerFactory, Sample, SimError, SquareIntegral};

pub use wingcheck_sim::modal::ModalBasis;

/// Entries kept per cache before it is cleared (bounds memory on sweeps over wing keys; the
/// search's memory estimate counts them).
pub const CACHE_ENTRIES: usize = 16;

/// Points evaluated with one set of caches ([`crate::TheoryCache`], [`RunCache`]) before they are
/// dropped and rebuilt: bounds their memory (the verdict cache holds ≈ 300 bytes per point)
/// while a sweep over wing keys rebuilds each wing's basis and pencil only once per window.
pub(crate) const CACHE_POINTS: usize = 1024;

/// sup |g(t_k) − ĝ_k| over the output samples of `cfg` (k a multiple of `samples_per_output`,
/// and k = K), per channel: ζ3 (N), ζ4 (N m) of (32) as
/// `wingcheck_claims::mu::disturbance_bounds` defines them (sup over the FTDO run's series).
pub fn sup_tilde(signal: &RecordedSignal, cfg: &Config) -> (f64, f64) {
    let (every, total) = (cfg.samples_per_output(), cfg.total_samples());
    let samples = signal.samples();
    // the output samples k = 0, every, 2·every, … and K, in that order
    // (`every` ≥ 1: `samples_per_output` rounds up to one, as the driver's `k % every` needs)
    let outputs = (0..=total).step_by(every).chain((total % every != 0).then_some(total));
    let sup = |c: usize| outputs.clone().map(|k| (samples[k].g[c] - samples[k].g_hat[c]).abs()).fold(0.0, f64::max);
    (sup(0), sup(1))
}

/// What the metrics need of a run, at the output samples: t (s), q(s,t) (m), θ(s,t) (rad),
/// τ1 (N), τ2 (N m), g̃ = g − ĝ per channel, and E(T) (J).
#[derive(Debug, Clone, Default, PartialEq, Serialize, schemars::JsonSchema)]
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
    /// Full-rate RMS of τ1 (N) and τ2 (N m) over [0, T]: √(∫τ² dt / T) from every integrator
    /// step, as `wingcheck_sim::windowed_rms` of the series' interval values over the run
    /// (|τ| at t = 0 for a run of zero length).
    pub tau_rms: [f64; 2],
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
    /// Empty, with room for `samples` output samples (allocated once: the search's memory
    /// estimate counts exactly these vectors).
    pub fn with_capacity(samples: usize) -> TipTrace {
        let v = || Vec::with_capacity(samples);
        TipTrace {
            t: v(),
            q_tip: v(),
            theta_tip: v(),
            tau1: v(),
            tau2: v(),
            g1_tilde: v(),
            g2_tilde: v(),
            ..Default::default()
        }
    }

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
            tau_rms: [&s.tau1_rms, &s.tau2_rms].map(|interval| {
                let t_end = s.t.last().copied().unwrap_or(0.0);
                wingcheck_sim::windowed_rms(&s.t, interval, 0.0, t_end)
                    .or_else(|| interval.first().copied())
                    .unwrap_or(0.0)
            }),
            g1_tilde: tilde(&s.g1, &s.g1_hat),
            g2_tilde: tilde(&s.g2, &s.g2_hat),
            energy_end: s.energy.last().copied().unwrap_or(0.0),
        }
    }
}

/// What the search records of a run: the tip trace at the output samples, the full-rate τ
/// square integral over the whole run and max |τ| (the values `simulate` folds into its `Peaks`
/// and RMS).
#[derive(Default)]
struct Trace {
    trace: TipTrace,
    squares: SquareIntegral,
    peak: [f64; 2],
}

impl Recorder for Trace {
    fn instant(
        &mut self,
        lp: &ModalLoop<'_>,
        st: &ModalState,
        t: f64,
        g_hat: [f64; 2],
        _: Option<[f64; 2]>,
        exact: Option<[f64; 2]>,
    ) {
        let tau = [0, 1].map(|c| lp.tau(c, st.x_tip[c], st.v_tip[c], g_hat[c]));
        for c in 0..2 {
            self.peak[c] = self.peak[c].max(tau[c].abs());
        }
        self.squares.update_step(t, tau, exact);
    }

    fn deferred_squares(&mut self, squares: [f64; 2]) {
        self.squares.add_squares(squares);
    }

    fn reads(&self) -> Reads {
        Reads::OUTPUTS
    }

    fn output(&mut self, _: &ModalState, s: &Sample, _: usize) -> Result<(), SimError> {
        let tr = &mut self.trace;
        tr.t.push(s.t);
        tr.q_tip.push(s.q_tip);
        tr.theta_tip.push(s.theta_tip);
        tr.tau1.push(s.tau1);
        tr.tau2.push(s.tau2);
        tr.g1_tilde.push(s.g1 - s.g1_hat);
        tr.g2_tilde.push(s.g2 - s.g2_hat);
        tr.energy_end = s.energy;
        Ok(())
    }
}

/// Run the closed loop of `cfg` on a shared basis and signal (built from configurations that
/// agree with `cfg` on the keys they read; [`RunCache`] guarantees it), with the scheme
/// `cfg.time_scheme(true)` selects (`discretisation.stepper`, `auto` resolved), through the
/// simulator's driver.
pub fn run(cfg: &Config, basis: &ModalBasis, signal: &RecordedSignal) -> Result<TipTrace, SimError> {
    cfg.validate().map_err(SimError::Config)?;
    let lp = ModalLoop::with_eigenbasis(cfg, basis)?;
    let mut st = lp.initial_state(cfg, basis);
    trace(cfg, basis, &lp, &mut st, &mut signal.replay())
}

/// [`run`] under a controller of the user's, made and reset for this run: its continuous
/// part in the loop, its held inputs sampled from the modal state at every t_k
/// ([`ControlledSignal`], as `simulate` does it; the exponential scheme in its dense form).
pub fn run_controlled(cfg: &Config, basis: &ModalBasis, make: ControllerFactory<'_>) -> Result<TipTrace, SimError> {
    cfg.validate().map_err(SimError::Config)?;
    let (lp, mut st, mut signal) = controlled_loop(cfg, basis, make)?;
    trace(cfg, basis, &lp, &mut st, &mut signal)
}

/// The trace of the loop `lp` from `st` under `signal`.
fn trace<S: Signal>(
    cfg: &Config,
    basis: &ModalBasis,
    lp: &ModalLoop<'_>,
    st: &mut ModalState,
    signal: &mut S,
) -> Result<TipTrace, SimError> {
    let mut rec = Trace { trace: TipTrace::with_capacity(cfg.output_samples()), ..Default::default() };
    drive(cfg, basis, lp, st, signal, &mut rec)?;
    rec.trace.tau_peak = rec.peak;
    // one interval: the whole run (the squares' start is t = 0, their end the last step's)
    rec.trace.tau_rms = rec.squares.take_rms();
    Ok(rec.trace)
}

/// A cache's entries: each value is built once, by the first thread that asks for it, while the
/// others asking for the same key wait for it (a signal of 2 GB was built by every worker at
/// once: 3 × 1.44 GB at 3 threads).
type Cells<T> = Mutex<HashMap<String, Arc<OnceLock<Arc<T>>>>>;

fn cache_get<T>(map: &Cells<T>, key: String, make: impl FnOnce() -> T) -> Arc<T> {
    let cell = {
        let mut m = map.lock().expect("cache lock");
        if !m.contains_key(&key) && m.len() >= CACHE_ENTRIES {
            m.clear();
        }
        m.entry(key).or_default().clone()
    };
    cell.get_or_init(|| Arc::new(make())).clone()
}

/// Shared modal bases and input signals of a search (thread-safe; values are pure functions
/// of their keys, so caching never changes a result).
#[derive(Default)]
pub struct RunCache {
    bases: Cells<Option<ModalBasis>>,
    signals: Cells<RecordedSignal>,
    /// [`sup_tilde`] of each signal (it reads the signal and the output sampling and horizon,
    /// which its key contains).
    sup_tildes: Cells<(f64, f64)>,
}

impl RunCache {
    /// Empty caches.
    pub fn new() -> Self {
        Self::default()
    }

    /// Modal basis of the wing, under the simulator's key for it ([`ModalBasis::key`]); `None`
    /// where the simulator runs `cfg` in another basis, or cannot make this one (the simulator,
    /// run instead, then says why).
    pub fn basis(&self, cfg: &Config) -> Arc<Option<ModalBasis>> {
        cache_get(&self.bases, ModalBasis::key(cfg), || {
            // the simulator's own choice of basis (`discretisation.basis`), so a point is run
            // in the modal basis exactly when `simulate` would be
            let disc = wingcheck_sim::Discretisation::new(cfg);
            match wingcheck_sim::resolved_basis(cfg, &disc) {
                Ok((_, basis)) => basis,
                Err(_) => None,
            }
        })
    }

    /// Observer signal of `cfg`, under the simulator's key for it ([`ObserverSignal::key`]).
    pub fn signal(&self, cfg: &Config) -> Arc<RecordedSignal> {
        cache_get(&self.signals, ObserverSignal::key(cfg), || RecordedSignal::new(cfg))
    }

    /// [`sup_tilde`] of the observer signal of `cfg`, once per signal (a pass over every
    /// sample of the run: ≈ 4 % of a point's time when it was computed for each point).
    pub fn sup_tilde(&self, cfg: &Config) -> (f64, f64) {
        *cache_get(&self.sup_tildes, ObserverSignal::key(cfg), || sup_tilde(&self.signal(cfg), cfg))
    }
}

//! The initial layer: where the solution varies faster than one step can show.
//!
//! With strong tip damping (large b) the tip rates jump at t = 0 and relax within microseconds,
//! a transient far shorter than `discretisation.dt`: an L-stable step damps it away, so the
//! full-rate peak of q̇(s,t) at dt = 1 ms can be 30 % below its dt → 0 value (measured at
//! a = 1, b = 3500: 3.16e-4 m/s against 4.47e-4 m/s at dt = 1e-6 s), and halving dt does not
//! reveal it. [`resolve`] re-runs the first [`LAYER_SAMPLES`] observer sample periods at
//! dt/10, dt/100, … until the layer's peaks converge (two successive refinements shrinking by
//! the scheme's order, the last change below [`LAYER_TOLERANCE`] relative), and takes each
//! full-rate peak as the larger of the resolved layer's and the base run's after the layer.
//!
//! After the layer, the held estimate jumps every sample period: the exponential scheme probes
//! the exact solution inside the first step after each jump (`crate::modal`'s sub-step probe,
//! [`crate::Peak::sub_step_error`]); the implicit schemes have no probe, and there a sub-step
//! transient after a later jump comes from the base run's steps (the implicit FTDO's later
//! jumps are small once the estimate has converged).

use serde::Serialize;
use wingcheck_model::Config;

use crate::{Peak, Peaks, SimError, SimOutput};

/// Observer sample periods at the start of a run re-run at finer steps (or the whole run when
/// it is shorter).
pub use wingcheck_model::work::LAYER_SAMPLES;

/// Refinement factor between successive layer runs, and the finest layer step relative to
/// `discretisation.dt` (never below validation's 1e-9 s); the runs stop earlier at their work
/// budget ([`wingcheck_model::work::layer_budget`]).
pub use wingcheck_model::work::{LAYER_MIN_FRACTION, LAYER_REFINEMENT};

/// Convergence of the layer's peaks: the last refinement changed no peak by more than this
/// fraction of its value (the change itself is then the peak's layer error, so this only
/// decides when to stop refining).
pub const LAYER_TOLERANCE: f64 = 1e-4;

/// Relative round-off floor of a full-rate peak: 256 ulp of its value (measured: τ2(0) off
/// by 1.6e-13 N m at 6.33 N m between bases and schemes, 2.5e-14 relative).
pub const PEAK_ROUND_OFF: f64 = 256.0 * f64::EPSILON;

/// How the initial layer was resolved.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
pub struct InitialLayer {
    /// End of the layer (s): [`LAYER_SAMPLES`] observer sample periods.
    pub t_end: f64,
    /// Step of the finest layer run (s).
    pub finest_dt: f64,
    /// Layer runs made (each [`LAYER_REFINEMENT`] × finer than the last).
    pub runs: usize,
    /// Whether the layer's peaks converged before the finest step ([`LAYER_TOLERANCE`]).
    pub converged: bool,
    /// Error of each layer peak, in the order of [`Peaks::signals`]: the whole change of the
    /// last refinement (a peak read at step ends converges erratically, so no extrapolation),
    /// or the whole value for a peak still changing by more than [`LAYER_TOLERANCE`] when the
    /// work budget ran out, plus the round-off floor.
    pub errors: [f64; 8],
    /// Whether a peak of the resolved layer exceeds the base run's (the base run missed a
    /// sub-step transient).
    pub raised: bool,
}

/// End of the initial layer of `cfg` (s).
pub fn layer_end(cfg: &Config) -> f64 {
    LAYER_SAMPLES.min(cfg.total_samples().max(1)) as f64 * cfg.observer.sample_period
}

/// The configuration of one layer run: the first [`layer_end`] seconds at step `dt`.
pub(crate) fn layer_config(cfg: &Config, dt: f64) -> Config {
    let mut c = cfg.clone();
    c.horizon.t_end = layer_end(cfg);
    c.horizon.sample_every = cfg.observer.sample_period;
    c.discretisation.dt = dt;
    c
}

/// Resolve the initial layer of `out` (a run of `cfg`): run the layer at successively finer
/// steps with `run`, and raise each peak of `out` to the resolved layer's when that is larger
/// than the base run's peak after the layer. Returns how it was resolved.
pub fn resolve(
    cfg: &Config,
    out: &mut SimOutput,
    mut run: impl FnMut(&Config) -> Result<SimOutput, SimError>,
) -> Result<InitialLayer, SimError> {
    let mut history: Vec<[f64; 8]> = Vec::new();
    let mut best: Option<Peaks> = None;
    let mut converged = false;
    let mut finest_run = cfg.discretisation.dt;
    // bounded: the runs model::work::layer_runs plans within layer_budget(cfg) steps, which the
    // work estimates count (model::work::layer_steps_max)
    for level in wingcheck_model::work::layer_runs(cfg) {
        let layer = run(&layer_config(cfg, level.dt))?;
        finest_run = level.dt;
        let values = layer.peaks.signals().map(|p| p.abs_max);
        if let Some(last) = history.last() {
            let change = max_relative_change(last, &values);
            let shrinking = history.len() < 2 || {
                let before = max_relative_change(&history[history.len() - 2], last);
                change <= before / 10.0 || change <= LAYER_TOLERANCE * 1e-6
            };
            converged = change <= LAYER_TOLERANCE && shrinking;
        }
        history.push(values);
        best = Some(layer.peaks);
        if converged {
            break;
        }
    }
    let layer = best.expect("at least the run at dt itself");
    let runs = history.len();
    let last = history[runs - 1];
    // the remaining error as the whole last change: a peak read at step ends converges
    // erratically (where the steps fall around the peak), so no tail ratio is trusted; not
    // converged within the budget, the layer's peak is not resolved: its whole value
    let errors: [f64; 8] = std::array::from_fn(|i| {
        let change = if runs >= 2 { (last[i] - history[runs - 2][i]).abs() } else { 0.0 };
        let unresolved = !converged && change > LAYER_TOLERANCE * last[i];
        (if unresolved { last[i] } else { change }) + PEAK_ROUND_OFF * last[i]
    });
    let after = out.peaks_after_layer;
    let merged = after.larger(&layer);
    let raised = merged.signals().iter().zip(out.peaks.signals()).any(|(m, p)| m.abs_max > p.abs_max);
    out.peaks = merged;
    Ok(InitialLayer { t_end: layer_end(cfg), finest_dt: finest_run, runs, converged, errors, raised })
}

/// max over the signals of |b − a| / max(|a|, |b|) (0 where both vanish).
fn max_relative_change(a: &[f64; 8], b: &[f64; 8]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            let scale = x.abs().max(y.abs());
            if scale > 0.0 {
                (x - y).abs() / scale
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}

impl Peaks {
    /// The eight signals in a fixed order: q, θ, q̇, θ̇, τ1, τ2, g̃1, g̃2.
    pub fn signals(&self) -> [Peak; 8] {
        [
            self.q_tip,
            self.theta_tip,
            self.q_tip_rate,
            self.theta_tip_rate,
            self.tau1,
            self.tau2,
            self.g1_error,
            self.g2_error,
        ]
    }

    /// Per signal, the peak with the larger |value| of `self` and `other` (`self` on a tie).
    pub fn larger(&self, other: &Peaks) -> Peaks {
        let pick = |a: Peak, b: Peak| if b.abs_max > a.abs_max { b } else { a };
        let [a, b] = [self.signals(), other.signals()];
        Peaks {
            q_tip: pick(a[0], b[0]),
            theta_tip: pick(a[1], b[1]),
            q_tip_rate: pick(a[2], b[2]),
            theta_tip_rate: pick(a[3], b[3]),
            tau1: pick(a[4], b[4]),
            tau2: pick(a[5], b[5]),
            g1_error: pick(a[6], b[6]),
            g2_error: pick(a[7], b[7]),
        }
    }
}

//! Simulations with error estimates: every tip value and full-rate peak of a run with an
//! estimated discretisation error from refinement in h and in dt (Richardson, order 2 in
//! each: FE with linear torsion elements and FD are O(h²), both time schemes O(dt²)):
//! e_h = |u(N) − u(2N)|·F, e_dt = |u(dt) − u(dt/2)|·F with F = 1.25·4/3 (Richardson for order
//! 2 with the grid-convergence-index safety factor 1.25), error = e_h + e_dt per output
//! sample, maximised over ±[`ENVELOPE_HALF_WIDTH`] around it. Cost: the base run plus one run on the doubled grid and one with half the step
//! (≈ 1 + 2 + 2 = 5 base runs of work).

use serde::Serialize;
use wingcheck_model::{Config, Method};

use crate::estimate::Estimate;
use crate::{simulate, Peaks, RunOptions, SchemeObstacle, SimError, SimOutput};

/// Tolerance the default grids are chosen to meet: absolute error on q(s,t) (m) and θ(s,t)
/// (rad) over the whole horizon, switch-on included.
pub const TIP_TOLERANCE: f64 = 2e-4;

/// Richardson factor 2^p/(2^p − 1) = 4/3 for p = 2, which turns a difference between grids h
/// and h/2 into an estimate of the error at h, times Roache's grid-convergence-index safety
/// factor 1.25 (for an order verified by refinement: 1.98 in h for FE, 1.86 for FD, 2.02 in dt,
/// tests/trajectories.rs): 5/3.
pub const RICHARDSON_2: f64 = 1.25 * 4.0 / 3.0;

/// A full-rate peak with its estimated error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
pub struct PeakEstimate {
    /// max |value| over the horizon at full rate, with its error.
    pub abs_max: Estimate,
    /// Time of the peak in the base run (s).
    pub t: f64,
    /// Whether three grids show the asymptotic order ([`grid_part`]): the N → 2N change is at
    /// least 3 × the 2N → 4N one (observed order ≥ log₂3; 2 expected), or at round-off level.
    /// Otherwise (no 4N run, or a change that does not shrink so: the tip-rate peak right after
    /// t = 0 with strong tip damping, whose layer sharpens with the grid; a post-jump tip-rate
    /// peak at large b, falling ≈ 3.5 % per halving of h) the grid part of the error is
    /// |u(N) − u(4N)| plus the geometric tail of the differences, or the whole value when they
    /// do not shrink, and every printed form says "not converged in the grid" with the trend.
    pub grid_converged: bool,
    /// The peak on the grid sequence N, 2N, 4N (elements or intervals, [`Self::grids`]); the 4N
    /// value is absent when that run was not made ([`EstimatedRun::third_grid`]).
    pub grid_values: [Option<f64>; 3],
    /// The grid sizes N, 2N, 4N of [`Self::grid_values`].
    pub grids: [usize; 3],
}

impl PeakEstimate {
    /// Whether the bar is at least half the value: the peak is unresolved (printed as a range,
    /// never as "value ± bar"), by the one rule of the number format
    /// ([`wingcheck_model::format::is_unresolved`]).
    pub fn unresolved(&self) -> bool {
        wingcheck_model::format::is_unresolved(self.abs_max.value, self.abs_max.error) || self.abs_max.error.is_nan()
    }

    /// The one printed form of a peak with its error, in `unit`: `2.2780e-3 ± 1.2e-4 rad/s`;
    /// an unresolved one as `unresolved: between 0 and 1.383 N`; one whose grid sequence does
    /// not converge followed by `(not converged in the grid: N 24 …, 2N 48 …, 4N 96 …; −3.5 %
    /// per halving)`. Used by `simulate` (text); the JSON carries the same fields.
    pub fn text(&self, unit: &str) -> String {
        use wingcheck_model::quantity::{format_error, format_value};
        let (v, e) = (self.abs_max.value, self.abs_max.error);
        let mut out = if self.unresolved() {
            format!(
                "unresolved: between {} and {} {unit}",
                format_value((v - e).max(0.0), None),
                format_value(v + e, None)
            )
        } else {
            format!("{} ± {} {unit}", format_value(v, Some(e)), format_error(e))
        };
        if !self.grid_converged {
            out.push_str(&format!(" (not converged in the grid: {})", self.trend()));
        }
        out
    }

    /// The grid sequence as printed: each grid's value and the last relative change per
    /// halving of h.
    fn trend(&self) -> String {
        let values: Vec<(usize, f64)> =
            self.grids.iter().zip(self.grid_values).filter_map(|(&n, v)| v.map(|v| (n, v))).collect();
        let mut parts: Vec<String> = values
            .iter()
            .map(|(n, v)| format!("{n}: {}", wingcheck_model::quantity::with_significant(*v, 5)))
            .collect();
        if let [.., (_, a), (_, b)] = values.as_slice() {
            if *a != 0.0 {
                parts.push(format!("{:+.2} % per halving of h", 100.0 * (b / a - 1.0)));
            }
        }
        if values.len() < 3 {
            parts.push(format!("{} not run", self.grids[2]));
        }
        parts.join(", ")
    }
}

/// Full-rate peaks with errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
pub struct PeakEstimates {
    /// |q(s,t)| (m).
    pub q_tip: PeakEstimate,
    /// |θ(s,t)| (rad).
    pub theta_tip: PeakEstimate,
    /// |q̇(s,t)| (m/s).
    pub q_tip_rate: PeakEstimate,
    /// |θ̇(s,t)| (rad/s).
    pub theta_tip_rate: PeakEstimate,
    /// |τ1| (N).
    pub tau1: PeakEstimate,
    /// |τ2| (N m).
    pub tau2: PeakEstimate,
    /// |g1 − ĝ1| (N).
    pub g1_error: PeakEstimate,
    /// |g2 − ĝ2| (N m).
    pub g2_error: PeakEstimate,
}

/// A run with its discretisation-error estimates.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct EstimatedRun {
    /// The base run (the configuration as given).
    pub output: SimOutput,
    /// Grid of the spatial refinement run (elements / intervals, 2N).
    pub refined_grid: usize,
    /// Step of the temporal refinement run (s, dt/2).
    pub refined_dt: f64,
    /// Time scheme of both refinement runs: the base run's (`stats.stepper`).
    pub refined_stepper: wingcheck_model::TimeScheme,
    /// Estimated absolute error of q(s,t_k) (m) at each output sample.
    pub q_tip_error: Vec<f64>,
    /// Estimated absolute error of θ(s,t_k) (rad) at each output sample.
    pub theta_tip_error: Vec<f64>,
    /// Max of `q_tip_error` over the horizon (m).
    pub max_q_tip_error: f64,
    /// Max of `theta_tip_error` over the horizon (rad).
    pub max_theta_tip_error: f64,
    /// Max spatial part over the horizon, max(q, θ).
    pub max_space_error: f64,
    /// Max temporal part over the horizon, max(q, θ).
    pub max_time_error: f64,
    /// Full-rate peaks with errors.
    pub peaks: PeakEstimates,
    /// [`TIP_TOLERANCE`].
    pub tolerance: f64,
    /// Whether both maxima are within the tolerance.
    pub meets_tolerance: bool,
    /// How the peaks were checked for sub-step transients after the initial layer.
    pub sub_step_check: SubStepCheck,
    /// The third grid (4N) of the peaks' grid sequence ([`third_grid_run`]).
    pub third_grid: ThirdGrid,
}

/// The 4N run of the peaks' grid sequence ([`third_grid_run`]).
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum ThirdGrid {
    /// It ran over [0, `t_end`] (s).
    Ran {
        /// Its horizon's end (s): the latest N or 2N peak plus one observer sample period.
        t_end: f64,
    },
    /// It was not made (the reason); no peak is then called converged in the grid.
    NotRun {
        /// Why.
        reason: String,
    },
}

/// How a run's full-rate peaks were checked for a transient shorter than dt after a later jump
/// of the held inputs (the initial layer is resolved by every run, [`crate::layer`]).
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum SubStepCheck {
    /// The base run's own scheme (exponential) probed the first step after every jump; each
    /// probed peak's ± includes the probe's resolution ([`crate::Peak::sub_step_error`]).
    Probed,
    /// The base run's scheme has no probe: a twin run with the exponential scheme (modal basis,
    /// same grid, step and observer) probed instead, and each peak's ± includes how far the
    /// twin's probed value after the layer (plus its resolution) exceeds the base's.
    Twin {
        /// Peaks whose ± the twin raised.
        raised: usize,
    },
    /// Neither was possible (the reason: e.g. a grid above the modal basis's limit).
    Unavailable {
        /// Why.
        reason: String,
    },
}

impl EstimatedRun {
    /// q(s,t) and θ(s,t) at time t (linear interpolation between output samples) with their
    /// errors (the larger error of the two bracketing samples).
    pub fn tip_at(&self, t: f64) -> (Estimate, Estimate) {
        let s = &self.output.series;
        let i = s.t.partition_point(|&x| x <= t).min(s.len() - 1);
        let j = i.saturating_sub(1);
        let err = |e: &[f64]| e[i].max(e[j]);
        (
            Estimate { value: s.at(&s.q_tip, t), error: err(&self.q_tip_error) },
            Estimate { value: s.at(&s.theta_tip, t), error: err(&self.theta_tip_error) },
        )
    }
}

fn refined_space(cfg: &Config) -> Config {
    wingcheck_model::work::refined_in_space(cfg)
}

fn refined_time(cfg: &Config) -> Config {
    wingcheck_model::work::refined_in_time(cfg)
}

impl PeakEstimates {
    /// The eight estimates in the order of [`Peaks::signals`]: q, θ, q̇, θ̇, τ1, τ2, g̃1, g̃2.
    pub fn signals(&self) -> [PeakEstimate; 8] {
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

    /// The same, to change.
    fn signals_mut(&mut self) -> [&mut PeakEstimate; 8] {
        let PeakEstimates { q_tip, theta_tip, q_tip_rate, theta_tip_rate, tau1, tau2, g1_error, g2_error } = self;
        [q_tip, theta_tip, q_tip_rate, theta_tip_rate, tau1, tau2, g1_error, g2_error]
    }
}

/// The grid part of a peak's error from its values u = [u(N), u(2N), u(4N)] (the last absent
/// when the 4N run was not made), and whether the grid sequence converges: with three grids
/// and the N → 2N change at least 3 × the 2N → 4N one (or at round-off level, 1e-10 relative:
/// far above it, far below any discretisation error this is used for), Richardson on the
/// coarse pair, (5/3)·|u(N) − u(2N)| ([`RICHARDSON_2`]; the whole geometric tail from N is at
/// most 1.5·|u(N) − u(2N)| then); with three grids otherwise, |u(N) − u(4N)| plus the
/// geometric tail d₂/(ρ − 1) (ρ = d₁/d₂ > 1.05), or |u(N)| when the changes do not shrink; with
/// two grids, the two-grid Richardson bar, not called converged.
pub fn grid_part(u: [Option<f64>; 3]) -> (f64, bool) {
    let (Some(u0), Some(u1)) = (u[0], u[1]) else {
        return (f64::INFINITY, false);
    };
    let d1 = (u0 - u1).abs();
    let Some(u2) = u[2] else {
        return (RICHARDSON_2 * d1, false);
    };
    let d2 = (u1 - u2).abs();
    if 3.0 * d2 <= d1 || d1 <= 1e-10 * u0.abs() {
        return (RICHARDSON_2 * d1, true);
    }
    let ratio = d1 / d2;
    let tail = if ratio > 1.05 { d2 / (ratio - 1.0) } else { u0.abs() };
    ((u0 - u2).abs() + tail, false)
}

/// Each peak's error: its grid part from N, 2N and 4N ([`grid_part`]; the refined runs resolve
/// their own initial layers), Richardson in dt, plus, for a peak inside the initial layer, the
/// layer's own error ([`crate::layer::InitialLayer::errors`]), plus, for a peak found inside a
/// step by the exponential scheme's sub-step probe, the probe's one-sided resolution
/// ([`crate::Peak::sub_step_error`]), plus the round-off floor [`crate::layer::PEAK_ROUND_OFF`]
/// of its value.
fn peak_estimates(
    base: &SimOutput,
    space: &Peaks,
    time: &Peaks,
    fourth: Option<&Peaks>,
    grids: [usize; 3],
) -> PeakEstimates {
    let layer = base.initial_layer;
    let [b, s, t] = [base.peaks.signals(), space.signals(), time.signals()];
    let fine = fourth.map(|p| p.signals());
    let e: [PeakEstimate; 8] = std::array::from_fn(|i| {
        let inside = layer.filter(|l| b[i].t <= l.t_end);
        let grid_values = [Some(b[i].abs_max), Some(s[i].abs_max), fine.map(|f| f[i].abs_max)];
        let (grid, grid_converged) = grid_part(grid_values);
        let time_part = RICHARDSON_2 * (b[i].abs_max - t[i].abs_max).abs();
        let in_layer = inside.map_or(0.0, |l| l.errors[i]);
        PeakEstimate {
            abs_max: Estimate {
                value: b[i].abs_max,
                error: grid + time_part + in_layer + b[i].sub_step_error + crate::layer::PEAK_ROUND_OFF * b[i].abs_max,
            },
            t: b[i].t,
            grid_converged,
            grid_values,
            grids,
        }
    });
    PeakEstimates {
        q_tip: e[0],
        theta_tip: e[1],
        q_tip_rate: e[2],
        theta_tip_rate: e[3],
        tau1: e[4],
        tau2: e[5],
        g1_error: e[6],
        g2_error: e[7],
    }
}

/// Half-width (s) of the window over which a pointwise estimate is maximised: the difference
/// between two grids crosses zero where the error itself need not.
pub const ENVELOPE_HALF_WIDTH: f64 = 0.1;

/// e_k ← max{e_j : |t_j − t_k| ≤ ENVELOPE_HALF_WIDTH} (two-pointer sliding maximum, O(n·w)).
fn envelope(t: &[f64], e: &[f64]) -> Vec<f64> {
    let n = t.len();
    let mut out = Vec::with_capacity(n);
    let (mut lo, mut hi) = (0usize, 0usize);
    for k in 0..n {
        while t[lo] < t[k] - ENVELOPE_HALF_WIDTH {
            lo += 1;
        }
        while hi + 1 < n && t[hi + 1] <= t[k] + ENVELOPE_HALF_WIDTH {
            hi += 1;
        }
        out.push(e[lo..=hi].iter().copied().fold(0.0, f64::max));
    }
    out
}

/// Run `cfg` and estimate the discretisation error of every output sample's tip values and of
/// the full-rate peaks by one refinement in h and one in dt. Refuses (as a configuration
/// error) a refinement the validation would refuse, e.g. a doubled grid above 4000. Both
/// refined runs use the time scheme the base run used (`stats.stepper`; with `auto` the doubled
/// grid could otherwise cross into the nodal basis and another scheme, whose error the estimate
/// would absorb); a refined grid that cannot run it is an error saying so.
pub fn simulate_with_error(cfg: &Config, opts: RunOptions<'_>) -> Result<EstimatedRun, SimError> {
    cfg.validate()?;
    let (mut space_cfg, mut time_cfg) = (refined_space(cfg), refined_time(cfg));
    space_cfg.validate()?;
    time_cfg.validate()?;
    let (cancel, controller) = (opts.cancel.clone(), opts.controller);
    let refined = || RunOptions { cancel: cancel.clone(), controller, ..Default::default() };
    let output = simulate(cfg, opts)?;
    let scheme = output.stats.stepper;
    space_cfg.discretisation.stepper = scheme;
    time_cfg.discretisation.stepper = scheme;
    let obstacle = |reason: SchemeObstacle| SimError::RefinementScheme {
        grid: space_cfg.discretisation.grid_size(),
        unit: if space_cfg.discretisation.method == Method::Fe { "elements" } else { "intervals" },
        scheme,
        reason,
    };
    let space = simulate(&space_cfg, refined()).map_err(|e| match e {
        SimError::Numerical(reason) => obstacle(reason.into()),
        SimError::NoModalBasis { reason } => obstacle(reason.into()),
        SimError::ExponentialNeedsModal(reason) => obstacle(reason.into()),
        other => other,
    })?;
    let time = simulate(&time_cfg, refined())?;
    let fourth = third_grid_run(&output, &space, &space_cfg, refined());
    let twin = (scheme != wingcheck_model::TimeScheme::Exponential).then(|| sub_step_twin(cfg, refined()));
    // the 4N run's, the twin's and the layer check's failures are findings, not errors: a
    // cancelled one is not
    cancel.check()?;
    let mut estimated = estimate_from_runs(output, &space, &time, fourth.as_ref(), &space_cfg, &time_cfg);
    if let Some(twin) = twin {
        estimated.apply_twin(twin);
    }
    Ok(estimated)
}

/// Why an extra run of the error estimate (the peaks' 4N grid, the exponential twin) was not
/// made; a finding recorded in [`ThirdGrid::NotRun`] / [`SubStepCheck::Unavailable`], not an
/// error of the estimate.
#[derive(Debug, thiserror::Error)]
pub enum ExtraRunError {
    /// Its configuration is not valid (e.g. 4N above the grid limit).
    #[error("the {run} is not a valid configuration: {cause}")]
    Invalid {
        /// The run (`4N grid`, `exponential twin`).
        run: &'static str,
        /// The validation error.
        #[source]
        cause: wingcheck_model::ConfigError,
    },
    /// It failed.
    #[error("the {run} did not run: {cause}")]
    Failed {
        /// The run (`4N run`, `exponential twin`).
        run: &'static str,
        /// The simulator's error.
        #[source]
        cause: SimError,
    },
    /// The caller did not make it, and why.
    #[error("not made: {0}")]
    NotMade(&'static str),
}

/// The twin of `cfg` that probes inside its steps: the exponential scheme in the modal basis,
/// at the configured step only (the base run resolves its own initial layer).
fn sub_step_twin(cfg: &Config, opts: RunOptions<'_>) -> Result<SimOutput, ExtraRunError> {
    let mut twin = cfg.clone();
    twin.discretisation.stepper = wingcheck_model::TimeScheme::Exponential;
    twin.discretisation.basis = wingcheck_model::StepBasis::Modal;
    twin.validate().map_err(|cause| ExtraRunError::Invalid { run: "exponential twin", cause })?;
    crate::simulate_base(&twin, opts).map_err(|cause| ExtraRunError::Failed { run: "exponential twin", cause })
}

impl EstimatedRun {
    /// Fold in the exponential twin's probed peaks ([`SubStepCheck::Twin`]), or say why there
    /// is none.
    fn apply_twin(&mut self, twin: Result<SimOutput, ExtraRunError>) {
        let twin = match twin {
            Ok(t) => t,
            Err(e) => {
                self.sub_step_check = SubStepCheck::Unavailable { reason: e.to_string() };
                return;
            }
        };
        let layer_end = self.output.initial_layer.map_or(0.0, |l| l.t_end);
        let base = self.output.peaks.signals();
        let mut raised = 0;
        // the probe sees q, θ, q̇, θ̇, τ1, τ2 (the first six); g̃ is the observer's
        let probed =
            self.peaks.signals_mut().into_iter().zip(twin.peaks.signals()).zip(base).take(crate::modal::PROBED);
        for ((e, t), b) in probed {
            let inside_a_step = t.sub_step_error > 0.0 && t.t > layer_end;
            let excess = t.abs_max + t.sub_step_error - b.abs_max;
            if inside_a_step && excess > 0.0 {
                e.abs_max.error += excess;
                raised += 1;
            }
        }
        self.sub_step_check = SubStepCheck::Twin { raised };
    }
}

/// The two refinements of `cfg` that [`simulate_with_error`] runs — the doubled grid and the
/// halved step — both with the time scheme `scheme` of the base run (`stats.stepper`), for a
/// caller that simulates them itself (e.g. through a cache shared with other runs).
pub fn refinements(cfg: &Config, scheme: wingcheck_model::TimeScheme) -> (Config, Config) {
    let (mut space_cfg, mut time_cfg) = (refined_space(cfg), refined_time(cfg));
    space_cfg.discretisation.stepper = scheme;
    time_cfg.discretisation.stepper = scheme;
    (space_cfg, time_cfg)
}

/// The error estimates of a base run from its two refinements ([`refinements`]) and the peaks'
/// third grid ([`third_grid_run`], or why it was not made): what [`simulate_with_error`]
/// returns, for runs simulated elsewhere.
pub fn estimate_from_runs(
    output: SimOutput,
    space: &SimOutput,
    time: &SimOutput,
    fourth: Result<&SimOutput, &ExtraRunError>,
    space_cfg: &Config,
    time_cfg: &Config,
) -> EstimatedRun {
    let output_scheme = output.stats.stepper;
    let (b, s, t) = (&output.series, &space.series, &time.series);
    let n = b.len();
    let (mut eq, mut et) = (Vec::with_capacity(n), Vec::with_capacity(n));
    let (mut max_space, mut max_time): (f64, f64) = (0.0, 0.0);
    for k in 0..n {
        let sq = RICHARDSON_2 * (b.q_tip[k] - s.q_tip[k]).abs();
        let st = RICHARDSON_2 * (b.theta_tip[k] - s.theta_tip[k]).abs();
        let tq = RICHARDSON_2 * (b.q_tip[k] - t.q_tip[k]).abs();
        let tt = RICHARDSON_2 * (b.theta_tip[k] - t.theta_tip[k]).abs();
        max_space = max_space.max(sq).max(st);
        max_time = max_time.max(tq).max(tt);
        eq.push(sq + tq);
        et.push(st + tt);
    }
    let eq = envelope(&b.t, &eq);
    let et = envelope(&b.t, &et);
    debug_assert_eq!(eq, series_error(&b.t, &b.q_tip, &s.q_tip, &t.q_tip));
    let max_q = eq.iter().copied().fold(0.0, f64::max);
    let max_t = et.iter().copied().fold(0.0, f64::max);
    let grid = space_cfg.discretisation.grid_size();
    let grids = [grid / 2, grid, 2 * grid];
    let peaks = peak_estimates(&output, &space.peaks, &time.peaks, fourth.ok().map(|o| &o.peaks), grids);
    let third_grid = match fourth {
        Ok(o) => ThirdGrid::Ran { t_end: o.series.t.last().copied().unwrap_or(0.0) },
        Err(e) => ThirdGrid::NotRun { reason: e.to_string() },
    };
    EstimatedRun {
        output,
        refined_grid: space_cfg.discretisation.grid_size(),
        refined_dt: time_cfg.discretisation.dt,
        refined_stepper: space.stats.stepper,
        q_tip_error: eq,
        theta_tip_error: et,
        max_q_tip_error: max_q,
        max_theta_tip_error: max_t,
        max_space_error: max_space,
        max_time_error: max_time,
        peaks,
        tolerance: TIP_TOLERANCE,
        meets_tolerance: max_q <= TIP_TOLERANCE && max_t <= TIP_TOLERANCE,
        sub_step_check: if output_scheme == wingcheck_model::TimeScheme::Exponential {
            SubStepCheck::Probed
        } else {
            SubStepCheck::Unavailable { reason: "no twin run was made for this estimate".into() }
        },
        third_grid,
    }
}

/// The third grid of the peaks' grid sequence ([`grid_part`]): the doubled grid of the spatial
/// refinement `space_cfg` (4N), its time scheme and step, over [0, t₄] with t₄ the latest time
/// of any peak of the base run and the 2N run plus one observer sample period (whole periods,
/// at most the horizon; a 4N maximum later than every N and 2N peak is not seen). Its own
/// initial layer and sub-step probe are resolved like every run's. The error when it cannot
/// run (e.g. 4N above the grid limit).
pub fn third_grid_run(
    output: &SimOutput,
    space: &SimOutput,
    space_cfg: &Config,
    opts: RunOptions,
) -> Result<SimOutput, ExtraRunError> {
    let mut fine = refined_space(space_cfg);
    fine.horizon = third_grid_horizon(output, space, space_cfg);
    fine.validate().map_err(|cause| ExtraRunError::Invalid { run: "4N grid", cause })?;
    simulate(&fine, opts).map_err(|cause| ExtraRunError::Failed { run: "4N run", cause })
}

/// The horizon of [`third_grid_run`]: [0, t₄] sampled every observer period.
fn third_grid_horizon(output: &SimOutput, space: &SimOutput, cfg: &Config) -> wingcheck_model::Horizon {
    let period = cfg.observer.sample_period;
    let latest = output.peaks.signals().iter().chain(space.peaks.signals().iter()).map(|p| p.t).fold(0.0, f64::max);
    let periods = ((latest / period).floor() as usize + 1).max(1);
    let mut h = cfg.horizon.clone();
    if periods >= cfg.total_samples() {
        return h;
    }
    h.t_end = periods as f64 * period;
    h.sample_every = period;
    h
}

/// The estimated error of any sampled series of a run from the same series of its two
/// refinements ([`refinements`]), by the rule of the tip values: F·(|u − u(2N)| + |u − u(dt/2)|)
/// per sample (F = [`RICHARDSON_2`]), maximised over ±[`ENVELOPE_HALF_WIDTH`].
pub fn series_error(t: &[f64], base: &[f64], space: &[f64], time: &[f64]) -> Vec<f64> {
    let e: Vec<f64> = base
        .iter()
        .zip(space.iter().zip(time))
        .map(|(b, (s, t))| RICHARDSON_2 * (b - s).abs() + RICHARDSON_2 * (b - t).abs())
        .collect();
    envelope(t, &e)
}

/// Work of [`simulate_with_error`] in units of the base run's unknown-steps (for the
/// bounded-work guards of callers): 1 + 2 (doubled grid) + 2 (half step) + at most 4 (the
/// peaks' 4N grid, [`third_grid_run`]) = 9.
pub const WORK_FACTOR: f64 = 9.0;

//! The `simulate --json` document ([`SimulateSummary`], docs/schema/simulate.schema.json): the
//! settings run, the cost, the tip values at the sample times and the full-rate peaks, built
//! from a [`SimulateResult`] by [`SimulateSummary::of`].

use serde::Serialize;
use wingcheck_sim::{EstimatedRun, SubStepCheck};

use crate::SimulateResult;

/// `simulate --json`: the settings run, the cost, the tip values at the requested times and the
/// full-rate peaks (docs/schema/simulate.schema.json).
#[derive(Serialize, schemars::JsonSchema)]
pub struct SimulateSummary {
    /// Layout version ([`wingcheck_io::SCHEMA_VERSION`]).
    pub schema_version: u32,
    /// Tool build and the configuration's SHA-256 (the files listed: `--out`, if given).
    pub provenance: wingcheck_io::Provenance,
    /// What was run.
    pub settings: RunSettings,
    /// Wall time of the run (s; not reproducible).
    pub run_seconds: f64,
    /// Cost statistics.
    pub stats: wingcheck_sim::RunStats,
    /// The tip at the sample times.
    pub tip: TipValues,
    /// Full-rate peaks (every integrator step, both sides of each jump).
    pub peaks: wingcheck_sim::Peaks,
    /// How the initial layer was resolved (peaks within it from runs at finer steps).
    pub initial_layer: Option<wingcheck_sim::layer::InitialLayer>,
    /// The output file written, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub out: Option<String>,
    /// With `--error-estimate`: the discretisation error estimate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_estimate: Option<ErrorSummary>,
}

/// The settings of a simulate run.
#[derive(Serialize, schemars::JsonSchema)]
pub struct RunSettings {
    /// Controller: none, pd, ftdo, dobc.
    pub controller: String,
    /// Observer rule: implicit or explicit.
    pub observer: String,
    /// Spatial discretisation: fe or fd.
    pub method: String,
    /// Elements (FE) or intervals (FD).
    pub elements: usize,
    /// Mesh grading (FE; 0 = uniform).
    pub grading: f64,
    /// Integrator step (s).
    pub dt: f64,
    /// The time scheme used.
    pub stepper: wingcheck_model::TimeScheme,
    /// Observer sample period (s).
    pub sample_period: f64,
    /// Horizon T (s).
    pub t_end: f64,
    /// Weight a of the control law (15) (dimensionless).
    pub a: f64,
    /// Weight b of the control law (15) (s).
    pub b: f64,
}

/// Tip values at the sample times, with their errors under `--error-estimate`.
#[derive(Serialize, schemars::JsonSchema)]
pub struct TipValues {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// q(s,t) (m).
    pub q: Vec<f64>,
    /// θ(s,t) (rad).
    pub theta: Vec<f64>,
    /// Estimated error of each q (m), with `--error-estimate`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub q_error: Option<Vec<f64>>,
    /// Estimated error of each θ (rad), with `--error-estimate`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub theta_error: Option<Vec<f64>>,
}

/// The error estimate of `--error-estimate`.
#[derive(Serialize, schemars::JsonSchema)]
pub struct ErrorSummary {
    /// Elements (intervals) of the refined grid.
    pub refined_grid: usize,
    /// Integrator step of the refined run (s).
    pub refined_dt: f64,
    /// Time scheme of the refined runs.
    pub refined_stepper: wingcheck_model::TimeScheme,
    /// Largest estimated error of q(s,t) over the horizon (m).
    pub max_q_tip_error: f64,
    /// Largest estimated error of θ(s,t) over the horizon (rad).
    pub max_theta_tip_error: f64,
    /// Its spatial part (relative to the tip scale).
    pub max_space_error: f64,
    /// Its time-step part.
    pub max_time_error: f64,
    /// The tolerance the estimate is held against.
    pub tolerance: f64,
    /// Whether the estimates meet it.
    pub meets_tolerance: bool,
    /// Peaks with their errors.
    pub peaks: wingcheck_sim::PeakEstimates,
    /// How the peaks were checked for sub-step transients after the initial layer.
    pub sub_step_check: SubStepCheck,
    /// The peaks' third grid (4N).
    pub third_grid: wingcheck_sim::ThirdGrid,
    /// How the estimate is made.
    pub basis: String,
}

fn summary_of(
    cfg: &wingcheck_model::Config,
    out: &wingcheck_sim::SimOutput,
    sample_times: &[f64],
    wall: f64,
    path: Option<&std::path::Path>,
    estimated: Option<&EstimatedRun>,
) -> SimulateSummary {
    let s = &out.series;
    let tips: Option<Vec<_>> = estimated.map(|e| sample_times.iter().map(|&t| e.tip_at(t)).collect());
    let files = path
        .map(|p| wingcheck_io::FileRecord {
            file: p.display().to_string(),
            contents: "the run written by --out".into(),
        })
        .into_iter()
        .collect();
    SimulateSummary {
        schema_version: wingcheck_io::SCHEMA_VERSION,
        provenance: wingcheck_io::Provenance::new(&cfg.sha256(), files),
        settings: RunSettings {
            controller: cfg.control.kind.name().into(),
            observer: cfg.observer.rule.name().into(),
            method: cfg.discretisation.method.name().into(),
            elements: cfg.discretisation.grid_size(),
            grading: cfg.discretisation.grading,
            dt: cfg.discretisation.dt,
            stepper: out.stats.stepper,
            sample_period: cfg.observer.sample_period,
            t_end: cfg.horizon.t_end,
            a: cfg.control.a,
            b: cfg.control.b,
        },
        run_seconds: wall,
        stats: out.stats.clone(),
        tip: TipValues {
            t: sample_times.to_vec(),
            q: sample_times.iter().map(|&t| s.at(&s.q_tip, t)).collect(),
            theta: sample_times.iter().map(|&t| s.at(&s.theta_tip, t)).collect(),
            q_error: tips.as_ref().map(|v| v.iter().map(|x| x.0.error).collect()),
            theta_error: tips.as_ref().map(|v| v.iter().map(|x| x.1.error).collect()),
        },
        peaks: out.peaks,
        initial_layer: out.initial_layer,
        out: path.map(|p| p.display().to_string()),
        error_estimate: estimated.map(|e| ErrorSummary {
            refined_grid: e.refined_grid,
            refined_dt: e.refined_dt,
            refined_stepper: e.refined_stepper,
            max_q_tip_error: e.max_q_tip_error,
            max_theta_tip_error: e.max_theta_tip_error,
            max_space_error: e.max_space_error,
            max_time_error: e.max_time_error,
            tolerance: e.tolerance,
            meets_tolerance: e.meets_tolerance,
            peaks: e.peaks,
            sub_step_check: e.sub_step_check.clone(),
            third_grid: e.third_grid.clone(),
            basis: "Richardson, order 2 in h and dt, safety factor 1.25: (5/3)·|u(N) − u(2N)| + (5/3)·|u(dt) − u(dt/2)| per output sample, maximised over ±0.1 s; peaks at full rate: the grid part from N, 2N and 4N (the 4N run to one sample period past the latest peak; Richardson when the changes shrink at least 3-fold, else |u(N) − u(4N)| plus the geometric tail or the whole value, called not converged in the grid), the initial layer resolved at finer steps (its last change), the sub-step probe's resolution after later jumps (the exponential scheme's own, or an exponential twin's excess over a scheme without one), and a round-off floor of 256 ulp".into(),
        }),
    }
}

impl SimulateSummary {
    /// The document of `result`, a run of `cfg` (`out`: the file written, if any).
    pub fn of(
        cfg: &wingcheck_model::Config,
        result: &SimulateResult,
        out: Option<&std::path::Path>,
    ) -> SimulateSummary {
        summary_of(cfg, &result.output, &result.sample_times, result.wall_seconds, out, result.estimate.as_ref())
    }
}

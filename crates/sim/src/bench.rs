//! Performance measurements of the simulator (used by `wingcheck bench`): whole-run time,
//! time per step next to the cost of one sparse solve, and scaling with grid size and horizon.

use std::time::Instant;

use serde::Serialize;
use wingcheck_model::Config;

use crate::banded::BandedCholesky;
use crate::sparse::SymMatrix;
use crate::{simulate, Discretisation, RunOptions, SimError};

/// One timed configuration.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct Timing {
    /// Elements / intervals.
    pub elements: usize,
    /// Unknowns.
    pub unknowns: usize,
    /// Basis the run was stepped in (`modal` or `nodal`).
    pub basis: wingcheck_model::StepBasis,
    /// Time scheme it was stepped with (`auto` resolved).
    pub stepper: wingcheck_model::TimeScheme,
    /// Horizon (s).
    pub t_end: f64,
    /// Integrator steps.
    pub steps: usize,
    /// Median wall time of the whole run (s), best of `repeats`.
    pub run_seconds: f64,
    /// Wall time per integrator step (s).
    pub seconds_per_step: f64,
    /// Wall time of one sparse solve with the step matrix (s).
    pub solve_seconds: f64,
}

/// Median of repeated measurements.
/// The median of timings taken at least once (`--repeats` ≥ 1, so never empty):
/// [`crate::metrics::median`], for every benchmark (simulator, check, report, search).
pub fn median(v: Vec<f64>) -> f64 {
    crate::metrics::median(v).expect("at least one timing")
}

/// Time one configuration: median of `repeats` full runs, plus the median cost of one solve.
pub fn time_config(cfg: &Config, repeats: usize) -> Result<Timing, SimError> {
    let mut runs = Vec::with_capacity(repeats);
    let mut steps = 0;
    let mut unknowns = 0;
    let mut basis = wingcheck_model::StepBasis::default();
    let mut stepper = wingcheck_model::TimeScheme::default();
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        let out = simulate(cfg, RunOptions::default())?;
        runs.push(t.elapsed().as_secs_f64());
        steps = out.stats.steps;
        unknowns = out.stats.unknowns;
        basis = out.stats.basis;
        stepper = out.stats.stepper;
    }
    let run_seconds = median(runs);
    Ok(Timing {
        elements: cfg.discretisation.grid_size(),
        unknowns,
        basis,
        stepper,
        t_end: cfg.horizon.t_end,
        steps,
        run_seconds,
        seconds_per_step: run_seconds / steps as f64,
        solve_seconds: time_solve(cfg)?,
    })
}

/// Median time of one in-place solve with the configuration's step matrix (banded Cholesky,
/// as used by the stepper).
pub fn time_solve(cfg: &Config) -> Result<f64, SimError> {
    let disc = Discretisation::new(cfg);
    let h = cfg.discretisation.dt;
    let step = SymMatrix::combine(&[(2.0 / h, &disc.mass), (cfg.wing.xi + 0.5 * h, &disc.stiffness)]);
    let mut solver = BandedCholesky::new(&step)?;
    let mut rhs: Vec<f64> = (0..disc.dim()).map(|i| 1.0 + i as f64 * 1e-3).collect();
    let batch = 2000;
    let mut samples = Vec::new();
    for _ in 0..7 {
        let t = Instant::now();
        for _ in 0..batch {
            solver.solve_in_place(&mut rhs);
            // keep the values O(1) so timing does not depend on denormals
            let scale = 1.0 / rhs[0].abs().max(1e-300);
            rhs.iter_mut().for_each(|x| *x *= scale);
        }
        samples.push(t.elapsed().as_secs_f64() / batch as f64);
    }
    Ok(median(samples))
}

/// Least-squares slope of log(y) against log(x): the empirical scaling exponent.
pub fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = lx.len() as f64;
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// Cost of `wingcheck modes` at its defaults: converged frequencies with error estimates.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct ModesTiming {
    /// Number of frequencies.
    pub count: usize,
    /// Meshes solved.
    pub meshes: Vec<usize>,
    /// Median wall time (s).
    pub seconds: f64,
    /// Largest relative error estimate.
    pub worst_relative_error: f64,
}

/// Median time of [`crate::modes::converged_frequencies`] (configured method, `count` modes,
/// default tolerance) over `repeats` runs.
pub fn time_modes(cfg: &Config, count: usize, repeats: usize) -> Result<ModesTiming, SimError> {
    let mut runs = Vec::new();
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        let m = crate::modes::converged_frequencies(
            cfg,
            cfg.discretisation.method,
            count,
            crate::modes::DEFAULT_MODE_TOLERANCE,
        )?;
        runs.push(t.elapsed().as_secs_f64());
        last = Some(m);
    }
    let m = last.expect("at least one run");
    Ok(ModesTiming {
        count,
        meshes: m.meshes.clone(),
        seconds: median(runs),
        worst_relative_error: m.modes.iter().map(|e| e.error / e.omega).fold(0.0, f64::max),
    })
}

/// Median wall time (s) of [`crate::simulate_with_error`] (the run plus its refinements).
pub fn time_error_estimate(cfg: &Config, repeats: usize) -> Result<f64, SimError> {
    let mut runs = Vec::new();
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        crate::simulate_with_error(cfg, RunOptions::default())?;
        runs.push(t.elapsed().as_secs_f64());
    }
    Ok(median(runs))
}

//! Performance measurements of the simulator (used by `wingcheck bench`): whole-run time,
//! time per step next to the cost of one sparse solve, and scaling with grid size and horizon.

use serde::Serialize;
use wingcheck_io::clock::{measure, Elapsed};
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
    /// Median wall time of the whole run over `repeats` runs (s).
    pub run_seconds: f64,
    /// Median CPU time of the whole run over the same runs (s; user + system of the process,
    /// [`wingcheck_io::clock`]); None off Linux.
    pub run_cpu_seconds: Option<f64>,
    /// Time per integrator step (s): CPU where known, else wall.
    pub seconds_per_step: f64,
    /// Time of one sparse solve with the step matrix (s): CPU where known, else wall.
    pub solve_seconds: f64,
}

impl Timing {
    /// The run's time a ratio is taken from: CPU where known, else wall (s).
    pub fn seconds(&self) -> f64 {
        self.run_cpu_seconds.unwrap_or(self.run_seconds)
    }
}

/// Medians of wall and CPU times (CPU only when every measurement has it).
pub fn median_elapsed(v: &[Elapsed]) -> Elapsed {
    let cpu: Option<Vec<f64>> = v.iter().map(|e| e.cpu_seconds).collect();
    Elapsed { wall_seconds: median(v.iter().map(|e| e.wall_seconds).collect()), cpu_seconds: cpu.map(median) }
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
        let (out, elapsed) = measure(|| simulate(cfg, RunOptions::default()));
        let out = out?;
        runs.push(elapsed);
        steps = out.stats.steps;
        unknowns = out.stats.unknowns;
        basis = out.stats.basis;
        stepper = out.stats.stepper;
    }
    let run = median_elapsed(&runs);
    Ok(Timing {
        elements: cfg.discretisation.grid_size(),
        unknowns,
        basis,
        stepper,
        t_end: cfg.horizon.t_end,
        steps,
        run_seconds: run.wall_seconds,
        run_cpu_seconds: run.cpu_seconds,
        seconds_per_step: run.seconds() / steps as f64,
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
        let ((), elapsed) = measure(|| {
            for _ in 0..batch {
                solver.solve_in_place(&mut rhs);
                // keep the values O(1) so timing does not depend on denormals
                let scale = 1.0 / rhs[0].abs().max(1e-300);
                rhs.iter_mut().for_each(|x| *x *= scale);
            }
        });
        samples.push(elapsed.seconds() / batch as f64);
    }
    Ok(median(samples))
}

/// Cost of `wingcheck modes` at its defaults: converged frequencies with error estimates.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct ModesTiming {
    /// Number of frequencies.
    pub count: usize,
    /// Meshes solved.
    pub meshes: Vec<usize>,
    /// Median wall and CPU time (s).
    pub elapsed: Elapsed,
    /// Largest relative error estimate.
    pub worst_relative_error: f64,
}

/// Median time of [`crate::modes::converged_frequencies`] (configured method, `count` modes,
/// default tolerance) over `repeats` runs.
pub fn time_modes(cfg: &Config, count: usize, repeats: usize) -> Result<ModesTiming, SimError> {
    let mut runs = Vec::new();
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let (m, elapsed) = measure(|| {
            crate::modes::converged_frequencies(
                cfg,
                cfg.discretisation.method,
                count,
                crate::modes::DEFAULT_MODE_TOLERANCE,
            )
        });
        runs.push(elapsed);
        last = Some(m?);
    }
    let m = last.expect("at least one run");
    Ok(ModesTiming {
        count,
        meshes: m.meshes.clone(),
        elapsed: median_elapsed(&runs),
        worst_relative_error: m.modes.iter().map(|e| e.error / e.omega).fold(0.0, f64::max),
    })
}

/// Median wall and CPU time (s) of [`crate::simulate_with_error`] (the run plus its
/// refinements).
pub fn time_error_estimate(cfg: &Config, repeats: usize) -> Result<Elapsed, SimError> {
    let mut runs = Vec::new();
    for _ in 0..repeats.max(1) {
        let (out, elapsed) = measure(|| crate::simulate_with_error(cfg, RunOptions::default()));
        out?;
        runs.push(elapsed);
    }
    Ok(median_elapsed(&runs))
}

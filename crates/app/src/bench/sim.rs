//! `bench --what sim`: the configured run against the other stepper, the other basis, the
//! explicit FTDO's two schemes, the error estimate and `modes`, and the scaling with grid and
//! horizon. Ratios and fitted exponents are from CPU time where known
//! ([`wingcheck_sim::bench::Timing::seconds`]).

use serde::Serialize;
use wingcheck_io::clock::Elapsed;
use wingcheck_model::{apply_overrides, Config, Method, StepBasis, TimeScheme};
use wingcheck_sim::bench::{time_config, time_error_estimate, time_modes, ModesTiming, Timing};
use wingcheck_sim::metrics::loglog_slope;

use crate::AppError;

/// Grid sizes of the grid scaling (elements or finite-difference points).
pub(crate) const GRID_SIZES: [usize; 5] = [8, 16, 32, 64, 128];

/// Horizons of the horizon scaling (s).
pub(crate) const HORIZONS: [f64; 4] = [5.0, 10.0, 20.0, 40.0];

/// The overrides of the explicit FTDO stepped with `scheme`.
fn explicit(scheme: &str) -> Vec<String> {
    vec!["control.kind=ftdo".into(), "observer.rule=explicit".into(), format!("discretisation.stepper={scheme}")]
}

/// The overrides of every variant the bench may time beside the configured run.
pub(crate) fn variants() -> Vec<Vec<String>> {
    vec![
        vec!["discretisation.stepper=trapezoid".into()],
        vec!["discretisation.stepper=trbdf2".into()],
        vec!["discretisation.basis=nodal".into()],
        vec!["discretisation.basis=modal".into()],
        explicit("exponential"),
        explicit("trbdf2"),
    ]
}

/// A variant's timing, or why it does not apply to this configuration.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct OtherTiming {
    /// The overrides that make the variant (`key=value`).
    pub overrides: Vec<String>,
    /// Its timing; none when the variant is refused for this configuration.
    pub timing: Option<Timing>,
    /// Why it was refused (the validator's or the simulator's message).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub not_available: Option<String>,
    /// The configured run's time over this one's (CPU where known).
    pub configured_over_this: Option<f64>,
}

/// The simulator's timings.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct SimBench {
    /// The configured run.
    pub configured: Timing,
    /// The other time scheme (trapezoid ↔ TR-BDF2).
    pub other_stepper: OtherTiming,
    /// The other basis (modal ↔ nodal).
    pub other_basis: OtherTiming,
    /// The explicit FTDO with its exponential scheme.
    pub explicit_exponential: OtherTiming,
    /// The explicit FTDO with TR-BDF2.
    pub explicit_trbdf2: OtherTiming,
    /// The run with its error estimate (refined in h and dt), median of up to 3.
    pub error_estimate: Elapsed,
    /// `modes` at 5 frequencies with error estimates.
    pub modes: ModesTiming,
    /// The configured run at 8 … 128 elements (or points), median of up to 3 each.
    pub grid_scaling: Vec<Timing>,
    /// Fitted exponent of time per step against unknowns (1 = linear).
    pub grid_exponent: f64,
    /// The configured run at T = 5 … 40 s, median of up to 3 each.
    pub horizon_scaling: Vec<Timing>,
    /// Fitted exponent of run time against steps (1 = linear).
    pub horizon_exponent: f64,
}

/// Time `cfg` with `overrides`, or say why not.
fn other(cfg: &Config, overrides: Vec<String>, repeats: usize, base: &Timing) -> OtherTiming {
    let timed = apply_overrides(cfg, &overrides)
        .map_err(|e| e.to_string())
        .and_then(|c| time_config(&c, repeats).map_err(|e| e.to_string()));
    match timed {
        Ok(t) => OtherTiming {
            configured_over_this: Some(base.seconds() / t.seconds()),
            overrides,
            timing: Some(t),
            not_available: None,
        },
        Err(e) => OtherTiming { overrides, timing: None, not_available: Some(e), configured_over_this: None },
    }
}

/// Run the simulator bench (guarded by the caller).
pub(crate) fn bench_sim(cfg: &Config, repeats: usize) -> Result<SimBench, AppError> {
    let base = time_config(cfg, repeats)?;
    let other_stepper = if base.stepper == TimeScheme::Trapezoid { "trbdf2" } else { "trapezoid" };
    let other_basis = if base.basis == StepBasis::Modal { "nodal" } else { "modal" };
    let few = repeats.min(3);
    let key = if cfg.discretisation.method == Method::Fd { "fd_points" } else { "elements" };
    let mut grid_scaling = Vec::new();
    for n in GRID_SIZES {
        grid_scaling.push(time_config(&apply_overrides(cfg, &[format!("discretisation.{key}={n}")])?, few)?);
    }
    let mut horizon_scaling = Vec::new();
    for t in HORIZONS {
        horizon_scaling.push(time_config(&apply_overrides(cfg, &[format!("horizon.t_end={t}")])?, few)?);
    }
    let grid_exponent = loglog_slope(
        &grid_scaling.iter().map(|t| t.unknowns as f64).collect::<Vec<_>>(),
        &grid_scaling.iter().map(|t| t.seconds_per_step).collect::<Vec<_>>(),
    );
    let horizon_exponent = loglog_slope(
        &horizon_scaling.iter().map(|t| t.steps as f64).collect::<Vec<_>>(),
        &horizon_scaling.iter().map(Timing::seconds).collect::<Vec<_>>(),
    );
    Ok(SimBench {
        other_stepper: other(cfg, vec![format!("discretisation.stepper={other_stepper}")], repeats, &base),
        other_basis: other(cfg, vec![format!("discretisation.basis={other_basis}")], repeats, &base),
        explicit_exponential: other(cfg, explicit("exponential"), repeats, &base),
        explicit_trbdf2: other(cfg, explicit("trbdf2"), repeats, &base),
        error_estimate: time_error_estimate(cfg, few)?,
        modes: time_modes(cfg, 5, repeats)?,
        configured: base,
        grid_scaling,
        grid_exponent,
        horizon_scaling,
        horizon_exponent,
    })
}

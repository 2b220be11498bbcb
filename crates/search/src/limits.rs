//! Work guards of a search, checked before any work starts: the number of points, the
//! estimated core time, and the number of worker threads.

use wingcheck_model::{apply_overrides, Config, TimeScheme};

use crate::axis::{Axis, Spacing};
use crate::SearchError;

/// Points a search may have without `--allow-large`. Finalising streams the chunks and keeps
/// 2 bytes per point (the theory verdicts), on 2-D searches ≈ 0.5 kB per point (three plotted
/// values and one heatmap SVG at a time; `tests/assembly.rs` measures both): ≈ 2 MB, or
/// ≈ 0.5 GB for a 2-D search, here.
pub const MAX_POINTS: usize = 1_000_000;

/// Points a search may never exceed, even with `--allow-large` (a 2-D search's heatmaps then
/// need ≈ 2 GB).
pub const MAX_POINTS_OVERRIDE: usize = 4_000_000;

/// Estimated core time (s) a search may take without `--allow-large`: 2 core-hours.
pub const MAX_CORE_SECONDS: f64 = 7200.0;

/// Largest number of unknowns a point runs in the modal basis (the simulator's `auto` rule).
pub use wingcheck_model::MODAL_AUTO_UNKNOWNS;

/// Cost per unknown and integrator step (s), modal runner: measured ≈ 2.4e-9 s with
/// `wingcheck bench --what search` (48 unknowns, one core); rounded up.
const SECONDS_PER_MODE_STEP: f64 = 4e-9;
/// Cost per unknown and integrator step (s), the simulator's sparse stepper: ≈ 1 µs per step
/// at 48 unknowns (README, "Speed"); rounded up.
const SECONDS_PER_UNKNOWN_STEP: f64 = 3e-8;
/// Theory per point (λ2, λ1, the μ and ε SOCPs): measured ≈ 4 ms; rounded up.
const SECONDS_PER_POINT_THEORY: f64 = 8e-3;

/// What a search will cost, estimated from its axes before any work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkEstimate {
    /// Number of points (saturates at `u128::MAX`).
    pub points: u128,
    /// Largest number of integrator steps of a point.
    pub steps_per_point: u64,
    /// Largest number of unknowns of a point.
    pub unknowns: usize,
    /// Estimated core time (s), the largest per-point cost times the number of points.
    pub core_seconds: f64,
}

/// Integrator steps and unknowns of one point.
fn point_cost(cfg: &Config) -> (u64, usize) {
    (cfg.total_samples() as u64 * cfg.steps_per_sample() as u64, cfg.unknowns())
}

/// Estimate the work of a grid over validated axes: for each axis the values of most steps
/// and most unknowns (range ends, or each of the first 256 list values) with the others at the
/// base; steps and unknowns are combined as products of their ratios to the base (they are
/// products of independent factors: horizon/dt, elements/method), and the cost per point is
/// that of the costliest combination.
pub fn estimate(base: &Config, axes: &[Axis]) -> WorkEstimate {
    let points = axes.iter().fold(1u128, |acc, a| acc.saturating_mul(a.len() as u128));
    let (steps0, n0) = point_cost(base);
    let (mut steps, mut n) = (steps0.max(1) as f64, n0.max(1) as f64);
    let mut exponential = base.expected_time_scheme() == TimeScheme::Exponential;
    for a in axes {
        let idx: Vec<usize> = match &a.spacing {
            Spacing::List { values } => (0..values.len().min(256)).collect(),
            _ => vec![0, a.len() - 1],
        };
        let (mut most_steps, mut most_n) = (steps0.max(1), n0.max(1));
        for i in idx {
            if let Ok(cfg) = apply_overrides(base, &[a.override_expr(i)]) {
                let (s, k) = point_cost(&cfg);
                most_steps = most_steps.max(s);
                most_n = most_n.max(k);
                exponential |= cfg.expected_time_scheme() == TimeScheme::Exponential;
            }
        }
        steps *= most_steps as f64 / steps0.max(1) as f64;
        n *= most_n as f64 / n0.max(1) as f64;
    }
    let per = if n <= MODAL_AUTO_UNKNOWNS as f64 { SECONDS_PER_MODE_STEP } else { SECONDS_PER_UNKNOWN_STEP };
    let mut point_seconds = steps * n * per + SECONDS_PER_POINT_THEORY;
    if exponential {
        point_seconds += wingcheck_model::work::exponential_seconds(steps, 2.0 * n);
    }
    WorkEstimate {
        points,
        steps_per_point: steps.min(u64::MAX as f64) as u64,
        unknowns: n.min(usize::MAX as f64) as usize,
        core_seconds: point_seconds * points as f64,
    }
}

fn short(x: f64) -> String {
    format!("{x:.3e}")
}

/// Refuse a search above the limits ([`MAX_POINTS`], [`MAX_CORE_SECONDS`]; with `allow_large`
/// only above [`MAX_POINTS_OVERRIDE`]), naming the estimate and the flag.
pub fn check(w: &WorkEstimate, allow_large: bool) -> Result<(), SearchError> {
    let what = format!(
        "{} points × up to {} steps × {} unknowns ≈ {} core-hours",
        w.points,
        w.steps_per_point,
        w.unknowns,
        short(w.core_seconds / 3600.0)
    );
    if w.points > MAX_POINTS_OVERRIDE as u128 {
        return Err(SearchError::TooLarge(format!(
            "{what}: more than {MAX_POINTS_OVERRIDE} points cannot be searched in one directory \
             (the heatmaps of a 2-D search are drawn in memory, ≈ 0.5 kB per point); \
             split the axes into several searches"
        )));
    }
    if !allow_large && (w.points > MAX_POINTS as u128 || w.core_seconds > MAX_CORE_SECONDS) {
        return Err(SearchError::TooLarge(format!(
            "{what}: above the limits of {MAX_POINTS} points and {} core-hours; \
             pass --allow-large to run it anyway (or --shard it over several machines)",
            MAX_CORE_SECONDS / 3600.0
        )));
    }
    Ok(())
}

/// Largest `--threads`: 4 × the cores available (at least 4).
pub fn max_threads() -> usize {
    4 * std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1)
}

/// Refuse a thread count outside [1, [`max_threads`]].
pub fn check_threads(n: usize) -> Result<(), SearchError> {
    let max = max_threads();
    if n == 0 || n > max {
        return Err(SearchError::Options(format!("--threads {n}: must lie in [1, {max}] (4 × the cores available)")));
    }
    Ok(())
}

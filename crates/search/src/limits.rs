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

/// Estimated memory a search may take without `--allow-large`: the commands' 4 GiB.
pub const MAX_MEMORY_BYTES: f64 = wingcheck_model::work::DEFAULT_LIMITS.memory_bytes;

/// Largest number of unknowns a point runs in the modal basis (the simulator's `auto` rule).
pub use wingcheck_model::MODAL_AUTO_UNKNOWNS;

/// Cost per unknown and integrator step (s), modal runner: measured ≈ 2.4e-9 s with
/// `wingcheck bench --what search` (48 unknowns, one core); rounded up.
const SECONDS_PER_MODE_STEP: f64 = 4e-9;
/// Cost per unknown and integrator step (s), the simulator's sparse stepper: ≈ 1 µs per step
/// at 48 unknowns (docs/performance.md); rounded up.
const SECONDS_PER_UNKNOWN_STEP: f64 = 3e-8;
/// Theory per point (λ2, λ1, the μ and ε SOCPs).
use wingcheck_model::work::SECONDS_PER_POINT_THEORY;

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
    /// Estimated peak memory (bytes): the observer signals held at once (3 f64 per integrator
    /// step, 4 per sample; the runner keeps up to [`crate::modal::CACHE_ENTRIES`] of them), the
    /// modal bases, per worker thread one point's run (its trace, or the simulator's nodal run
    /// above 300 unknowns), and the final assembly's per-point summary.
    pub memory_bytes: f64,
}

/// Config keys the cost of a point depends on ([`point_cost`] and [`point_memory`] read exactly
/// these, through the horizon, the time step, the sample periods, the grid and the scheme): for
/// a list axis over any of them every value is estimated, for any other key one value is.
const COST_KEYS: [&str; 11] = [
    "horizon.t_end",
    "horizon.sample_every",
    "observer.sample_period",
    "observer.rule",
    "control.kind",
    "discretisation.dt",
    "discretisation.method",
    "discretisation.elements",
    "discretisation.fd_points",
    "discretisation.stepper",
    "discretisation.basis",
];

/// Config key prefixes an observer signal depends on ([`crate::modal::RunCache::signal`]'s key):
/// an axis over one of them needs a signal per value.
const SIGNAL_KEYS: [&str; 10] = [
    "observer.",
    "disturbance.",
    "initial.",
    "horizon.",
    "control.kind",
    "discretisation.dt",
    "wing.span",
    "wing.ei",
    "wing.gj",
    "wing.xi",
];

/// Integrator steps and unknowns of one point.
fn point_cost(cfg: &Config) -> (u64, usize) {
    (cfg.total_samples() as u64 * cfg.steps_per_sample() as u64, cfg.unknowns())
}

/// Bytes of one point's observer signal, its run (trace at the output samples, or the
/// simulator's nodal run) and its modal basis.
fn point_memory(cfg: &Config) -> (f64, f64, f64) {
    let (steps, samples) = (point_cost(cfg).0 as f64, cfg.total_samples() as f64 + 1.0);
    let signal = 8.0 * (3.0 * steps + 4.0 * samples);
    let outputs = (cfg.horizon.t_end / cfg.horizon.sample_every).floor() + 2.0;
    let n = cfg.unknowns() as f64;
    let run = if cfg.expected_modal() {
        8.0 * 9.0 * outputs + 8.0 * 4.0 * (2.0 * n) * (2.0 * n)
    } else {
        wingcheck_model::work::WorkEstimate::simulation(cfg, false, None).memory_bytes
    };
    (signal, run, 8.0 * 4.0 * n * n)
}

/// The axis's value indices the estimate looks at: every value of a list over a cost key, the
/// ends of a range, else the first value (the cost does not depend on it).
pub(crate) fn estimated_values(a: &Axis) -> Vec<usize> {
    match &a.spacing {
        Spacing::List { values } if COST_KEYS.contains(&a.key.as_str()) => (0..values.len()).collect(),
        Spacing::List { .. } => vec![0],
        _ => vec![0, a.len() - 1],
    }
}

/// Estimate the work of a grid over validated axes: for each axis the values of most steps,
/// most unknowns and most memory (range ends, or every list value of a key the cost depends
/// on) with the others at the base; steps and unknowns are combined as products of their
/// ratios to the base (they are products of independent factors: horizon/dt, elements/method),
/// and the cost per point is that of the costliest combination. `threads`: worker threads.
pub fn estimate(base: &Config, axes: &[Axis]) -> WorkEstimate {
    estimate_with_threads(base, axes, std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1))
}

/// [`estimate`] for `threads` worker threads (memory holds one run per thread).
pub fn estimate_with_threads(base: &Config, axes: &[Axis], threads: usize) -> WorkEstimate {
    let points = axes.iter().fold(1u128, |acc, a| acc.saturating_mul(a.len() as u128));
    let (steps0, n0) = point_cost(base);
    let (mut steps, mut n) = (steps0.max(1) as f64, n0.max(1) as f64);
    let mem0 = point_memory(base);
    let (mut signal, mut run, mut basis) = mem0;
    let mut exponential = base.expected_time_scheme() == TimeScheme::Exponential;
    for a in axes {
        let (mut most_steps, mut most_n) = (steps0.max(1), n0.max(1));
        let mut most_mem = mem0;
        for i in estimated_values(a) {
            if let Ok(cfg) = apply_overrides(base, &[a.override_expr(i)]) {
                let (s, k) = point_cost(&cfg);
                most_steps = most_steps.max(s);
                most_n = most_n.max(k);
                let m = point_memory(&cfg);
                most_mem = (most_mem.0.max(m.0), most_mem.1.max(m.1), most_mem.2.max(m.2));
                exponential |= cfg.expected_time_scheme() == TimeScheme::Exponential;
            }
        }
        steps *= most_steps as f64 / steps0.max(1) as f64;
        n *= most_n as f64 / n0.max(1) as f64;
        signal *= most_mem.0 / mem0.0.max(1.0);
        run *= most_mem.1 / mem0.1.max(1.0);
        basis *= most_mem.2 / mem0.2.max(1.0);
    }
    let per = if n <= MODAL_AUTO_UNKNOWNS as f64 { SECONDS_PER_MODE_STEP } else { SECONDS_PER_UNKNOWN_STEP };
    let mut point_seconds = steps * n * per + SECONDS_PER_POINT_THEORY;
    if exponential {
        point_seconds += wingcheck_model::work::exponential_seconds(steps, 2.0 * n);
    }
    let cached = crate::modal::CACHE_ENTRIES as f64 + threads as f64;
    let varies = |prefixes: &[&str]| axes.iter().any(|a| prefixes.iter().any(|p| a.key.starts_with(p)));
    let signals = if varies(&SIGNAL_KEYS) { cached.min(points as f64) } else { 1.0 };
    let bases = if varies(&["wing.", "discretisation.", "initial.", "disturbance.distributed", "horizon.field_points"])
    {
        cached.min(points as f64)
    } else {
        1.0
    };
    // the assembly keeps 2 bytes per point, ≈ 600 on 2-D searches (heatmaps; tests/assembly.rs)
    let per_point = if axes.len() == 2 { 600.0 } else { 2.0 };
    let memory = signals * signal + bases * basis + threads as f64 * run + per_point * points as f64;
    WorkEstimate {
        points,
        steps_per_point: steps.min(u64::MAX as f64) as u64,
        unknowns: n.min(usize::MAX as f64) as usize,
        core_seconds: point_seconds * points as f64,
        memory_bytes: memory,
    }
}

fn short(x: f64) -> String {
    format!("{x:.3e}")
}

/// Refuse a search above the limits ([`MAX_POINTS`], [`MAX_CORE_SECONDS`]; with `allow_large`
/// only above [`MAX_POINTS_OVERRIDE`]), naming the estimate and the flag.
pub fn check(w: &WorkEstimate, allow_large: bool) -> Result<(), SearchError> {
    check_with_flag(w, allow_large, wingcheck_model::work::ALLOW_LARGE_FLAG)
}

/// [`check`] naming `flag` as the override (a front end's spelling of `--allow-large`).
pub fn check_with_flag(w: &WorkEstimate, allow_large: bool, flag: &str) -> Result<(), SearchError> {
    let what = format!(
        "{} points × up to {} steps × {} unknowns ≈ {} core-hours, {:.3} GB of memory",
        w.points,
        w.steps_per_point,
        w.unknowns,
        short(w.core_seconds / 3600.0),
        w.memory_bytes / 1e9
    );
    if w.points > MAX_POINTS_OVERRIDE as u128 {
        return Err(SearchError::TooLarge(format!(
            "{what}: more than {MAX_POINTS_OVERRIDE} points cannot be searched in one directory \
             (the heatmaps of a 2-D search are drawn in memory, ≈ 0.5 kB per point); \
             split the axes into several searches"
        )));
    }
    if !allow_large
        && (w.points > MAX_POINTS as u128 || w.core_seconds > MAX_CORE_SECONDS || w.memory_bytes > MAX_MEMORY_BYTES)
    {
        return Err(SearchError::TooLarge(format!(
            "{what}: above the limits of {MAX_POINTS} points, {} core-hours and {:.3} GB of memory; \
             pass {flag} to run it anyway (or --shard it over several machines; a long horizon or a \
             small dt costs memory per point: the observer signal holds 3 numbers per integrator step)",
            MAX_CORE_SECONDS / 3600.0,
            MAX_MEMORY_BYTES / 1e9
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

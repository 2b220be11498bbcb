//! Work guards of a search, checked before any work starts: the number of points, the
//! estimated core time, and the number of worker threads.

use wingcheck_model::{apply_overrides, Config, TimeScheme};

use crate::axis::{Axis, Spacing};
use crate::{SearchError, WorkLimit};

/// Points a search may have without `--allow-large`. Finalising streams the chunks and keeps
/// 2 bytes per point (the theory verdicts), on 2-D searches ≈ 140 bytes per point (three plotted
/// values and one heatmap at a time, its marks per block of cells; `tests/assembly.rs` measures
/// both): ≈ 2 MB, or ≈ 0.14 GB for a 2-D search, here.
pub const MAX_POINTS: usize = 1_000_000;

/// Points a search may never exceed, even with `--allow-large` (a 2-D search's assembly then
/// holds ≈ 0.6 GB, at the 140 bytes per point measured).
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

/// Resident memory of a search process before its points (the binary, the allocator, the
/// first thread): measured 10–12 MB (`/usr/bin/time -v`, a 1-point search at 1 thread), rounded up.
pub const PROCESS_BASE_BYTES: f64 = 16e6;
/// Resident memory each further worker thread adds before its points (its stack and its
/// allocator arena): measured 2.7 MB per thread (12.4 MB at 1 thread, 26.3 MB at 8 on an
/// 8-point search of 50 steps each), rounded up.
pub const THREAD_BASE_BYTES: f64 = 4e6;

/// What a search holds in memory at its peak, buffer by buffer (bytes): the model the guard
/// applies ([`MAX_MEMORY_BYTES`]) and `search` prints with its estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MemoryEstimate {
    /// Worker threads the estimate is for.
    pub threads: usize,
    /// The process and its threads before any point ([`PROCESS_BASE_BYTES`],
    /// [`THREAD_BASE_BYTES`] per further thread).
    pub process: f64,
    /// Observer signals held at once: one per distinct signal (each built once, whichever
    /// thread asks first; a point whose controller is not the FTDO also reads the FTDO's), at
    /// most the cache's [`crate::modal::CACHE_ENTRIES`] plus one in use per thread.
    pub signals: f64,
    /// Bytes of the largest signal (`RecordedSignal::bytes`: 24 per integrator step, 48 per
    /// observer sample).
    pub signal_bytes: f64,
    /// Modal bases held at once (as the signals).
    pub bases: f64,
    /// Bytes of the largest basis (its mode shapes at the tip and on the output grid).
    pub basis_bytes: f64,
    /// Per worker thread: one point's run (its tip trace at the output samples, the modal
    /// loop's dense matrices and the basis being built, or the simulator's nodal run above
    /// [`MODAL_AUTO_UNKNOWNS`] unknowns).
    pub per_thread: f64,
    /// The final assembly's per-point summary (2 bytes per point, ≈ 600 on 2-D searches).
    pub assembly: f64,
}

impl MemoryEstimate {
    /// The total (bytes).
    pub fn total(&self) -> f64 {
        self.process
            + self.signals * self.signal_bytes
            + self.bases * self.basis_bytes
            + self.threads as f64 * self.per_thread
            + self.assembly
    }

    /// The estimate in words, buffer by buffer.
    pub fn text(&self) -> String {
        let gb = wingcheck_model::work::human_bytes;
        format!(
            "{} of memory at {} threads: {:.0} observer signal(s) × {}, {:.0} modal basis(es) × {}, {} per thread \
             (a point's run), {} for the process, {} for the assembly",
            gb(self.total()),
            self.threads,
            self.signals,
            gb(self.signal_bytes),
            self.bases,
            gb(self.basis_bytes),
            gb(self.per_thread),
            gb(self.process),
            gb(self.assembly)
        )
    }
}

/// What a search will cost, estimated from its axes before any work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkEstimate {
    /// Number of points (saturates at `u128::MAX`).
    pub points: u128,
    /// Largest number of integrator steps of a point.
    pub steps_per_point: u64,
    /// Largest number of unknowns of a point.
    pub unknowns: usize,
    /// Estimated core time (s) of the costliest point (its closed loop and theory).
    pub point_seconds: f64,
    /// Estimated core time (s): `point_seconds` times the number of points, and g_hmax's grid
    /// once per distinct disturbance, span and horizon.
    pub core_seconds: f64,
    /// Estimated peak memory (bytes): [`MemoryEstimate::total`] of `memory`.
    pub memory_bytes: f64,
    /// The memory by buffer.
    pub memory: MemoryEstimate,
}

/// Config keys the cost of a point depends on ([`point_cost`] and [`point_memory`] read exactly
/// these, through the horizon, the time step, the sample periods, the grid and the scheme): for
/// a list axis over any of them every value is estimated, for any other key one value is.
const COST_KEYS: [&str; 12] = [
    "horizon.t_end",
    "horizon.sample_every",
    "horizon.field_points",
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

/// Config key prefixes a modal basis depends on ([`crate::modal::ModalBasis::key`]).
const BASIS_KEYS: [&str; 5] =
    ["wing.", "discretisation.", "initial.", "disturbance.distributed", "horizon.field_points"];

/// Integrator steps and unknowns of one point.
fn point_cost(cfg: &Config) -> (u64, usize) {
    (cfg.total_samples() as u64 * cfg.steps_per_sample() as u64, cfg.unknowns())
}

/// `f64` vectors of a point's tip trace ([`crate::modal::TipTrace`]: t, q, θ, τ1, τ2, g̃1, g̃2),
/// allocated at the run's output samples.
const TRACE_VECTORS: f64 = 7.0;

/// Bytes of one point's observer signal, its run per thread, and its modal basis.
fn point_memory(cfg: &Config) -> (f64, f64, f64) {
    let signal = wingcheck_sim::modal::RecordedSignal::bytes(cfg);
    let outputs = cfg.output_samples() as f64;
    let n = cfg.unknowns() as f64;
    let run = if cfg.expected_modal() {
        // the trace; the loop's dense matrices (4 of (2n)²); the basis's dense eigenproblem
        // while it is built (8 of n²); the exponential scheme's sub-step probe rows
        let probe = if cfg.expected_time_scheme() == TimeScheme::Exponential {
            wingcheck_model::work::SUB_STEP_PROBE_ROWS * 2.0 * n * 8.0
        } else {
            0.0
        };
        8.0 * TRACE_VECTORS * outputs + 8.0 * 4.0 * (2.0 * n) * (2.0 * n) + 8.0 * 8.0 * n * n + probe
    } else {
        wingcheck_model::work::WorkEstimate::simulation(cfg, false, None).memory_bytes
    };
    // ω², Φᵀf, η(0) and both tip rows (5 n), the field rows (2 × field_points × n)
    let basis = 8.0 * n * (5.0 + 2.0 * cfg.horizon.field_points as f64);
    (signal, run, basis)
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
    estimate_with_threads(base, axes, wingcheck_io::clock::cores())
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
    let memory = memory_model(base, axes, points, threads, (signal, run, basis));
    WorkEstimate {
        points,
        steps_per_point: steps.min(u64::MAX as f64) as u64,
        unknowns: n.min(usize::MAX as f64) as usize,
        point_seconds,
        core_seconds: point_seconds * points as f64 + g_hmax_seconds(base, axes, points, threads),
        memory_bytes: memory.total(),
        memory,
    }
}

/// Core seconds of g_hmax (φ on a 1e-4 s grid over the horizon, `wingcheck_model::work::g_hmax_seconds`,
/// at the longest horizon): the theory cache computes it once per disturbance, span and horizon
/// in each window of [`crate::modal::CACHE_POINTS`] points, and each thread may compute it once
/// more while another is at it.
fn g_hmax_seconds(base: &Config, axes: &[Axis], points: u128, threads: usize) -> f64 {
    let longest = axes.iter().filter(|a| a.key == "horizon.t_end").fold(base.clone(), |most, a| {
        estimated_values(a)
            .into_iter()
            .filter_map(|i| apply_overrides(base, &[a.override_expr(i)]).ok())
            .fold(most, |m, c| if c.horizon.t_end > m.horizon.t_end { c } else { m })
    });
    let keys = distinct_values(axes, &["disturbance.distributed", "wing.span", "horizon.t_end"]);
    let windows = (points as f64 / crate::modal::CACHE_POINTS as f64).ceil().max(1.0);
    let per_window = (keys + threads as f64).min(points as f64);
    wingcheck_model::work::g_hmax_seconds(&longest) * per_window * windows
}

/// Distinct values of the axes over keys starting with one of `prefixes` (their product;
/// 1 when no axis is over such a key).
fn distinct_values(axes: &[Axis], prefixes: &[&str]) -> f64 {
    axes.iter().filter(|a| prefixes.iter().any(|p| a.key.starts_with(p))).map(|a| a.len() as f64).product()
}

/// The memory model of a search: the largest signal, run and basis of any point
/// (`largest`), and how many of each are held at once.
fn memory_model(
    base: &Config,
    axes: &[Axis],
    points: u128,
    threads: usize,
    largest: (f64, f64, f64),
) -> MemoryEstimate {
    let (signal_bytes, per_thread, basis_bytes) = largest;
    let held = |distinct: f64| distinct.min(crate::modal::CACHE_ENTRIES as f64 + threads as f64).min(points as f64);
    // a point whose controller is not the FTDO also reads the FTDO's signal (ζ3, ζ4)
    let not_ftdo =
        base.control.kind != wingcheck_model::ControllerKind::Ftdo || axes.iter().any(|a| a.key == "control.kind");
    let signals = held(distinct_values(axes, &SIGNAL_KEYS) * if not_ftdo { 2.0 } else { 1.0 });
    let bases = held(distinct_values(axes, &BASIS_KEYS));
    // the assembly keeps 2 bytes per point; 600 allowed on 2-D searches (heatmaps: 137 measured
    // since their marks are drawn per block of cells, 603 before; tests/assembly.rs bounds it at 300)
    let per_point = if axes.len() == 2 { 600.0 } else { 2.0 };
    MemoryEstimate {
        threads,
        process: PROCESS_BASE_BYTES + THREAD_BASE_BYTES * threads.saturating_sub(1) as f64,
        signals,
        signal_bytes,
        bases,
        basis_bytes,
        per_thread,
        assembly: per_point * points as f64,
    }
}

fn short(x: f64) -> String {
    format!("{x:.3e}")
}

impl WorkEstimate {
    /// The estimate in words: points, steps, unknowns, core-hours and the memory by buffer.
    pub fn text(&self) -> String {
        format!(
            "{} points × up to {} steps × {} unknowns ≈ {} core-hours; {}",
            self.points,
            self.steps_per_point,
            self.unknowns,
            short(self.core_seconds / 3600.0),
            self.memory.text()
        )
    }
}

/// Refuse a search above the limits ([`MAX_POINTS`], [`MAX_CORE_SECONDS`]; with `allow_large`
/// only above [`MAX_POINTS_OVERRIDE`]), naming the estimate and the flag.
pub fn check(w: &WorkEstimate, allow_large: bool) -> Result<(), SearchError> {
    check_with_flag(w, allow_large, wingcheck_model::work::ALLOW_LARGE_FLAG)
}

/// [`check`] naming `flag` as the override (a front end's spelling of `--allow-large`).
pub fn check_with_flag(w: &WorkEstimate, allow_large: bool, flag: &str) -> Result<(), SearchError> {
    let refuse = |limit| Err(SearchError::TooLarge { estimate: Box::new(*w), limit });
    if w.points > MAX_POINTS_OVERRIDE as u128 {
        return refuse(WorkLimit::Override);
    }
    if !allow_large
        && (w.points > MAX_POINTS as u128 || w.core_seconds > MAX_CORE_SECONDS || w.memory_bytes > MAX_MEMORY_BYTES)
    {
        return refuse(WorkLimit::Limits { flag: flag.to_string() });
    }
    Ok(())
}

/// Largest `--threads`: 4 × the cores available (at least 4).
pub fn max_threads() -> usize {
    4 * wingcheck_io::clock::cores()
}

/// Refuse a thread count outside [1, [`max_threads`]].
pub fn check_threads(n: usize) -> Result<(), SearchError> {
    let max = max_threads();
    if n == 0 || n > max {
        return Err(SearchError::Threads { requested: n, max });
    }
    Ok(())
}

//! Work estimates made before any work starts: integrator steps, run time, memory and output
//! size of `simulate`, `check`, `report` and `modes` for a configuration, and the documented
//! limits above which the command refuses unless `--allow-large` is given.
//!
//! The estimates are deliberately simple and err on the high side: cost per step is linear in
//! the unknowns (sparse Cholesky solves with a banded factor), memory is dominated by the
//! stored samples, and the JSON output by the pretty-printed numbers.

use crate::{format_number, Config, Method};

/// Seconds per integrator step per state (2 × unknowns), measured on one core: ≈ 1e-8 for the
/// default 20-s run (20 000 steps, 144 states, nodal), rising to 3e-8 CPU seconds at 24 000
/// states (FE 4000 elements, nodal: the banded factor no longer fits the caches); 4e-8 is used.
pub const SECONDS_PER_UNKNOWN_STEP: f64 = 4e-8;
/// Seconds per integrator step per entry of the exponential scheme's (2n)² step operator,
/// measured ≈ 1.5e-10 s on one core (144 states, 3.1 µs per step), doubled.
pub const SECONDS_PER_EXPONENTIAL_ENTRY_STEP: f64 = 3e-10;
/// Seconds of the exponential scheme's setup per (2n)³, measured ≈ 4e-9 s (13 ms at 144 states)
/// when each of its ≈ 20 doublings made five dense products, rounded up for the stiffer, longer
/// chains of finer grids. Since the τ Gramians are carried as low-rank factors a doubling makes
/// one dense product (setup ≈ 2× faster, measured 2026-12-02), so the estimate errs high.
pub const SECONDS_PER_EXPONENTIAL_SETUP_CUBE: f64 = 1e-8;
/// Estimated seconds of the exponential scheme's work beyond the per-unknown stepping cost, for
/// `steps` integrator steps of a loop with `states` states (displacements + velocities): one
/// dense states² product per step after the O(states³) setup. Used by every work estimate (the
/// commands' and the search's).
pub fn exponential_seconds(steps: f64, states: f64) -> f64 {
    steps * states * states * SECONDS_PER_EXPONENTIAL_ENTRY_STEP + states.powi(3) * SECONDS_PER_EXPONENTIAL_SETUP_CUBE
}
/// Estimated seconds of the exponential scheme's sub-step probe over `probes` probed steps of a
/// loop with `states` states: its coarse grid is about as many entries as the step operator
/// (measured: the probe adds 0.3–0.6 × the stepping of the default explicit run), counted as 1 ×.
pub fn sub_step_probe_seconds(probes: f64, states: f64) -> f64 {
    probes * states * states * SECONDS_PER_EXPONENTIAL_ENTRY_STEP
}
/// Rows of length `states` the sub-step probe stores: 32 fine points per octave of s and the
/// coarse grid's copy over up to 30 octaves, 4 rows (q, θ, q̇, θ̇) each.
pub const SUB_STEP_PROBE_ROWS: f64 = 33.0 * 30.0 * 4.0;
/// Observer sample periods at the start of a run that `simulate` re-runs at finer steps to
/// resolve a sub-step transient (the initial layer; sim's `layer` module).
pub const LAYER_SAMPLES: usize = 2;
/// At most this many layer runs (dt, dt/10, …, dt/10⁵).
pub const LAYER_RUNS_MAX: usize = 6;
/// The layer runs together take at most this many × the base run's steps, or
/// [`LAYER_STEPS_FLOOR`] steps if that is more (the first two layer runs, at dt and dt/10, are
/// always made).
pub const LAYER_WORK_FRACTION: f64 = 2.0;
/// Steps the layer runs may always take: enough for dt/10⁴ over a layer of two steps
/// (2 + 20 + … + 20000 = 22222 steps, the default run's layer; ≈ 0.02 s in the modal basis).
pub const LAYER_STEPS_FLOOR: f64 = 25_000.0;

/// Steps of the layer run at `dt` (the first one).
pub fn layer_first_steps(cfg: &Config) -> f64 {
    LAYER_SAMPLES.min(cfg.total_samples().max(1)) as f64 * cfg.steps_per_sample() as f64
}

/// Finest step of the layer runs relative to `discretisation.dt` (at most
/// [`LAYER_RUNS_MAX`] − 1 refinements by 10), and never below validation's 1e-9 s.
pub const LAYER_MIN_FRACTION: f64 = 1e-5;
/// Refinement factor between successive layer runs.
pub const LAYER_REFINEMENT: f64 = 10.0;

/// The steps `simulate` grants the initial-layer runs of `cfg`: [`LAYER_WORK_FRACTION`] × the
/// base run's steps or [`LAYER_STEPS_FLOOR`], whichever is more (at least the runs at dt and
/// dt/10). The runs stop at the first refinement that would exceed it.
pub fn layer_budget(cfg: &Config) -> f64 {
    let base_steps = (cfg.horizon.t_end / cfg.discretisation.dt).ceil();
    (11.0 * layer_first_steps(cfg)).max(LAYER_WORK_FRACTION * base_steps).max(LAYER_STEPS_FLOOR)
}

/// One initial-layer run of `simulate`: its step and its number of integrator steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerRun {
    /// The run's step (s).
    pub dt: f64,
    /// Integrator steps of the run over the layer.
    pub steps: f64,
}

/// The initial-layer runs `simulate` may make for `cfg`, coarse to fine: dt, dt/10, … down to
/// the finest step, as many as fit in [`layer_budget`]. Sim's `layer::resolve` runs them in
/// order until the peaks converge; the work estimates count them all ([`layer_steps_max`]).
pub fn layer_runs(cfg: &Config) -> Vec<LayerRun> {
    let dt0 = cfg.discretisation.dt;
    let finest = (dt0 * LAYER_MIN_FRACTION).max(1e-9);
    let budget = layer_budget(cfg);
    let (mut runs, mut spent) = (Vec::new(), 0.0);
    let mut next = LayerRun { dt: dt0, steps: layer_first_steps(cfg) };
    while next.dt >= finest * (1.0 - 1e-9) && spent + next.steps <= budget {
        spent += next.steps;
        runs.push(next);
        next = LayerRun { dt: decimal_tenth(next.dt), steps: next.steps * LAYER_REFINEMENT };
    }
    runs
}

/// `x`/[`LAYER_REFINEMENT`] in decimal: the double nearest `x`'s shortest decimal form with its
/// exponent lowered by one, so a step typed as 1e-6 s refines to 1e-7 s and prints so (binary
/// division gives 1.0000000000000002e-7 s, repeated divisions drift further); within two ulps
/// of the binary quotient x/10.
pub fn decimal_tenth(x: f64) -> f64 {
    const _: () = assert!(LAYER_REFINEMENT == 10.0, "decimal_tenth divides by ten");
    let shifted = format!("{x:e}")
        .split_once('e')
        .and_then(|(mantissa, exponent)| Some(format!("{mantissa}e{}", exponent.parse::<i32>().ok()? - 1)));
    shifted.and_then(|s| s.parse().ok()).unwrap_or(x / LAYER_REFINEMENT)
}

/// The most steps the initial-layer runs of one `simulate` of `cfg` can take: all of
/// [`layer_runs`].
pub fn layer_steps_max(cfg: &Config) -> f64 {
    layer_runs(cfg).iter().map(|r| r.steps).sum()
}

/// Seconds of a run's modal-basis setup per unknown³ (the SVD and its check, once per run):
/// measured ≤ 6.5e-10 CPU ([`crate::MODAL_SETUP_SECONDS_PER_CUBE`]: 0.11 s at 576 unknowns,
/// 2.3 s at 1 536), doubled and rounded up.
pub const SECONDS_PER_MODAL_SETUP_CUBE: f64 = 1.5e-9;
/// Worst-case seconds of the W-bounds row's SDP cross-check at N = 2 … 32: it is bounded by an
/// iteration budget (600 interior-point iterations, claims' `SDP_ITERATION_BUDGET`), ≈ 0.4 s on
/// the paper's wing and ≈ 3 s at the budget.
pub const CHECK_SDP_SECONDS: f64 = 3.0;
/// Worst-case seconds of the W-bounds row's certified ω₁ enclosure: the ledger tries coarse
/// plans first (≈ 0.01–0.1 s), and needs the tightest one only when a/b lies within ~1e-6 of ω₁,
/// measured at 0.77 s on the paper's wing and 5.1 s on a wing whose span has 16 significant
/// digits (exact integers grow with the decimals' length), doubled.
pub const CHECK_ENCLOSURE_SECONDS: f64 = 10.0;
/// Work of `check` that does not depend on the configured grid or horizon (s, one core):
/// [`CHECK_SDP_SECONDS`], [`CHECK_ENCLOSURE_SECONDS`], plus the Galerkin eigenvalues, ω₁ over
/// uniform meshes up to 2048 elements, the μ SOCPs, Lemma 1–3 and the Filippov integrations
/// (≈ 0.3 s together on the paper config, up to ≈ 1 s on extreme wings), doubled.
pub const CHECK_FIXED_SECONDS: f64 = CHECK_SDP_SECONDS + CHECK_ENCLOSURE_SECONDS + 2.0;
/// Hold periods T (s) of the finite-time rows' digital-observer study (`check`'s
/// `finite_time::PERIODS` is this constant).
pub const FINITE_TIME_PERIODS: [f64; 3] = [1e-2, 1e-3, 1e-4];
/// Chatter window at the end of each digital run of the finite-time rows (s).
pub const FINITE_TIME_WINDOW_S: f64 = 0.5;
/// Evaluations of g_h's time factor φ(t) per second of horizon in `g_hmax` (a 1e-4 s grid).
pub const G_HMAX_SAMPLES_PER_SECOND: f64 = 1e4;
/// Seconds per evaluation of φ(t) (a cosine and a sine, ≈ 20 ns), doubled.
pub const SECONDS_PER_G_HMAX_SAMPLE: f64 = 4e-8;
/// Seconds of a search point's theory (λ2, λ1, the μ and ε SOCPs): measured ≈ 4 ms; doubled.
/// Used by the search's estimate and by `report`'s region map, which evaluates search points.
pub const SECONDS_PER_POINT_THEORY: f64 = 8e-3;
/// Most points of `report`'s (a, b) region map: at most 14 values of a times 7 of b (half
/// decades over b0 · 10^±1.5; `crates/report/src/region.rs` refuses more).
pub const REGION_MAP_MAX_POINTS: usize = 14 * 7;

/// The configuration of one digital FTDO run of the finite-time rows: `cfg` with the given
/// sampling rule and hold period T (s), integrator step dt = T / ⌈T/dt_cfg⌉ (≤ the configured
/// dt, a whole fraction of T), horizon `t_end` (s), an output at every sample (the runs
/// measure σ, ĝ and τ sample by sample; sample_every = T is valid whatever the configured one).
pub fn finite_time_config(cfg: &Config, rule: crate::ObserverRule, period: f64, t_end: f64) -> Config {
    let mut c = cfg.clone();
    c.control.kind = crate::ControllerKind::Ftdo;
    c.observer.rule = rule;
    c.observer.sample_period = period;
    c.discretisation.dt = period / (period / cfg.discretisation.dt).ceil().max(1.0);
    c.horizon.t_end = t_end;
    c.horizon.sample_every = period;
    c
}

/// The longest horizon of the finite-time rows' digital runs (s): they run long enough for the
/// reaching-time bounds plus two chatter windows, but never beyond max(t_end, 2·window + 0.01).
pub fn finite_time_horizon_max(cfg: &Config) -> f64 {
    cfg.horizon.t_end.max(2.0 * FINITE_TIME_WINDOW_S + 0.01)
}

/// `cfg` with the grid doubled: the space refinement of `simulate --error-estimate`.
pub fn refined_in_space(cfg: &Config) -> Config {
    let mut c = cfg.clone();
    match c.discretisation.method {
        Method::Fe => c.discretisation.elements *= 2,
        Method::Fd => c.discretisation.fd_points *= 2,
    }
    c
}

/// `cfg` with one output interval, [0, t_end] (`horizon.sample_every = t_end`, a whole number of
/// sample periods as t_end is): the configuration of a statistics run, which serves whole-run
/// quantities only (`wingcheck_claims::Study::statistics`, the run the work estimate counts).
pub fn one_output_interval(cfg: &Config) -> Config {
    let mut c = cfg.clone();
    c.horizon.sample_every = cfg.horizon.t_end;
    c
}

/// `cfg` with the time step halved: the time refinement of `simulate --error-estimate`.
pub fn refined_in_time(cfg: &Config) -> Config {
    let mut c = cfg.clone();
    c.discretisation.dt *= 0.5;
    c
}

/// Seconds of one `g_hmax` evaluation for `cfg` (φ on a 1e-4 s grid over the horizon).
pub fn g_hmax_seconds(cfg: &Config) -> f64 {
    cfg.horizon.t_end * G_HMAX_SAMPLES_PER_SECOND * SECONDS_PER_G_HMAX_SAMPLE
}
/// Columns of the simulator's time series: `wingcheck_sim::Series::COLUMNS` is an array of
/// this length (its type), so the estimate's width follows the series.
pub const SERIES_COLUMNS: usize = 19;
/// `f64` values per output sample of the full-rate envelope `wingcheck_sim::Envelope` ((min, max)
/// of τ1, τ2, g̃1, g̃2; a compile-time assertion there ties it to the type).
pub const ENVELOPE_VALUES: usize = 8;
/// Bytes per stored output sample of a run: the series' [`SERIES_COLUMNS`] and the envelope's
/// [`ENVELOPE_VALUES`] `f64` (the runners allocate them at the run's exact sample count,
/// `Config::output_samples`).
pub const SERIES_BYTES_PER_SAMPLE: f64 = ((SERIES_COLUMNS + ENVELOPE_VALUES) * 8) as f64;
/// Bytes per output sample of the stored fields beyond their values: two `Vec` headers (24 bytes)
/// and two heap blocks' allocator overhead (16 bytes).
pub const FIELD_OVERHEAD_BYTES_PER_SAMPLE: f64 = 2.0 * (24.0 + 16.0);
/// Bytes per number in pretty JSON output (digits, punctuation and indentation), measured on
/// run.json files of the default configuration (≈ 30) and rounded up.
pub const JSON_BYTES_PER_NUMBER: f64 = 32.0;
/// Stepper set-ups `check` makes for σ(0): one per channel for the finite-time rows (shared by
/// both rows with their digital runs) and one for Lemma 3, each building the modal basis when
/// the run would be modal.
pub const CHECK_SIGMA0_SETUPS: f64 = 3.0;
/// Element counts of the report's accuracy study.
pub const REPORT_ACCURACY_GRIDS: [usize; 4] = [8, 16, 32, 64];

/// Coarsest mesh (elements or FD intervals) of `modes`' extrapolation (sim's `converged_frequencies`).
pub const MODES_COARSEST: usize = 16;
/// Finest mesh `modes` refines to (FE: 3·N unknowns, FD: 2·N).
pub const MODES_FINEST: usize = 2048;
/// Subspace iterations per mesh before `modes` gives up (sim's `lowest_eigenvalues`).
pub const MODES_ITERATIONS_MAX: usize = 500;
/// Seconds per subspace iteration per block vector per unknown for its solve: a banded
/// strain solve, ≈ 1e-8 s per unknown, doubled.
pub const SECONDS_PER_MODES_SOLVE: f64 = 2e-8;
/// Seconds per subspace iteration per (block vector)² per unknown (the Ritz matrix and the Ritz
/// vectors): measured 409 s wall at load 10 on 2 cores for `modes --count 50 --tol 1e-13` on a
/// wing whose iteration did not converge (block 100, meshes 128…2048: 500 iterations each),
/// i.e. ≤ 6.9e-9.
pub const SECONDS_PER_MODES_PRODUCT: f64 = 6.9e-9;

/// The block size of `modes`' subspace iteration for `count` frequencies on `unknowns` unknowns.
pub fn modes_block(count: usize, unknowns: usize) -> usize {
    unknowns.min((2 * count).max(count + 8))
}

/// The meshes `modes` may use for `count` frequencies: from `max(16, next power of two ≥ 2·count)`
/// doubling to [`MODES_FINEST`].
pub fn modes_meshes(count: usize) -> Vec<usize> {
    let mut n = MODES_COARSEST.max((2 * count).next_power_of_two());
    let mut out = Vec::new();
    while n <= MODES_FINEST {
        out.push(n);
        n *= 2;
    }
    out
}

/// The command-line flag that runs a command above the limits (named in [`WorkRefused`]).
pub const ALLOW_LARGE_FLAG: &str = "--allow-large";

/// Limits above which a command refuses without `--allow-large`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkLimits {
    /// Estimated run time (s).
    pub seconds: f64,
    /// Estimated peak memory (bytes).
    pub memory_bytes: f64,
    /// Estimated output size (bytes).
    pub output_bytes: f64,
}

/// The documented default limits: 10 minutes, 4 GiB of memory, 1 GiB of output.
pub const DEFAULT_LIMITS: WorkLimits =
    WorkLimits { seconds: 600.0, memory_bytes: 4.0 * 1073741824.0, output_bytes: 1073741824.0 };

/// An estimate of one command's work.
#[derive(Debug, Clone, PartialEq)]
pub struct WorkEstimate {
    /// What is estimated, e.g. `simulate`.
    pub what: String,
    /// Total integrator steps over all simulations.
    pub steps: f64,
    /// Estimated run time (s) on one core.
    pub seconds: f64,
    /// Estimated peak memory (bytes).
    pub memory_bytes: f64,
    /// Estimated output size (bytes).
    pub output_bytes: f64,
}

/// A refused estimate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{what} refused before starting: estimated {details}; the limits are {limits}. {advice}, or pass {override_flag} to run anyway")]
pub struct WorkRefused {
    /// The command.
    pub what: String,
    /// How the front end that asked overrides the limits ([`ALLOW_LARGE_FLAG`] on the command
    /// line; the Python binding's keyword argument).
    pub override_flag: String,
    /// The estimate, in words.
    pub details: String,
    /// The limits, in words.
    pub limits: String,
    /// What to change to come within the limits.
    pub advice: String,
}

/// What to change to bring the work of command `what` within the limits.
fn advice(what: &str) -> &'static str {
    if what == "modes" {
        "Ask for fewer frequencies (--count)"
    } else {
        "Reduce horizon.t_end, raise discretisation.dt or horizon.sample_every, use fewer elements"
    }
}

/// A size in binary units, as every work estimate and limit states it (the limits are
/// 4 GiB and 1 GiB): "4.000 GiB", "12.500 MiB", "3 KiB" (KiB rounded up).
pub fn human_bytes(b: f64) -> String {
    const KIB: f64 = 1024.0;
    const MIB: f64 = KIB * KIB;
    const GIB: f64 = MIB * KIB;
    if b >= GIB {
        format!("{:.3} GiB", b / GIB)
    } else if b >= MIB {
        format!("{:.3} MiB", b / MIB)
    } else {
        format!("{:.0} KiB", (b / KIB).ceil())
    }
}

fn human_seconds(s: f64) -> String {
    if s >= 3600.0 {
        format!("{:.1} h", s / 3600.0)
    } else if s >= 60.0 {
        format!("{:.1} min", s / 60.0)
    } else {
        format!("{s:.2} s")
    }
}

impl WorkEstimate {
    /// One simulation of `cfg` (at its grid), storing fields if `fields`, writing JSON
    /// (`json_output`) or CSV.
    /// Counts the initial layer's re-runs ([`layer_steps_max`]).
    pub fn simulation(cfg: &Config, fields: bool, json_output: Option<bool>) -> WorkEstimate {
        Self::run(cfg, fields, json_output, layer_steps_max(cfg), 1 + LAYER_RUNS_MAX)
    }

    /// One run of `cfg` at its configured step only, without the initial layer's re-runs (the
    /// search's and the region map's closed-loop runs, sim's `simulate_base`).
    pub fn simulation_base(cfg: &Config) -> WorkEstimate {
        Self::run(cfg, false, None, 0.0, 1)
    }

    /// `runs`: the base run and its initial-layer re-runs, which share one modal basis (sim's
    /// `simulate` builds it once) but each set up their own time scheme.
    fn run(cfg: &Config, fields: bool, json_output: Option<bool>, layer_steps: f64, runs: usize) -> WorkEstimate {
        let base_steps = (cfg.horizon.t_end / cfg.discretisation.dt).ceil();
        let steps = base_steps + layer_steps;
        let samples = cfg.output_samples() as f64;
        let n = 2.0 * cfg.unknowns() as f64;
        let field_values = if fields { 2.0 * cfg.horizon.field_points as f64 } else { 0.0 };
        let field_bytes = if fields { 8.0 * field_values + FIELD_OVERHEAD_BYTES_PER_SAMPLE } else { 0.0 };
        let columns = SERIES_COLUMNS as f64;
        let output = match json_output {
            None => 0.0,
            Some(true) => samples * (columns + ENVELOPE_VALUES as f64 + field_values) * JSON_BYTES_PER_NUMBER,
            Some(false) => samples * columns * 25.0,
        };
        // the series (and fields), the solver's work vectors, and the output's text, which is
        // built in memory before it is written
        let memory = samples * (SERIES_BYTES_PER_SAMPLE + field_bytes) + 200.0 * n * 8.0 + output;
        // the exponential scheme (the modal basis, n = displacements + velocities states): one
        // dense product per step after an O(n³) setup, and the sub-step probe of the first step
        // of every sample period with its rows (≈ 16 points per octave of s × 6 outputs)
        let is_exponential = cfg.expected_time_scheme() == crate::TimeScheme::Exponential;
        let exponential = if is_exponential {
            let layer_periods = (LAYER_SAMPLES * (runs - 1)) as f64;
            let periods = (cfg.horizon.t_end / cfg.observer.sample_period).ceil() + layer_periods;
            exponential_seconds(steps, n) + sub_step_probe_seconds(periods, n)
        } else {
            0.0
        };
        let memory = memory + if is_exponential { SUB_STEP_PROBE_ROWS * n * 8.0 } else { 0.0 };
        WorkEstimate {
            what: "simulate".into(),
            steps,
            seconds: steps * n * SECONDS_PER_UNKNOWN_STEP + exponential + Self::setup_seconds(cfg),
            memory_bytes: memory,
            output_bytes: output,
        }
    }

    /// Seconds of one run's set-up beyond its steps: the modal basis's SVD (O(unknowns³)) when the run is expected in the modal basis (once per `simulate`: its
    /// initial-layer re-runs step in the same basis).
    pub fn setup_seconds(cfg: &Config) -> f64 {
        if cfg.expected_modal() {
            (cfg.unknowns() as f64).powi(3) * SECONDS_PER_MODAL_SETUP_CUBE
        } else {
            0.0
        }
    }

    /// `simulate --error-estimate`: the run, the run on the doubled grid and the run at dt/2,
    /// the peaks' 4N run (counted over the whole horizon: it stops one sample period after
    /// the latest peak), and for a scheme without the sub-step probe its exponential twin
    /// (modal basis, at the configured step only).
    pub fn simulation_with_error(cfg: &Config, fields: bool, json_output: Option<bool>) -> WorkEstimate {
        let base = Self::simulation(cfg, fields, json_output);
        let space = Self::simulation(&refined_in_space(cfg), false, None);
        let time = Self::simulation(&refined_in_time(cfg), false, None);
        let fourth = Self::simulation(&refined_in_space(&refined_in_space(cfg)), false, None);
        let twin = if cfg.expected_time_scheme() == crate::TimeScheme::Exponential {
            None
        } else {
            let mut t = cfg.clone();
            t.discretisation.stepper = crate::TimeScheme::Exponential;
            t.discretisation.basis = crate::StepBasis::Modal;
            Some(Self::simulation_base(&t))
        };
        let (twin_steps, twin_seconds, twin_memory) =
            twin.map_or((0.0, 0.0, 0.0), |t| (t.steps, t.seconds, t.memory_bytes));
        WorkEstimate {
            what: "simulate".into(),
            steps: base.steps + space.steps + time.steps + fourth.steps + twin_steps,
            seconds: base.seconds + space.seconds + time.seconds + fourth.seconds + twin_seconds,
            memory_bytes: base.memory_bytes
                + space.memory_bytes.max(time.memory_bytes).max(fourth.memory_bytes).max(twin_memory),
            output_bytes: base.output_bytes,
        }
    }

    /// The finite-time rows' digital runs (one set, read by both rows): the FTDO with both sampling
    /// rules at each of [`FINITE_TIME_PERIODS`] over (at most) [`finite_time_horizon_max`],
    /// whatever the configured horizon and sample period; plus the σ(0) set-ups.
    pub fn finite_time(cfg: &Config) -> WorkEstimate {
        let horizon = finite_time_horizon_max(cfg);
        let (mut steps, mut seconds, mut memory) = (0.0, 0.0, 0.0_f64);
        // One set of runs serves both rows, and again on the doubled grid and at dt/2 for the
        // values' errors; the runs may all be in flight at once.
        let refined = [cfg.clone(), refined_in_space(cfg), refined_in_time(cfg)];
        for (c, rule) in refined
            .iter()
            .flat_map(|c| [crate::ObserverRule::Implicit, crate::ObserverRule::Explicit].map(move |rule| (c, rule)))
        {
            for &period in &FINITE_TIME_PERIODS {
                let run = Self::simulation(&finite_time_config(c, rule, period, horizon), false, None);
                steps += run.steps;
                seconds += run.seconds;
                // per run: σ_k of both channels at every sample (16 bytes), and the traces
                memory += run.memory_bytes + 48.0 * (horizon / period).ceil();
            }
        }
        seconds += CHECK_SIGMA0_SETUPS * Self::setup_seconds(cfg);
        WorkEstimate { what: "check".into(), steps, seconds, memory_bytes: memory, output_bytes: 0.0 }
    }

    /// `modes` at most: every mesh of [`modes_meshes`] with [`MODES_ITERATIONS_MAX`]
    /// iterations (a tolerance the extrapolation never meets and an iteration that never
    /// converges), in the method `method` of `cfg`'s wing. Memory: six blocks of vectors on the
    /// finest mesh.
    pub fn modes(cfg: &Config, method: Method, count: usize) -> WorkEstimate {
        let (mut steps, mut seconds, mut memory) = (0.0, 0.0, 0.0f64);
        for mesh in modes_meshes(count) {
            let mut c = cfg.clone();
            c.discretisation.method = method;
            c.discretisation.elements = mesh;
            c.discretisation.fd_points = mesh;
            let n = c.unknowns();
            let p = modes_block(count, n) as f64;
            let iterations = MODES_ITERATIONS_MAX as f64;
            steps += iterations;
            seconds += iterations * p * n as f64 * (SECONDS_PER_MODES_SOLVE + p * SECONDS_PER_MODES_PRODUCT);
            memory = memory.max(6.0 * p * n as f64 * 8.0 + 200.0 * n as f64 * 8.0);
        }
        WorkEstimate { what: "modes".into(), steps, seconds, memory_bytes: memory, output_bytes: 0.0 }
    }

    /// `Ok` within `limits`, else [`WorkRefused`] naming every exceeded quantity.
    pub fn within(&self, limits: &WorkLimits) -> Result<(), WorkRefused> {
        let mut over = Vec::new();
        if self.seconds > limits.seconds {
            if self.steps > 0.0 {
                over.push(format!(
                    "{} steps, ~{} of computing",
                    format_number(self.steps),
                    human_seconds(self.seconds)
                ));
            } else {
                over.push(format!("~{} of computing", human_seconds(self.seconds)));
            }
        }
        if self.memory_bytes > limits.memory_bytes {
            over.push(format!("{} of memory", human_bytes(self.memory_bytes)));
        }
        if self.output_bytes > limits.output_bytes {
            over.push(format!("{} of output", human_bytes(self.output_bytes)));
        }
        if over.is_empty() {
            return Ok(());
        }
        Err(WorkRefused {
            what: self.what.clone(),
            advice: advice(&self.what).to_string(),
            override_flag: ALLOW_LARGE_FLAG.into(),
            details: over.join(", "),
            limits: format!(
                "{} of computing, {} of memory, {} of output",
                human_seconds(limits.seconds),
                human_bytes(limits.memory_bytes),
                human_bytes(limits.output_bytes)
            ),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The layer's steps are the typed step's decimal tenths (the strings below are the values
    /// a user reads), each within two ulps of the binary quotient.
    #[test]
    fn layer_steps_are_decimal_tenths_of_the_typed_step() {
        let cases: [(f64, [&str; 4]); 5] = [
            (1e-3, ["1e-4", "1e-5", "1e-6", "1e-7"]),
            (1e-4, ["1e-5", "1e-6", "1e-7", "1e-8"]),
            (5e-4, ["5e-5", "5e-6", "5e-7", "5e-8"]),
            (2.5e-5, ["2.5e-6", "2.5e-7", "2.5e-8", "2.5e-9"]),
            (3e-4, ["3e-5", "3e-6", "3e-7", "3e-8"]),
        ];
        for (typed, expected) in cases {
            let mut dt = typed;
            for want in expected {
                let next = decimal_tenth(dt);
                assert_eq!(format!("{next:e}"), want, "from {typed:e}");
                let quotient = dt / 10.0;
                assert!((next - quotient).abs() <= 2.0 * (quotient.next_up() - quotient), "{next:e} vs {quotient:e}");
                dt = next;
            }
        }
        let mut cfg = Config::paper();
        cfg.discretisation.dt = 1e-3;
        let steps: Vec<String> = layer_runs(&cfg).iter().map(|r| format!("{:e}", r.dt)).collect();
        assert!(
            steps.len() >= 2 && steps.iter().zip(["1e-3", "1e-4", "1e-5", "1e-6", "1e-7"]).all(|(s, w)| s == w),
            "{steps:?}"
        );
    }

    use super::WorkEstimate;
    use crate::{apply_overrides, Config};

    fn seconds(sets: &[&str]) -> f64 {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        WorkEstimate::simulation(&apply_overrides(&Config::paper(), &sets).unwrap(), false, None).seconds
    }

    #[test]
    fn estimates_follow_the_grid_actually_used_and_the_scheme() {
        // FD's grid is `fd_points`, not `elements` (4× the intervals: ≥ 3× the estimate)
        let fd = ["discretisation.method=fd", "discretisation.grading=0"];
        let coarse = seconds(&[fd[0], fd[1], "discretisation.fd_points=24"]);
        let fine = seconds(&[fd[0], fd[1], "discretisation.fd_points=96"]);
        assert!(fine > 3.0 * coarse, "{fine} vs {coarse}");
        // the exponential scheme's dense step (the `auto` choice for the explicit FTDO) costs
        // more than TR-BDF2's O(n) one: (2n)² per step against 2n (144 states here)
        let trbdf2 = seconds(&["observer.rule=explicit", "discretisation.stepper=trbdf2"]);
        let exponential = seconds(&["observer.rule=explicit"]);
        assert!(exponential > 2.0 * trbdf2, "{exponential} vs {trbdf2}");
        // above MODAL_AUTO_UNKNOWNS `auto` runs the explicit FTDO in nodal TR-BDF2 (the modal
        // basis would mean the exponential scheme's dense steps), and is estimated as such
        let fine = ["observer.rule=explicit", "discretisation.elements=200"];
        let auto = seconds(&fine);
        let nodal = seconds(&[fine[0], fine[1], "discretisation.stepper=trbdf2", "discretisation.basis=nodal"]);
        assert_eq!(auto, nodal);
        // TR-BDF2 asked for there is stepped in the modal basis, whose setup the estimate counts
        let modal = seconds(&[fine[0], fine[1], "discretisation.stepper=trbdf2"]);
        assert!(modal > nodal, "{modal} vs {nodal}");
        // a forced exponential scheme there is estimated with its dense step
        assert!(seconds(&[fine[0], fine[1], "discretisation.stepper=exponential"]) > 10.0 * nodal);
    }
}

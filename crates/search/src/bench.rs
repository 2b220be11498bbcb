//! `wingcheck bench --what search`: points per second on the paper's 32×32 (a, b) grid with
//! 1 and 2 threads, where the time goes, and the ratios the search is held to, each measured in
//! the same run: the search's wall time against `points` × one default `simulate` run, and the
//! explicit observer's cost per point against the implicit one's.

use serde::Serialize;
use std::path::Path;
use wingcheck_io::clock::{measure, Elapsed, MachineLoad};
use wingcheck_model::{apply_overrides, Config};
use wingcheck_sim::{simulate, RunOptions};

use crate::modal::{ModalBasis, RunCache};
use crate::{finalize, run, RunControl, Search, SearchError, SearchOptions};
use wingcheck_sim::modal::RecordedSignal;

/// One timed run of the whole search.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct ThreadTiming {
    /// Worker threads.
    pub threads: usize,
    /// Wall time of the run, evaluation and final files (s).
    pub wall_seconds: f64,
    /// Points per second (points / wall time).
    pub points_per_second: f64,
    /// Closed-loop runs, summed over points (s).
    pub closed_loop_seconds: f64,
    /// Theory (eigenvalues, μ and ε SOCPs), summed over points (s).
    pub theory_seconds: f64,
    /// Points that failed (see failures.csv of a real run).
    pub failed: usize,
    /// CPU time of the process during the run (user + system, s; [`wingcheck_io::clock`],
    /// None off Linux): on a shared machine, points per CPU-second is the load-independent figure.
    pub cpu_seconds: Option<f64>,
}

/// The benchmark's result.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct SearchBench {
    /// Axes (command-line form).
    pub axes: Vec<String>,
    /// Points.
    pub points: usize,
    /// Cores and the machine's load at the start and the end: timings on a shared machine are
    /// only comparable at similar load.
    pub machine: MachineLoad,
    /// One run per thread count.
    pub runs: Vec<ThreadTiming>,
    /// Once per search: the modal basis of the wing (s).
    pub modal_basis_seconds: f64,
    /// Once per search: the observer/input signal (s).
    pub input_signal_seconds: f64,
    /// Writing the final files (boundaries, heatmaps, CSV/JSON) of the complete search (s).
    pub finalize_seconds: f64,
    /// One point's closed loop as the search runs it (shared basis and signal), median of 5 (s;
    /// CPU where known, else wall, like every `_seconds` of a single-threaded piece here).
    pub modal_point_seconds: f64,
    /// The same point with the simulator (`simulate` of the base configuration: modal basis,
    /// observer signal, full series and peaks), median of all its timings: 5 before the thread
    /// runs, and 5 before and 5 after each of the [`SEARCH_REPEATS`] runs with the most threads
    /// (s; CPU where known).
    pub simulator_point_seconds: f64,
    /// Wall times of the [`SEARCH_REPEATS`] runs with the most threads (s), each between 5
    /// `simulate` timings before and 5 after it.
    pub most_threads_wall_seconds: Vec<f64>,
    /// Per run of `most_threads_wall_seconds`: the median of the 10 `simulate` timings around
    /// it (s).
    pub simulate_around_seconds: Vec<f64>,
    /// The median over those runs of wall / (points × the `simulate_around_seconds` of the run):
    /// each ratio within one stretch of time. It moves with the machine's load (the search's
    /// threads compete with other processes, one `simulate` less so).
    pub wall_over_simulate_runs: f64,
    /// CPU times of the same runs (s; None off Linux).
    pub most_threads_cpu_seconds: Vec<Option<f64>>,
    /// Per run: the median CPU time of the 10 `simulate` runs around it (s).
    pub simulate_around_cpu_seconds: Vec<Option<f64>>,
    /// The median over those runs of CPU / (points × `simulate_around_cpu_seconds`): the
    /// search's work per point against one `simulate` run's, load-independent (None off Linux).
    pub cpu_over_simulate_runs: Option<f64>,
    /// The implicit and the explicit observer on a smaller grid of the same axes.
    pub rules: Vec<RuleTiming>,
    /// Explicit / implicit observer cost per point, wall time: the median over
    /// [`RULE_ROUNDS`] rounds of the ratio within each round (the two searches back to back,
    /// so a change of the machine's load between rounds cancels).
    pub explicit_over_implicit_wall: f64,
    /// The same ratio of CPU time, where measurable.
    pub explicit_over_implicit_cpu: Option<f64>,
}

/// Runs of the whole search with the most threads, interleaved with `simulate` timings, for
/// the search's ratio (a single run moved it by ±25 % with the machine's load).
pub const SEARCH_REPEATS: usize = 3;

/// Points per axis of the benchmark's grid (`wingcheck bench --what search`).
pub const GRID_POINTS: usize = 32;

/// Thread counts the benchmark times the whole search with.
pub const THREAD_COUNTS: [usize; 2] = [1, 2];

/// The observer rules compared (`observer.rule`), in the order of [`SearchBench::rules`].
const RULES: [&str; 2] = ["implicit", "explicit"];

/// Rounds of the observer-rule comparison: each runs both rules' searches back to back, in
/// alternating order.
pub const RULE_ROUNDS: usize = 5;

/// A search with one observer rule (`observer.rule`), on the 8 × 8 grid of the same axes with
/// the most threads: its cost per point, median over [`RULE_ROUNDS`] runs.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct RuleTiming {
    /// `implicit` or `explicit`.
    pub rule: String,
    /// The time scheme its points use (`discretisation.stepper`, `auto` resolved).
    pub scheme: String,
    /// Points.
    pub points: usize,
    /// Wall time per point (s).
    pub wall_seconds_per_point: f64,
    /// Process CPU time per point (s), where measurable.
    pub cpu_seconds_per_point: Option<f64>,
}

use wingcheck_sim::bench::{median, median_elapsed};

/// One rule's cost per point in one round: wall time and, where measurable, CPU time (s).
type PerPoint = (f64, Option<f64>);

/// One timed whole search of `axes` on `base` with `threads` threads in a new directory under
/// `tmp`: (wall and CPU time, summary).
fn timed_run(
    base: &Config,
    axes: &[String],
    threads: usize,
    dir: &std::path::Path,
) -> Result<(Elapsed, crate::RunSummary), SearchError> {
    let search = Search::new(base.clone(), axes, SearchOptions::default())?;
    let (s, elapsed) = measure(|| run(&search, dir, RunControl { threads: Some(threads), ..Default::default() }));
    Ok((elapsed, s?))
}

/// Wall and CPU times of `repeats` default `simulate` runs of `cfg`.
fn simulate_seconds(cfg: &Config, repeats: usize) -> Result<Vec<Elapsed>, SearchError> {
    (0..repeats)
        .map(|_| {
            let (out, elapsed) = measure(|| simulate(cfg, RunOptions::default()));
            out?;
            Ok(elapsed)
        })
        .collect()
}

/// The work of [`bench_search`] on `base` (`n` × `n` grid, `thread_counts`), estimated before it
/// starts from the models its parts are guarded by: the `simulate` timings
/// (`wingcheck_model::work::WorkEstimate::simulation`, 5 + 10 per repeat), each whole search and
/// the rule comparison's searches ([`crate::limits`]: core time, memory at their threads), and
/// the closed-loop timings. Steps and seconds add up; memory is the largest part's (the parts run
/// one after another).
pub fn bench_estimate(
    base: &Config,
    n: usize,
    thread_counts: &[usize],
) -> Result<wingcheck_model::work::WorkEstimate, SearchError> {
    use wingcheck_model::work::WorkEstimate as Run;
    let axes = vec![format!("control.a=1e-4..10:log:{n}"), format!("control.b=1e-2..1e4:log:{n}")];
    let small = vec!["control.a=1e-4..10:log:8".to_string(), "control.b=1e-2..1e4:log:8".to_string()];
    let most = thread_counts.iter().copied().max().unwrap_or(1);
    let sim = Run::simulation(base, false, None);
    let simulate_runs = (5 + SEARCH_REPEATS * 10) as f64;
    let mut searches: Vec<crate::WorkEstimate> = Vec::new();
    let grid = Search::new(base.clone(), &axes, SearchOptions::default())?;
    searches.extend(thread_counts.iter().map(|&t| grid.estimate_with_threads(t)));
    searches.extend((0..SEARCH_REPEATS).map(|_| grid.estimate_with_threads(most)));
    for rule in RULES {
        let cfg = apply_overrides(base, &[format!("observer.rule={rule}")])?;
        let s = Search::new(cfg, &small, SearchOptions::default())?.estimate_with_threads(most);
        searches.extend(std::iter::repeat_n(s, RULE_ROUNDS));
    }
    // the modal basis, the signal and 5 closed loops of the base point (one thread)
    let point =
        Search::new(base.clone(), &["control.a=1".to_string()], SearchOptions::default())?.estimate_with_threads(1);
    searches.extend(std::iter::repeat_n(point, 6));
    Ok(Run {
        what: "bench --what search".into(),
        steps: simulate_runs * sim.steps
            + searches.iter().map(|w| w.points as f64 * w.steps_per_point as f64).sum::<f64>(),
        seconds: simulate_runs * sim.seconds + searches.iter().map(|w| w.core_seconds).sum::<f64>(),
        memory_bytes: searches.iter().map(|w| w.memory_bytes).fold(sim.memory_bytes, f64::max),
        output_bytes: 0.0,
    })
}

/// One search per thread count on the base grid, and the finalisation's time of the last.
fn thread_runs(
    base: &Config,
    axes: &[String],
    thread_counts: &[usize],
    tmp: &Path,
) -> Result<(Vec<ThreadTiming>, f64), SearchError> {
    let mut runs = Vec::new();
    let mut finalize_seconds = 0.0;
    for (k, &threads) in thread_counts.iter().enumerate() {
        let dir = tmp.join(format!("run-{k}"));
        let (elapsed, s) = timed_run(base, axes, threads, &dir)?;
        runs.push(ThreadTiming {
            threads,
            wall_seconds: elapsed.wall_seconds,
            points_per_second: s.evaluated as f64 / elapsed.wall_seconds,
            closed_loop_seconds: s.sim_seconds,
            theory_seconds: s.theory_seconds,
            failed: s.failed,
            cpu_seconds: elapsed.cpu_seconds,
        });
        let (done, elapsed) = measure(|| finalize(&dir));
        done?;
        finalize_seconds = elapsed.wall_seconds;
    }
    Ok((runs, finalize_seconds))
}

/// The two sampling rules on a small grid at `most` threads, alternating over
/// [`RULE_ROUNDS`] rounds: per rule the median time per point, and the median paired ratios
/// explicit / implicit (wall, CPU).
fn rule_timings(base: &Config, most: usize, tmp: &Path) -> Result<(Vec<RuleTiming>, f64, Option<f64>), SearchError> {
    let small = vec!["control.a=1e-4..10:log:8".to_string(), "control.b=1e-2..1e4:log:8".to_string()];
    let rule_cfg = |rule: &str| apply_overrides(base, &[format!("observer.rule={rule}")]).map_err(SearchError::from);
    let rule_cfgs = [rule_cfg(RULES[0])?, rule_cfg(RULES[1])?];
    // per rule: (wall, CPU) per point of each round, and the points
    let mut per_point: [Vec<PerPoint>; 2] = [Vec::new(), Vec::new()];
    let mut evaluated = [0usize; 2];
    for round in 0..RULE_ROUNDS {
        let order = if round % 2 == 0 { [0, 1] } else { [1, 0] };
        for r in order {
            let dir = tmp.join(format!("rule-{r}-{round}"));
            let (elapsed, s) = timed_run(&rule_cfgs[r], &small, most, &dir)?;
            let points = s.evaluated.max(1) as f64;
            per_point[r].push((elapsed.wall_seconds / points, elapsed.cpu_seconds.map(|c| c / points)));
            evaluated[r] = s.evaluated;
        }
    }
    let cpu_of = |v: &[PerPoint]| v.iter().map(|p| p.1).collect::<Option<Vec<f64>>>();
    let rules: Vec<RuleTiming> = (0..2)
        .map(|r| RuleTiming {
            rule: RULES[r].into(),
            scheme: rule_cfgs[r].time_scheme(true).name().into(),
            points: evaluated[r],
            wall_seconds_per_point: median(per_point[r].iter().map(|p| p.0).collect()),
            cpu_seconds_per_point: cpu_of(&per_point[r]).map(median),
        })
        .collect();
    let paired = |f: &dyn Fn(&PerPoint) -> Option<f64>| -> Option<f64> {
        let ratios: Option<Vec<f64>> =
            per_point[0].iter().zip(&per_point[1]).map(|(i, e)| Some(f(e)? / f(i)?)).collect();
        ratios.map(median)
    };
    let explicit_over_implicit_wall = paired(&|p| Some(p.0)).unwrap_or(0.0);
    let explicit_over_implicit_cpu = paired(&|p| p.1);
    Ok((rules, explicit_over_implicit_wall, explicit_over_implicit_cpu))
}

/// The modal basis's and the input signal's set-up times, and five timed modal point runs.
fn modal_setups(cfg: &Config) -> Result<(f64, f64, Vec<Elapsed>), SearchError> {
    let (basis, elapsed) = measure(|| ModalBasis::new(cfg));
    let basis = basis?;
    let modal_basis_seconds = elapsed.seconds();
    let (signal, elapsed) = measure(|| RecordedSignal::new(cfg));
    let input_signal_seconds = elapsed.seconds();
    let mut modal = Vec::new();
    let runs_cache = RunCache::new();
    for _ in 0..5 {
        let (out, elapsed) = measure(|| crate::point::closed_loop(cfg, &runs_cache, None));
        out?;
        modal.push(elapsed);
    }
    drop((basis, signal));
    Ok((modal_basis_seconds, input_signal_seconds, modal))
}

/// Run the benchmark on `base` (the paper config by default): the grid
/// a ∈ [1e-4, 10] × b ∈ [1e-2, 1e4], n × n log points, with 1 and `max_threads` threads.
pub fn bench_search(base: &Config, n: usize, thread_counts: &[usize]) -> Result<SearchBench, SearchError> {
    let mut machine = MachineLoad::at_start();
    let axes = vec![format!("control.a=1e-4..10:log:{n}"), format!("control.b=1e-2..1e4:log:{n}")];
    let search = Search::new(base.clone(), &axes, SearchOptions::default())?;
    let tmp = tempfile::tempdir().map_err(|source| SearchError::FileSystem { path: std::env::temp_dir(), source })?;
    let cfg = apply_overrides(base, &[])?;
    let mut simulator = simulate_seconds(&cfg, 5)?;
    let (runs, finalize_seconds) = thread_runs(base, &axes, thread_counts, tmp.path())?;
    let most = thread_counts.iter().copied().max().unwrap_or(1);
    // Each ratio from one search run and the `simulate` timings just before and after it, so
    // that a change of the machine's speed between runs (this VM's neighbours) cancels; the
    // median of the ratios is reported. (The quotient of two medians over the whole bench moved
    // from 0.255 to 0.329 between two runs 12 minutes apart, its `simulate` from 8.0 to 5.7 ms.)
    let (mut most_threads, mut simulate_around) = (Vec::new(), Vec::new());
    for k in 0..SEARCH_REPEATS {
        let mut around = simulate_seconds(&cfg, 5)?;
        let (elapsed, _) = timed_run(base, &axes, most, &tmp.path().join(format!("repeat-{k}")))?;
        around.extend(simulate_seconds(&cfg, 5)?);
        most_threads.push(elapsed);
        simulate_around.push(median_elapsed(&around));
        simulator.extend(around);
    }
    let points = search.points() as f64;
    let ratios: Vec<f64> = most_threads
        .iter()
        .zip(&simulate_around)
        .map(|(r, sim)| r.wall_seconds / (points * sim.wall_seconds))
        .collect();
    let cpu_ratios: Option<Vec<f64>> = most_threads
        .iter()
        .zip(&simulate_around)
        .map(|(r, sim)| Some(r.cpu_seconds? / (points * sim.cpu_seconds?)))
        .collect();
    let simulator_point_seconds = median_elapsed(&simulator).seconds();
    let (rules, explicit_over_implicit_wall, explicit_over_implicit_cpu) = rule_timings(base, most, tmp.path())?;
    let (modal_basis_seconds, input_signal_seconds, modal) = modal_setups(&cfg)?;
    let wall_over_simulate_runs = median(ratios);
    machine.finish();
    Ok(SearchBench {
        axes,
        points: search.points(),
        machine,
        runs,
        modal_basis_seconds,
        input_signal_seconds,
        finalize_seconds,
        modal_point_seconds: median_elapsed(&modal).seconds(),
        simulator_point_seconds,
        most_threads_wall_seconds: most_threads.iter().map(|e| e.wall_seconds).collect(),
        simulate_around_seconds: simulate_around.iter().map(|e| e.wall_seconds).collect(),
        wall_over_simulate_runs,
        most_threads_cpu_seconds: most_threads.iter().map(|e| e.cpu_seconds).collect(),
        simulate_around_cpu_seconds: simulate_around.iter().map(|e| e.cpu_seconds).collect(),
        cpu_over_simulate_runs: cpu_ratios.map(median),
        rules,
        explicit_over_implicit_wall,
        explicit_over_implicit_cpu,
    })
}

//! `wingcheck bench --what search`: points per second on the paper's 32×32 (a, b) grid with
//! 1 and 2 threads, and where the time goes.

use std::time::Instant;

use serde::Serialize;
use wingcheck_model::{apply_overrides, Config};
use wingcheck_sim::{simulate, RunOptions};

use crate::modal::{ModalBasis, RunCache};
use crate::{finalize, run, RunControl, Search, SearchError, SearchOptions};
use wingcheck_sim::modal::RecordedSignal;

/// One timed run of the whole search.
#[derive(Debug, Clone, Serialize)]
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
    /// CPU time of the process during the run (user + system, s; Linux `/proc/self/stat`,
    /// None elsewhere): on a shared machine, points per CPU-second is the load-independent figure.
    pub cpu_seconds: Option<f64>,
}

/// User + system CPU time of this process (s), from `/proc/self/stat` (fields 14, 15, in the
/// kernel's USER_HZ = 100 ticks per second).
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // fields after the parenthesised command name (which may contain spaces)
    let rest = stat.rsplit_once(')')?.1;
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// The benchmark's result.
#[derive(Debug, Clone, Serialize)]
pub struct SearchBench {
    /// Axes (command-line form).
    pub axes: Vec<String>,
    /// Points.
    pub points: usize,
    /// 1-minute load average of the machine when the benchmark started (Linux; None
    /// elsewhere): timings on a shared machine are only comparable at similar load.
    pub load_average: Option<f64>,
    /// Cores available.
    pub cores: usize,
    /// One run per thread count.
    pub runs: Vec<ThreadTiming>,
    /// Once per search: the modal basis of the wing (s).
    pub modal_basis_seconds: f64,
    /// Once per search: the observer/input signal (s).
    pub input_signal_seconds: f64,
    /// Writing the final files (boundaries, heatmaps, CSV/JSON) of the complete search (s).
    pub finalize_seconds: f64,
    /// One point's closed loop in the modal runner, median of 5 (s).
    pub modal_point_seconds: f64,
    /// The same point with the simulator (`simulate`: sparse step solve, observer in the
    /// loop, full series), median of 5 (s) — the search's per-point cost before.
    pub simulator_point_seconds: f64,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Run the benchmark on `base` (the paper config by default): the grid
/// a ∈ [1e-4, 10] × b ∈ [1e-2, 1e4], n × n log points, with 1 and `max_threads` threads.
pub fn bench_search(base: &Config, n: usize, thread_counts: &[usize]) -> Result<SearchBench, SearchError> {
    let load_average = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|x| x.parse().ok()));
    let cores = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    let axes = vec![format!("control.a=1e-4..10:log:{n}"), format!("control.b=1e-2..1e4:log:{n}")];
    let search = Search::new(base.clone(), &axes, SearchOptions::default())?;
    let tmp = tempfile::tempdir().map_err(|e| SearchError::Io { path: "temp dir".into(), detail: e.to_string() })?;
    let mut runs = Vec::new();
    let mut finalize_seconds = 0.0;
    for (k, &threads) in thread_counts.iter().enumerate() {
        let dir = tmp.path().join(format!("run-{k}"));
        let (start, cpu0) = (Instant::now(), process_cpu_seconds());
        let s = run(&search, &dir, RunControl { threads: Some(threads), ..Default::default() })?;
        let wall = start.elapsed().as_secs_f64();
        let cpu_seconds = cpu0.zip(process_cpu_seconds()).map(|(a, b)| b - a);
        runs.push(ThreadTiming {
            threads,
            wall_seconds: wall,
            points_per_second: s.evaluated as f64 / wall,
            closed_loop_seconds: s.sim_seconds,
            theory_seconds: s.theory_seconds,
            failed: s.failed,
            cpu_seconds,
        });
        let start = Instant::now();
        finalize(&dir)?;
        finalize_seconds = start.elapsed().as_secs_f64();
    }
    let cfg = apply_overrides(base, &[]).map_err(|e| SearchError::Options(e.to_string()))?;
    let start = Instant::now();
    let basis = ModalBasis::new(&cfg).map_err(|e| SearchError::Options(e.to_string()))?;
    let modal_basis_seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let signal = RecordedSignal::new(&cfg);
    let input_signal_seconds = start.elapsed().as_secs_f64();
    let (mut modal, mut simulator) = (Vec::new(), Vec::new());
    let runs_cache = RunCache::new();
    for _ in 0..5 {
        let start = Instant::now();
        crate::point::closed_loop(&cfg, &runs_cache).map_err(|e| SearchError::Options(e.to_string()))?;
        modal.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        simulate(&cfg, RunOptions::default()).map_err(|e| SearchError::Options(e.to_string()))?;
        simulator.push(start.elapsed().as_secs_f64());
    }
    drop((basis, signal));
    Ok(SearchBench {
        axes,
        points: search.points(),
        load_average,
        cores,
        runs,
        modal_basis_seconds,
        input_signal_seconds,
        finalize_seconds,
        modal_point_seconds: median(modal),
        simulator_point_seconds: median(simulator),
    })
}

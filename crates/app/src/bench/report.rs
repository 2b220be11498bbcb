//! `bench --what report`: the whole report with its stages; for a configuration with the
//! implicit observer also the same report with `observer.rule = explicit`, the two alternating
//! run by run in one sitting so that their ratio (the explicit observer's extra cost: its
//! exponential scheme in the simulations and the region map) is measured under one load.

use serde::Serialize;
use wingcheck_io::clock::{measure, Elapsed};
use wingcheck_model::{Config, ObserverRule};
use wingcheck_sim::bench::median_elapsed;

use crate::AppError;

/// One stage of the last report run (wall time: the stages overlap on the worker threads).
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct StageTiming {
    /// The stage.
    pub stage: String,
    /// Its wall time (s).
    pub wall_seconds: f64,
}

/// The report's timings.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct ReportBench {
    /// The whole report, median of the repeats.
    pub report: Elapsed,
    /// Runs timed.
    pub runs: usize,
    /// The stages of the last run.
    pub stages: Vec<StageTiming>,
    /// The same report with `observer.rule = explicit` (configurations with the implicit
    /// observer only), median of as many runs, alternating with the configured ones.
    pub explicit_observer: Option<Elapsed>,
    /// Its time over the configured report's (CPU where known).
    pub explicit_over_configured: Option<f64>,
}

/// `cfg` with `observer.rule = explicit` where it has the implicit observer: the report the
/// bench times beside the configured one (and its estimate counts).
pub(crate) fn explicit_twin(cfg: &Config) -> Option<Config> {
    (cfg.observer.rule == ObserverRule::Implicit).then(|| {
        let mut c = cfg.clone();
        c.observer.rule = ObserverRule::Explicit;
        c
    })
}

/// One report of `c` into a fresh temporary directory, removed afterwards.
fn timed(c: &Config) -> Result<(Elapsed, wingcheck_report::ReportSummary), AppError> {
    let tmp = tempfile::tempdir().map_err(|e| AppError::OutputPath {
        path: std::env::temp_dir(),
        message: format!("temporary directory: {e}"),
    })?;
    let dir = tmp.path().join("report");
    let (summary, elapsed) = measure(|| wingcheck_report::write_report(c, &dir, &Default::default()));
    Ok((elapsed, summary?))
}

/// Run the report bench (guarded by the caller).
pub(crate) fn bench_report(cfg: &Config, repeats: usize) -> Result<ReportBench, AppError> {
    let explicit = explicit_twin(cfg);
    let (mut runs, mut explicit_runs, mut last) = (Vec::new(), Vec::new(), None);
    for _ in 0..repeats.max(1) {
        let (elapsed, summary) = timed(cfg)?;
        runs.push(elapsed);
        last = Some(summary);
        if let Some(c) = &explicit {
            explicit_runs.push(timed(c)?.0);
        }
    }
    let report = median_elapsed(&runs);
    let explicit_observer = explicit.as_ref().map(|_| median_elapsed(&explicit_runs));
    let stages = last
        .map(|s| s.timings.into_iter().map(|t| StageTiming { stage: t.name, wall_seconds: t.seconds }).collect())
        .unwrap_or_default();
    Ok(ReportBench {
        report,
        runs: runs.len(),
        stages,
        explicit_over_configured: explicit_observer.map(|e| e.seconds() / report.seconds()),
        explicit_observer,
    })
}

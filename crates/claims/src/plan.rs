//! The run plan of `check`: every closed-loop simulation the rows ask the [`crate::Study`] for,
//! listed by the same functions the rows use to build them, so the work estimate counts
//! exactly the runs `check` makes (a test compares the plan with what a study simulated).

use std::collections::BTreeMap;

use wingcheck_model::work::{g_hmax_seconds, WorkEstimate, CHECK_FIXED_SECONDS};
use wingcheck_model::{Config, ControllerKind};

use crate::settings::CheckSettings;

/// The distinct configurations `check` simulates (each once, by the study), in a stable order.
pub fn check_runs(cfg: &Config, settings: &CheckSettings) -> Vec<Config> {
    let mut runs: Vec<Config> = Vec::new();
    // mu-conditions: ζ3, ζ4 from the FTDO run at the configured gains
    let mut ftdo = cfg.clone();
    ftdo.control.kind = ControllerKind::Ftdo;
    // and their errors from its refinements (Study::zeta_errors)
    let refined = crate::study::refine::refinements(&ftdo);
    runs.push(ftdo);
    runs.extend(refined);
    // UUB: the configured run, and the FTDO at the operating point (when (32) can hold)
    runs.push(cfg.clone());
    if let Some((a, b)) = crate::mu::operating_point(cfg) {
        runs.push(crate::uub::operating_run(cfg, a, b));
    }
    // ftdo-vs-dobc
    let comparison = crate::comparison::Runs::of(cfg, settings);
    runs.extend(comparison.full().into_iter().cloned());
    runs.extend(comparison.error_runs().map(wingcheck_model::work::one_output_interval));
    // the refinements behind the comparison's ± (Study::refinement)
    runs.extend(comparison.refined());
    distinct(runs)
}

/// `runs` without repeats (by configuration hash), first occurrence kept.
pub fn distinct(runs: Vec<Config>) -> Vec<Config> {
    let mut seen = BTreeMap::new();
    runs.into_iter().filter(|c| seen.insert(crate::config_sha256(c), ()).is_none()).collect()
}

/// The work estimate of `wingcheck check` at `cfg`: the planned runs (each with fields, as the
/// study records them, all held at once), the finite-time rows' digital runs, g_hmax's grid
/// (twice: the mu row and the search's theory), and the configuration-independent work.
pub fn check_estimate(cfg: &Config, settings: &CheckSettings) -> WorkEstimate {
    let runs: Vec<WorkEstimate> =
        check_runs(cfg, settings).iter().map(|c| WorkEstimate::simulation(c, true, None)).collect();
    let finite = WorkEstimate::finite_time(cfg);
    WorkEstimate {
        what: "check".into(),
        steps: runs.iter().map(|r| r.steps).sum::<f64>() + finite.steps,
        seconds: runs.iter().map(|r| r.seconds).sum::<f64>()
            + finite.seconds
            + 2.0 * g_hmax_seconds(cfg)
            + CHECK_FIXED_SECONDS,
        memory_bytes: runs.iter().map(|r| r.memory_bytes).sum::<f64>() + finite.memory_bytes,
        output_bytes: 0.0,
    }
}

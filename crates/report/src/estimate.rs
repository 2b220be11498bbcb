//! The work estimate of `wingcheck report`, from its own run plan: the claim checker's runs
//! ([`wingcheck_claims::plan`]), the figures' runs ([`crate::runs::plan`], shared with the
//! ledger where they coincide), the region map's points and the page's CSV output.

use wingcheck_claims::plan::{check_estimate, check_runs, distinct};
use wingcheck_claims::CheckSettings;
use wingcheck_model::work::{g_hmax_seconds, WorkEstimate, REGION_MAP_MAX_POINTS, SECONDS_PER_POINT_THEORY};
use wingcheck_model::Config;

/// Memory of the region map (a search over (a, b), [`crate::region`]) on the rayon pool's
/// threads, from the search's own model ([`wingcheck_search::limits`]): its signal, basis and
/// one point's run per thread (the a, b values do not change the cost; the process's base is
/// counted by the rest of the report). 0 when the map's axes cannot be posed (it is then
/// skipped).
fn region_memory(cfg: &Config) -> f64 {
    use wingcheck_search::{Axis, Search};
    let a: Vec<f64> = (1..=14).map(f64::from).collect();
    let b: Vec<f64> = (1..=7).map(f64::from).collect();
    let axes = Axis::of_numbers("control.a", &a).and_then(|a| Ok(vec![a, Axis::of_numbers("control.b", &b)?]));
    match axes.and_then(|axes| Search::from_axes(cfg.clone(), axes, Default::default())) {
        Ok(s) => {
            let m = s.estimate_for(None).memory;
            m.total() - m.process
        }
        Err(_) => 0.0,
    }
}

/// Estimated work of [`crate::write_report`] at `cfg`.
pub fn report_estimate(cfg: &Config) -> WorkEstimate {
    let settings = CheckSettings::default();
    let check = check_estimate(cfg, &settings);
    let ledger_runs: Vec<String> = check_runs(cfg, &settings).iter().map(wingcheck_claims::config_sha256).collect();
    // the figures' runs the ledger does not already make (the study runs each once)
    let extra: Vec<Config> = distinct(crate::runs::plan(cfg))
        .into_iter()
        .filter(|c| !ledger_runs.contains(&wingcheck_claims::config_sha256(c)))
        .collect();
    let runs: Vec<WorkEstimate> = extra.iter().map(|c| WorkEstimate::simulation(c, true, None)).collect();
    // the region map's closed-loop runs (search's, at the configured step: no layer re-runs)
    let one = WorkEstimate::simulation_base(cfg);
    let region = REGION_MAP_MAX_POINTS as f64;
    // the page's CSVs: the three controllers' series and fields
    let csv = WorkEstimate::simulation(cfg, true, Some(false)).output_bytes * 3.0 * 2.0;
    WorkEstimate {
        what: "report".into(),
        steps: check.steps + runs.iter().map(|r| r.steps).sum::<f64>() + region * one.steps,
        seconds: check.seconds
            + runs.iter().map(|r| r.seconds).sum::<f64>()
            + region * (one.seconds + SECONDS_PER_POINT_THEORY)
            + g_hmax_seconds(cfg),
        memory_bytes: check.memory_bytes + runs.iter().map(|r| r.memory_bytes).sum::<f64>() + region_memory(cfg),
        output_bytes: csv,
    }
}

//! The work of a whole benchmark, estimated before it starts (every timed run times its
//! repetitions), so `bench` is guarded like the commands it times.

use wingcheck_model::work::WorkEstimate;
use wingcheck_model::{apply_overrides, Config, Method};

use super::report::explicit_twin;
use super::sim::{variants, GRID_SIZES, HORIZONS};
use super::BenchKind;

/// Steps and seconds add up over the timed runs; memory is the largest run's (they run one
/// after another). `search`: `wingcheck_search::bench::bench_estimate` (its `simulate`
/// timings and every search it runs); a search axis that does not fit the configuration fails
/// in the benchmark itself before any work.
pub fn bench_estimate(cfg: &Config, what: BenchKind, repeats: usize) -> WorkEstimate {
    let set = |sets: &[String]| apply_overrides(cfg, sets).ok();
    let mut parts: Vec<(f64, WorkEstimate)> = Vec::new();
    let sim = |c: &Config| WorkEstimate::simulation(c, false, None);
    let (r, r3) = (repeats as f64, repeats.min(3) as f64);
    match what {
        BenchKind::Check => {
            parts.push((r, wingcheck_claims::plan::check_estimate(cfg, &wingcheck_claims::CheckSettings::default())))
        }
        BenchKind::Report => {
            parts.push((r, wingcheck_report::report_estimate(cfg)));
            // the same report with the explicit observer, alternating with it
            if let Some(c) = explicit_twin(cfg) {
                parts.push((r, wingcheck_report::report_estimate(&c)));
            }
        }
        BenchKind::Search => {
            use wingcheck_search::bench::{GRID_POINTS, THREAD_COUNTS};
            if let Ok(e) = wingcheck_search::bench::bench_estimate(cfg, GRID_POINTS, &THREAD_COUNTS) {
                parts.push((1.0, e));
            }
        }
        BenchKind::Sim => {
            parts.push((r, sim(cfg)));
            // every variant the simulator bench may time (both steppers and bases: which one is
            // "the other" depends on the configuration)
            for variant in variants() {
                if let Some(c) = set(&variant) {
                    parts.push((r, sim(&c)));
                }
            }
            parts.push((r3, WorkEstimate::simulation_with_error(cfg, false, None)));
            parts.push((r, WorkEstimate::modes(cfg, cfg.discretisation.method, 5)));
            let key = if cfg.discretisation.method == Method::Fd { "fd_points" } else { "elements" };
            for n in GRID_SIZES {
                if let Some(c) = set(&[format!("discretisation.{key}={n}")]) {
                    parts.push((r3, sim(&c)));
                }
            }
            for t in HORIZONS {
                if let Some(c) = set(&[format!("horizon.t_end={t}")]) {
                    parts.push((r3, sim(&c)));
                }
            }
        }
    }
    let mut total =
        WorkEstimate { what: "bench".into(), steps: 0.0, seconds: 0.0, memory_bytes: 0.0, output_bytes: 0.0 };
    for (times, e) in parts {
        total.steps += times * e.steps;
        total.seconds += times * e.seconds;
        total.memory_bytes = total.memory_bytes.max(e.memory_bytes);
    }
    total
}

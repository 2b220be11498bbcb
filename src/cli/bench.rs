//! `wingcheck bench`: simulator performance.

use clap::Args;
use serde_json::json;
use wingcheck_model::work::WorkEstimate;
use wingcheck_model::{apply_overrides, Config};
use wingcheck_sim::bench::{loglog_slope, time_config, time_error_estimate, time_modes, Timing};

use super::common::ConfigArgs;

/// Arguments of `wingcheck bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    config: ConfigArgs,
    /// Repetitions per configuration (the median is reported), 1 to 1000.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u16).range(1..=1000))]
    repeats: u16,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// What to measure: the simulator (`sim`), the claim checker (`check`), the report
    /// (`report`) or the search (`search`: the 32×32 paper grid with 1 and 2 threads).
    #[arg(long, default_value = "sim", value_parser = ["sim", "check", "report", "search"])]
    what: String,
    #[command(flatten)]
    work: super::common::WorkArgs,
}

/// The work of the whole benchmark, estimated before it starts (every timed run times its
/// repetitions), so `bench` is guarded like the commands it times; `search` by
/// `wingcheck_search::bench::bench_estimate` (its `simulate` timings and every search it runs).
fn estimate(cfg: &Config, what: &str, repeats: usize) -> WorkEstimate {
    let set = |sets: &[String]| apply_overrides(cfg, sets).ok();
    let mut parts: Vec<(f64, WorkEstimate)> = Vec::new();
    let sim = |c: &Config| WorkEstimate::simulation(c, false, None);
    let (r, r3) = (repeats as f64, repeats.min(3) as f64);
    match what {
        "check" => {
            parts.push((r, wingcheck_claims::plan::check_estimate(cfg, &wingcheck_claims::CheckSettings::default())))
        }
        "report" => {
            parts.push((r, wingcheck_report::report_estimate(cfg)));
            // the same report with the explicit observer, alternating with it (bench_report)
            if let Some(c) = explicit_twin(cfg) {
                parts.push((r, wingcheck_report::report_estimate(&c)));
            }
        }
        "search" => {
            use wingcheck_search::bench::{bench_estimate, GRID_POINTS, THREAD_COUNTS};
            // axes that do not fit this configuration fail in `bench_search` before any work
            if let Ok(e) = bench_estimate(cfg, GRID_POINTS, &THREAD_COUNTS) {
                parts.push((1.0, e));
            }
        }
        _ => {
            parts.push((r, sim(cfg)));
            for variant in [
                vec!["discretisation.stepper=trapezoid".to_string()],
                vec!["discretisation.stepper=trbdf2".to_string()],
                vec!["discretisation.basis=nodal".to_string()],
                vec!["discretisation.basis=modal".to_string()],
                vec![
                    "control.kind=ftdo".into(),
                    "observer.rule=explicit".into(),
                    "discretisation.stepper=exponential".into(),
                ],
                vec![
                    "control.kind=ftdo".into(),
                    "observer.rule=explicit".into(),
                    "discretisation.stepper=trbdf2".into(),
                ],
            ] {
                if let Some(c) = set(&variant) {
                    parts.push((r, sim(&c)));
                }
            }
            parts.push((r3, WorkEstimate::simulation_with_error(cfg, false, None)));
            // time_modes: 5 frequencies, `repeats` times
            parts.push((r, WorkEstimate::modes(cfg, cfg.discretisation.method, 5)));
            let key = if cfg.discretisation.method == wingcheck_model::Method::Fd { "fd_points" } else { "elements" };
            for n in [8usize, 16, 32, 64, 128] {
                if let Some(c) = set(&[format!("discretisation.{key}={n}")]) {
                    parts.push((r3, sim(&c)));
                }
            }
            for t in [5.0, 10.0, 20.0, 40.0] {
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

pub fn run(a: BenchArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    a.work.guard(&estimate(&cfg, &a.what, usize::from(a.repeats)))?;
    match a.what.as_str() {
        "check" => return bench_check(&cfg, usize::from(a.repeats), a.json),
        "report" => return bench_report(&cfg, usize::from(a.repeats), a.json),
        "search" => return bench_search(&cfg, a.json),
        _ => {}
    }
    let base = time_config(&cfg, usize::from(a.repeats))?;
    // the other time scheme, measured in the same run for the cost ratio
    let other = if base.stepper == wingcheck_model::TimeScheme::Trapezoid { "trbdf2" } else { "trapezoid" };
    let other_cfg = apply_overrides(&cfg, &[format!("discretisation.stepper={other}")])?;
    let other_timing = time_config(&other_cfg, usize::from(a.repeats))?;
    // the other basis, measured in the same run for the cost ratio
    let other_basis = if base.basis == wingcheck_model::StepBasis::Modal { "nodal" } else { "modal" };
    let other_basis_timing = apply_overrides(&cfg, &[format!("discretisation.basis={other_basis}")])
        .map_err(anyhow::Error::from)
        .and_then(|c| time_config(&c, usize::from(a.repeats)).map_err(anyhow::Error::from));
    // the explicit FTDO, whose `auto` scheme is the exponential one, against TR-BDF2
    let explicit_timing = |scheme: &str| {
        apply_overrides(
            &cfg,
            &["control.kind=ftdo".into(), "observer.rule=explicit".into(), format!("discretisation.stepper={scheme}")],
        )
        .map_err(anyhow::Error::from)
        .and_then(|c| time_config(&c, usize::from(a.repeats)).map_err(anyhow::Error::from))
    };
    let explicit = explicit_timing("exponential").and_then(|e| Ok((e, explicit_timing("trbdf2")?)));
    let estimate_seconds = time_error_estimate(&cfg, usize::from(a.repeats).min(3))?;
    let modes = time_modes(&cfg, 5, usize::from(a.repeats))?;
    let mut grid: Vec<Timing> = Vec::new();
    for n in [8usize, 16, 32, 64, 128] {
        let key = if cfg.discretisation.method == wingcheck_model::Method::Fd { "fd_points" } else { "elements" };
        let c = apply_overrides(&cfg, &[format!("discretisation.{key}={n}")])?;
        grid.push(time_config(&c, usize::from(a.repeats).min(3))?);
    }
    let mut horizon: Vec<Timing> = Vec::new();
    for t in [5.0, 10.0, 20.0, 40.0] {
        let c = apply_overrides(&cfg, &[format!("horizon.t_end={t}")])?;
        horizon.push(time_config(&c, usize::from(a.repeats).min(3))?);
    }
    let grid_slope = loglog_slope(
        &grid.iter().map(|t| t.unknowns as f64).collect::<Vec<_>>(),
        &grid.iter().map(|t| t.seconds_per_step).collect::<Vec<_>>(),
    );
    let horizon_slope = loglog_slope(
        &horizon.iter().map(|t| t.steps as f64).collect::<Vec<_>>(),
        &horizon.iter().map(|t| t.run_seconds).collect::<Vec<_>>(),
    );
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&json!({
                "default": base,
                "other_stepper": { "stepper": other, "timing": other_timing },
                "other_basis": other_basis_timing.as_ref().ok().map(|t| json!({ "basis": other_basis, "timing": t })),
                "explicit_ftdo": explicit.as_ref().ok().map(|(e, t)| json!({ "exponential": e, "trbdf2": t })),
                "error_estimate_seconds": estimate_seconds,
                "modes": modes,
                "grid_scaling": grid,
                "grid_exponent": grid_slope,
                "horizon_scaling": horizon,
                "horizon_exponent": horizon_slope,
            }))?
        );
        return Ok(());
    }
    println!(
        "default run ({} controller, {} with {} elements, dt = {} s, {}, {} basis, T = {} s): {:.2} ms ({} steps, {} unknowns)",
        cfg.control.kind.name(),
        cfg.discretisation.method.name(),
        cfg.discretisation.grid_size(),
        cfg.discretisation.dt,
        base.stepper,
        base.basis,
        cfg.horizon.t_end,
        base.run_seconds * 1e3,
        base.steps,
        base.unknowns
    );
    println!(
        "  per step {:.3} µs = {:.2} × one step-matrix solve ({:.3} µs)",
        base.seconds_per_step * 1e6,
        base.seconds_per_step / base.solve_seconds,
        base.solve_seconds * 1e6
    );
    println!(
        "  {} stepper: {:.2} ms; ratio {} / {} = {:.2} (same run)",
        other,
        other_timing.run_seconds * 1e3,
        base.stepper,
        other,
        base.run_seconds / other_timing.run_seconds
    );
    match &other_basis_timing {
        Ok(t) => println!(
            "  {} basis: {:.2} ms; ratio {} / {} = {:.2} (same run)",
            other_basis,
            t.run_seconds * 1e3,
            base.basis,
            other_basis,
            base.run_seconds / t.run_seconds
        ),
        Err(e) => println!("  {other_basis} basis: not available here ({e})"),
    }
    match &explicit {
        Ok((e, t)) => println!(
            "  explicit FTDO: exponential scheme {:.2} ms, trbdf2 {:.2} ms; ratio exponential / trbdf2 = {:.1} (same run)",
            e.run_seconds * 1e3,
            t.run_seconds * 1e3,
            e.run_seconds / t.run_seconds
        ),
        Err(e) => println!("  explicit FTDO, exponential scheme: not available here ({e})"),
    }
    println!(
        "  with error estimates (refined in h and dt): {:.2} ms = {:.2} × the run",
        estimate_seconds * 1e3,
        estimate_seconds / base.run_seconds
    );
    println!(
        "modes (5, with error estimates, {} meshes {:?}): {:.2} ms, worst relative estimate {:.1e}",
        cfg.discretisation.method.name(),
        modes.meshes,
        modes.seconds * 1e3,
        modes.worst_relative_error
    );
    println!("grid scaling (T = {} s):", cfg.horizon.t_end);
    println!(
        "{:>9} {:>9} {:>6} {:>12} {:>12} {:>10}",
        "elements", "unknowns", "basis", "µs/step", "µs/solve", "step/solve"
    );
    for t in &grid {
        println!(
            "{:>9} {:>9} {:>6} {:>12.3} {:>12.3} {:>10.2}",
            t.elements,
            t.unknowns,
            t.basis,
            t.seconds_per_step * 1e6,
            t.solve_seconds * 1e6,
            t.seconds_per_step / t.solve_seconds
        );
    }
    println!("  fitted exponent of time per step vs unknowns: {grid_slope:.2} (1 = linear; the basis column says where `auto` switches)");
    println!("horizon scaling:");
    println!("{:>9} {:>9} {:>12}", "T (s)", "steps", "run (ms)");
    for t in &horizon {
        println!("{:>9} {:>9} {:>12.2}", t.t_end, t.steps, t.run_seconds * 1e3);
    }
    println!("  fitted exponent of run time vs steps: {horizon_slope:.2} (1 = linear)");
    Ok(())
}

use wingcheck_sim::bench::median;

/// Whole `wingcheck check` wall time (median of `repeats`) with the per-row breakdown and the
/// exact re-verification of the certificates.
fn bench_check(cfg: &wingcheck_model::Config, repeats: usize, as_json: bool) -> anyhow::Result<()> {
    use std::time::Instant;
    let mut totals = Vec::new();
    let mut rows: Vec<(String, Vec<f64>)> = Vec::new();
    let mut sdp = Vec::new();
    let mut digital = Vec::new();
    let mut sims = 0;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        let study = wingcheck_claims::Study::new();
        let ledger = wingcheck_claims::check_all_with(cfg, &study, &wingcheck_claims::CheckSettings::default())?;
        totals.push(t.elapsed().as_secs_f64());
        sims = study.simulations_run();
        for (i, r) in ledger.rows.iter().enumerate() {
            if rows.len() <= i {
                rows.push((r.id.to_string(), Vec::new()));
            }
            rows[i].1.push(ledger.wall_seconds_of(r.id.name()).unwrap_or(0.0));
        }
        sdp.push(ledger.wall_seconds_of(wingcheck_claims::SDP_CROSS_CHECK).unwrap_or(0.0));
        digital.push(ledger.wall_seconds_of(wingcheck_claims::DIGITAL_RUNS).unwrap_or(0.0));
    }
    let tmp = std::env::temp_dir().join(format!("wingcheck-bench-proofs-{}", std::process::id()));
    let t = Instant::now();
    let files = wingcheck_claims::certify::write_all(cfg, &tmp)?;
    let certify_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let set = wingcheck_claims::certify::verify_set(&tmp);
    let verify_s = t.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&tmp);
    let ok = set?.certs.len();
    let (compute_s, check_s, worst_s) = bench_enclosure(cfg)?;
    let breakdown: Vec<(String, f64)> = rows.into_iter().map(|(id, v)| (id, median(v))).collect();
    if as_json {
        println!(
            "{}",
            serde_json::to_string_pretty(&json!({
                "check_seconds": median(totals),
                "rows": breakdown.iter().map(|(id, s)| json!({"id": id, "seconds": s})).collect::<Vec<_>>(),
                "sdp_seconds": median(sdp),
                "finite_time_digital_runs_seconds": median(digital),
                "distinct_simulations": sims,
                "certify_seconds": certify_s,
                "verify_seconds": verify_s,
                "certificates": files.len(),
                "omega1_enclosure": {"compute_seconds": compute_s, "check_seconds": check_s, "worst_case_check_seconds": worst_s},
            }))?
        );
        return Ok(());
    }
    println!("wingcheck check: {:.3} s (median of {})", median(totals.clone()), totals.len());
    for (id, s) in &breakdown {
        println!("  {id:<14} {s:>7.3} s");
    }
    println!("  (SDP cross-check at N = 2…32, started first beside the rest of W-bounds: {:.4} s)", median(sdp));
    println!("  (the finite-time rows' digital runs, once for both rows: {:.4} s)", median(digital));
    println!("  distinct closed-loop simulations (each run once): {sims}");
    println!(
        "certify: {} certificates in {certify_s:.3} s; exact re-verification ({ok} ok) in {verify_s:.3} s",
        files.len()
    );
    println!(
        "  ω₁ enclosure: made and checked in {compute_s:.3} s (uncached); exact check alone {check_s:.3} s; \
         the slowest valid certificate (the verifier's limits, every number a 32-character fraction) {worst_s:.3} s"
    );
    Ok(())
}

/// `cfg` with `observer.rule = explicit` where it has the implicit observer: the report
/// [`bench_report`] times beside the configured one (and [`estimate`] counts).
fn explicit_twin(cfg: &Config) -> Option<Config> {
    (cfg.observer.rule == wingcheck_model::ObserverRule::Implicit).then(|| {
        let mut c = cfg.clone();
        c.observer.rule = wingcheck_model::ObserverRule::Explicit;
        c
    })
}

/// Whole `wingcheck report` wall time with the stage breakdown; for a configuration with the
/// implicit observer also the same report with `observer.rule = explicit`, the two alternating
/// run by run in one sitting so that their ratio (the explicit observer's extra cost: its
/// exponential scheme in the simulations and the region map) is measured under one load.
fn bench_report(cfg: &wingcheck_model::Config, repeats: usize, as_json: bool) -> anyhow::Result<()> {
    let explicit = explicit_twin(cfg);
    let (mut runs, mut explicit_runs) = (Vec::new(), Vec::new());
    let mut last = None;
    let timed = |c: &wingcheck_model::Config, tag: &str, i: usize| -> anyhow::Result<(f64, _)> {
        let dir = std::env::temp_dir().join(format!("wingcheck-bench-report-{}-{tag}{i}", std::process::id()));
        let t = std::time::Instant::now();
        let summary = wingcheck_report::write_report(c, &dir, &Default::default());
        let seconds = t.elapsed().as_secs_f64();
        let _ = std::fs::remove_dir_all(&dir);
        Ok((seconds, summary?))
    };
    for i in 0..repeats.max(1) {
        let (seconds, summary) = timed(cfg, "", i)?;
        runs.push(seconds);
        last = Some(summary);
        if let Some(c) = &explicit {
            explicit_runs.push(timed(c, "explicit-", i)?.0);
        }
    }
    let summary = last.expect("at least one run");
    let report_seconds = median(runs.clone());
    // (explicit-observer median, its ratio to the configured report's)
    let explicit = explicit.as_ref().map(|_| {
        let seconds = median(explicit_runs.clone());
        (seconds, seconds / report_seconds)
    });
    if as_json {
        let mut out = json!({
            "report_seconds": report_seconds,
            "stages": summary.timings.iter().map(|t| json!({"stage": t.name, "seconds": t.seconds})).collect::<Vec<_>>(),
        });
        if let Some((seconds, ratio)) = explicit {
            out["explicit_observer_report_seconds"] = json!(seconds);
            out["explicit_over_configured"] = json!(ratio);
        }
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    println!("wingcheck report: {report_seconds:.3} s (median of {})", runs.len());
    for t in &summary.timings {
        println!("  {:<12} {:>7.3} s (last run)", t.name, t.seconds);
    }
    if let Some((seconds, ratio)) = explicit {
        println!(
            "with observer.rule=explicit: {seconds:.3} s (median of {}, alternating with the runs above); \
             ratio {ratio:.2}",
            explicit_runs.len()
        );
    }
    Ok(())
}

fn bench_search(cfg: &wingcheck_model::Config, as_json: bool) -> anyhow::Result<()> {
    use wingcheck_search::bench::{GRID_POINTS, THREAD_COUNTS};
    let b = wingcheck_search::bench::bench_search(cfg, GRID_POINTS, &THREAD_COUNTS)?;
    if as_json {
        println!("{}", serde_json::to_string_pretty(&b)?);
        return Ok(());
    }
    println!("search: {} points ({}), one run per thread count", b.points, b.axes.join(" × "));
    if let Some(l) = b.load_average {
        println!("machine: {} cores, load average {l:.2} when started (other processes share the cores)", b.cores);
    }
    println!("threads  wall (s)  points/s  CPU (s)  points/CPU-s  closed loop Σ (s)  theory Σ (s)  failed points");
    for r in &b.runs {
        let cpu = r.cpu_seconds.map_or("-".to_string(), |c| format!("{c:.2}"));
        let per_cpu = r.cpu_seconds.map_or("-".to_string(), |c| format!("{:.1}", b.points as f64 / c));
        println!(
            "{:>7}  {:>8.2}  {:>8.1}  {:>7}  {:>12}  {:>17.2}  {:>12.2}  {:>13}",
            r.threads,
            r.wall_seconds,
            r.points_per_second,
            cpu,
            per_cpu,
            r.closed_loop_seconds,
            r.theory_seconds,
            r.failed
        );
    }
    println!("(Σ columns are wall times summed over points: they include time the threads were preempted)");
    let n = b.points as f64;
    if let Some(r) = b.runs.first() {
        println!(
            "per point (1 thread): closed loop {:.2} ms, theory {:.2} ms",
            1e3 * r.closed_loop_seconds / n,
            1e3 * r.theory_seconds / n
        );
    }
    println!(
        "one point's closed loop: {:.2} ms in the search vs {:.2} ms for the default `simulate` run (ratio {:.2})",
        1e3 * b.modal_point_seconds,
        1e3 * b.simulator_point_seconds,
        b.modal_point_seconds / b.simulator_point_seconds
    );
    if let Some(r) = b.runs.last() {
        let walls: Vec<String> = b.most_threads_wall_seconds.iter().map(|w| format!("{w:.3}")).collect();
        println!(
            "ratio: search wall at {} threads ({} s) / ({} × one default simulate run timed just before and after each, median {:.2} ms overall) = {:.3}, the median of the runs' ratios",
            r.threads,
            walls.join(", "),
            b.points,
            1e3 * b.simulator_point_seconds,
            b.wall_over_simulate_runs
        );
    }
    for r in &b.rules {
        let cpu = r.cpu_seconds_per_point.map_or("-".into(), |c| format!("{:.2}", 1e3 * c));
        println!(
            "observer.rule={} ({} scheme), {} points: {:.2} ms wall, {cpu} ms CPU per point (median of {} runs)",
            r.rule,
            r.scheme,
            r.points,
            1e3 * r.wall_seconds_per_point,
            wingcheck_search::bench::RULE_ROUNDS
        );
    }
    let cpu = b.explicit_over_implicit_cpu.map_or("-".into(), |c| format!("{c:.2}"));
    println!(
        "ratio: explicit / implicit observer per point = {:.2} (wall), {cpu} (CPU); medians of the ratios of {} \
         back-to-back pairs",
        b.explicit_over_implicit_wall,
        wingcheck_search::bench::RULE_ROUNDS
    );
    println!(
        "once per search: modal basis {:.2} ms, observer signal {:.2} ms; final files {:.2} s",
        1e3 * b.modal_basis_seconds,
        1e3 * b.input_signal_seconds,
        b.finalize_seconds
    );
    if let Some(r) = b.runs.last() {
        println!(
            "10 000 points at {} threads: ≈ {:.0} s (at the measured {:.1} points/s)",
            r.threads,
            1e4 / r.points_per_second,
            r.points_per_second
        );
    }
    Ok(())
}

/// The ω₁ enclosure's costs: [`omega1::compute_with`] uncached (a plan the ledger does not use,
/// so nothing is cached), the exact check of the configured certificate, and the exact check
/// of the slowest certificate the verifier accepts (k, both meshes at their limits, every
/// shift and vector entry a 32-character fraction).
fn bench_enclosure(cfg: &wingcheck_model::Config) -> anyhow::Result<(f64, f64, f64)> {
    use std::time::Instant;
    use wingcheck_claims::certify::omega1::{self, Plan, LIMITS};
    let t = Instant::now();
    let plan = Plan { rayleigh_elements: omega1::PLAN.rayleigh_elements + 1, ..omega1::PLAN };
    let _ = omega1::compute_with(cfg, &plan)?;
    let compute_s = t.elapsed().as_secs_f64();
    let cert = omega1::compute(cfg)?.0.clone();
    let t = Instant::now();
    cert.check_exact()?;
    let check_s = t.elapsed().as_secs_f64();
    let limits = Plan {
        modes: LIMITS.max_modes,
        inertia_elements: LIMITS.max_inertia_elements,
        rayleigh_elements: LIMITS.max_rayleigh_elements,
    };
    let mut worst = omega1::compute_with(cfg, &limits)?.0.clone();
    // p/q of exactly 32 characters just above each shift (still valid), and each vector entry.
    let fraction = |v: f64, up: bool| {
        let mut q: u128 = 98_765_432_109_876_543;
        loop {
            let p = (v.abs() * q as f64).ceil() as u128 + u128::from(up);
            let t = format!("{}{p}/{q}", if v < 0.0 { "-" } else { "" });
            if t.len() <= 32 {
                return t;
            }
            q = q / 10 + 7;
        }
    };
    for s in worst.shifts.iter_mut() {
        *s = fraction(s.parse::<f64>()? * 1.0001, true);
    }
    for s in worst.vector.iter_mut().skip(3) {
        let v: f64 = s.parse()?;
        if v != 0.0 {
            *s = fraction(v, false);
        }
    }
    let t = Instant::now();
    worst.check_exact()?;
    Ok((compute_s, check_s, t.elapsed().as_secs_f64()))
}

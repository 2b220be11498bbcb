//! `wingcheck bench`: the tool's measurements of itself, made by `wingcheck_app::bench` and
//! printed here as text (or as the document with `--json`). Ratios are from CPU time where
//! the platform gives it; every output names the machine's cores and load.

use clap::Args;
use wingcheck_app::bench::{BenchKind, BenchRequest, CheckBench, OtherTiming, ReportBench, SimBench};
use wingcheck_io::clock::Elapsed;
use wingcheck_sim::bench::Timing;

use super::common::ConfigArgs;

/// Arguments of `wingcheck bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    config: ConfigArgs,
    /// Repetitions per configuration (the median is reported), 1 to 1000.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u16).range(1..=1000))]
    repeats: u16,
    /// Print JSON (docs/schema/bench.schema.json).
    #[arg(long)]
    json: bool,
    /// What to measure: the simulator (`sim`), the claim checker (`check`), the report
    /// (`report`) or the search (`search`: the 32×32 paper grid with 1 and 2 threads).
    #[arg(long, default_value = "sim", value_parser = ["sim", "check", "report", "search"])]
    what: String,
    #[command(flatten)]
    work: super::common::WorkArgs,
}

pub fn run(a: BenchArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    let what = match a.what.as_str() {
        "check" => BenchKind::Check,
        "report" => BenchKind::Report,
        "search" => BenchKind::Search,
        _ => BenchKind::Sim,
    };
    let doc = BenchRequest { what, repeats: usize::from(a.repeats) }.run(&cfg, a.work.policy())?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&doc)?);
        return Ok(());
    }
    println!("machine: {}", doc.machine.describe());
    let cpu_known = wingcheck_io::clock::process_cpu_seconds().is_some();
    println!(
        "times: {} (medians over --repeats {} unless said); ratios from {}",
        if cpu_known { "wall and CPU (user + system of the process)" } else { "wall" },
        doc.repeats,
        if cpu_known { "CPU time" } else { "wall time" }
    );
    if let Some(s) = &doc.sim {
        print_sim(&cfg, s);
    }
    if let Some(c) = &doc.check {
        print_check(c);
    }
    if let Some(r) = &doc.report {
        print_report(r);
    }
    if let Some(s) = &doc.search {
        super::bench_search::print(s);
    }
    Ok(())
}

/// "12.34 ms wall, 11.90 ms CPU" (CPU omitted where unknown).
fn ms(e: Elapsed) -> String {
    match e.cpu_seconds {
        Some(c) => format!("{:.2} ms wall, {:.2} ms CPU", e.wall_seconds * 1e3, c * 1e3),
        None => format!("{:.2} ms wall", e.wall_seconds * 1e3),
    }
}

fn run_ms(t: &Timing) -> String {
    ms(Elapsed { wall_seconds: t.run_seconds, cpu_seconds: t.run_cpu_seconds })
}

fn print_other(label: &str, o: &OtherTiming, base: &Timing) {
    match (&o.timing, o.configured_over_this) {
        (Some(t), Some(r)) => {
            println!("  {label}: {}; ratio {} / {label} = {r:.2} (same sitting)", run_ms(t), configured_name(base))
        }
        _ => println!("  {label}: not available here ({})", o.not_available.as_deref().unwrap_or("refused")),
    }
}

fn configured_name(t: &Timing) -> String {
    format!("{} {}", t.stepper, t.basis)
}

fn print_sim(cfg: &wingcheck_model::Config, s: &SimBench) {
    let base = &s.configured;
    let controller = wingcheck_app::simulate::controller_phrase(cfg);
    println!(
        "configured run ({controller}, {} with {} elements, dt = {} s, {}, {} basis, T = {} s): {} ({} steps, {} unknowns)",
        cfg.discretisation.method.name(),
        cfg.discretisation.grid_size(),
        cfg.discretisation.dt,
        base.stepper,
        base.basis,
        cfg.horizon.t_end,
        run_ms(base),
        base.steps,
        base.unknowns
    );
    println!(
        "  per step {:.3} µs = {:.2} × one step-matrix solve ({:.3} µs)",
        base.seconds_per_step * 1e6,
        base.seconds_per_step / base.solve_seconds,
        base.solve_seconds * 1e6
    );
    print_other(&format!("{} stepper", stepper_of(&s.other_stepper)), &s.other_stepper, base);
    print_other(&format!("{} basis", basis_of(&s.other_basis)), &s.other_basis, base);
    match (&s.explicit_exponential.timing, &s.explicit_trbdf2.timing) {
        (Some(e), Some(t)) => println!(
            "  explicit FTDO: exponential scheme {}, trbdf2 {}; ratio exponential / trbdf2 = {:.2} (same sitting)",
            run_ms(e),
            run_ms(t),
            e.seconds() / t.seconds()
        ),
        _ => println!("  explicit FTDO: not available here"),
    }
    println!(
        "  with error estimates (refined in h and dt): {} = {:.2} × the run",
        ms(s.error_estimate),
        s.error_estimate.seconds() / base.seconds()
    );
    println!(
        "modes (5, with error estimates, {} meshes {:?}): {}, worst relative estimate {:.1e}",
        cfg.discretisation.method.name(),
        s.modes.meshes,
        ms(s.modes.elapsed),
        s.modes.worst_relative_error
    );
    println!("grid scaling (T = {} s; per-step and solve times from CPU where known):", cfg.horizon.t_end);
    println!(
        "{:>9} {:>9} {:>6} {:>12} {:>12} {:>10}",
        "elements", "unknowns", "basis", "µs/step", "µs/solve", "step/solve"
    );
    for t in &s.grid_scaling {
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
    println!(
        "  fitted exponent of time per step vs unknowns: {:.2} (1 = linear; the basis column says where `auto` switches)",
        s.grid_exponent
    );
    println!("horizon scaling:");
    println!("{:>9} {:>9} {:>14} {:>14}", "T (s)", "steps", "wall (ms)", "CPU (ms)");
    for t in &s.horizon_scaling {
        let cpu = t.run_cpu_seconds.map_or("-".to_string(), |c| format!("{:.2}", c * 1e3));
        println!("{:>9} {:>9} {:>14.2} {:>14}", t.t_end, t.steps, t.run_seconds * 1e3, cpu);
    }
    println!("  fitted exponent of run time vs steps: {:.2} (1 = linear)", s.horizon_exponent);
}

/// The stepper a variant sets (`discretisation.stepper=…`).
fn stepper_of(o: &OtherTiming) -> String {
    o.overrides.iter().find_map(|s| s.strip_prefix("discretisation.stepper=")).unwrap_or("other").to_string()
}

/// The basis a variant sets (`discretisation.basis=…`).
fn basis_of(o: &OtherTiming) -> String {
    o.overrides.iter().find_map(|s| s.strip_prefix("discretisation.basis=")).unwrap_or("other").to_string()
}

fn print_check(c: &CheckBench) {
    println!("wingcheck check: {} (median of {})", secs(c.check), c.runs);
    for r in &c.rows {
        println!("  {:<14} {:>7.3} s wall", r.id, r.wall_seconds);
    }
    println!(
        "  (SDP cross-check at N = 2…32, started first beside the rest of W-bounds: {:.4} s wall)",
        c.sdp_wall_seconds
    );
    println!(
        "  (the finite-time rows' digital runs, once for both rows: {:.4} s wall)",
        c.finite_time_digital_runs_wall_seconds
    );
    println!("  distinct closed-loop simulations (each run once): {}", c.distinct_simulations);
    println!(
        "certify: {} certificates in {}; exact re-verification in {}",
        c.certificates,
        secs(c.certify),
        secs(c.verify)
    );
    let e = &c.omega1_enclosure;
    println!(
        "  ω₁ enclosure (CPU): made and checked in {:.3} s (uncached); exact check alone {:.3} s; \
         the slowest valid certificate (the verifier's limits, every number a 32-character fraction) {:.3} s",
        e.compute_seconds, e.check_seconds, e.worst_case_check_seconds
    );
}

/// "1.234 s wall, 2.100 s CPU".
fn secs(e: Elapsed) -> String {
    match e.cpu_seconds {
        Some(c) => format!("{:.3} s wall, {c:.3} s CPU", e.wall_seconds),
        None => format!("{:.3} s wall", e.wall_seconds),
    }
}

fn print_report(r: &ReportBench) {
    println!("wingcheck report: {} (median of {})", secs(r.report), r.runs);
    for t in &r.stages {
        println!("  {:<12} {:>7.3} s wall (last run; stages overlap)", t.stage, t.wall_seconds);
    }
    if let (Some(e), Some(ratio)) = (r.explicit_observer, r.explicit_over_configured) {
        println!(
            "with observer.rule=explicit: {} (median of {}, alternating with the runs above); ratio {ratio:.2}",
            secs(e),
            r.runs
        );
    }
}

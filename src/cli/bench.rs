//! `wingcheck bench`: simulator performance.

use clap::Args;
use serde_json::json;
use wingcheck_model::apply_overrides;
use wingcheck_sim::bench::{loglog_slope, time_config, Timing};

use super::common::ConfigArgs;

/// Arguments of `wingcheck bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    config: ConfigArgs,
    /// Repetitions per configuration (the median is reported).
    #[arg(long, default_value_t = 5)]
    repeats: usize,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(a: BenchArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    let base = time_config(&cfg, a.repeats)?;
    let mut grid: Vec<Timing> = Vec::new();
    for n in [8usize, 16, 32, 64, 128] {
        let c = apply_overrides(&cfg, &[format!("discretisation.elements={n}")])?;
        grid.push(time_config(&c, a.repeats.min(3))?);
    }
    let mut horizon: Vec<Timing> = Vec::new();
    for t in [5.0, 10.0, 20.0, 40.0] {
        let c = apply_overrides(&cfg, &[format!("horizon.t_end={t}")])?;
        horizon.push(time_config(&c, a.repeats.min(3))?);
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
                "grid_scaling": grid,
                "grid_exponent": grid_slope,
                "horizon_scaling": horizon,
                "horizon_exponent": horizon_slope,
            }))?
        );
        return Ok(());
    }
    println!(
        "default run ({} controller, {} with {} elements, dt = {} s, T = {} s): {:.2} ms ({} steps, {} unknowns)",
        cfg.control.kind.name(),
        cfg.discretisation.method.name(),
        cfg.discretisation.elements,
        cfg.discretisation.dt,
        cfg.horizon.t_end,
        base.run_seconds * 1e3,
        base.steps,
        base.unknowns
    );
    println!(
        "  per step {:.3} µs = {:.2} × one sparse solve ({:.3} µs)",
        base.seconds_per_step * 1e6,
        base.seconds_per_step / base.solve_seconds,
        base.solve_seconds * 1e6
    );
    println!("grid scaling (T = {} s):", cfg.horizon.t_end);
    println!("{:>9} {:>9} {:>12} {:>12} {:>10}", "elements", "unknowns", "µs/step", "µs/solve", "step/solve");
    for t in &grid {
        println!(
            "{:>9} {:>9} {:>12.3} {:>12.3} {:>10.2}",
            t.elements,
            t.unknowns,
            t.seconds_per_step * 1e6,
            t.solve_seconds * 1e6,
            t.seconds_per_step / t.solve_seconds
        );
    }
    println!("  fitted exponent of time per step vs unknowns: {grid_slope:.2} (1 = linear)");
    println!("horizon scaling:");
    println!("{:>9} {:>9} {:>12}", "T (s)", "steps", "run (ms)");
    for t in &horizon {
        println!("{:>9} {:>9} {:>12.2}", t.t_end, t.steps, t.run_seconds * 1e3);
    }
    println!("  fitted exponent of run time vs steps: {horizon_slope:.2} (1 = linear)");
    Ok(())
}

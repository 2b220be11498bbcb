//! `wingcheck modes`: converged natural frequencies, each with its error estimate.

use clap::Args;
use wingcheck_app::ModesRequest;
use wingcheck_model::Method;
use wingcheck_sim::modes;

use super::common::ConfigArgs;

/// Arguments of `wingcheck modes`.
#[derive(Debug, Args)]
pub struct ModesArgs {
    #[command(flatten)]
    config: ConfigArgs,
    #[command(flatten)]
    work: super::common::WorkArgs,
    /// Number of frequencies (1..=50).
    #[arg(long, default_value_t = 5)]
    count: usize,
    /// Spatial discretisation: fd or fe (default: discretisation.method of the config).
    #[arg(long)]
    method: Option<Method>,
    /// Relative tolerance on every frequency's error estimate (>= 1e-13).
    #[arg(long, default_value_t = Tolerance(modes::DEFAULT_MODE_TOLERANCE))]
    tol: Tolerance,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// A relative tolerance, shown in `--help` in exponent form (`1e-9`, not `0.000000001`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance(pub f64);

impl std::fmt::Display for Tolerance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:e}", self.0)
    }
}

impl std::str::FromStr for Tolerance {
    type Err = std::num::ParseFloatError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        s.trim().parse().map(Tolerance)
    }
}

pub fn run(a: ModesArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    let req = ModesRequest { count: a.count, method: a.method, tol: a.tol.0 };
    let doc = req.run(&cfg, a.work.policy())?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&doc)?);
        return Ok(());
    }
    let status = if doc.converged {
        format!("every estimate ≤ {:e} relative", doc.tolerance)
    } else {
        format!(
            "NOT converged to {:e}: the finest mesh ({}) was reached; the estimates below are what was achieved",
            doc.tolerance,
            doc.meshes.last().copied().unwrap_or(0)
        )
    };
    println!("natural frequencies (rad/s), {} extrapolated over uniform meshes {:?}: {status}", doc.method, doc.meshes);
    println!("analytic = uncoupled (ρx_c = 0), exact");
    println!("{:>3} {:>20} {:>10} {:>6} {:>18}", "n", "coupled", "± error", "order", "uncoupled analytic");
    for i in 0..doc.coupled_rad_s.len() {
        let order = doc.coupled_observed_order[i].map(|p| format!("{p:.2}")).unwrap_or_else(|| "-".into());
        println!(
            "{:>3} {:>20.12} {:>10.1e} {:>6} {:>18.12}",
            i + 1,
            doc.coupled_rad_s[i],
            doc.coupled_error_rad_s[i],
            order,
            doc.uncoupled_analytic_rad_s[i]
        );
    }
    Ok(())
}

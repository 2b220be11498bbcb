//! `wingcheck modes`: converged natural frequencies, each with its error estimate.

use clap::Args;
use serde_json::json;
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
    let tol = a.tol.0;
    let cfg = a.config.load()?;
    let method = a.method.unwrap_or(cfg.discretisation.method);
    if !(1..=50).contains(&a.count) {
        anyhow::bail!("--count {}: use an integer in [1, 50]", a.count);
    }
    if !(tol.is_finite() && tol >= 1e-13) {
        anyhow::bail!("--tol {}: use a relative tolerance >= 1e-13", tol);
    }
    let count = a.count;
    a.work.guard(&wingcheck_model::work::WorkEstimate::modes(&cfg, method, count))?;
    let conv = modes::converged_frequencies(&cfg, method, count, tol)?;
    let w = &cfg.wing;
    let bending = modes::bending_frequencies(w.span, w.ei, w.rho, count);
    let torsion = modes::torsion_frequencies(w.span, w.gj, w.ip, count);
    let uncoupled = modes::uncoupled_frequencies(w.span, w.ei, w.rho, w.gj, w.ip, count);
    let status = if conv.converged {
        format!("every estimate ≤ {:e} relative", tol)
    } else {
        format!(
            "NOT converged to {:e}: the finest mesh ({}) was reached; the estimates below are what was achieved",
            tol,
            conv.meshes.last().copied().unwrap_or(0)
        )
    };
    if a.json {
        let doc = json!({
            "method": method.name(),
            "meshes": conv.meshes,
            "tolerance": tol,
            "converged": conv.converged,
            "coupled_rad_s": conv.modes.iter().map(|m| m.omega).collect::<Vec<_>>(),
            "coupled_error_rad_s": conv.modes.iter().map(|m| m.error).collect::<Vec<_>>(),
            "coupled_observed_order": conv.modes.iter().map(|m| match m.observed_order {
                Some(p) => json!(p),
                None => json!("round-off"),
            }).collect::<Vec<_>>(),
            "uncoupled_analytic_rad_s": uncoupled,
            "bending_analytic_rad_s": bending,
            "torsion_analytic_rad_s": torsion,
            "note": "coupled: K φ = ω² M φ of the undamped, uncontrolled wing on uniform meshes (sparse shift-invert through the strain factorisation K = GᵀDG), Romberg-extrapolated in h²; coupled_error_rad_s[i] bounds |ω − ω_exact| (the larger of the last two Romberg corrections plus the eigen-solver bound); analytic: ρx_c = 0, exact (cantilever roots of 1 + cos βs cosh βs = 0 and (2n−1)π/(2s)·√(GJ/I_p))",
        });
        println!("{}", serde_json::to_string_pretty(&doc)?);
    } else {
        println!(
            "natural frequencies (rad/s), {} extrapolated over uniform meshes {:?}: {status}",
            method.name(),
            conv.meshes
        );
        println!("analytic = uncoupled (ρx_c = 0), exact");
        println!("{:>3} {:>20} {:>10} {:>6} {:>18}", "n", "coupled", "± error", "order", "uncoupled analytic");
        for (i, m) in conv.modes.iter().enumerate() {
            let order = m.observed_order.map(|p| format!("{p:.2}")).unwrap_or_else(|| "-".into());
            println!("{:>3} {:>20.12} {:>10.1e} {:>6} {:>18.12}", i + 1, m.omega, m.error, order, uncoupled[i]);
        }
    }
    Ok(())
}

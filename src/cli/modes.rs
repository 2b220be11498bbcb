//! `wingcheck modes`.

use clap::Args;
use serde_json::json;
use wingcheck_model::Method;
use wingcheck_sim::{modes, Discretisation};

use super::common::ConfigArgs;

/// Arguments of `wingcheck modes`.
#[derive(Debug, Args)]
pub struct ModesArgs {
    #[command(flatten)]
    config: ConfigArgs,
    #[command(flatten)]
    work: super::common::WorkArgs,
    /// Number of frequencies.
    #[arg(long, default_value_t = 5)]
    count: usize,
    /// Spatial discretisation: fd or fe.
    #[arg(long)]
    method: Option<Method>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(a: ModesArgs) -> anyhow::Result<()> {
    let mut cfg = a.config.load()?;
    if let Some(m) = a.method {
        cfg.discretisation.method = m;
    }
    if a.count == 0 {
        anyhow::bail!("--count must be at least 1");
    }
    a.work.guard(&wingcheck_model::work::WorkEstimate::modes(&cfg))?;
    let disc = Discretisation::new(&cfg);
    if a.count > disc.dim() {
        anyhow::bail!(
            "--count {} exceeds the {} degrees of freedom of this discretisation (allowed: 1 to {}); refine with --set discretisation.elements=N",
            a.count,
            disc.dim(),
            disc.dim()
        );
    }
    let count = a.count;
    let coupled = modes::natural_frequencies(&disc, count)?;
    let w = &cfg.wing;
    let bending = modes::bending_frequencies(w.span, w.ei, w.rho, count);
    let torsion = modes::torsion_frequencies(w.span, w.gj, w.ip, count);
    let uncoupled = modes::uncoupled_frequencies(w.span, w.ei, w.rho, w.gj, w.ip, count);
    if a.json {
        let doc = json!({
            "method": cfg.discretisation.method.name(),
            "elements": cfg.discretisation.elements,
            "coupled_rad_s": coupled,
            "uncoupled_analytic_rad_s": uncoupled,
            "bending_analytic_rad_s": bending,
            "torsion_analytic_rad_s": torsion,
            "note": "coupled: generalised eigenproblem K φ = ω² M φ of the discretised undamped, uncontrolled wing; analytic: ρx_c = 0, cantilever roots of 1 + cos βs cosh βs = 0 and (2n−1)π/(2s)·√(GJ/I_p)",
        });
        println!("{}", serde_json::to_string_pretty(&doc)?);
    } else {
        println!(
            "natural frequencies (rad/s), {} with {} elements; analytic = uncoupled (ρx_c = 0)",
            cfg.discretisation.method.name(),
            cfg.discretisation.elements
        );
        println!("{:>3} {:>14} {:>18}", "n", "coupled", "uncoupled analytic");
        for i in 0..count {
            println!("{:>3} {:>14.6} {:>18.6}", i + 1, coupled[i], uncoupled[i]);
        }
    }
    Ok(())
}

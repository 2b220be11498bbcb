//! `wingcheck check`: the claim ledger.

use clap::Args;
use wingcheck_claims::check_all;

use super::common::ConfigArgs;

/// Arguments of `wingcheck check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    #[command(flatten)]
    config: ConfigArgs,
    #[command(flatten)]
    work: super::common::WorkArgs,
    /// Print the ledger as JSON (rows with evidence, assumptions and plot data).
    #[arg(long)]
    json: bool,
}

pub fn run(a: CheckArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    a.work.guard(&wingcheck_model::work::WorkEstimate::check(&cfg))?;
    let ledger = check_all(&cfg)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&ledger)?);
        return Ok(());
    }
    println!("claim ledger ({}, config sha256 {})", ledger.tool, &ledger.config_sha256[..12]);
    println!("{:<14} {:<28} {:<23} {:<18} {:>7}", "id", "equation", "verdict", "basis", "time");
    for r in &ledger.rows {
        println!("{:<14} {:<28} {:<23} {:<18} {:>6.2}s", r.id, r.equation, r.verdict.name(), r.basis.name(), r.seconds);
    }
    for r in &ledger.rows {
        println!("\n[{}] {} — {}", r.id, r.verdict.name(), r.claim);
        println!("  {}", r.summary);
        if let Some(c) = &r.correction {
            println!("  correction: {c}");
        }
        for (k, v) in &r.evidence {
            println!("  {k} = {v}");
        }
        for s in &r.assumptions {
            println!("  assumed: {s}");
        }
        for c in &r.certificates {
            println!("  certificate: {c}");
        }
    }
    Ok(())
}
